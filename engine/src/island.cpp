#include "island.h"

#include <algorithm>
#include <limits>
#include <numeric>

#include "integrator.h"

namespace tumble {
namespace {

bool isTouching(const Contact& contact) {
    return contact.manifold.pointCount > 0;
}

/// An island that touches nothing falls asleep only in a step whose every body is within this
/// fraction of its static balance: frozen where it is, its spring stretches are within 1e-4 of
/// the static ones (docs/ARCHITECTURE.md, "Islands and sleeping", derives the bound below).
constexpr Real kBalanceFraction = 1e-4;
/// The acceleration the fraction is taken of when the world has no gravity (m/s^2).
constexpr Real kStandardGravity = 9.81;

/// How much the step changed the velocity of the body's fastest-changing point (m/s): the net
/// effect of gravity, springs, joints, drag and controllers, so no force needs adding up.
Real velocityChange(const BodyStore& bodies, std::uint32_t index) {
    const BodyMotion& m = bodies.motion[index];
    const BodyMotion& before = bodies.previousMotion[index];
    return (m.linearVelocity - before.linearVelocity).norm() +
           bodies.info[index].extent * (m.angularVelocity - before.angularVelocity).norm();
}

/// The speed of the body's fastest point (m/s): its centre's plus its turn at its extent.
Real pointSpeed(const BodyStore& bodies, std::uint32_t index) {
    const BodyMotion& m = bodies.motion[index];
    return m.linearVelocity.norm() + bodies.info[index].extent * m.angularVelocity.norm();
}

/// In balance: frozen now, the body would gain at most 1e-4 g h in its next step. Its unbalanced
/// static force F = M dv/h + D v (D any damping on it), so both the step's velocity change and
/// the velocity itself are bounded, by half the budget each: F / (M g) <= 1e-4 (1 + h D/M) / 2.
/// A body nothing links or damps has D = 0: its velocity is free (a slow drift in empty space).
bool inBalance(const BodyStore& bodies, std::uint32_t index, bool damped, Real bound) {
    return velocityChange(bodies, index) <= bound &&
           (!damped || pointSpeed(bodies, index) <= bound);
}

}  // namespace

void Islands::wake(BodyStore& bodies, ContactManager& contacts, std::uint32_t index,
                   const StepContext* midStep) {
    bodies.info[index].sleepTime = 0;
    if (!bodies.isSleeping(index))
        return;
    stack_.clear();
    stack_.push_back(index);
    markAwake(bodies, index);
    while (!stack_.empty()) {
        const std::uint32_t body = stack_.back();
        stack_.pop_back();
        bodies.info[body].sleepTime = 0;
        if (midStep != nullptr)
            integrateVelocity(bodies, body, *midStep);
        contacts.forEachContact(
            bodies, body, [&](std::uint32_t slot, const Contact& contact, std::uint32_t other) {
                contacts.activate(slot);
                if (isTouching(contact) && bodies.isSleeping(other)) {
                    markAwake(bodies, other);
                    stack_.push_back(other);
                }
            });
        // Joints join islands too; a body left asleep across a joint is woken by
        // wakeJointLinked before the solve.
    }
}

void Islands::push(BodyStore& bodies, ContactManager& contacts, std::uint32_t index) {
    if (bodies.info[index].type != BodyType::Dynamic)
        return;
    bodies.info[index].pushed = true;
    wake(bodies, contacts, index);
}

void Islands::wakeAround(BodyStore& bodies, ContactManager& contacts, std::uint32_t index,
                         bool touchingOnly) {
    push(bodies, contacts, index);
    // Collect first: waking activates contacts, which the walk must not see half-done.
    sleepers_.clear();
    contacts.forEachContact(
        bodies, index, [&](std::uint32_t, const Contact& contact, std::uint32_t other) {
            if ((!touchingOnly || isTouching(contact)) && bodies.isSleeping(other))
                sleepers_.push_back(other);
        });
    for (const std::uint32_t other : sleepers_)
        wake(bodies, contacts, other);
}

void Islands::sleepIslandOf(BodyStore& bodies, ContactManager& contacts, std::uint32_t index) {
    if (!bodies.isAwakeDynamic(index))
        return;
    visited_.assign(bodies.awake.size(), 0);
    sleepers_.clear();
    stack_.clear();
    stack_.push_back(index);
    visited_[bodies.info[index].awakeIndex] = 1;
    while (!stack_.empty()) {
        const std::uint32_t body = stack_.back();
        stack_.pop_back();
        sleepers_.push_back(body);
        contacts.forEachContact(bodies, body,
                                [&](std::uint32_t, const Contact& contact, std::uint32_t other) {
                                    if (!isTouching(contact) || !bodies.isAwakeDynamic(other) ||
                                        visited_[bodies.info[other].awakeIndex] != 0)
                                        return;
                                    visited_[bodies.info[other].awakeIndex] = 1;
                                    stack_.push_back(other);
                                });
    }
    putToSleep(bodies, contacts, sleepers_);
}

void Islands::wakeTouched(BodyStore& bodies, ContactManager& contacts, const StepContext& context) {
    for (const std::uint32_t index : contacts.wakeRequests())
        wake(bodies, contacts, index, &context);
    contacts.clearWakeRequests();
    contacts.flushActivations();
}

void Islands::updateSleep(BodyStore& bodies, ContactManager& contacts, const SpringStore& springs,
                          const DragStore& drag, const JointStore& joints,
                          const StepContext& context, const WorldDef& settings) {
    if (!settings.enableSleep)
        return;
    const Real linear = settings.linearSleepVelocity;
    const Real angular = settings.angularSleepVelocity;
    bool anySleepy = false;
    for (const std::uint32_t index : bodies.awake) {
        BodyInfo& info = bodies.info[index];
        if (info.type != BodyType::Dynamic)
            continue;
        const BodyMotion& m = bodies.motion[index];
        // Still when no point of the body moves faster than the linear threshold (its centre's
        // speed plus its turn at its extent), and it turns slower than the angular threshold.
        const Real turn = m.angularVelocity.norm();
        if (info.pushed || !info.allowSleep || turn > angular ||
            m.linearVelocity.norm() + info.extent * turn > linear) {
            info.sleepTime = 0;
            info.pushed = false;
        } else {
            info.sleepTime += context.h;
            anySleepy = anySleepy || info.sleepTime >= settings.timeToSleep;
        }
    }
    if (!anySleepy)
        return;  // the common case while things move: no union-find at all

    const std::uint32_t count = static_cast<std::uint32_t>(bodies.awake.size());
    parent_.resize(count);
    std::iota(parent_.begin(), parent_.end(), 0u);
    flags_.assign(count, 0);
    for (const std::uint32_t slot : contacts.touchingSlots()) {
        const Contact& contact = contacts.contact(slot);
        if (!contacts.isActive(slot) || !isTouching(contact))
            continue;
        // Live while the contact is (shapePose says why): unchecked, as buildConstraints'.
        const std::uint32_t a = bodies.checkedIndexOf(contact.bodyA);
        const std::uint32_t b = bodies.checkedIndexOf(contact.bodyB);
        const bool dynamicA = bodies.isAwakeDynamic(a);
        const bool dynamicB = bodies.isAwakeDynamic(b);
        if (dynamicA)
            flags_[bodies.info[a].awakeIndex] |= kTouches;
        if (dynamicB)
            flags_[bodies.info[b].awakeIndex] |= kTouches;
        if (dynamicA && dynamicB) {
            unite(bodies.info[a].awakeIndex, bodies.info[b].awakeIndex);
        } else if (dynamicA && bodies.isMovingKinematic(b)) {
            bodies.info[a].sleepTime = 0;  // carried or pushed: not at rest
        } else if (dynamicB && bodies.isMovingKinematic(a)) {
            bodies.info[b].sleepTime = 0;
        }
    }
    // What may damp a body: a spring or joint on it (dampers, joint drives, controllers' kd),
    // drag, or its own damping.
    const auto markDamped = [&](std::uint32_t index) {
        if (bodies.isAwakeDynamic(index))
            flags_[bodies.info[index].awakeIndex] |= kDamped;
    };
    for (const BodyId body : drag.bodies)
        markDamped(bodies.indexOf(body));
    // Springs and unbroken joints unite their two bodies exactly as touching contacts do (one
    // to a world point joins nothing).
    const auto link = [&](BodyId bodyA, BodyId bodyB) {
        markDamped(bodies.indexOf(bodyA));
        if (bodyB.isNull())
            return;
        const std::uint32_t a = bodies.indexOf(bodyA);
        const std::uint32_t b = bodies.indexOf(bodyB);
        markDamped(b);
        const bool dynamicA = bodies.isAwakeDynamic(a);
        const bool dynamicB = bodies.isAwakeDynamic(b);
        if (dynamicA && dynamicB) {
            unite(bodies.info[a].awakeIndex, bodies.info[b].awakeIndex);
        } else if (dynamicA && bodies.isMovingKinematic(b)) {
            bodies.info[a].sleepTime = 0;
        } else if (dynamicB && bodies.isMovingKinematic(a)) {
            bodies.info[b].sleepTime = 0;
        }
    };
    for (const SpringDef& def : springs.defs)
        link(def.bodyA, def.bodyB);
    for (std::uint32_t i = 0; i < joints.count(); ++i) {
        if (joints.state[i].broken)
            continue;
        const JointDef& def = joints.records[i].def;
        link(def.bodyA, def.bodyB);
        // A running motor drives its bodies however slowly they turn: they never count as still.
        if (def.enableMotor && def.motorSpeed != 0 && def.maxMotorForce > 0) {
            bodies.info[bodies.indexOf(def.bodyA)].sleepTime = 0;
            if (!def.bodyB.isNull())
                bodies.info[bodies.indexOf(def.bodyB)].sleepTime = 0;
        }
    }

    islandSleepTime_.assign(count, std::numeric_limits<Real>::infinity());
    islandBalance_.assign(count, kInBalance);
    const Real gravity = context.gravity.norm();
    const Real bound =
        0.5 * kBalanceFraction * (gravity > 0 ? gravity : kStandardGravity) * context.h;
    for (std::uint32_t k = 0; k < count; ++k) {
        const BodyInfo& info = bodies.info[bodies.awake[k]];
        if (info.type == BodyType::Dynamic) {
            const std::uint32_t root = find(k);
            islandSleepTime_[root] = std::min(islandSleepTime_[root], info.sleepTime);
            const bool damped =
                (flags_[k] & kDamped) != 0 || info.linearDamping > 0 || info.angularDamping > 0;
            if ((flags_[k] & kTouches) != 0)
                islandBalance_[root] = kHeld;
            else if (islandBalance_[root] == kInBalance &&
                     !inBalance(bodies, bodies.awake[k], damped, bound))
                islandBalance_[root] = kOutOfBalance;
        }
    }
    sleepers_.clear();
    for (std::uint32_t k = 0; k < count; ++k) {
        const std::uint32_t index = bodies.awake[k];
        const std::uint32_t root = find(k);
        if (bodies.info[index].type == BodyType::Dynamic &&
            islandSleepTime_[root] >= settings.timeToSleep && islandBalance_[root] != kOutOfBalance)
            sleepers_.push_back(index);
    }
    putToSleep(bodies, contacts, sleepers_);
}

void Islands::putToSleep(BodyStore& bodies, ContactManager& contacts,
                         std::span<const std::uint32_t> indices) {
    for (const std::uint32_t index : indices) {
        markAsleep(bodies, index);
        BodyMotion& m = bodies.motion[index];
        m.linearVelocity.setZero();
        m.angularVelocity.setZero();
        bodies.previousMotion[index] = m;  // interpolation shows the resting pose
        bodies.forces[index] = {};
    }
    // Park the contacts with nothing awake on the other side; a contact with an awake body
    // (not touching, or it would be in the island) stays active so that body still collides.
    for (const std::uint32_t index : indices) {
        contacts.forEachContact(bodies, index,
                                [&](std::uint32_t slot, const Contact&, std::uint32_t other) {
                                    if (!bodies.isAwake(other))
                                        contacts.deactivate(slot);
                                });
    }
}

void Islands::markAwake(BodyStore& bodies, std::uint32_t index) {
    bodies.markAwake(index);
    if (events != nullptr)
        events->sleep.push_back({bodies.idAt(index), false});
}

void Islands::markAsleep(BodyStore& bodies, std::uint32_t index) {
    bodies.markNotAwake(index);
    if (events != nullptr)
        events->sleep.push_back({bodies.idAt(index), true});
}

void Islands::reserve(std::size_t bodyCount) {
    parent_.reserve(bodyCount);
    islandSleepTime_.reserve(bodyCount);
    flags_.reserve(bodyCount);
    islandBalance_.reserve(bodyCount);
    stack_.reserve(bodyCount);
    visited_.reserve(bodyCount);
    sleepers_.reserve(bodyCount);
}

std::uint32_t Islands::find(std::uint32_t position) {
    while (parent_[position] != position) {
        parent_[position] = parent_[parent_[position]];
        position = parent_[position];
    }
    return position;
}

void Islands::unite(std::uint32_t a, std::uint32_t b) {
    const std::uint32_t rootA = find(a);
    const std::uint32_t rootB = find(b);
    // The smaller position becomes the root: the sets never depend on the order of unions.
    if (rootA < rootB)
        parent_[rootB] = rootA;
    else if (rootB < rootA)
        parent_[rootA] = rootB;
}

}  // namespace tumble
