// motor: a hinge motor with a torque cap spins up a free body at the rate the cap allows.
//
// A box (2 kg, 1 x 0.4 x 0.2 m) on a hinge through its centre of mass about its z axis (a
// principal axis, I = m (a^2 + b^2) / 12), gravity along the axis so it applies no torque. The
// motor's target is 10 rad/s with at most 1 N m: the angular acceleration is tau / I until the
// target is reached at t = omega I / tau, then the speed holds. Measured: the acceleration (speed
// at t = 1 s over 1 s) and the speed at the end, both within 2 % of the cap's prediction; and
// that the reported motor torque is the cap while accelerating.

#include <cmath>
#include <string>

#include "../case.h"
#include "tumble/tumble.h"

namespace tumble::validation {
namespace {

CaseResult run(const CaseOptions& options) {
    CaseResult r;
    const double h = 1.0 / 60.0;
    const double mass = 2;
    const double a = 1;
    const double b = 0.4;
    const double c = 0.2;
    const double torque = 1;
    const double target = 10;
    const double inertia = mass * (a * a + b * b) / 12;
    WorldDef settings;
    settings.timeStep = h;
    settings.enableSleep = false;
    World world(settings);
    BodyDef def;
    def.position = Vec3(0, 0, 1);
    def.mass.mass = mass;
    def.mass.inertia =
        (Vec3(b * b + c * c, a * a + c * c, a * a + b * b) * (mass / 12)).asDiagonal();
    const BodyId box = world.createBody(def);
    JointDef joint;
    joint.type = JointType::Hinge;
    joint.bodyA = box;
    joint.anchor = def.position;
    joint.axis = Vec3::UnitZ();
    joint.enableMotor = true;
    joint.motorSpeed = target;
    joint.maxMotorForce = torque;
    const JointId motor = world.createJoint(joint);

    const double rate = torque / inertia;
    const double reach = target / rate;
    const double duration = options.fast ? reach + 0.5 : reach + 3;
    const int steps = static_cast<int>(std::round(duration / h));
    const int oneSecond = static_cast<int>(std::round(1 / h));
    double speedAtOne = 0;
    double torqueAtOne = 0;
    for (int i = 1; i <= steps; ++i) {
        world.step();
        if (i == oneSecond) {
            speedAtOne = world.jointState(motor).speed;
            torqueAtOne = world.jointState(motor).torque.z();
        }
    }
    const double finalSpeed = world.jointState(motor).speed;
    const double measuredRate = speedAtOne / 1.0;
    r.metric("predicted acceleration tau / I (rad/s^2)", rate);
    r.metric("measured acceleration (rad/s^2)", measuredRate);
    r.metric("acceleration rel. error", measuredRate / rate - 1);
    r.metric("motor torque while accelerating (N m)", torqueAtOne);
    r.metric("target speed (rad/s)", target);
    r.metric("final speed (rad/s)", finalSpeed);
    r.metric("final speed rel. error", finalSpeed / target - 1);
    r.metric(
        "off-axis spin (rad/s)",
        (world.angularVelocity(box) - world.angularVelocity(box).dot(Vec3::UnitZ()) * Vec3::UnitZ())
            .norm());
    r.tolerance("relative", 0.02);
    r.check(std::abs(measuredRate / rate - 1) <= 0.02,
            "acceleration " + std::to_string(measuredRate) +
                " rad/s^2 is not tau / I = " + std::to_string(rate) + " within 2 %");
    r.check(std::abs(finalSpeed / target - 1) <= 0.02,
            "final speed " + std::to_string(finalSpeed) + " rad/s is not the target within 2 %");
    r.check(std::abs(torqueAtOne / torque - 1) <= 0.02,
            "the motor's torque while accelerating is not the cap within 2 %");
    return r;
}

}  // namespace

ValidationCase motorCase() {
    return {"motor",
            "a hinge motor capped at 1 N m spins a box up at tau / I to its 10 rad/s target "
            "(2 %)",
            run};
}

}  // namespace tumble::validation
