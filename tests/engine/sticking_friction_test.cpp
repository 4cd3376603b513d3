// A box on a kinematic platform that turns ever faster: it must stick until the friction it
// needs, m r sqrt(omega^4 + alpha^2), reaches mu m g, then slip (issue 20 item 4). Two faults
// kept it from that. The warm-started friction of a manifold grew a self-equilibrated part
// (equilibrateFriction): the points reached their Coulomb discs while the net friction was a
// fifth of the limit, and the cube slipped at 0.82 of mu g. And velocity-level friction holds
// velocities, not places: the cube crept outward by omega^2 r h^2 / 2 a step (r = 1 -> 1.33 m
// by omega = 1.72); friction anchors (SolverSettings::frictionAnchors) hold it.

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <numbers>
#include <random>
#include <vector>

#include "testkit/scenes.h"
#include "tumble/lumped.h"
#include "tumble/world.h"

namespace tumble {
namespace {

using testkit::kGravity;

constexpr Real kHalf = 0.1;  // the cube's half edge (m)
// Speed of the cube's centre against the platform's point under it that counts as slipping
// (m/s). Sticking, it is below 1e-8; past the onset it grows as j t^2 / 2 (j = 2 omega alpha r,
// 0.2 m/s^3 in the case), which reaches this within 0.3 % of the onset's omega.
constexpr Real kSlipSpeed = 1e-3;

struct Ride {
    Real mu = 0.4;
    Real radius = 1;    ///< of the cube's centre (m)
    Real heading = 0;   ///< of the cube's spot from the axis (rad)
    Real yaw = 0;       ///< of the cube about its vertical (rad)
    Real alpha = 0.05;  ///< the platform's angular acceleration (rad/s^2)
    Real h = 1.0 / 60;
    bool anchors = SolverSettings{}.frictionAnchors;  // on by default
    testkit::StepChoice step{};
    /// Slipping judged on the centre's speed over the platform, from its places in the
    /// platform's frame one step apart, instead of on its velocity (SoftStepTurningPlatform).
    bool slipOnPlaces = false;
    /// Slipping judged on the velocity against the platform's at the centre's pose of the
    /// step's end (SoftStepTurningPlatform, where the friction targets turn within the step).
    bool slipAtTheEnd = false;
};

struct Outcome {
    Real slipOmega = -1;  ///< platform's spin when the cube slipped (rad/s); -1: never
    Real slipRadius = 0;  ///< the cube's distance from the axis then (m)
    Real worstDrift = 0;  ///< largest distance from its spot on the platform before `holdUntil`
    /// while sticking, the largest share of its disc a point uses beyond both half of it and
    /// the share the manifold's net friction needs
    Real worstCrowding = 0;
    Real worstSlip = 0;  ///< largest slip speed read before `holdUntil` (m/s)
};

// The spin at which the friction needed at radius r reaches mu g (rad/s).
Real slipOmega(const Ride& ride, Real r) {
    const Real limit = ride.mu * kGravity / r;
    return std::sqrt(std::sqrt(limit * limit - ride.alpha * ride.alpha));
}

// A point's place in the slab's frame (m).
Vec3 place(const World& world, BodyId slab, const Vec3& point) {
    const Transform frame = world.transform(slab);
    return frame.rotation.conjugate() * (point - frame.position);
}

// A 0.2 m cube on a 4 x 4 m kinematic slab, both of friction mu, the slab turning at alpha t.
Outcome ride(const Ride& ride, Real holdUntil) {
    WorldDef def = testkit::quietWorld(ride.h);
    def.solver.frictionAnchors = ride.anchors;
    def.solver.softSubsteps = 0;  // the default step, pinned, unless ride.step asks for another
    testkit::applyStep(def.solver, ride.step);
    World world(def);
    const Material surface{.friction = ride.mu};
    const BodyId slab =
        world.createBody(BodyDef{.type = BodyType::Kinematic, .position = Vec3(0, 0, -kHalf)});
    world.createShape(slab, ShapeDef{.geometry = Box{Vec3(2, 2, kHalf)}, .material = surface});
    const Vec3 spot(ride.radius * std::cos(ride.heading), ride.radius * std::sin(ride.heading),
                    kHalf);
    const BodyId cube = world.createBody(BodyDef{
        .position = spot, .orientation = Quat(Eigen::AngleAxis<Real>(ride.yaw, Vec3::UnitZ()))});
    world.createShape(cube, ShapeDef{.geometry = Box{Vec3::Constant(kHalf)}, .material = surface});
    Outcome out;
    const int steps = static_cast<int>(1.2 * slipOmega(ride, ride.radius) / ride.alpha / ride.h);
    for (int i = 0; i < steps; ++i) {
        const Real omega = ride.alpha * i * ride.h;
        world.setAngularVelocity(slab, Vec3(0, 0, omega));
        const Vec3 before = world.centerOfMass(cube);
        const Vec3 placeBefore = place(world, slab, before);
        world.step();
        const Vec3 onSlab = place(world, slab, world.centerOfMass(cube));
        // Against the platform's velocity at the centre's pose of the step's start, which the
        // default step's contact matches when it sticks (or of its end, slipAtTheEnd); or over
        // the platform, from places.
        const Vec3 reference = ride.slipAtTheEnd ? world.centerOfMass(cube) : before;
        const Vec3 slip =
            ride.slipOnPlaces
                ? Vec3((onSlab - placeBefore) / ride.h)
                : Vec3(world.linearVelocity(cube) - Vec3(0, 0, omega).cross(reference));
        if (omega < holdUntil)
            out.worstSlip = std::max(out.worstSlip, slip.head<2>().norm());
        if (slip.head<2>().norm() > kSlipSpeed) {
            out.slipOmega = omega;
            out.slipRadius = before.head<2>().norm();
            return out;
        }
        if (omega < holdUntil)
            out.worstDrift = std::max(out.worstDrift, (onSlab - spot).head<2>().norm());
        for (const Contact& contact : world.contacts()) {
            Vec3 sum = Vec3::Zero();
            Real load = 0;
            Real crowded = 0;  // the largest share of its Coulomb disc a point uses
            for (int k = 0; k < contact.manifold.pointCount; ++k) {
                sum += contact.tangentImpulse[k];
                load += contact.normalImpulse[k];
                crowded = std::max(crowded, contact.tangentImpulse[k].norm() /
                                                (ride.mu * contact.normalImpulse[k]));
            }
            const Real needed = sum.norm() / (ride.mu * load);
            out.worstCrowding = std::max(out.worstCrowding, crowded - std::max(0.5, needed));
        }
    }
    return out;
}

// Random spots, yaws, mu, radii, step lengths. The platform's acceleration is chosen so that
// the creep without anchors, exp(h omega^3 / (6 alpha)), stays within 1.1 (the cube stays
// on the slab), so the rides without anchors test the friction alone.
std::vector<Ride> randomRides(bool anchors) {
    std::mt19937 random(20);
    std::uniform_real_distribution<Real> radius(0.6, 1.5);
    std::uniform_real_distribution<Real> angle(0, 2 * std::numbers::pi);
    std::uniform_real_distribution<Real> mu(0.2, 0.9);
    std::uniform_real_distribution<Real> pace(2, 6);
    std::vector<Ride> rides;
    for (const Real h : {1.0 / 60, 1.0 / 120}) {
        for (int k = 0; k < 4; ++k) {
            Ride ride{.mu = mu(random),
                      .radius = radius(random),
                      .heading = angle(random),
                      .yaw = angle(random),
                      .h = h,
                      .anchors = anchors};
            const Real omega = std::sqrt(ride.mu * kGravity / ride.radius);
            ride.alpha = pace(random) * h * omega * omega * omega;
            rides.push_back(ride);
        }
    }
    return rides;
}

// The steps the StickingFriction rides run on: the default step (pinned) and the soft step at
// 3 x 45. The soft step's slip is judged on the velocity against the platform's at the centre's
// pose of the step's end (SoftStepTurningPlatform below says why), the default step's at its start.
std::vector<Ride> onBothSteps(const Ride& r) {
    std::vector<Ride> rides;
    for (const testkit::StepChoice& step : {testkit::kStepChoices[0], testkit::kStepChoices[1]}) {
        Ride onStep = r;
        onStep.step = step;
        onStep.slipAtTheEnd = step.softSubsteps > 0;
        rides.push_back(onStep);
    }
    return rides;
}

// (With anchors: equilibrateFriction runs only with them, see solve_stage.cpp.) The cube
// radius it has reached is mu g, and while it sticks no point's friction uses more of its disc
// than half or the manifold's net friction needs (before the fix: points on their discs at a
// fifth of the net limit).
TEST(StickingFriction, BoxOnATurningPlatformSlipsWhenItNeedsMuG) {
    for (const Ride& random : randomRides(true)) {
        for (const Ride& r : onBothSteps(random)) {
            SCOPED_TRACE(testing::Message()
                         << testkit::stepName(r.step) << " mu " << r.mu << " r " << r.radius
                         << " alpha " << r.alpha << " h " << r.h << " yaw " << r.yaw);
            const Outcome out = ride(r, 0);
            ASSERT_GT(out.slipOmega, 0);
            EXPECT_NEAR(out.slipOmega / slipOmega(r, out.slipRadius), 1, 0.03);
            EXPECT_LT(out.worstCrowding, 0.05);
        }
    }
}

// The reproduction at the default settings (anchors on): r = 1 m, omega = 0.05 t,
// mu = 0.4, h = 1/60. The cube stays within 1 mm of its spot until the friction it needs is
// 0.98 of mu g (then the manifold reaches 0.99 of its limit and lets its anchors go), and slips
// within 3 % of omega = sqrt(mu g / r) = 1.98. Without anchors: 0.32 m outward by then, and it
// left at 1.78.
// The cube within 1 mm of its spot until 0.99 of the onset, slipping within 3 % of it.
void expectHeldUntilTheOnset(const Ride& r) {
    const Real onset = slipOmega(r, r.radius);
    const Outcome out = ride(r, 0.99 * onset);
    std::printf(
        "within %.2g m of its spot, slip read up to %.2g m/s; slips at omega = %.4f "
        "(analytic %.4f)\n",
        out.worstDrift, out.worstSlip, out.slipOmega, onset);
    EXPECT_LT(out.worstDrift, 1e-3);
    EXPECT_NEAR(out.slipOmega / onset, 1, 0.03);
}

TEST(StickingFriction, CubeOnATurningPlatformStaysOnItsSpotUntilOmegaSquaredREqualsMuG) {
    for (const Ride& r : onBothSteps(Ride{})) {
        SCOPED_TRACE(testkit::stepName(r.step));
        ASSERT_TRUE(r.anchors);
        expectHeldUntilTheOnset(r);
    }
}

// Random spots, yaws, mu, radii and rates with anchors: held within 1 mm, slipping within 3 %.
TEST(StickingFriction, AnchoredBoxOnATurningPlatformHoldsItsSpotUntilItNeedsMuG) {
    for (const Ride& random : randomRides(true)) {
        for (const Ride& r : onBothSteps(random)) {
            SCOPED_TRACE(testing::Message()
                         << testkit::stepName(r.step) << " mu " << r.mu << " r " << r.radius
                         << " alpha " << r.alpha << " h " << r.h << " yaw " << r.yaw);
            const Real onset = slipOmega(r, r.radius);
            const Outcome out = ride(r, 0.99 * onset);
            EXPECT_LT(out.worstDrift, 1e-3);
            ASSERT_GT(out.slipOmega, 0);
            EXPECT_NEAR(out.slipOmega / onset, 1, 0.03);
        }
    }
}

// The case under the soft step, to the same tolerances: its friction anchors hold the
// cube within 1 mm of its spot until 0.99 of the onset, and it slips within 3 % of it (without
// anchors it had crept 8.6 mm at 3 x 45 and 24 mm at 4 x 30 by omega = 0.58 and 0.80). Slipping
// is judged on places here, from the cube's centre over the platform; on its velocity below.
class SoftStepTurningPlatform : public testing::TestWithParam<testkit::StepChoice> {};

INSTANTIATE_TEST_SUITE_P(Steps, SoftStepTurningPlatform,
                         testing::Values(testkit::kStepChoices[1], testkit::kStepChoices[2]),
                         [](const auto& choice) { return testkit::stepName(choice.param); });

TEST_P(SoftStepTurningPlatform, CubeStaysOnItsSpotUntilOmegaSquaredREqualsMuG) {
    expectHeldUntilTheOnset({.step = GetParam(), .slipOnPlaces = true});
}

// The same, judged on the cube's velocity against the platform's at its centre's pose of the
// step's END, to the default step's tolerances. Why the end: the soft step's friction targets
// turn with the pair within the step (ContactSolver::softTargets), so a sticking cube is held to
// the platform's point velocity where it stands after each substep, and after the last one that
// is omega x c_end, as the default step's contact, collided at the start pose, holds omega x
// c_start. Both are the platform's velocity at the cube's place; they differ by a step's turn of
// it, omega^2 r h (0.065 m/s at the onset), which the start's reference would read as slip.
TEST_P(SoftStepTurningPlatform, CubeStaysOnItsSpotAndMovesWithThePlatformUntilItNeedsMuG) {
    expectHeldUntilTheOnset({.step = GetParam(), .slipAtTheEnd = true});
}

// The random rides of BoxOnATurningPlatformSlipsWhenItNeedsMuG and AnchoredBox... under the
// soft step, judged on the velocity at the end pose (above): held within 1 mm of the spot until
// 0.99 of the onset, slipping within 3 % of it, no point crowding its disc.
TEST_P(SoftStepTurningPlatform, AnchoredBoxMovesWithThePlatformUntilItNeedsMuG) {
    for (Ride r : randomRides(true)) {
        r.step = GetParam();
        r.slipAtTheEnd = true;
        SCOPED_TRACE(testing::Message() << "mu " << r.mu << " r " << r.radius << " alpha "
                                        << r.alpha << " h " << r.h << " yaw " << r.yaw);
        const Real onset = slipOmega(r, r.radius);
        const Outcome out = ride(r, 0.99 * onset);
        std::printf("slip read up to %.2g m/s, drift %.2g m; slips at %.4f of the onset\n",
                    out.worstSlip, out.worstDrift, out.slipOmega / slipOmega(r, out.slipRadius));
        EXPECT_LT(out.worstDrift, 1e-3);
        ASSERT_GT(out.slipOmega, 0);
        EXPECT_NEAR(out.slipOmega / slipOmega(r, out.slipRadius), 1, 0.03);
        EXPECT_LT(out.worstCrowding, 0.05);
    }
}

// A pile under a capture net falls asleep with anchors on as with them off (the 5,000-body
// soak's pile never slept with them: the anchor pass moved the net's nodes against their stiff
// threads, which threw them back at 0.05-0.1 m/s every step; solve_stage.cpp). 60 mixed bodies
// of the soak's rain in a 2 x 2 m box, a 10 x 10 net dropped on them at 2 s, with the soak's drag.
Real firstAllAsleep(bool anchors) {
    WorldDef def{.timeStep = 1.0 / 60};
    def.solver.frictionAnchors = anchors;
    World world(def);
    testkit::PileUnderNet pile(world);
    for (int i = 0; i < 12 * 60; ++i) {
        pile.feed(world, i);
        if (!world.step().ok())
            return -2;
        if (i > testkit::PileUnderNet::kNetStep && world.awakeBodyCount() == 0)
            return (i + 1) * def.timeStep;
    }
    return -1;
}

TEST(StickingFriction, APileUnderANetFallsAsleepWithAnchorsAsWithout) {
    const Real without = firstAllAsleep(false);
    const Real with = firstAllAsleep(true);
    std::printf("all asleep at %.2f s without anchors, %.2f s with\n", without, with);
    ASSERT_GT(without, 0);
    ASSERT_GT(with, 0);
    EXPECT_LT(with, without + 1);
}

// A 10 x 10 net (the soak's, with its drag) dropped from 1 m onto nine boxes resting on the
// ground, its centre `offset` off theirs; when everything first sleeps (s after the drop), or
// -1 if not within 15 s, -2 if a step failed.
Real netOnBoxesAsleep(bool anchors, const Vec3& offset) {
    WorldDef def{.timeStep = 1.0 / 60};
    def.solver.frictionAnchors = anchors;
    World world(def);
    const Material rain = testkit::soakMaterial();
    testkit::addGround(world, rain);
    for (int i = 0; i < 9; ++i)
        testkit::addBox(world, Vec3(0.4 * (i % 3 - 1), 0.4 * (i / 3 - 1), 0.1),
                        Vec3(0.15, 0.12, 0.1), rain);
    const Lumped net = createNet(world, testkit::captureNet(10, 0.2, offset + Vec3(0, 0, 1)));
    for (const BodyId node : net.nodes)
        world.setDrag(node, Drag{.linear = world.massProperties(node).mass});
    for (int i = 0; i < 15 * 60; ++i) {
        if (!world.step().ok())
            return -2;
        if (world.awakeBodyCount() == 0)
            return (i + 1) * def.timeStep;
    }
    return -1;
}

// Anchors hold the boxes' contacts with the ground, not the nodes' (holdAnchors): they must not
// keep the net from settling. One drop's time to sleep is one trajectory's (the last node's
// timer), so the mean over drops at several offsets is compared. Bound written before
// measuring: half a second, the sleep timer (WorldDef::timeToSleep) -- a delay shorter than one
// timer is how the last body's timer happens to start, a longer one is motion kept up.
TEST(StickingFriction, ANetOnAnchoredBoxesSettlesAsWithoutAnchors) {
    constexpr int kDrops = 6;
    constexpr Real kBound = 0.5;  // (s)
    Real without = 0;
    Real with = 0;
    for (int k = 0; k < kDrops; ++k) {
        const Vec3 offset(0.05 * k - 0.125, 0.03 * k - 0.075, 0);
        const Real a = netOnBoxesAsleep(false, offset);
        const Real b = netOnBoxesAsleep(true, offset);
        std::printf("drop %d: asleep at %.2f s without anchors, %.2f s with\n", k, a, b);
        ASSERT_GT(a, 0);
        ASSERT_GT(b, 0);
        without += a / kDrops;
        with += b / kDrops;
    }
    std::printf("mean: %.2f s without anchors, %.2f s with\n", without, with);
    EXPECT_LT(with, without + kBound);
}

}  // namespace
}  // namespace tumble
