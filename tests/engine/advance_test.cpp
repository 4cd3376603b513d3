// The real-time driver: whole steps from frame times, a cap, and the interpolation fraction.

#include <gtest/gtest.h>

#include "tumble/world.h"

namespace tumble {
namespace {

TEST(Advance, RunsWholeStepsAndCarriesTheRemainder) {
    World world(WorldDef{.timeStep = 0.01});
    AdvanceResult r = world.advance(0.025);
    EXPECT_EQ(r.steps, 2);
    EXPECT_NEAR(r.fraction, 0.5, 1e-9);
    r = world.advance(0.005);
    EXPECT_EQ(r.steps, 1);
    EXPECT_NEAR(r.fraction, 0.0, 1e-9);
    EXPECT_EQ(world.stepCount(), 3u);
}

TEST(Advance, FramesOfExactlyOneStepNeverSkip) {
    World world(WorldDef{.timeStep = 1.0 / 60});
    int steps = 0;
    for (int i = 0; i < 6000; ++i)
        steps += world.advance(1.0 / 60).steps;
    EXPECT_EQ(steps, 6000);
}

TEST(Advance, CapsStepsPerCallAndDropsTheExcess) {
    World world(WorldDef{.timeStep = 0.01, .maxStepsPerAdvance = 4});
    const AdvanceResult r = world.advance(1.0);  // a one-second hitch
    EXPECT_EQ(r.steps, 4);
    EXPECT_NEAR(r.droppedTime, 0.96, 1e-9);
    EXPECT_LT(r.fraction, 1.0);
    const AdvanceResult next = world.advance(0.01);
    EXPECT_EQ(next.steps, 1) << "no backlog carried into the next frame";
}

TEST(Advance, InterpolatedPoseLiesBetweenTheLastTwoSteps) {
    World world(WorldDef{.gravity = Vec3::Zero(), .timeStep = 0.01});
    BodyDef def;
    def.linearVelocity = Vec3(1, 0, 0);
    def.angularVelocity = Vec3(0, 0, 10);
    const BodyId body = world.createBody(def);
    const AdvanceResult r = world.advance(0.035);
    ASSERT_EQ(r.steps, 3);
    const Transform t = world.interpolatedTransform(body, r.fraction);
    EXPECT_NEAR(t.position.x(), 0.025, 1e-9);
    const Quat expected(Eigen::AngleAxis<Real>(0.25, Vec3::UnitZ()));
    EXPECT_NEAR(t.rotation.angularDistance(expected), 0, 1e-9);
    EXPECT_TRUE(world.interpolatedTransform(body, 1).position.isApprox(world.position(body)));
}

}  // namespace
}  // namespace tumble
