#include "springs.h"

#include <algorithm>
#include <cmath>

namespace tumble {
namespace {

Vec3 anchorVelocity(const BodyStore& bodies, BodyId body, const Vec3& position) {
    if (body.isNull())
        return Vec3::Zero();
    const BodyMotion& m = bodies.motion[bodies.indexOf(body)];
    return m.linearVelocity + m.angularVelocity.cross(position - m.center);
}

void addForce(BodyStore& bodies, BodyId body, const Vec3& force, const Vec3& point) {
    if (body.isNull())
        return;
    const std::uint32_t i = bodies.indexOf(body);
    if (!bodies.isAwakeDynamic(i))
        return;
    bodies.forces[i].force += force;
    bodies.forces[i].torque += (point - bodies.motion[i].center).cross(force);
}

bool isAwakeDynamic(const BodyStore& bodies, BodyId body) {
    return !body.isNull() && bodies.isAwakeDynamic(bodies.indexOf(body));
}

}  // namespace

Vec3 anchorPosition(const BodyStore& bodies, BodyId body, const Vec3& localAnchor) {
    if (body.isNull())
        return localAnchor;
    const std::uint32_t i = bodies.indexOf(body);
    const BodyMotion& m = bodies.motion[i];
    return m.center + m.orientation * (localAnchor - bodies.inertia[i].localCenter);
}

Real springLength(const SpringStore& springs, const BodyStore& bodies, std::uint32_t index) {
    const SpringDef& def = springs.defs[index];
    return (anchorPosition(bodies, def.bodyB, def.localAnchorB) -
            anchorPosition(bodies, def.bodyA, def.localAnchorA))
        .norm();
}

Real springPotentialEnergy(const SpringStore& springs, const BodyStore& bodies) {
    Real energy = 0;
    for (std::uint32_t i = 0; i < springs.count(); ++i) {
        const SpringDef& def = springs.defs[i];
        const Real stretch = springLength(springs, bodies, i) - def.restLength;
        if (def.tensionOnly && stretch <= 0)
            continue;
        energy += 0.5 * def.stiffness * stretch * stretch;
    }
    return energy;
}

void wakeSpringLinked(const SpringStore& springs, BodyStore& bodies, ContactManager& contacts,
                      Islands& islands) {
    // Cheap test first: nothing sleeps in most scenes that have springs.
    bool anySleeping = false;
    for (std::uint32_t i = 0; i < springs.count() && !anySleeping; ++i) {
        const SpringDef& def = springs.defs[i];
        anySleeping = bodies.isSleeping(bodies.indexOf(def.bodyA)) ||
                      (!def.bodyB.isNull() && bodies.isSleeping(bodies.indexOf(def.bodyB)));
    }
    if (!anySleeping)
        return;
    auto drives = [&](std::uint32_t i) {
        return bodies.isAwakeDynamic(i) || bodies.isMovingKinematic(i);
    };
    for (bool woke = true; woke;) {
        woke = false;
        for (std::uint32_t i = 0; i < springs.count(); ++i) {
            const SpringDef& def = springs.defs[i];
            if (def.bodyB.isNull())
                continue;
            const std::uint32_t a = bodies.indexOf(def.bodyA);
            const std::uint32_t b = bodies.indexOf(def.bodyB);
            if (bodies.isSleeping(a) && drives(b)) {
                islands.wake(bodies, contacts, a);
                woke = true;
            } else if (bodies.isSleeping(b) && drives(a)) {
                islands.wake(bodies, contacts, b);
                woke = true;
            }
        }
    }
}

void ForceElements::apply(SpringStore& springs, const DragStore& drag, BodyStore& bodies) {
    applied_ = springs.count() > springs.implicitCount || !drag.empty();
    if (!applied_)
        return;
    saved_.resize(bodies.awake.size());
    for (std::size_t k = 0; k < bodies.awake.size(); ++k)
        saved_[k] = bodies.forces[bodies.awake[k]];

    for (std::uint32_t i = 0; i < springs.count(); ++i) {
        const SpringDef& def = springs.defs[i];
        if (def.formulation != SpringFormulation::Explicit)
            continue;
        if (!isAwakeDynamic(bodies, def.bodyA) && !isAwakeDynamic(bodies, def.bodyB))
            continue;
        const Vec3 pA = anchorPosition(bodies, def.bodyA, def.localAnchorA);
        const Vec3 pB = anchorPosition(bodies, def.bodyB, def.localAnchorB);
        const Vec3 d = pB - pA;
        const Real length = d.norm();
        const Vec3 n = length > 0 ? Vec3(d / length) : Vec3::Zero();
        const Real lengthRate =
            n.dot(anchorVelocity(bodies, def.bodyB, pB) - anchorVelocity(bodies, def.bodyA, pA));
        Real tension = def.stiffness * (length - def.restLength) + def.damping * lengthRate;
        if (def.tensionOnly)
            tension = length > def.restLength ? std::max<Real>(tension, 0) : 0;
        springs.state[i] = {tension, def.tensionOnly && tension == 0};
        const Vec3 force = tension * n;  // on A, towards B
        addForce(bodies, def.bodyA, force, pA);
        addForce(bodies, def.bodyB, -force, pB);
    }

    for (std::size_t j = 0; j < drag.bodies.size(); ++j) {
        const std::uint32_t i = bodies.indexOf(drag.bodies[j]);
        if (!bodies.isAwakeDynamic(i))
            continue;
        const Drag& d = drag.drags[j];
        const Vec3 u = d.projection * bodies.motion[i].linearVelocity;
        bodies.forces[i].force -= (d.linear + d.quadratic * u.norm()) * u;
    }
}

void ForceElements::restore(BodyStore& bodies) {
    if (!applied_)
        return;
    // The awake list cannot change between apply() and restore(): both sit around the
    // velocity update.
    for (std::size_t k = 0; k < bodies.awake.size(); ++k)
        bodies.forces[bodies.awake[k]] = saved_[k];
    applied_ = false;
}

}  // namespace tumble
