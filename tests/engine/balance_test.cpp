// Rest and balance: where bodies held by springs, damping and controllers come to rest, and that
// sleep freezes them only there (docs/ARCHITECTURE.md, "Islands and sleeping").

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>

#include "tumble/world.h"

namespace tumble {
namespace {

constexpr Real kGravity = 9.81;

// A shapeless body of mass m hanging at (0, 0, -1) from the world's origin on a spring of rest
// length 1 m, stiffness k and damper c.
struct Hanging {
    BodyId body;
    SpringId spring;
};
Hanging hang(World& world, Real mass, Real k, Real c, Real linearDamping = 0) {
    BodyDef def{.position = Vec3(0, 0, -1)};
    def.mass.mass = mass;
    def.mass.inertia = mass * Mat3::Identity();
    def.linearDamping = linearDamping;
    const BodyId body = world.createBody(def);
    SpringDef spring;  // from the body's origin to the world's
    spring.bodyA = body;
    spring.restLength = 1;
    spring.stiffness = k;
    spring.damping = c;
    return {body, world.createSpring(spring)};
}

// The stretch over the static one, m g / k.
Real stretchRatio(const World& world, BodyId body, Real mass, Real k) {
    return (-world.position(body).z() - 1) / (mass * kGravity / k);
}

// The balance rule's bound: frozen, a spring-held body is within 1e-4 (1 + h c / m) / 2 of its
// static stretch, so within 1e-4 while h c / m <= 1. Swept over mass, stiffness, damping ratio
// and step; each must fall asleep within 25 time constants of its slowest decay.
TEST(Balance, ASpringHeldBodySleepsWithinATenThousandthOfItsStaticStretch) {
    for (const Real h : {1.0 / 30.0, 1.0 / 60.0, 1.0 / 240.0}) {
        for (const Real mass : {0.5, 2.0, 50.0}) {
            for (const Real k : {36.0, 400.0, 5000.0}) {
                for (const Real zeta : {0.2, 1.0}) {
                    const Real omega = std::sqrt(k / mass);
                    const Real c = 2 * zeta * omega * mass;
                    const Real rate = zeta < 1 ? zeta * omega : omega;  // slowest decay (1/s)
                    World world(WorldDef{.timeStep = h});
                    const Hanging held = hang(world, mass, k, c);
                    const int maxSteps = static_cast<int>((5 + 25 / rate) / h);
                    int steps = 0;
                    while (world.isAwake(held.body) && steps < maxSteps) {
                        ASSERT_TRUE(world.step().ok());
                        ++steps;
                    }
                    const std::string name = "h = 1/" + std::to_string(std::lround(1 / h)) +
                                             ", m = " + std::to_string(mass) +
                                             ", k = " + std::to_string(k) +
                                             ", zeta = " + std::to_string(zeta);
                    ASSERT_FALSE(world.isAwake(held.body)) << name << ": never fell asleep";
                    const Real bound = 1e-4 * std::max<Real>(1, (1 + h * c / mass) / 2);
                    EXPECT_NEAR(stretchRatio(world, held.body, mass, k), 1, bound)
                        << name << ", asleep at t = " << world.time();
                }
            }
        }
    }
}

// Linear damping c on a body hanging from an undamped spring. The implicit damping divided the
// step's velocity, gravity's included, by 1 + h c before the spring acted, so the spring carried
// only m g / (1 + h c): the body rested 3.2 % short at c = 2 /s, h = 1/60.
TEST(Balance, ADampedBodyOnASpringRestsAtItsStaticStretch) {
    for (const Real h : {1.0 / 60.0, 1.0 / 240.0}) {
        for (const Real c : {2.0, 20.0}) {
            World world(WorldDef{.timeStep = h, .enableSleep = false});
            const Real mass = 1;
            const Real k = 100;
            const Hanging held = hang(world, mass, k, 0, c);
            for (int i = 0; i < static_cast<int>(40 / h); ++i)  // >= 40 decay times
                ASSERT_TRUE(world.step().ok());
            EXPECT_NEAR(stretchRatio(world, held.body, mass, k), 1, 1e-6)
                << "h = " << h << ", c = " << c;
            EXPECT_NEAR(world.springState(held.spring).tension / (mass * kGravity), 1, 1e-6);
        }
    }
}

// A falling body with linear damping c reaches the terminal speed g / c of dv/dt = g - c v.
TEST(Balance, AFallingDampedBodyReachesTerminalVelocity) {
    for (const Real c : {0.5, 2.0, 50.0}) {
        const Real h = 1.0 / 60.0;
        World world(WorldDef{.timeStep = h});
        BodyDef def;
        def.linearDamping = c;
        def.mass.mass = 3;
        def.mass.inertia = Mat3::Identity();
        const BodyId body = world.createBody(def);
        for (int i = 0; i < static_cast<int>(std::max<Real>(30 / c, 1) / h); ++i)
            ASSERT_TRUE(world.step().ok());
        EXPECT_NEAR(world.linearVelocity(body).z() / (-kGravity / c), 1, 1e-6) << "c = " << c;
    }
}

// A body of inertia 1 kg m^2 about z on a hinge about z, joined to the world (gravity along the
// axis: the hinge carries the weight, the angle feels none).
struct Turntable {
    BodyId body;
    JointId joint;
};
Turntable addTurntable(World& world) {
    BodyDef def;
    def.mass.mass = 1;
    def.mass.inertia = Mat3::Identity();
    const BodyId body = world.createBody(def);
    const JointId joint = world.createJoint(
        JointDef{.type = JointType::Hinge, .bodyA = body, .bodyB = {}, .axis = Vec3::UnitZ()});
    return {body, joint};
}

// An overdamped PD (zeta = 5) turns the turntable toward 0.5 rad at under 0.05 rad/s, slower than
// the sleep thresholds, and nothing else acts on it: it fell asleep at 0.5 s, far from its
// target. A controller short of its target keeps its bodies awake; once there they may sleep.
TEST(Balance, AControlledJointSleepsOnlyAtItsTarget) {
    World world;
    const Turntable t = addTurntable(world);
    const Real target = -0.5;  // joint angle; the body turns +0.5 rad (world is B)
    world.setJointController(t.joint, ControllerDef{.target = target, .kp = 1, .kd = 10});
    const Real h = world.settings().timeStep;
    int steps = 0;
    while (world.isAwake(t.body) && steps < static_cast<int>(120 / h)) {
        ASSERT_TRUE(world.step().ok());
        ++steps;
    }
    ASSERT_FALSE(world.isAwake(t.body)) << "at its target it may sleep";
    EXPECT_NEAR(world.jointState(t.joint).position, target, 2e-4)
        << "asleep at t = " << world.time();
    EXPECT_GT(world.time(), 60) << "the loop's slow mode, kp / kd = 0.1 /s, needs ~85 s";
}

// A joint motor turning at 0.01 rad/s moves its body far slower than the sleep thresholds; it
// must keep turning.
TEST(Balance, AJointMotorKeepsItsBodiesAwake) {
    World world;
    const Turntable t = addTurntable(world);
    world.setJointMotor(t.joint, true, 0.01, 10);
    for (int i = 0; i < 600; ++i)
        ASSERT_TRUE(world.step().ok());
    EXPECT_TRUE(world.isAwake(t.body));
    EXPECT_NEAR(world.jointState(t.joint).position, 0.1, 1e-3) << "10 s at 0.01 rad/s";
}

}  // namespace
}  // namespace tumble
