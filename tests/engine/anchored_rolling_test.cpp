// Friction anchors and bodies that roll. A rolling body's contact point moves
// over both surfaces while nothing slips, so the material points it leaves behind part (as a
// cycloid) without any slip: anchors kept on them pulled a ball rolling down a slope and changed
// its acceleration by 4.2e-5 relative (validate.rolling-resistance). Anchors must hold a
// sticking contact in place and leave a rolling one alone (anchor_table.cpp).

#include <gtest/gtest.h>

#include <cmath>

#include "testkit/scenes.h"
#include "tumble/world.h"

namespace tumble {
namespace {

using testkit::kGravity;

constexpr Real kRadius = 0.1;  // of the ball and the cylinder (m)
constexpr Real kH = 1.0 / 60;

// The world of a slope tilted by theta: a flat ground, gravity turned by theta about y, so that
// "down the slope" is +x.
World slopeWorld(Real theta) {
    WorldDef def = testkit::quietWorld(kH, kGravity * Vec3(std::sin(theta), 0, -std::cos(theta)));
    def.solver.frictionAnchors = true;
    World world(def);
    testkit::addGround(world, testkit::material(0.8));
    return world;
}

// A ball, or a cylinder lying on its side (axis along y), resting exactly on the ground.
BodyId addRoller(World& world, bool ball) {
    const BodyId body = world.createBody(
        BodyDef{.position = Vec3(0, 0, kRadius),
                .orientation = ball ? Quat::Identity()
                                    : Quat(Eigen::AngleAxis<Real>(M_PI / 2, Vec3::UnitX()))});
    const Material surface = testkit::material(0.8, 0, 1000);
    if (ball)
        world.createShape(body, ShapeDef{.geometry = Sphere{kRadius}, .material = surface});
    else
        world.createShape(body, ShapeDef{.geometry = Cylinder{kRadius, 0.2}, .material = surface});
    return body;
}

// Starting from rest the centre's speed after n steps is a n h exactly when a is constant.
Real slopeAcceleration(bool ball, Real theta, int steps) {
    World world = slopeWorld(theta);
    const BodyId body = addRoller(world, ball);
    for (int i = 0; i < steps; ++i)
        EXPECT_TRUE(world.step().ok());
    return world.linearVelocity(body).x() / (steps * kH);
}

// A ball rolls down at 5/7 g sin(theta), a solid cylinder at 2/3 g sin(theta), as without
// anchors: their contacts roll, and nothing pulls them. (Measured: 1 to 1e-9. At theta = 0.4 the
// cylinder reached only 0.63 of 2/3 g sin(theta), anchors on or off, until its half-space
// contact became the line's two ends: RollingHalfSpace.*.)
TEST(AnchoredRolling, BallAndCylinderRollDownASlopeAtTheAnalyticAcceleration) {
    for (const Real theta : {0.05, 0.2, 0.4}) {
        SCOPED_TRACE(theta);
        const Real g = kGravity * std::sin(theta);
        EXPECT_NEAR(slopeAcceleration(true, theta, 180) / (5.0 / 7.0 * g), 1, 1e-6);
        EXPECT_NEAR(slopeAcceleration(false, theta, 180) / (2.0 / 3.0 * g), 1, 1e-6);
    }
}

// Rolling at a steady speed on flat ground neither slows nor speeds up.
TEST(AnchoredRolling, BallAndCylinderRollOnFlatGroundAtTheirSpeed) {
    for (const bool ball : {true, false}) {
        for (const Real v : {1e-3, 0.05, 2.0}) {
            SCOPED_TRACE(testing::Message() << (ball ? "ball " : "cylinder ") << v);
            World world = slopeWorld(0);
            const BodyId body = addRoller(world, ball);
            world.setLinearVelocity(body, Vec3(v, 0, 0));
            world.setAngularVelocity(body, Vec3(0, v / kRadius, 0));
            for (int i = 0; i < 300; ++i)
                EXPECT_TRUE(world.step().ok());
            EXPECT_NEAR(world.linearVelocity(body).x() / v, 1, 1e-6);
            EXPECT_NEAR(world.position(body).x() / (300 * kH * v), 1, 1e-6);
        }
    }
}

}  // namespace
}  // namespace tumble
