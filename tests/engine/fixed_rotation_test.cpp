// Translation-only bodies (BodyDef::fixedRotation): point masses that torques, contacts and
// joints never turn -- the lumped nodes of strings and nets.

#include <gtest/gtest.h>

#include <cmath>

#include "refusal.h"
#include "testkit/same_ids.h"
#include "testkit/scenes.h"
#include "tumble/checkpoint.h"
#include "tumble/world.h"

namespace tumble {
namespace {

using test::contains;
using test::refusal;

constexpr Real kG = 9.81;

MassProperties boxMass(Real mass) {
    MassProperties m;
    m.mass = mass;
    m.inertia = Vec3(0.3, 0.4, 0.5).asDiagonal();
    return m;
}

// An off-centre force, a torque and an off-centre impulse: the linear motion is exactly that of
// a point mass (F / m, closed form under semi-implicit Euler) and the body never turns. The soft
// step too: its first substep takes the applied forces' whole impulse (soft_step.cpp).
void expectOffCentreLoadsTranslateWithoutTurning(const testkit::StepChoice& step) {
    const Real h = 1.0 / 60.0;
    WorldDef def{.gravity = Vec3::Zero(), .timeStep = h};
    testkit::applyStep(def.solver, step);
    World world(def);
    const Quat tilt(Eigen::AngleAxis<Real>(0.4, Vec3(1, 2, 3).normalized()));
    const BodyId body =
        world.createBody(BodyDef{.orientation = tilt, .mass = boxMass(2), .fixedRotation = true});
    world.applyLinearImpulse(body, Vec3(0, 4, 0), world.position(body) + Vec3(1, 0, 0));
    const Vec3 force(6, 0, 0);
    const int steps = 30;
    for (int i = 0; i < steps; ++i) {
        world.applyForce(body, force, world.position(body) + Vec3(0, 0.5, 0.5));
        world.applyTorque(body, Vec3(1, -2, 3));
        ASSERT_TRUE(world.step().ok());
    }
    EXPECT_EQ(world.angularVelocity(body), Vec3::Zero());
    EXPECT_EQ(world.orientation(body).coeffs(), tilt.coeffs());
    const Vec3 velocity = Vec3(0, 2, 0) + steps * h * force / 2;
    EXPECT_TRUE(world.linearVelocity(body).isApprox(velocity, 1e-12));
    // x_n = v_impulse n h + a h^2 n (n + 1) / 2 for v += h a; x += h v.
    const Vec3 position =
        Vec3(0, 2, 0) * steps * h + force / 2 * (h * h * steps * (steps + 1) / 2.0);
    EXPECT_TRUE(world.position(body).isApprox(position, 1e-12));
}

TEST(FixedRotation, OffCentreLoadsTranslateWithoutTurning) {
    expectOffCentreLoadsTranslateWithoutTurning({});
}

class SoftStepFixedRotation : public testing::TestWithParam<testkit::StepChoice> {};

INSTANTIATE_TEST_SUITE_P(Steps, SoftStepFixedRotation,
                         testing::Values(testkit::kStepChoices[1], testkit::kStepChoices[2]),
                         [](const auto& choice) { return testkit::stepName(choice.param); });

TEST_P(SoftStepFixedRotation, OffCentreLoadsTranslateWithoutTurning) {
    expectOffCentreLoadsTranslateWithoutTurning(GetParam());
}

struct Slide {
    Real distance = 0;  // travelled along x (m)
    Real speed = 0;     // at the end (m/s)
    Real maxSpin = 0;   // largest |omega| seen (rad/s)
};

// A sphere launched along the ground at v0 with no spin, for `seconds`.
Slide slide(bool fixedRotation, Real v0, Real friction, Real h, Real seconds) {
    World world(WorldDef{.timeStep = h, .enableSleep = false});
    const BodyId ground = world.createBody(BodyDef{.type = BodyType::Static});
    ShapeDef groundShape{.geometry = HalfSpace{}};
    groundShape.material.friction = friction;
    world.createShape(ground, groundShape);
    const Real radius = 0.1;
    const BodyId ball = world.createBody(BodyDef{.position = Vec3(0, 0, radius),
                                                 .linearVelocity = Vec3(v0, 0, 0),
                                                 .fixedRotation = fixedRotation});
    ShapeDef ballShape{.geometry = Sphere{radius}};
    ballShape.material.friction = friction;
    world.createShape(ball, ballShape);
    Slide s;
    for (int i = 0; i < static_cast<int>(seconds / h); ++i) {
        EXPECT_TRUE(world.step().ok());
        s.maxSpin = std::max(s.maxSpin, world.angularVelocity(ball).norm());
    }
    s.distance = world.position(ball).x();
    s.speed = world.linearVelocity(ball).norm();
    return s;
}

// Coulomb sliding: a translation-only sphere cannot roll, so kinetic friction mu m g stops it
// after v0^2 / (2 mu g) -- to within one step's travel, the discrete sum's offset. A rotating
// sphere instead rolls away at 5/7 v0 (friction's torque spins it up until it rolls), the
// textbook result that checks the two cases really differ.
TEST(FixedRotation, SlidingPointMassStopsAtTheCoulombDistance) {
    const Real v0 = 2, mu = 0.5, h = 1.0 / 240.0;
    const Slide point = slide(true, v0, mu, h, 1.0);
    EXPECT_EQ(point.maxSpin, 0);
    EXPECT_LT(point.speed, 1e-9);
    EXPECT_NEAR(point.distance, v0 * v0 / (2 * mu * kG), v0 * h);

    const Slide sphere = slide(false, v0, mu, h, 1.0);
    EXPECT_NEAR(sphere.speed, 5.0 / 7.0 * v0, 0.01 * v0);
    EXPECT_GT(sphere.maxSpin, 0.9 * sphere.speed / 0.1);
}

TEST(FixedRotation, RotationRequestsAreRefused) {
    World world;
    EXPECT_TRUE(contains(refusal([&] {
                             world.createBody(
                                 BodyDef{.type = BodyType::Kinematic, .fixedRotation = true});
                         }),
                         "BodyDef.fixedRotation"));
    EXPECT_TRUE(contains(refusal([&] {
                             world.createBody(
                                 BodyDef{.angularVelocity = Vec3(0, 0, 1), .fixedRotation = true});
                         }),
                         "BodyDef.fixedRotation with angularVelocity = (0, 0, 1)"));
    EXPECT_EQ(world.bodyCount(), 0);
    const BodyId body = world.createBody(BodyDef{.fixedRotation = true});
    EXPECT_TRUE(contains(refusal([&] { world.setAngularVelocity(body, Vec3(1, 0, 0)); }),
                         "translation-only"));
    EXPECT_EQ(refusal([&] { world.setAngularVelocity(body, Vec3::Zero()); }), "");
    EXPECT_EQ(world.angularVelocity(body), Vec3::Zero());
}

// The flag is part of the body's state: after a resume, new mass properties still give a body
// that a torque cannot turn.
TEST(FixedRotation, SurvivesACheckpoint) {
    World world(WorldDef{.gravity = Vec3::Zero()});
    const BodyId body = world.createBody(BodyDef{.mass = boxMass(1), .fixedRotation = true});
    World resumed;
    restoreCheckpoint(resumed, checkpointBytes(world));
    const BodyId same = test::sameBody(resumed, body);
    ASSERT_TRUE(resumed.isValid(same));
    resumed.setMassProperties(same, boxMass(3));
    resumed.applyTorque(same, Vec3(1, 2, 3));
    ASSERT_TRUE(resumed.step().ok());
    EXPECT_EQ(resumed.angularVelocity(same), Vec3::Zero());
}

}  // namespace
}  // namespace tumble
