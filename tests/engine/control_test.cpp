// Joint controllers (PD, PID, velocity mode, the cap), the pre-step callback, and the refusals.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <vector>

#include "refusal.h"
#include "testkit/scenes.h"
#include "tumble/world.h"

namespace tumble {
namespace {

using test::contains;
using test::refusal;

constexpr Real kGravity = 9.81;
constexpr Real kPi = std::numbers::pi_v<Real>;

using testkit::quietWorld;

// A body with inertia `inertia` about z, on a hinge about z through its centre of mass (gravity
// along the axis: no torque), joined to the world.
struct Turntable {
    BodyId body;
    JointId joint;
};
Turntable addTurntable(World& world, Real inertia) {
    BodyDef def;
    def.mass.mass = 1;
    def.mass.inertia = Vec3(1, 1, inertia).asDiagonal();
    const BodyId body = world.createBody(def);
    const JointId joint = world.createJoint(
        JointDef{.type = JointType::Hinge, .bodyA = body, .bodyB = {}, .axis = Vec3::UnitZ()});
    return {body, joint};
}

// The hinge angle of the body: the world is B, so the joint angle is minus the body's turn.
Real turn(const World& world, const Turntable& t) {
    return -world.jointState(t.joint).position;
}

// An underdamped PD on a free inertia is the textbook second-order loop: its peak overshoot is
// exp(-zeta pi / sqrt(1 - zeta^2)) and it settles on the set-point. At omega h = 0.02 the
// explicit law's discretisation changes the overshoot by O(omega h).
TEST(Control, PdOnAnInertiaOvershootsAsTheSecondOrderLoopPredicts) {
    const Real h = 1.0 / 240.0;
    World world(quietWorld(h));
    const Real inertia = 0.5;
    const Turntable t = addTurntable(world, inertia);
    const Real omega = 5;  // rad/s
    const Real zeta = 0.3;
    const Real target = -1;  // joint angle; the body turns +1 rad
    world.setJointController(t.joint, ControllerDef{.target = target,
                                                    .kp = inertia * omega * omega,
                                                    .kd = 2 * zeta * omega * inertia});
    Real peak = 0;
    for (int i = 0; i < static_cast<int>(8 / h); ++i) {
        ASSERT_TRUE(world.step().ok());
        peak = std::max(peak, turn(world, t));
    }
    const Real predicted = std::exp(-zeta * kPi / std::sqrt(1 - zeta * zeta));
    EXPECT_NEAR(peak - 1, predicted, 0.02 * predicted);
    EXPECT_NEAR(turn(world, t), 1, 1e-4);
    EXPECT_NEAR(world.jointControllerState(t.joint).error, 0, 1e-4);
}

// The cap holds the output: a saturated PD accelerates the inertia at cap / I.
TEST(Control, OutputIsCappedAtMaxForce) {
    const Real h = 1.0 / 240.0;
    World world(quietWorld(h));
    const Real inertia = 0.5;
    const Turntable t = addTurntable(world, inertia);
    const Real cap = 0.2;
    world.setJointController(t.joint,
                             ControllerDef{.target = -2, .kp = 100, .kd = 1, .maxForce = cap});
    const int steps = 24;  // 0.1 s: the output stays saturated
    for (int i = 0; i < steps; ++i) {
        ASSERT_TRUE(world.step().ok());
        EXPECT_NEAR(std::abs(world.jointControllerState(t.joint).output), cap, 1e-12);
    }
    const Real speed = world.angularVelocity(t.body).z();
    EXPECT_NEAR(speed, cap / inertia * steps * h, 1e-9);
}

// A horizontal arm on a hinge under gravity: a PD holds it below the set-point by the torque
// gravity needs (m g l / kp); the integral term removes that error.
TEST(Control, IntegralTermRemovesTheSteadyStateError) {
    const Real h = 1.0 / 240.0;
    const Real mass = 1;
    const Real length = 0.5;  // to the centre of mass
    const Real kp = 200;
    const auto finalError = [&](Real ki) {
        World world(quietWorld(h));
        BodyDef def;
        def.position = Vec3(length, 0, 0);
        def.mass.mass = mass;
        def.mass.inertia = Mat3::Identity() * 0.02;
        const BodyId arm = world.createBody(def);
        const JointId joint = world.createJoint(
            JointDef{.type = JointType::Hinge, .bodyA = arm, .bodyB = {}, .axis = Vec3::UnitY()});
        world.setJointController(joint, ControllerDef{.target = 0, .kp = kp, .ki = ki, .kd = 20});
        for (int i = 0; i < static_cast<int>(20 / h); ++i)
            EXPECT_TRUE(world.step().ok());
        return world.jointControllerState(joint).error;
    };
    const Real pd = finalError(0);
    EXPECT_NEAR(std::abs(pd), mass * kGravity * length / kp, 1e-3 * mass * kGravity * length / kp);
    EXPECT_LT(std::abs(finalError(200)), 1e-5);
}

// A slider driven to a position along its axis, against no load.
TEST(Control, SliderReachesItsPosition) {
    const Real h = 1.0 / 240.0;
    World world(quietWorld(h));
    BodyDef def;
    def.mass.mass = 2;
    def.mass.inertia = Mat3::Identity() * 0.1;
    const BodyId carriage = world.createBody(def);
    const BodyId base = world.createBody(BodyDef{.type = BodyType::Static});
    const JointId joint = world.createJoint(JointDef{
        .type = JointType::Slider, .bodyA = base, .bodyB = carriage, .axis = Vec3::UnitX()});
    world.setJointController(joint, ControllerDef{.target = 0.3, .kp = 200, .kd = 40});
    for (int i = 0; i < static_cast<int>(5 / h); ++i)
        ASSERT_TRUE(world.step().ok());
    EXPECT_NEAR(world.position(carriage).x(), 0.3, 1e-4);
    EXPECT_NEAR(world.jointState(joint).position, 0.3, 1e-4);
    EXPECT_NEAR(world.position(carriage).y(), 0, 1e-9);
}

// Velocity mode: a PI drives the spin to its target against viscous damping on the body.
TEST(Control, VelocityModeHoldsTheSpeed) {
    const Real h = 1.0 / 240.0;
    World world(quietWorld(h));
    BodyDef def;
    def.mass.mass = 1;
    def.mass.inertia = Vec3(1, 1, 0.5).asDiagonal();
    def.angularDamping = 1;  // (1/s): a load the integral has to carry
    const BodyId body = world.createBody(def);
    const JointId joint = world.createJoint(
        JointDef{.type = JointType::Hinge, .bodyA = body, .bodyB = {}, .axis = Vec3::UnitZ()});
    world.setJointController(
        joint,
        ControllerDef{.mode = ControlMode::Velocity, .targetVelocity = -3, .kp = 5, .ki = 10});
    for (int i = 0; i < static_cast<int>(10 / h); ++i)
        ASSERT_TRUE(world.step().ok());
    EXPECT_NEAR(world.jointState(joint).speed, -3, 1e-3);
}

// The pre-step callback runs once per step with the time at the start of the step; through it
// the set-point changes at t = 1 s and the joint follows.
TEST(Control, PreStepCallbackChangesTheTarget) {
    const Real h = 1.0 / 240.0;
    World world(quietWorld(h));
    const Turntable t = addTurntable(world, 0.5);
    world.setJointController(t.joint, ControllerDef{.target = 0, .kp = 50, .kd = 10});
    std::vector<Real> times;
    world.setPreStepCallback([&](World& w, Real time) {
        times.push_back(time);
        if (time >= 1.0 - 1e-9)
            w.setJointControllerTarget(t.joint, -0.5);
    });
    const int steps = static_cast<int>(std::lround(4 / h));
    for (int i = 0; i < steps; ++i)
        ASSERT_TRUE(world.step().ok());
    ASSERT_EQ(times.size(), static_cast<std::size_t>(steps));
    for (int i = 0; i < steps; ++i)
        EXPECT_NEAR(times[i], i * h, 1e-12);
    EXPECT_NEAR(turn(world, t), 0.5, 1e-3);
    EXPECT_EQ(world.jointController(t.joint)->target, -0.5);

    // Misuse from inside the callback is refused; the world is left untouched.
    world.setPreStepCallback([](World& w, Real) { w.step(); });
    EXPECT_TRUE(contains(refusal([&] { world.step(); }), "pre-step callback"));
    world.setPreStepCallback([](World& w, Real) { w.setPreStepCallback({}); });
    EXPECT_TRUE(contains(refusal([&] { world.step(); }), "setPreStepCallback"));
    world.setPreStepCallback({});
    EXPECT_TRUE(world.step().ok());
}

TEST(Control, BadControllersAreRefusedByName) {
    World world(quietWorld(1.0 / 60.0));
    const Turntable t = addTurntable(world, 0.5);
    EXPECT_TRUE(contains(refusal([&] { world.setJointController(t.joint, {.kp = -1}); }),
                         "ControllerDef.kp = -1"));
    EXPECT_TRUE(contains(refusal([&] { world.setJointController(t.joint, {.ki = -0.5}); }),
                         "ControllerDef.ki = -0.5"));
    EXPECT_TRUE(contains(refusal([&] { world.setJointController(t.joint, {.kd = -2}); }),
                         "ControllerDef.kd = -2"));
    EXPECT_TRUE(contains(refusal([&] { world.setJointController(t.joint, {.kp = std::nan("")}); }),
                         "ControllerDef.kp"));
    EXPECT_TRUE(contains(refusal([&] { world.setJointController(t.joint, {.maxForce = 0}); }),
                         "ControllerDef.maxForce"));
    EXPECT_TRUE(contains(refusal([&] {
                             world.setJointController(
                                 t.joint, {.target = std::numeric_limits<Real>::infinity()});
                         }),
                         "target"));
    EXPECT_TRUE(
        contains(refusal([&] { world.setJointControllerTarget(t.joint, 1); }), "no controller"));
    EXPECT_FALSE(world.jointController(t.joint).has_value());

    const JointId ball = world.createJoint(
        JointDef{.type = JointType::Ball, .bodyA = t.body, .bodyB = {}, .anchor = Vec3(0, 0, 1)});
    EXPECT_TRUE(contains(refusal([&] { world.setJointController(ball, {.kp = 1}); }),
                         "only hinge and slider"));

    // A destroyed joint's controller goes with it.
    world.setJointController(t.joint, {.kp = 1});
    world.destroyJoint(t.joint);
    EXPECT_TRUE(world.step().ok());
    EXPECT_FALSE(refusal([&] { world.jointController(t.joint); }).empty());
}

}  // namespace
}  // namespace tumble
