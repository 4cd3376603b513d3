// The semi-implicit Euler stepper through the public API.

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "testkit/scenes.h"
#include "tumble/world.h"

namespace tumble {
namespace {

// Velocities first, then positions from the new velocities, at the integrator's step k: h on the
// default step, h / n on the soft step's n substeps.
TEST(Integrator, FreeFallFollowsSemiImplicitEulerClosedForm) {
    for (const testkit::StepChoice& step : testkit::kIntegratorStepChoices) {
        SCOPED_TRACE(testkit::stepName(step));
        WorldDef worldDef;
        testkit::applyStep(worldDef.solver, step);
        World world(worldDef);
        BodyDef def;
        def.linearVelocity = Vec3(1, 0, 3);
        const BodyId body = world.createBody(def);
        const Vec3 g = world.settings().gravity;
        const int steps = 90;
        for (int i = 0; i < steps; ++i)
            world.step();
        const int perStep = testkit::integratorStepsPerStep(step);
        const Real k = world.settings().timeStep / perStep;
        const int n = steps * perStep;
        const Vec3 expected = n * k * def.linearVelocity + k * k * g * (n * (n + 1.0) / 2);
        EXPECT_NEAR((world.position(body) - expected).norm(), 0, 1e-13);
        EXPECT_NEAR((world.linearVelocity(body) - (def.linearVelocity + n * k * g)).norm(), 0,
                    1e-13);
    }
}

TEST(Integrator, ConstantSpinRotatesByExactlyOmegaT) {
    // With isotropic inertia there is no gyroscopic torque, so the spin is constant and the
    // exponential map must rotate by exactly |w| t.
    World world(WorldDef{.gravity = Vec3::Zero(), .timeStep = 0.1});
    BodyDef def;
    const Vec3 axis = Vec3(1, -2, 0.5).normalized();
    def.angularVelocity = 2.0 * axis;
    const BodyId body = world.createBody(def);
    for (int i = 0; i < 10; ++i)
        world.step();
    const Quat expected(Eigen::AngleAxis<Real>(2.0, axis));
    EXPECT_NEAR(world.orientation(body).angularDistance(expected), 0, 1e-12);
    EXPECT_NEAR(world.orientation(body).norm(), 1, 1e-15);
}

TEST(Integrator, AsymmetricSpinConservesMomentumMagnitudeAndEnergy) {
    World world(WorldDef{.gravity = Vec3::Zero(), .timeStep = 1.0 / 60});
    BodyDef def;
    def.mass.inertia = Vec3(0.5, 1.0, 1.3).asDiagonal();
    def.angularVelocity = Vec3(0.2, 6.0, 0.1);  // about the intermediate axis: unstable
    const BodyId body = world.createBody(def);
    const Real momentum0 = world.angularMomentum(body).norm();
    const Real energy0 = world.kineticEnergy(body);
    for (int i = 0; i < 6000; ++i) {
        ASSERT_TRUE(world.step().ok());
    }
    // Implicit midpoint keeps both quadratic invariants to rounding, whatever the flips.
    EXPECT_NEAR(world.angularMomentum(body).norm() / momentum0, 1, 1e-10);
    EXPECT_NEAR(world.kineticEnergy(body) / energy0, 1, 1e-10);
}

TEST(Integrator, TorqueChangesAngularMomentumByTorqueTimesTime) {
    World world(WorldDef{.gravity = Vec3::Zero()});
    BodyDef def;
    def.mass.inertia = Vec3(1, 2, 3).asDiagonal();
    def.orientation = Quat(Eigen::AngleAxis<Real>(0.7, Vec3(0, 1, 1).normalized()));
    const BodyId body = world.createBody(def);
    const Vec3 torque(0.3, -0.2, 0.5);
    const int n = 120;
    for (int i = 0; i < n; ++i) {
        world.applyTorque(body, torque);
        world.step();
    }
    // dL/dt = torque exactly; the gyroscopic term only redistributes L in body axes. The
    // integrator applies the torque as an impulse and then rotates L by the midpoint rule, so the
    // world-frame sum holds to O(h^2) per step, well inside 1e-3 relative here.
    const Vec3 expected = torque * n * world.settings().timeStep;
    EXPECT_LT((world.angularMomentum(body) - expected).norm() / expected.norm(), 1e-3);
}

}  // namespace
}  // namespace tumble
