// A cylinder lying on a half-space touches it along a line: its contact is the two ends of that
// line, whatever its speed. Its rim's other points, offered within a speculative margin grown
// by a fast roll, once took the place of the line's far end in the manifold and held the
// spinning rim off the plane: rolling down a slope at theta = 0.4 it sank 13 mm and reached
// 0.63 of (2/3) g sin(theta) after 3 s (issue 20, item 1).

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <random>

#include "testkit/scenes.h"
#include "tumble/collision/narrowphase.h"
#include "tumble/world.h"

namespace tumble {
namespace {

using testkit::kGravity;

constexpr Real kRadius = 0.1;
constexpr Real kHalfLength = 0.2;
constexpr Real kH = 1.0 / 60;

// Flat ground; gravity turned by theta about y, so "down the slope" is +x. A cylinder lying
// across the slope (axis along y) exactly on the ground, of friction 0.8: it rolls without
// slip while tan(theta) / 3 < 0.8.
WorldDef slopeWorld(Real theta, const testkit::StepChoice& step) {
    WorldDef def = testkit::quietWorld(kH, kGravity * Vec3(std::sin(theta), 0, -std::cos(theta)));
    testkit::applyStep(def.solver, step);
    return def;
}

struct Slope {
    World world;
    BodyId cylinder;
    explicit Slope(Real theta, const testkit::StepChoice& step = {})
        : world(slopeWorld(theta, step)) {
        testkit::addGround(world, testkit::material(0.8));
        cylinder = world.createBody(BodyDef{
            .position = Vec3(0, 0, kRadius),
            .orientation = Quat(Eigen::AngleAxis<Real>(std::numbers::pi / 2, Vec3::UnitX()))});
        world.createShape(cylinder, ShapeDef{.geometry = Cylinder{kRadius, kHalfLength},
                                             .material = testkit::material(0.8, 0, 1000)});
    }
};

// The soft step's choices (the default's are the plain tests).
class RollingHalfSpaceSteps : public testing::TestWithParam<testkit::StepChoice> {};

INSTANTIATE_TEST_SUITE_P(Steps, RollingHalfSpaceSteps,
                         testing::Values(testkit::kStepChoices[1], testkit::kStepChoices[2]),
                         [](const auto& choice) { return testkit::stepName(choice.param); });

// Up to theta = 0.8 (3 s: 10 m/s, 1.6 rad a step at the end) the centre's speed after n steps
// from rest is (2/3) g sin(theta) n h, within 1 %, and it stays on the ground.
void expectRollsDownSlopes(const testkit::StepChoice& step) {
    for (const Real theta : {0.1, 0.3, 0.4, 0.6, 0.8}) {
        SCOPED_TRACE(theta);
        Slope slope(theta, step);
        const int steps = 180;
        Real lowest = kRadius;
        for (int i = 0; i < steps; ++i) {
            ASSERT_TRUE(slope.world.step().ok());
            lowest = std::min(lowest, slope.world.position(slope.cylinder).z());
        }
        const Real expected = 2.0 / 3.0 * kGravity * std::sin(theta);
        const Real measured = slope.world.linearVelocity(slope.cylinder).x() / (steps * kH);
        EXPECT_NEAR(measured / expected, 1, 0.01);
        EXPECT_GT(lowest, kRadius - 1e-3) << "sank into the ground";
    }
}

TEST(RollingHalfSpace, CylinderRollsDownSlopesAtTwoThirdsGSinTheta) {
    expectRollsDownSlopes({});
}

// The soft step too: its friction anchors once bent the line contact's ends by the spin of the
// step's start, and at 10 m/s the cylinder rolled backwards after 4 s (soft_step.cpp).
TEST_P(RollingHalfSpaceSteps, CylinderRollsDownSlopesAtTwoThirdsGSinTheta) {
    expectRollsDownSlopes(GetParam());
}

// Rolling on flat ground at up to 10 m/s (1.7 rad a step) keeps its speed within 0.1 %.
void expectRollsAtItsSpeed(const testkit::StepChoice& step) {
    for (const Real v : {0.5, 5.0, 10.0}) {
        SCOPED_TRACE(v);
        Slope flat(0, step);
        flat.world.setLinearVelocity(flat.cylinder, Vec3(v, 0, 0));
        flat.world.setAngularVelocity(flat.cylinder, Vec3(0, v / kRadius, 0));
        for (int i = 0; i < 300; ++i)
            ASSERT_TRUE(flat.world.step().ok());
        EXPECT_NEAR(flat.world.linearVelocity(flat.cylinder).x() / v, 1, 1e-3);
        EXPECT_NEAR(flat.world.position(flat.cylinder).z(), kRadius, 1e-4);
    }
}

TEST(RollingHalfSpace, CylinderRollsOnFlatGroundAtItsSpeed) {
    expectRollsAtItsSpeed({});
}

TEST_P(RollingHalfSpaceSteps, CylinderRollsOnFlatGroundAtItsSpeed) {
    expectRollsAtItsSpeed(GetParam());
}

// The separation of a cylinder from the plane z = 0 (m): its lowest point's height.
Real exactSeparation(const Cylinder& c, const Transform& pose) {
    const Vec3 axis = pose.rotation * Vec3::UnitZ();
    const Real along = std::abs(axis.z());
    return pose.position.z() - c.halfLength * along -
           c.radius * std::sqrt(std::max<Real>(0, 1 - along * along));
}

// 2,000 random poses touching or up to 1 mm into a half-space: the normal is the plane's, the
// deepest point at the true depth within 1e-6 m, no point deeper; lying within 45 degrees of
// the plane, the contact is the line's two ends (or its one end that is within the margin), also
// within a margin of twice the radius.
TEST(RollingHalfSpace, CylinderOnAHalfSpaceAtRandomPoses) {
    std::mt19937 random(20);
    std::uniform_real_distribution<Real> unit(-1, 1);
    std::uniform_real_distribution<Real> depth(0, 1e-3);
    std::uniform_real_distribution<Real> size(0.05, 1);
    const HalfSpace ground;
    const Transform groundPose;
    int lying = 0;
    for (int trial = 0; trial < 2000; ++trial) {
        const Cylinder c{size(random), size(random)};
        Transform pose;
        pose.rotation = Quat(unit(random), unit(random), unit(random), unit(random)).normalized();
        if (trial % 2 == 0)  // half of them within 1 degree of lying flat on their side
            pose.rotation =
                Quat(Eigen::AngleAxis<Real>(std::numbers::pi / 2 + unit(random) * 0.017,
                                            Vec3(unit(random), unit(random), 0).normalized())) *
                Quat(Eigen::AngleAxis<Real>(unit(random) * 3.2, Vec3::UnitZ()));
        pose.position = Vec3(unit(random), unit(random), 0);
        pose.position.z() -= exactSeparation(c, pose) + (trial % 3 == 0 ? 0 : depth(random));
        const Real exact = exactSeparation(c, pose);
        Manifold m;
        collide(c, pose, ground, groundPose, 0.02, m);
        ASSERT_GE(m.pointCount, 1) << trial;
        EXPECT_LT(std::acos(std::min<Real>(1, -m.normal.z())), std::numbers::pi / 180) << trial;
        Real deepest = 1;
        for (int i = 0; i < m.pointCount; ++i)
            deepest = std::min(deepest, m.points[static_cast<std::size_t>(i)].separation);
        EXPECT_NEAR(deepest, exact, 1e-6) << trial;
        const Real axisUp = std::abs((pose.rotation * Vec3::UnitZ()).z());
        if (axisUp < std::numbers::sqrt2 / 2) {
            ++lying;
            EXPECT_LE(m.pointCount, 2) << trial;
            // Also within the margin of a fast roll (h |v| beyond the radius).
            Manifold fast;
            collide(c, pose, ground, groundPose, 2 * c.radius, fast);
            EXPECT_LE(fast.pointCount, 2) << trial;
        }
    }
    EXPECT_GT(lying, 1000);
}

}  // namespace
}  // namespace tumble
