#include "controllers.h"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "joints.h"

namespace tumble {
namespace {

// An angle difference wrapped into (-pi, pi]: a set-point across the hinge angle's seam at pi
// is reached the short way.
Real wrapAngle(Real angle) {
    const Real pi = std::numbers::pi_v<Real>;
    const Real wrapped = std::remainder(angle, 2 * pi);
    return wrapped == -pi ? pi : wrapped;
}

// The law of control.h for one step of length h; updates the record's state.
Real controlOutput(ControllerRecord& record, const JointFrame& frame, bool hinge, Real h) {
    const ControllerDef& def = record.def;
    ControllerState& state = record.state;
    Real error = 0;
    Real derivative = 0;
    if (def.mode == ControlMode::Position) {
        error = hinge ? wrapAngle(def.target - frame.position) : def.target - frame.position;
        derivative = def.targetVelocity - frame.speed;
    } else {
        error = def.targetVelocity - frame.speed;
        derivative = record.started ? (error - state.error) / h : 0;
    }
    const Real integral = state.integral + error * h;
    Real output = def.kp * error + def.ki * integral + def.kd * derivative;
    // Conditional integration: a saturated output pushing the way the error asks keeps the old
    // integral, so it does not wind up while the actuator cannot follow.
    const bool saturated = std::abs(output) > def.maxForce;
    if (!(saturated && output * error > 0))
        state.integral = integral;
    output = std::clamp(output, -def.maxForce, def.maxForce);
    state.error = error;
    state.output = output;
    record.started = true;
    return output;
}

// At its target: within this of it (rad or m; rad/s or m/s in velocity mode).
constexpr Real kTargetTolerance = 1e-4;
// Stalled: the joint moves slower than this (rad/s or m/s), so over timeToSleep (0.5 s) it would
// close less than a twentieth of the target tolerance.
constexpr Real kStalledSpeed = 1e-5;

// May the controller's bodies sleep? Only at the target, or -- for a law without an integral,
// whose output then no longer changes -- stalled short of it in balance (a PD arm drooping under
// gravity, or pressed against something). A moving set-point is never reached.
bool settled(const ControllerRecord& record, const JointFrame& frame) {
    const ControllerDef& def = record.def;
    if (def.targetVelocity != 0)
        return false;
    if (def.mode == ControlMode::Velocity)
        return std::abs(record.state.error) <= kTargetTolerance;
    return std::abs(record.state.error) <= kTargetTolerance ||
           (def.ki == 0 && std::abs(frame.speed) <= kStalledSpeed);
}

}  // namespace

ControllerRecord* Controllers::find(JointId joint) {
    for (ControllerRecord& record : records_) {
        if (record.joint == joint)
            return &record;
    }
    return nullptr;
}

const ControllerRecord* Controllers::find(JointId joint) const {
    for (const ControllerRecord& record : records_) {
        if (record.joint == joint)
            return &record;
    }
    return nullptr;
}

void Controllers::set(JointId joint, const ControllerDef& def) {
    ControllerRecord* record = find(joint);
    if (record == nullptr)
        record = &records_.emplace_back();
    *record = ControllerRecord{};
    record->joint = joint;
    record->def = def;
}

bool Controllers::remove(JointId joint) {
    const auto at = std::find_if(records_.begin(), records_.end(),
                                 [&](const ControllerRecord& r) { return r.joint == joint; });
    if (at == records_.end())
        return false;
    records_.erase(at);  // keeps the order of the others
    return true;
}

void Controllers::apply(const JointStore& joints, BodyStore& bodies, Real h) {
    std::erase_if(records_, [&](const ControllerRecord& r) { return !joints.isValid(r.joint); });
    for (ControllerRecord& record : records_) {
        const std::uint32_t index = joints.indexOf(record.joint);
        if (joints.state[index].broken) {
            record.state.output = 0;
            continue;
        }
        const JointRecord& joint = joints.records[index];
        const JointFrame frame = jointFrame(joint, bodies);
        const bool movesA = bodies.isAwakeDynamic(frame.a);
        const bool movesB = !frame.world && bodies.isAwakeDynamic(frame.b);
        if (!movesA && !movesB)
            continue;  // asleep (or held by static bodies): nothing to drive, nothing to integrate
        const bool hinge = joint.def.type == JointType::Hinge;
        const Real output = controlOutput(record, frame, hinge, h);
        if (!settled(record, frame)) {
            // Still driving: the bodies do not count as still this step (Islands::updateSleep).
            if (movesA)
                bodies.info[frame.a].pushed = true;
            if (movesB)
                bodies.info[frame.b].pushed = true;
        }
        if (hinge) {
            // A torque along the axis turns B counter-clockwise relative to A: angle up.
            const Vec3 torque = output * frame.axis;
            if (movesA)
                bodies.forces[frame.a].torque -= torque;
            if (movesB)
                bodies.forces[frame.b].torque += torque;
        } else {
            // A force along the axis at B's anchor pushes B out along it; A takes the opposite
            // at the same point, so the pair gets no net force or moment.
            const Vec3 force = output * frame.axis;
            if (movesA) {
                bodies.forces[frame.a].force -= force;
                bodies.forces[frame.a].torque -= (frame.rA + frame.separation).cross(force);
            }
            if (movesB) {
                bodies.forces[frame.b].force += force;
                bodies.forces[frame.b].torque += frame.rB.cross(force);
            }
        }
    }
}

void Controllers::save() {
    for (ControllerRecord& record : records_) {
        record.previousState = record.state;
        record.previousStarted = record.started;
    }
}

void Controllers::restore() {
    for (ControllerRecord& record : records_) {
        record.state = record.previousState;
        record.started = record.previousStarted;
    }
}

}  // namespace tumble
