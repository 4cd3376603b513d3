// World: joint controllers, the pre-step callback, and the event arrays.

#include <cmath>
#include <utility>

#include "controllers.h"
#include "tumble/core/error.h"
#include "tumble/world.h"
#include "world_impl.h"

namespace tumble {
namespace {

void checkGain(Real gain, const char* name) {
    if (!(std::isfinite(gain) && gain >= 0))
        fail("ControllerDef.", name, " = ", gain, " must be finite and >= 0 (a gain, not a sign)");
}

void checkTargets(Real target, Real targetVelocity, const char* where) {
    if (!std::isfinite(target))
        fail(where, " target = ", target, " (rad or m) must be finite");
    if (!std::isfinite(targetVelocity))
        fail(where, " targetVelocity = ", targetVelocity, " (rad/s or m/s) must be finite");
}

void checkControllerDef(const ControllerDef& def) {
    if (def.mode != ControlMode::Position && def.mode != ControlMode::Velocity)
        fail("ControllerDef.mode = ", static_cast<int>(def.mode), " is not a control mode");
    checkTargets(def.target, def.targetVelocity, "ControllerDef");
    checkGain(def.kp, "kp");
    checkGain(def.ki, "ki");
    checkGain(def.kd, "kd");
    if (!(def.maxForce > 0)) {
        fail("ControllerDef.maxForce = ", def.maxForce,
             " (N m or N) must be > 0 (infinity: no cap)");
    }
}

// A pushed joint: its bodies wake and start counting as still afresh. (A template: World::Impl
// is private, so it cannot be named here.)
template <typename Impl>
void wakeJoint(Impl& w, const JointDef& def) {
    w.islands.push(w.bodies, w.contacts, w.bodies.indexOf(def.bodyA));
    if (!def.bodyB.isNull())
        w.islands.push(w.bodies, w.contacts, w.bodies.indexOf(def.bodyB));
}

}  // namespace

void World::setJointController(JointId id, const ControllerDef& def) {
    Impl& w = *impl_;
    const JointDef& joint = w.joints.records[w.joints.indexOf(id)].def;
    if (joint.type != JointType::Hinge && joint.type != JointType::Slider)
        fail("setJointController: only hinge and slider joints can be controlled");
    checkControllerDef(def);
    w.controllers.set(id, def);
    wakeJoint(w, joint);
}

void World::setJointControllerTarget(JointId id, Real target, Real targetVelocity) {
    Impl& w = *impl_;
    const JointDef& joint = w.joints.records[w.joints.indexOf(id)].def;
    checkTargets(target, targetVelocity, "setJointControllerTarget");
    ControllerRecord* record = w.controllers.find(id);
    if (record == nullptr)
        fail("setJointControllerTarget: the joint has no controller (setJointController first)");
    record->def.target = target;
    record->def.targetVelocity = targetVelocity;
    wakeJoint(w, joint);
}

void World::clearJointController(JointId id) {
    Impl& w = *impl_;
    const JointDef& joint = w.joints.records[w.joints.indexOf(id)].def;
    if (w.controllers.remove(id))
        wakeJoint(w, joint);
}

std::optional<ControllerDef> World::jointController(JointId id) const {
    const Impl& w = *impl_;
    w.joints.indexOf(id);  // refuses a stale id
    const ControllerRecord* record = w.controllers.find(id);
    if (record == nullptr)
        return std::nullopt;
    return record->def;
}

ControllerState World::jointControllerState(JointId id) const {
    const Impl& w = *impl_;
    w.joints.indexOf(id);
    const ControllerRecord* record = w.controllers.find(id);
    if (record == nullptr)
        fail("jointControllerState: the joint has no controller");
    return record->state;
}

void World::setPreStepCallback(std::function<void(World&, Real)> callback) {
    if (impl_->inPreStep)
        fail("setPreStepCallback: called from the pre-step callback itself");
    impl_->preStep = std::move(callback);
}

void World::Impl::runPreStep(World& world) {
    if (inPreStep)
        fail("step() or advance() called from the pre-step callback");
    if (!preStep)
        return;
    // Reset the guard however the callback leaves (it may throw).
    struct Guard {
        bool& flag;
        ~Guard() { flag = false; }
    } guard{inPreStep};
    inPreStep = true;
    preStep(world, time);
}

std::span<const ContactEvent> World::contactBeginEvents() const {
    return impl_->events.contactBegin;
}
std::span<const ContactEvent> World::contactEndEvents() const {
    return impl_->events.contactEnd;
}
std::span<const ImpactEvent> World::impactEvents() const {
    return impl_->events.impact;
}
std::span<const JointBreakEvent> World::jointBreakEvents() const {
    return impl_->events.jointBreak;
}
std::span<const SleepEvent> World::sleepEvents() const {
    return impl_->events.sleep;
}

}  // namespace tumble
