// Substeps: one step of h is N substeps of h / N -- free fall lands where N times as many
// semi-implicit Euler steps put it, a pendulum drifts less in energy, events are reported once
// per step, a failing substep rolls the whole step back, and bad counts are refused.

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <string>

#include "refusal.h"
#include "tumble/world.h"

namespace tumble {
namespace {

using test::contains;
using test::refusal;

constexpr Real kGravity = 9.81;

// Semi-implicit Euler with step k from rest at z0: v_j = v_{j-1} - g k, z_j = z_{j-1} + k v_j,
// so v_n = -n g k and z_n = z0 - g k^2 (1 + 2 + ... + n) = z0 - g k^2 n (n + 1) / 2. S steps of
// h with N substeps are n = N S steps of k = h / N: z = z0 - g h^2 S (N S + 1) / (2 N), which
// for N = 4 differs from N = 1 by 3 g h^2 S / 8 (31 mm for h = 1/60 and S = 30). Either step's
// count: the default step's four substeps (WorldDef::substeps) or the soft step's
// (SolverSettings::softSubsteps, 4 x 60 Hz), which a world takes one at a time.
TEST(Substeps, FreeFallLandsWhereFourEulerSubstepsPerStepPutIt) {
    constexpr Real h = 1.0 / 60;
    constexpr int kSubsteps = 4;
    constexpr int kSteps = 30;
    constexpr Real z0 = 10;
    const WorldDef fall{.gravity = Vec3(0, 0, -kGravity), .timeStep = h};
    WorldDef stepped = fall;
    stepped.substeps = kSubsteps;
    stepped.solver.softSubsteps = 0;
    WorldDef soft = fall;
    soft.substeps = 1;
    soft.solver.softSubsteps = kSubsteps;
    soft.solver.contactHertz = 60;
    for (const WorldDef& worldDef : {stepped, soft}) {
        SCOPED_TRACE(worldDef.solver.softSubsteps == 0 ? "default step" : "soft step");
        World world(worldDef);
        BodyDef def;
        def.position = Vec3(0, 0, z0);
        const BodyId body = world.createBody(def);
        world.createShape(body, ShapeDef{.geometry = Sphere{0.5}});
        const Real k = h / kSubsteps;
        const auto height = [&](int substeps) {
            return z0 - kGravity * k * k * substeps * (substeps + 1) / 2;
        };
        for (int s = 1; s <= kSteps; ++s) {
            ASSERT_TRUE(world.step().ok());
            const int n = kSubsteps * s;
            EXPECT_NEAR(world.position(body).z(), height(n), 1e-12) << "step " << s;
            EXPECT_NEAR(world.linearVelocity(body).z(), -n * kGravity * k, 1e-12) << "step " << s;
            // Interpolation spans the whole step: fraction 0 is where the step began.
            EXPECT_NEAR(world.interpolatedTransform(body, 0).position.z(), height(n - kSubsteps),
                        1e-12)
                << "step " << s;
        }
        const Real oneSubstep = z0 - kGravity * h * h * kSteps * (kSteps + 1) / 2;
        EXPECT_GT(std::abs(world.position(body).z() - oneSubstep), 0.03);
        EXPECT_EQ(world.stepCount(), static_cast<std::uint64_t>(kSteps));
        EXPECT_NEAR(world.time(), kSteps * h, 1e-12);
    }
}

// A 1 kg point-like bob on a 1 m ball joint, released horizontal: the largest deviation of
// kinetic plus potential energy over 3 s at h = 1/60, relative to m g L.
Real pendulumEnergyDrift(int substeps) {
    World world(WorldDef{.gravity = Vec3(0, 0, -kGravity),
                         .timeStep = 1.0 / 60,
                         .substeps = substeps,
                         .solver = SolverSettings{.softSubsteps = 0},
                         .enableSleep = false});
    BodyDef def;
    def.position = Vec3(1, 0, 0);
    def.mass.mass = 1;
    def.mass.inertia = Mat3::Identity() * 1e-3;
    const BodyId bob = world.createBody(def);
    world.createJoint(
        JointDef{.type = JointType::Ball, .bodyA = bob, .bodyB = {}, .anchor = Vec3::Zero()});
    const auto energy = [&] {
        return world.kineticEnergy() + kGravity * world.centerOfMass(bob).z();
    };
    const Real initial = energy();
    Real worst = 0;
    for (int i = 0; i < 180; ++i) {
        EXPECT_TRUE(world.step().ok());
        worst = std::max(worst, std::abs(energy() - initial) / kGravity);
    }
    return worst;
}

// Measured: largest deviation 0.312 of m g L with one substep, 0.0058 with four. A first-order
// method's error falls at least with h / N; the check asks for that factor of 4 only.
TEST(Substeps, PendulumEnergyDriftsLessWithFourSubsteps) {
    const Real one = pendulumEnergyDrift(1);
    const Real four = pendulumEnergyDrift(4);
    std::printf("pendulum energy deviation: 1 substep %.3e, 4 substeps %.3e\n", one, four);
    EXPECT_LT(four, one / 4);
}

TEST(Substeps, ZeroOrNegativeCountsAreRefused) {
    for (const int substeps : {0, -1, -100}) {
        const std::string message = refusal([&] { World world(WorldDef{.substeps = substeps}); });
        EXPECT_TRUE(
            contains(message, "WorldDef.substeps = " + std::to_string(substeps) + " must be >= 1"));
    }
}

// One count of substeps per step: the soft step's (softSubsteps) or the default step's
// (substeps), never both compounded; the World and setSolverSettings name the two fields.
TEST(Substeps, BesideTheSoftStepOnlyOneIsRefusedByName) {
    const std::string expected =
        ": WorldDef.substeps = 4 with WorldDef.solver.softSubsteps = 3: one count of substeps per "
        "step";
    EXPECT_TRUE(contains(refusal([] {
                             World world(WorldDef{.substeps = 4,
                                                  .solver = SolverSettings{.softSubsteps = 3}});
                         }),
                         "World" + expected));
    World stepped(WorldDef{.substeps = 4, .solver = SolverSettings{.softSubsteps = 0}});
    EXPECT_TRUE(
        contains(refusal([&] { stepped.setSolverSettings(SolverSettings{.softSubsteps = 3}); }),
                 "setSolverSettings" + expected));
    EXPECT_EQ(stepped.settings().solver.softSubsteps, 0);
    // Either count alone is taken.
    World soft(WorldDef{.substeps = 1, .solver = SolverSettings{.softSubsteps = 3}});
    EXPECT_EQ(soft.settings().solver.softSubsteps, 3);
    stepped.setSolverSettings(SolverSettings{.softSubsteps = 0, .contactHertz = 45});
    EXPECT_EQ(stepped.settings().solver.contactHertz, 45);
}

// A ball dropped onto the ground with four substeps: the contact begins in some substep of one
// step and stays; it is reported once, and so is the impact.
TEST(Substeps, AContactBeginningInASubstepIsReportedOnce) {
    World world(WorldDef{.gravity = Vec3(0, 0, -kGravity),
                         .timeStep = 1.0 / 60,
                         .substeps = 4,
                         .solver = SolverSettings{.softSubsteps = 0}});
    const BodyId ground = world.createBody(BodyDef{.type = BodyType::Static});
    world.createShape(ground, ShapeDef{.geometry = HalfSpace{}});
    BodyDef def;
    def.position = Vec3(0, 0, 1);
    const BodyId ball = world.createBody(def);
    world.createShape(ball, ShapeDef{.geometry = Sphere{0.5}});
    std::size_t begins = 0, ends = 0, impacts = 0;
    for (int i = 0; i < 120; ++i) {
        ASSERT_TRUE(world.step().ok());
        begins += world.contactBeginEvents().size();
        ends += world.contactEndEvents().size();
        impacts += world.impactEvents().size();
    }
    EXPECT_EQ(begins, 1u);
    EXPECT_EQ(ends, 0u);
    EXPECT_EQ(impacts, 1u);  // lands at 3.1 m/s, above the 0.5 m/s threshold, once
    EXPECT_NEAR(world.position(ball).z(), 0.5, 0.01);
}

// h = 4 s in four substeps of 1 s, 1 kg pushed by 8e307 N: the velocity is 8e307 m/s after the
// first substep (finite), the position 8e307 + 1.6e308 m after the second (infinite). The step
// fails in its second substep and must leave every body as it was before the step, including a
// second body that the first substep moved.
TEST(Substeps, AFailingSubstepRestoresTheStateBeforeTheStep) {
    World world(WorldDef{.gravity = Vec3(0, 0, -kGravity),
                         .timeStep = 4,
                         .substeps = 4,
                         .solver = SolverSettings{.softSubsteps = 0}});
    BodyDef def;
    def.mass.mass = 1;
    def.mass.inertia = Mat3::Identity();
    def.linearVelocity = Vec3(1, 0, 0);
    const BodyId bystander = world.createBody(def);
    def.position = Vec3(0, 5, 0);
    const BodyId pushed = world.createBody(def);
    ASSERT_TRUE(world.step().ok());
    const auto bits = [&](BodyId b) {
        return std::array<std::uint64_t, 3>{
            std::bit_cast<std::uint64_t>(world.position(b).x()),
            std::bit_cast<std::uint64_t>(world.position(b).z()),
            std::bit_cast<std::uint64_t>(world.linearVelocity(b).z())};
    };
    const auto before = bits(bystander);
    const auto pushedBefore = bits(pushed);
    world.applyForceToCenter(pushed, Vec3(0, 0, 8e307));
    const StepStatus status = world.step();
    EXPECT_FALSE(status.ok());
    EXPECT_EQ(status.body, pushed);
    EXPECT_EQ(bits(bystander), before);
    EXPECT_EQ(bits(pushed), pushedBefore);
    EXPECT_EQ(world.stepCount(), 1u);
}

// The profile's stages nest: the solver's own stages are parts of the solve, every stage is a
// part of the step, and with substeps each is summed over them (so the solve stages of a
// resting box, which has a contact in every substep, are all timed).
TEST(Substeps, ProfileStagesArePartsOfTheStep) {
    // The default step's substeps; the soft step, which takes no substeps and measures no
    // residual, has its own (SoftStep.ProfileStagesArePartsOfTheStep, Profile::solveStages).
    World world(WorldDef{.substeps = 4, .solver = SolverSettings{.softSubsteps = 0}});
    const BodyId ground = world.createBody(BodyDef{.type = BodyType::Static});
    world.createShape(ground, ShapeDef{.geometry = HalfSpace{}});
    const BodyId box = world.createBody(BodyDef{.position = Vec3(0, 0, 0.5)});
    world.createShape(box, ShapeDef{.geometry = Box{Vec3(0.5, 0.5, 0.5)}});
    for (int i = 0; i < 10; ++i)
        ASSERT_TRUE(world.step().ok());
    const Profile& p = world.profile();
    const SolverProfile& s = p.solveStages;
    for (const double t : {s.prepare, s.velocity, s.relax, s.residual, s.positions})
        EXPECT_GT(t, 0);
    EXPECT_LE(s.prepare + s.velocity + s.relax + s.residual + s.positions, p.solve);
    EXPECT_GT(p.bounds, 0);
    EXPECT_LE(p.forces + p.broadphase + p.narrowphase + p.islands + p.solve + p.integrate +
                  p.finalize + p.bounds + p.sleep,
              p.total);
}

}  // namespace
}  // namespace tumble
