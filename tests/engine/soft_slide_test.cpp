// The soft step's friction as a face starts to slide (slide_patch.cpp): a cube kicked along the
// ground takes mu m g h of friction, against the kick, in the very step it starts to slide.

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <random>

#include "testkit/scenes.h"
#include "tumble/world.h"

namespace tumble {
namespace {

constexpr Real kGravity = 9.81;

// The summed friction impulse of the step just taken (N s, world frame).
Vec3 frictionImpulse(const World& world) {
    Vec3 sum = Vec3::Zero();
    for (const Contact& contact : world.contacts()) {
        for (int i = 0; i < contact.manifold.pointCount; ++i)
            sum += contact.tangentImpulse[i];
    }
    return sum;
}

// A unit cube at rest on the ground (1 s, never asleep) under a random yaw, kicked at a speed
// along a random direction: its four points start to slide together, and the step's friction is
// the Coulomb limit, mu m g h against the slip, in that step and the next; in the first, its
// substeps move it as the closed form of their own (before the biased sweep kept the patch, the
// pushed cube's first substep lost a fifth of its friction and moved 3e-5 m too far). Swept: the
// soft step's two settings, mass (density), mu, speed, both yaws. Tolerances, written before the
// sweep was run: 1e-6 of mu m g h, and 1e-6 of the step's travel (the pushed box's closed form
// in sleep_test.cpp). Before the
// patch the step it started to slide in fell 4.5e-3 short (3 x 45, the pushed 1000 kg cube:
// the points' coupled rows scattered the friction across the slip).
TEST(SoftSlide, KickedCubeTakesTheCoulombLimitFromTheFirstStep) {
    std::mt19937 random(21);
    std::uniform_real_distribution<Real> turn(0, 2 * std::numbers::pi);
    const testkit::StepChoice steps[] = {{3, 45}, {4, 30}};
    int cases = 0;
    for (const testkit::StepChoice& step : steps) {
        for (const Real density : {0.3, 1.0, 1000.0}) {
            for (const Real mu : {0.2, 0.5, 0.9}) {
                for (const Real speed : {0.5, 2.0, 6.0}) {
                    WorldDef def;
                    def.solver.softSubsteps = step.softSubsteps;
                    def.solver.contactHertz = step.contactHertz;
                    World world(def);
                    testkit::addGround(world, testkit::material(mu));
                    const Real yaw = turn(random);
                    BodyDef body{.position = Vec3(0, 0, 0.5),
                                 .orientation = Quat(Eigen::AngleAxis<Real>(yaw, Vec3::UnitZ()))};
                    body.allowSleep = false;
                    const BodyId cube = testkit::addBox(world, body, Vec3::Constant(0.5),
                                                        testkit::material(mu, 0, density));
                    for (int i = 0; i < 60; ++i)
                        ASSERT_TRUE(world.step().ok());
                    const Real heading = turn(random);
                    const Vec3 along(std::cos(heading), std::sin(heading), 0);
                    world.setLinearVelocity(cube, speed * along);
                    const Real h = world.settings().timeStep;
                    const Real limit = mu * world.massProperties(cube).mass * kGravity * h;
                    const Vec3 start = world.position(cube);
                    for (int k = 0; k < 2; ++k) {
                        ASSERT_TRUE(world.step().ok());
                        const Vec3 friction = frictionImpulse(world);
                        SCOPED_TRACE(testing::Message()
                                     << testkit::stepName(step) << " density " << density << " mu "
                                     << mu << " speed " << speed << " yaw " << yaw << " heading "
                                     << heading << " step " << k);
                        EXPECT_NEAR(friction.dot(along), -limit, 1e-6 * limit);
                        EXPECT_NEAR(friction.cross(along).norm(), 0, 1e-6 * limit);
                        if (k == 0) {
                            // Each substep of hs slows it by mu g hs before it moves:
                            // x = n hs v0 - mu g hs^2 n (n + 1) / 2.
                            const int n = step.softSubsteps;
                            const Real hs = h / n;
                            const Real x =
                                n * hs * speed - mu * kGravity * hs * hs * n * (n + 1) / 2;
                            const Vec3 moved = world.position(cube) - start;
                            EXPECT_NEAR(moved.dot(along), x, 1e-6 * x);
                            EXPECT_NEAR(moved.cross(along).head<2>().norm(), 0, 1e-6 * x);
                        }
                    }
                    ++cases;
                }
            }
        }
    }
    EXPECT_EQ(cases, 54);
}

}  // namespace
}  // namespace tumble
