// The contact solver on hand-built constraints: no shapes, no engine.

#include "tumble/solver/constraint_solver.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <vector>

#include "testkit/solver_scenes.h"
#include "tumble/core/error.h"

namespace tumble {
namespace {

constexpr Real kG = 9.81;
constexpr Real kH = 1.0 / 60;

// Body 0: static ground. Body 1: a unit cube of mass m (solid: I = m/6), centre at z = 0.5.
struct Scene {
    std::vector<SolverBody> bodies;
    std::vector<ContactConstraint> constraints;
    std::vector<PseudoVelocity> pseudo;
    ConstraintSolver solver;
    SolverSettings settings;

    explicit Scene(Real mass = 2, Real friction = 0.5, Real separation = 0) {
        bodies.resize(2);
        bodies[1].inverseMass = 1 / mass;
        bodies[1].inverseInertia = Mat3::Identity() * (6 / mass);
        constraints.push_back(testkit::cubeOnGround(1, friction, separation));
        // These tests check the converged answer of each kind of row; how close a fixed budget
        // gets is measured by the validation cases.
        settings.iterations = 200;
        settings.relaxIterations = 200;
    }
    SolverBody& box() { return bodies[1]; }
    // One step's velocity update: gravity, then the solve.
    SolverStats step() {
        box().linearVelocity.z() -= kG * kH;
        return solver.solve(bodies, constraints, pseudo, kH, settings);
    }
    Real totalNormalImpulse() const {
        Real sum = 0;
        for (int i = 0; i < 4; ++i)
            sum += constraints[0].points[i].normalImpulse;
        return sum;
    }
};

TEST(ContactSolver, RestingBoxCarriesItsWeightExactly) {
    Scene scene;
    for (int s = 0; s < 20; ++s)
        scene.step();
    const SolverStats stats = scene.step();
    // The split between four legs is not unique; their sum is: m g h per step. The four legs'
    // block is singular and solved with a 1e-10 relative regularisation (normal_block.h), which
    // leaves ~1e-11 m/s: the velocity bounds below are that, not rounding.
    EXPECT_NEAR(scene.totalNormalImpulse(), 2 * kG * kH, 1e-12);
    EXPECT_NEAR(scene.box().linearVelocity.norm(), 0, 1e-10);
    EXPECT_NEAR(scene.box().angularVelocity.norm(), 0, 1e-12);
    EXPECT_LT(stats.maxResidual, 1e-10);
    // Symmetric legs: the minimum-norm split is the even one, to the regularisation's
    // amplification of rounding (1e-16 / 1e-10).
    for (int i = 0; i < 4; ++i) {
        EXPECT_NEAR(scene.constraints[0].points[i].normalImpulse, 2 * kG * kH / 4,
                    1e-6 * 2 * kG * kH / 4);
    }
}

// A box sliding at 2 m/s in direction theta: one step of friction removes mu g h of speed,
// whatever the direction, with coupled friction; the box model removes up to sqrt(2) times that.
Real speedLostInOneStep(FrictionModel model, Real theta) {
    Scene scene(2, 0.5);
    scene.settings.friction = model;
    scene.settings.warmStart = false;
    const Vec3 v0(2 * std::cos(theta), 2 * std::sin(theta), 0);
    scene.box().linearVelocity = v0;
    scene.step();
    const Vec3 v = scene.box().linearVelocity;
    // 1e-8 rad: the four legs' load split carries rounding amplified by the normal block's
    // regularisation (~1e-6 relative, normal_block.h), so the legs' friction discs differ by as
    // much and turn the result by ~1e-9 rad. The box model is off by ~0.1 rad here.
    EXPECT_NEAR(v.cross(v0).norm() / (v.norm() * v0.norm()), 0,
                theta == 0 || model == FrictionModel::Coupled ? 1e-8 : 1)
        << "coupled friction acts against the sliding direction";
    return v0.norm() - v.head<2>().norm();
}

TEST(ContactSolver, CoupledFrictionIsIsotropic) {
    const Real expected = 0.5 * kG * kH;
    for (int k = 0; k < 8; ++k) {
        const Real theta = k * std::numbers::pi / 8 + 0.1;
        EXPECT_NEAR(speedLostInOneStep(FrictionModel::Coupled, theta), expected, 1e-9 * expected)
            << theta;
    }
}

TEST(ContactSolver, BoxFrictionOverestimatesOffAxisBySqrtTwo) {
    const Real expected = 0.5 * kG * kH;
    EXPECT_NEAR(speedLostInOneStep(FrictionModel::Box, 0), expected, 1e-9);
    EXPECT_NEAR(speedLostInOneStep(FrictionModel::Box, std::numbers::pi / 4) / expected,
                std::sqrt(2.0), 1e-6);
}

TEST(ContactSolver, SlowSlidingBoxSticks) {
    Scene scene;
    scene.box().linearVelocity = Vec3(0.01, -0.02, 0);  // less than mu g h = 0.08 m/s
    scene.step();
    EXPECT_NEAR(scene.box().linearVelocity.norm(), 0, 1e-9);
}

TEST(ContactSolver, RestitutionUsesTheApproachSpeedBeforeTheSolve) {
    Scene scene(2, 0, 0);
    scene.constraints[0].restitution = 0.5;
    scene.box().linearVelocity = Vec3(0, 0, -3 + kG * kH);  // -3 m/s after gravity
    scene.step();
    EXPECT_NEAR(scene.box().linearVelocity.z(), 1.5, 1e-9);
    EXPECT_NEAR(scene.box().angularVelocity.norm(), 0, 1e-9);

    Scene slow(2, 0, 0);
    slow.constraints[0].restitution = 0.5;
    slow.box().linearVelocity = Vec3(0, 0, -0.5 + kG * kH);  // below the 1 m/s threshold
    slow.step();
    EXPECT_NEAR(slow.box().linearVelocity.z(), 0, 1e-9);
}

TEST(ContactSolver, SplitImpulseNeverFeedsTheRealVelocity) {
    const Real depth = 0.02;
    Scene scene(2, 0.5, -depth);
    scene.step();
    EXPECT_NEAR(scene.box().linearVelocity.norm(), 0, 1e-10) << "no energy from stabilisation";
    const Real expected = scene.settings.splitImpulseFactor / kH * (depth - scene.settings.slop);
    EXPECT_NEAR(scene.pseudo[1].linear.z(), expected, 1e-9);

    Scene baumgarte(2, 0.5, -depth);
    baumgarte.settings.stabilisation = Stabilisation::Baumgarte;
    baumgarte.step();
    EXPECT_NEAR(baumgarte.box().linearVelocity.z(), 0.2 / kH * (depth - 0.005), 1e-9)
        << "the study's bias";
    EXPECT_NEAR(baumgarte.pseudo[1].linear.norm(), 0, 0);
}

TEST(ContactSolver, SpeculativeContactClosesTheGapButNoMore) {
    const Real gap = 0.05;
    Scene scene(2, 0, gap);
    scene.box().linearVelocity = Vec3(0, 0, -10);
    scene.step();
    EXPECT_NEAR(scene.box().linearVelocity.z(), -gap / kH, 1e-9);

    Scene slow(2, 0, gap);
    slow.box().linearVelocity = Vec3(0, 0, -1);  // will not reach the ground this step
    slow.step();
    EXPECT_NEAR(slow.box().linearVelocity.z(), -1 - kG * kH, 1e-12);
    EXPECT_EQ(slow.totalNormalImpulse(), 0);
}

TEST(ContactSolver, ToleranceStopsEarlyAndWarmStartHelps) {
    Scene scene;
    scene.settings.iterations = 100;
    scene.settings.tolerance = 1e-9;
    const SolverStats cold = scene.step();
    SolverStats warm;
    for (int s = 0; s < 5; ++s)
        warm = scene.step();
    EXPECT_LT(cold.iterations, 100);
    EXPECT_LE(warm.iterations, 2) << "the cached impulses are already the answer";
    EXPECT_LT(warm.maxResidual, 1e-8);
}

// The default sweep skips body 0's updates as the static world's (SweepRows::sweepPlain); a
// solver whose body 0 moves must still get them. A box of 3 kg as body 0 rising into a falling
// box of 2 kg: the inelastic contact conserves momentum and leaves its points closing at 0, with
// one, two or four points (tolerances: rounding of a 200-sweep solve, 1e-12 of the 2 kg m/s).
TEST(ContactSolver, AMovingBodyZeroTakesItsImpulses) {
    for (int points : {1, 2, 4}) {
        Scene scene(2, 0.5);
        scene.bodies[0].inverseMass = 1.0 / 3;
        scene.bodies[0].inverseInertia = Mat3::Identity() * (6.0 / 3);
        scene.bodies[0].linearVelocity = Vec3(0, 0, 0.5);
        scene.box().linearVelocity = Vec3(0, 0, -1);
        scene.constraints[0].pointCount = points;
        scene.solver.solve(scene.bodies, scene.constraints, scene.pseudo, kH, scene.settings);
        const Vec3 momentum = 3 * scene.bodies[0].linearVelocity + 2 * scene.box().linearVelocity;
        EXPECT_NEAR(momentum.z(), 3 * 0.5 - 2 * 1, 1e-12) << points << " points";
        for (int i = 0; i < points; ++i) {
            const ContactConstraintPoint& p = scene.constraints[0].points[i];
            const Real closing =
                scene.box().velocityAt(p.rB).z() - scene.bodies[0].velocityAt(p.rA).z();
            EXPECT_NEAR(closing, 0, 1e-9) << points << " points, point " << i;
        }
    }
}

TEST(ContactSolver, BadSettingsAreRefused) {
    SolverSettings s;
    s.iterations = -1;
    EXPECT_THROW(checkSolverSettings(s), InvalidArgument);
    s = {};
    s.relaxation = 2;
    EXPECT_THROW(checkSolverSettings(s), InvalidArgument);
    s = {};
    s.slop = -0.1;
    EXPECT_THROW(checkSolverSettings(s), InvalidArgument);
    s = {};
    s.baumgarte = 1.5;
    EXPECT_THROW(checkSolverSettings(s), InvalidArgument);
    EXPECT_NO_THROW(checkSolverSettings({}));
}

}  // namespace
}  // namespace tumble
