// Islands and sleeping: when bodies fall asleep, what wakes them, and that sleeping changes
// nothing it should not.

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <limits>
#include <vector>

#include "refusal.h"
#include "testkit/same_ids.h"
#include "testkit/scenes.h"
#include "tumble/checkpoint.h"
#include "tumble/world.h"

namespace tumble {
namespace {

using test::contains;
using test::refusal;

// Friction 0.5 (the default material's) on the ground and the boxes; the boxes unit cubes of
// 1,000 kg at the default density.
using testkit::addBox;
using testkit::addGround;

// The sleep test (WorldDef::linearSleepVelocity): no point of the body, which reaches `extent`
// from its centre of mass, moves faster than the linear threshold, and it turns slower than the
// angular one.
bool isStill(const World& world, BodyId id, Real extent) {
    const WorldDef& s = world.settings();
    const Real turn = world.angularVelocity(id).norm();
    return world.linearVelocity(id).norm() + extent * turn <= s.linearSleepVelocity &&
           turn <= s.angularSleepVelocity;
}

// Steps until the body sleeps; returns the number of steps taken, or -1 after maxSteps.
int stepUntilAsleep(World& world, BodyId id, int maxSteps) {
    for (int i = 1; i <= maxSteps; ++i) {
        EXPECT_TRUE(world.step().ok());
        if (!world.isAwake(id))
            return i;
    }
    return -1;
}

// Everything a body reports, as raw doubles, for bitwise comparison.
std::vector<Real> stateOf(const World& world, BodyId id) {
    const Quat q = world.orientation(id);
    const Vec3 p = world.position(id);
    const Vec3 v = world.linearVelocity(id);
    const Vec3 w = world.angularVelocity(id);
    const Transform t = world.interpolatedTransform(id, 0.5);
    return {p.x(),          p.y(),          p.z(),          q.w(),          q.x(),
            q.y(),          q.z(),          v.x(),          v.y(),          v.z(),
            w.x(),          w.y(),          w.z(),          t.position.x(), t.position.y(),
            t.position.z(), t.rotation.w(), t.rotation.x(), t.rotation.y(), t.rotation.z()};
}

bool bitwiseEqual(const std::vector<Real>& a, const std::vector<Real>& b) {
    return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(Real)) == 0;
}

TEST(Sleep, DroppedBoxFallsAsleepOnlyAfterStayingStillForTimeToSleep) {
    World world;
    addGround(world);
    const BodyId box = addBox(
        world,
        BodyDef{.position = Vec3(0, 0, 1.5),
                .orientation = Quat(Eigen::AngleAxis<Real>(0.3, Vec3(1, 1, 0).normalized()))});
    const Real h = world.settings().timeStep;
    // The timer must cover timeToSleep: this many still steps, the last being the one it
    // falls asleep in (its velocities are zeroed then, so that one is not observed).
    const int stillSteps = static_cast<int>(std::lround(world.settings().timeToSleep / h));

    int stillRun = 0;
    int asleepAt = -1;
    for (int i = 1; i <= 600 && asleepAt < 0; ++i) {
        ASSERT_TRUE(world.step().ok());
        if (!world.isAwake(box)) {
            asleepAt = i;
            break;
        }
        stillRun = isStill(world, box, std::sqrt(0.75)) ? stillRun + 1 : 0;  // half-diagonal
    }
    ASSERT_GT(asleepAt, 0) << "the box never fell asleep";
    EXPECT_GE(stillRun, stillSteps - 1) << "it fell asleep before it had been still for long";
    EXPECT_LE(stillRun, stillSteps) << "it stayed awake after being still for timeToSleep";
    // Asleep at rest on a face, with its velocities zeroed.
    EXPECT_NEAR(world.position(box).z(), 0.5, world.settings().solver.slop + 1e-3);
    EXPECT_EQ(world.linearVelocity(box), Vec3::Zero());
    EXPECT_EQ(world.angularVelocity(box), Vec3::Zero());
    EXPECT_EQ(world.awakeBodyCount(), 0);
}

TEST(Sleep, SleepingBoxKeepsItsContactAndCachedImpulses) {
    World world;
    addGround(world);
    const BodyId box = addBox(world, Vec3(0, 0, 0.5));
    ASSERT_GT(stepUntilAsleep(world, box, 300), 0);
    ASSERT_EQ(world.contacts().size(), 1u);
    const Contact& contact = world.contacts()[0];
    ASSERT_EQ(contact.manifold.pointCount, 4);
    // At rest the normal impulses of a step carry the weight: sum = m g h (the split between
    // the four corners is not unique).
    Real sum = 0;
    for (int i = 0; i < 4; ++i)
        sum += contact.normalImpulse[i];
    const Real weightImpulse = world.massProperties(box).mass * 9.81 * world.settings().timeStep;
    EXPECT_NEAR(sum, weightImpulse, 0.01 * weightImpulse);
}

// A box resting on another, dropped with and without sleeping: the highest the lower box gets
// kicked up by the impact, and where the upper one comes to rest.
struct DropOnto {
    Real restZ = 0;         // lower box before the drop (m)
    Real highestLower = 0;  // (m)
    Real upperZ = 0;        // (m)
    bool lowerSleptBeforeTouch = true;
    bool lowerWoke = false;
    bool oneState = true;   // once touched, both awake or both asleep
    int bothAsleepAt = -1;  // step after the drop, -1 if never
};

DropOnto dropOnto(bool enableSleep) {
    World world(WorldDef{.enableSleep = enableSleep});
    addGround(world);
    const BodyId lower = addBox(world, Vec3(0, 0, 0.5));
    for (int i = 0; i < 90; ++i)
        world.step();
    DropOnto r;
    r.restZ = world.position(lower).z();
    r.highestLower = r.restZ;
    const BodyId upper = addBox(world, Vec3(0.2, -0.1, 2.5));
    for (int i = 0; i < 600; ++i) {
        world.step();
        // Falling 1 m takes 27 steps: for the first 10 it is far from touching.
        if (i < 10)
            r.lowerSleptBeforeTouch = r.lowerSleptBeforeTouch && !world.isAwake(lower);
        r.lowerWoke = r.lowerWoke || (i >= 10 && world.isAwake(lower));
        if (r.lowerWoke)
            r.oneState = r.oneState && world.isAwake(lower) == world.isAwake(upper);
        r.highestLower = std::max(r.highestLower, world.position(lower).z());
        if (r.bothAsleepAt < 0 && !world.isAwake(lower) && !world.isAwake(upper))
            r.bothAsleepAt = i;
    }
    r.upperZ = world.position(upper).z();
    return r;
}

TEST(Sleep, SleepingBoxIsWokenByABoxDroppedOnItAndThePairSleepsAgain) {
    const DropOnto sleeping = dropOnto(true);
    EXPECT_TRUE(sleeping.lowerSleptBeforeTouch);
    EXPECT_TRUE(sleeping.lowerWoke);
    EXPECT_TRUE(sleeping.oneState) << "they touch: one island, one state";
    EXPECT_GE(sleeping.bothAsleepAt, 0) << "the pair never fell asleep again";
    // Waking in the middle of the step it is hit in must not kick the lower box: it moves as it
    // would had it never slept (its cached impulses meet this step's gravity).
    const DropOnto awake = dropOnto(false);
    EXPECT_NEAR(sleeping.highestLower - sleeping.restZ, awake.highestLower - awake.restZ, 1e-4);
    EXPECT_NEAR(sleeping.upperZ, awake.upperZ, 1e-3);
    EXPECT_NEAR(sleeping.upperZ, 1.5, 2 * (SolverSettings{}.slop + 1e-3));
}

// Each way of pushing or changing a body through the API wakes it.
TEST(Sleep, ApiChangesWakeTheBody) {
    struct Case {
        const char* name;
        void (*change)(World&, BodyId);
    };
    const Case cases[] = {
        {"applyForce",
         [](World& w, BodyId b) { w.applyForce(b, Vec3(5, 0, 0), w.centerOfMass(b)); }},
        {"applyForceToCenter", [](World& w, BodyId b) { w.applyForceToCenter(b, Vec3(5, 0, 0)); }},
        {"applyTorque", [](World& w, BodyId b) { w.applyTorque(b, Vec3(0, 0, 5)); }},
        {"applyLinearImpulse",
         [](World& w, BodyId b) { w.applyLinearImpulse(b, Vec3(1, 0, 0), w.centerOfMass(b)); }},
        {"applyAngularImpulse",
         [](World& w, BodyId b) { w.applyAngularImpulse(b, Vec3(0, 0, 1)); }},
        {"setLinearVelocity", [](World& w, BodyId b) { w.setLinearVelocity(b, Vec3(1, 0, 0)); }},
        {"setAngularVelocity", [](World& w, BodyId b) { w.setAngularVelocity(b, Vec3(0, 0, 1)); }},
        {"setTransform",
         [](World& w, BodyId b) { w.setTransform(b, Vec3(0, 0, 2), Quat::Identity()); }},
        {"setMassProperties",
         [](World& w, BodyId b) {
             MassProperties mass;
             mass.mass = 2;
             mass.inertia = Mat3::Identity() / 3;
             w.setMassProperties(b, mass);
         }},
        {"createShape",
         [](World& w, BodyId b) {
             w.createShape(b, ShapeDef{.geometry = Sphere{0.2},
                                       .localPose = {Vec3(0, 0, 0.5), Quat::Identity()}});
         }},
        {"destroyShape",
         [](World& w, BodyId b) {
             const Contact& ground = w.contacts()[0];
             w.destroyShape(ground.bodyA == b ? ground.shapeA : ground.shapeB);
         }},
        {"setAwake", [](World& w, BodyId b) { w.setAwake(b, true); }},
    };
    for (const Case& c : cases) {
        World world;
        addGround(world);
        const BodyId box = addBox(world, Vec3(0, 0, 0.5));
        ASSERT_GT(stepUntilAsleep(world, box, 300), 0) << c.name;
        c.change(world, box);
        EXPECT_TRUE(world.isAwake(box)) << c.name;
        EXPECT_EQ(world.awakeBodyCount(), 1) << c.name;
    }
}

// A woken body answers a push as if it had never slept: sliding friction mu m g against twice
// that, a = mu g, under semi-implicit Euler at the integrator's step k = h / n (n = 1 on the
// default step, the soft step's substeps else). The push's impulse h F comes in the first of
// the n (the soft step's applied forces), the friction's mu m g k in each, so a step maps
// v' = v + a h and x' = x + h v + 2 a h^2 - a k^2 n (n + 1) / 2: after S steps from rest
// v = a h S, x = a h^2 S (S - 1) / 2 + S (2 a h^2 - a k^2 n (n + 1) / 2), for n = 1 the
// familiar a h^2 S (S + 1) / 2.
TEST(Sleep, PushedBodyMovesAfterWaking) {
    for (const testkit::StepChoice& step : testkit::kIntegratorStepChoices) {
        SCOPED_TRACE(testkit::stepName(step));
        WorldDef def;
        testkit::applyStep(def.solver, step);
        World world(def);
        addGround(world);
        const BodyId box = addBox(world, Vec3(0, 0, 0.5));
        ASSERT_GT(stepUntilAsleep(world, box, 300), 0);
        const Real x0 = world.position(box).x();
        const Real mu = 0.5;
        const Real push = 2 * mu * world.massProperties(box).mass * 9.81;
        const int steps = 30;
        for (int i = 0; i < steps; ++i) {
            world.applyForceToCenter(box, Vec3(push, 0, 0));
            ASSERT_TRUE(world.step().ok());
            EXPECT_TRUE(world.isAwake(box));
        }
        const Real h = world.settings().timeStep;
        const int n = testkit::integratorStepsPerStep(step);
        const Real k = h / n;
        const Real a = mu * 9.81;
        // To the solver's convergence (PGS at a fixed budget), 1e-6 relative.
        const Real v = a * steps * h;
        const Real x = a * h * h * steps * (steps - 1) / 2 +
                       steps * (2 * a * h * h - a * k * k * n * (n + 1) / 2);
        EXPECT_NEAR(world.linearVelocity(box).x(), v, 1e-6 * v);
        EXPECT_NEAR(world.position(box).x() - x0, x, 1e-6 * x);
    }
}

// A unit cube resting on the ground at the origin that may not sleep.
BodyId addRestlessBox(World& world) {
    BodyDef restless{.position = Vec3(0, 0, 0.5)};
    restless.allowSleep = false;
    return addBox(world, restless);
}

TEST(Sleep, BodyThatMayNotSleepKeepsItsIslandAwake) {
    World world;
    addGround(world);
    const BodyId lower = addRestlessBox(world);
    const BodyId upper = addBox(world, Vec3(0, 0, 1.5));
    const BodyId apart = addBox(world, Vec3(5, 0, 0.5));
    for (int i = 0; i < 300; ++i)
        ASSERT_TRUE(world.step().ok());
    EXPECT_TRUE(world.isAwake(lower));
    EXPECT_TRUE(world.isAwake(upper)) << "it rests on a body that may not sleep";
    EXPECT_FALSE(world.isAwake(apart)) << "a separate island sleeps";
}

// The gap of the two tests below: beyond contactMargin (2 cm), so two resting boxes this far
// apart are two islands, but within contactMargin + g h^2 (2.27 cm at 1/60), the margin the
// pair had once one of them slept -- the narrowphase sees the awake body's velocity after
// gravity's push for the step, a sleeper's without. Such a pair woke the sleeper the step after
// it fell asleep, over and over (the 5,000-body soak's body by the wall).
constexpr Real kBlinkGap = 0.021;

// A body asleep beside a resting body that stays awake is not woken by it: it falls asleep
// after timeToSleep (tolerance, set before measuring: by 1 s) and then stays asleep for the
// 5 s that follow (every step checked). Before the fix it was awake again one step after each
// time it fell asleep.
TEST(Sleep, BodyBesideARestingAwakeBodyStaysAsleep) {
    World world;
    addGround(world);
    const BodyId awake = addRestlessBox(world);
    const BodyId lone = addBox(world, Vec3(1 + kBlinkGap, 0, 0.5));
    const int perSecond = static_cast<int>(std::lround(1 / world.settings().timeStep));
    const int asleepAt = stepUntilAsleep(world, lone, perSecond);
    ASSERT_GT(asleepAt, 0) << "the lone box did not fall asleep within 1 s";
    for (int i = 0; i < 5 * perSecond; ++i) {
        ASSERT_TRUE(world.step().ok());
        ASSERT_FALSE(world.isAwake(lone)) << "woken " << i + 1 << " steps after falling asleep";
    }
    EXPECT_TRUE(world.isAwake(awake));
}

// A small pile placed at rest, and a box dropped from 0.3 m beside it that settles later: the
// pile falls asleep first, the box beside it after. Everything is asleep by 2 s (tolerance, set
// before measuring) and stays asleep for the 5 s that follow -- neither wakes the other.
TEST(Sleep, PileAndABodyThatSettledBesideItLaterAllStayAsleep) {
    World world;
    addGround(world);
    for (int i = 0; i < 3; ++i)
        addBox(world, Vec3(i, 0, 0.5));
    addBox(world, Vec3(1, 0, 1.5));
    addBox(world, Vec3(3 + kBlinkGap, 0, 0.8));
    const int perSecond = static_cast<int>(std::lround(1 / world.settings().timeStep));
    int allAsleepAt = -1;
    for (int i = 1; i <= 2 * perSecond && allAsleepAt < 0; ++i) {
        ASSERT_TRUE(world.step().ok());
        if (world.awakeBodyCount() == 0)
            allAsleepAt = i;
    }
    ASSERT_GT(allAsleepAt, 0) << "not all asleep by 2 s";
    for (int i = 0; i < 5 * perSecond; ++i) {
        ASSERT_TRUE(world.step().ok());
        ASSERT_EQ(world.awakeBodyCount(), 0) << "woken " << i + 1 << " steps after all slept";
    }
}

// A sphere on the ground spinning slowly about the vertical: a point contact has no friction
// about its normal, so nothing stops the spin (checked: it keeps its angular velocity), and a
// bare angular threshold below 0.2 rad/s would keep it -- and any pile it is part of -- awake
// for good. Its surface moves at 0.2 rad/s x 0.15 m = 3 cm/s, below the 5 cm/s threshold: it
// counts as still and falls asleep after timeToSleep.
TEST(Sleep, SmallBodySpinningSlowlyAboutItsContactNormalFallsAsleep) {
    World world;
    addGround(world);
    const BodyId sphere = world.createBody(BodyDef{.position = Vec3(0, 0, 0.15)});
    ShapeDef shape{.geometry = Sphere{0.15}};
    shape.material.friction = 0.5;
    world.createShape(sphere, shape);
    world.setAngularVelocity(sphere, Vec3(0, 0, 0.2));
    const Real h = world.settings().timeStep;
    const int stillSteps = static_cast<int>(std::lround(world.settings().timeToSleep / h));
    for (int i = 0; i < stillSteps / 2; ++i)
        ASSERT_TRUE(world.step().ok());
    EXPECT_NEAR(world.angularVelocity(sphere).z(), 0.2, 1e-9) << "the spin is not opposed";
    const int asleepAt = stepUntilAsleep(world, sphere, stillSteps);
    EXPECT_GT(asleepAt, 0) << "a 15 cm sphere turning at 0.2 rad/s never fell asleep";
}

// What stays awake: a 10 m beam turning at 0.02 rad/s (its ends move at 0.1 m/s, though its
// angular speed is far below the angular threshold), and a 2 cm bead spinning at 1 rad/s (its
// surface moves at 2 cm/s, but it turns faster than the 0.5 rad/s the threshold allows). Both
// float free of gravity, each its own island. The beam's extent is derived data, recomputed
// when a checkpoint is loaded: the restored beam must stay awake too.
TEST(Sleep, LongBodyTurningSlowlyAndSmallBodySpinningFastStayAwake) {
    World world(WorldDef{.gravity = Vec3::Zero()});
    const BodyId beam = world.createBody(BodyDef{.angularVelocity = Vec3(0, 0, 0.02)});
    world.createShape(beam, ShapeDef{.geometry = Box{Vec3(5, 0.1, 0.1)}});
    const BodyId bead =
        world.createBody(BodyDef{.position = Vec3(0, 3, 0), .angularVelocity = Vec3(1, 0, 0)});
    world.createShape(bead, ShapeDef{.geometry = Sphere{0.02}});
    const BodyId slow =
        world.createBody(BodyDef{.position = Vec3(0, -3, 0), .angularVelocity = Vec3(0.2, 0, 0)});
    world.createShape(slow, ShapeDef{.geometry = Sphere{0.02}});
    for (int i = 0; i < 120; ++i)
        ASSERT_TRUE(world.step().ok());
    EXPECT_TRUE(world.isAwake(beam)) << "its ends move at 0.1 m/s";
    EXPECT_TRUE(world.isAwake(bead)) << "it spins at 1 rad/s";
    EXPECT_FALSE(world.isAwake(slow)) << "the same bead at 0.2 rad/s is still";

    World resumed(WorldDef{.gravity = Vec3::Zero()});
    restoreCheckpoint(resumed, checkpointBytes(world));
    for (int i = 0; i < 120; ++i)
        ASSERT_TRUE(resumed.step().ok());
    EXPECT_TRUE(resumed.isAwake(test::sameBody(resumed, beam)))
        << "the loaded beam lost its extent";
}

// A 1 kg body hangs from a world point on a spring, released at the spring's rest length; the
// backward-Euler spring damps the bounce (the default scheme keeps an undamped spring's bounce
// for good, as it should). It used to fall asleep (k = 36 N/m) at 1.008 times the
// static deflection, tension 9.888 N against a weight of 9.81 N: slow enough to count as still,
// but out of balance. It must sleep in balance: stretched by m g / k to 0.1 %. (With a damper the
// rule leaves c v / k, v below linearSleepVelocity: docs/ARCHITECTURE.md.)
TEST(Sleep, BodyOnASpringSleepsOnlyInBalance) {
    for (const Real k : {36.0, 100.0, 400.0}) {
        World world;
        const BodyId body = world.createBody(BodyDef{.position = Vec3(0, 0, -1)});
        SpringDef def;  // from the body's origin to the world's
        def.bodyA = body;
        def.restLength = 1;
        def.stiffness = k;
        def.formulation = SpringFormulation::BackwardEuler;
        const SpringId spring = world.createSpring(def);
        const Real weight = world.settings().gravity.norm();  // m g, m = 1 kg
        const int steps = stepUntilAsleep(world, body, 120 * 60);
        ASSERT_GT(steps, 0) << "k = " << k << ": it must sleep once settled";
        const Real stretch = -world.position(body).z() - 1;
        EXPECT_NEAR(stretch / (weight / k), 1, 1e-3)
            << "k = " << k << ", asleep at t = " << world.time();
        EXPECT_NEAR(world.springState(spring).tension / weight, 1, 1e-3) << "k = " << k;
    }
}

TEST(Sleep, StackOfFiveSleepsAsOneIslandAndWakingTheTopWakesAll) {
    World world;
    addGround(world);
    const std::vector<BodyId> stack = testkit::buildStack(world, 5);
    int previous = world.awakeBodyCount();
    int fellAsleepAt = -1;
    for (int i = 0; i < 900 && fellAsleepAt < 0; ++i) {
        ASSERT_TRUE(world.step().ok());
        const int awake = world.awakeBodyCount();
        if (awake != previous) {
            EXPECT_EQ(previous, 5);
            EXPECT_EQ(awake, 0) << "the stack fell asleep in parts";
            fellAsleepAt = i;
        }
        previous = awake;
    }
    ASSERT_GE(fellAsleepAt, 0) << "the stack never fell asleep";
    EXPECT_NEAR(world.position(stack.back()).z(), 4.5, 5 * (world.settings().solver.slop + 1e-3));

    world.setAwake(stack.back(), true);
    EXPECT_EQ(world.awakeBodyCount(), 5);
    for (BodyId id : stack)
        EXPECT_TRUE(world.isAwake(id));
    // And put to sleep again as one island from its bottom.
    world.setAwake(stack.front(), false);
    EXPECT_EQ(world.awakeBodyCount(), 0);
}

TEST(Sleep, SleepingBodyDoesNotChangeBitwise) {
    World world;
    addGround(world);
    const BodyId box = addBox(world, Vec3(0, 0, 0.5));
    // Something awake elsewhere, so the steps do run their stages.
    BodyDef rolling;
    rolling.allowSleep = false;
    rolling.position = Vec3(10, 0, 0.3);
    rolling.linearVelocity = Vec3(0, 1, 0);
    const BodyId ball = world.createBody(rolling);
    world.createShape(ball, ShapeDef{.geometry = Sphere{0.3}});
    ASSERT_GT(stepUntilAsleep(world, box, 300), 0);
    const std::vector<Real> before = stateOf(world, box);
    const Vec3 ballBefore = world.position(ball);
    for (int i = 0; i < 200; ++i) {
        ASSERT_TRUE(world.step().ok());
        ASSERT_FALSE(world.isAwake(box));
    }
    EXPECT_TRUE(bitwiseEqual(stateOf(world, box), before));
    EXPECT_GT((world.position(ball) - ballBefore).norm(), 1.0);
}

TEST(Sleep, DisabledSleepNeverPutsBodiesToSleep) {
    World world(WorldDef{.enableSleep = false});
    addGround(world);
    const BodyId box = addBox(world, Vec3(0, 0, 0.5));
    for (int i = 0; i < 300; ++i)
        ASSERT_TRUE(world.step().ok());
    EXPECT_TRUE(world.isAwake(box));
    EXPECT_EQ(world.awakeBodyCount(), 1);
}

TEST(Sleep, BodyCreatedAsleepStaysAsleepUntilTouched) {
    World world;
    addGround(world);
    BodyDef asleep{.position = Vec3(0, 0, 0.5)};
    asleep.awake = false;
    const BodyId lower = addBox(world, asleep);  // shape added after creation
    EXPECT_FALSE(world.isAwake(lower));
    EXPECT_EQ(world.awakeBodyCount(), 0);
    for (int i = 0; i < 30; ++i)
        ASSERT_TRUE(world.step().ok());
    EXPECT_FALSE(world.isAwake(lower));
    EXPECT_EQ(world.position(lower), Vec3(0, 0, 0.5));

    addBox(world, Vec3(0, 0, 2));
    bool woke = false;
    for (int i = 0; i < 60 && !woke; ++i) {
        ASSERT_TRUE(world.step().ok());
        woke = world.isAwake(lower);
    }
    EXPECT_TRUE(woke);
}

TEST(Sleep, DestroyingOrMovingTheGroundWakesWhatRestsOnIt) {
    for (const bool destroy : {true, false}) {
        World world;
        const BodyId ground = addGround(world);
        const BodyId box = addBox(world, Vec3(0, 0, 0.5));
        ASSERT_GT(stepUntilAsleep(world, box, 300), 0);
        const Real z0 = world.position(box).z();
        if (destroy)
            world.destroyBody(ground);
        else
            world.setTransform(ground, Vec3(0, 0, -1), Quat::Identity());
        EXPECT_TRUE(world.isAwake(box)) << (destroy ? "destroyBody" : "setTransform");
        for (int i = 0; i < 10; ++i)
            ASSERT_TRUE(world.step().ok());
        EXPECT_LT(world.position(box).z(), z0 - 0.05) << "it falls";
    }
}

TEST(Sleep, DestroyingABodyWakesWhatRestsOnIt) {
    World world;
    addGround(world);
    const BodyId lower = addBox(world, Vec3(0, 0, 0.5));
    const BodyId upper = addBox(world, Vec3(0, 0, 1.5));
    ASSERT_GT(stepUntilAsleep(world, upper, 600), 0);
    world.destroyBody(lower);
    EXPECT_TRUE(world.isAwake(upper));
    for (int i = 0; i < 60; ++i)
        ASSERT_TRUE(world.step().ok());
    EXPECT_NEAR(world.position(upper).z(), 0.5, 0.01) << "it fell to the ground";
}

TEST(Sleep, KinematicBodyWakesAndCarriesOnlyWhileItMoves) {
    World world;
    BodyDef platformDef;
    platformDef.type = BodyType::Kinematic;
    platformDef.position = Vec3(0, 0, -0.1);
    const BodyId platform = world.createBody(platformDef);
    world.createShape(platform, ShapeDef{.geometry = Box{Vec3(2, 2, 0.1)}});
    const BodyId box = addBox(world, Vec3(0, 0, 0.5));
    ASSERT_GT(stepUntilAsleep(world, box, 300), 0) << "a kinematic body at rest lets it sleep";
    EXPECT_TRUE(world.isAwake(platform));
    EXPECT_EQ(world.awakeBodyCount(), 1);

    // Lifted at 1 cm/s, slower than the sleep threshold: carried, so never asleep.
    world.setLinearVelocity(platform, Vec3(0, 0, 0.01));
    const Real z0 = world.position(box).z();
    for (int i = 0; i < 180; ++i) {
        ASSERT_TRUE(world.step().ok());
        ASSERT_TRUE(world.isAwake(box)) << "asleep at step " << i;
    }
    EXPECT_NEAR(world.position(box).z() - z0, 0.03, 2e-3);
    EXPECT_THROW(world.setAwake(platform, false), InvalidArgument);
}

TEST(Sleep, StaticBodyIsNeverAwake) {
    World world;
    const BodyId ground = addGround(world);
    EXPECT_FALSE(world.isAwake(ground));
    world.setAwake(ground, true);  // nothing to wake
    world.setAwake(ground, false);
    EXPECT_FALSE(world.isAwake(ground));
    EXPECT_EQ(world.awakeBodyCount(), 0);
}

// A pile that falls asleep, is partly woken and destroyed from, run twice: bitwise the same.
TEST(Sleep, SleepingIsDeterministic) {
    auto run = [] {
        World world;
        addGround(world);
        std::vector<BodyId> ids;
        for (int i = 0; i < 24; ++i) {
            BodyDef def;
            def.orientation = Quat(Eigen::AngleAxis<Real>(0.1 * i, Vec3(1, 2, 3).normalized()));
            def.position = Vec3((i % 3) * 0.7, ((i / 3) % 2) * 0.7, 0.4 + (i / 6) * 0.9);
            const BodyId id = world.createBody(def);
            if (i % 3 == 0) {
                world.createShape(id, ShapeDef{.geometry = Sphere{0.3}});
            } else {
                world.createShape(id, ShapeDef{.geometry = Box{Vec3(0.3, 0.25, 0.2)}});
            }
            ids.push_back(id);
        }
        int minAwake = world.awakeBodyCount();
        std::vector<Real> trace;
        for (int s = 0; s < 900; ++s) {
            if (s == 500)
                world.applyLinearImpulse(ids[4], Vec3(2, 0, 1), world.centerOfMass(ids[4]));
            if (s == 600)
                world.destroyBody(ids[10]);
            world.step();
            minAwake = std::min(minAwake, world.awakeBodyCount());
            trace.push_back(static_cast<Real>(world.awakeBodyCount()));
        }
        for (BodyId id : ids) {
            if (!world.isValid(id))
                continue;
            const std::vector<Real> state = stateOf(world, id);
            trace.insert(trace.end(), state.begin(), state.end());
        }
        EXPECT_LT(minAwake, 24) << "something fell asleep during the run";
        return trace;
    };
    EXPECT_TRUE(bitwiseEqual(run(), run()));
}

TEST(Sleep, BadSettingsAreRefused) {
    const Real nan = std::numeric_limits<Real>::quiet_NaN();
    const Real inf = std::numeric_limits<Real>::infinity();
    EXPECT_TRUE(contains(refusal([] { World w(WorldDef{.linearSleepVelocity = -0.1}); }),
                         "WorldDef.linearSleepVelocity"));
    EXPECT_TRUE(contains(refusal([&] { World w(WorldDef{.linearSleepVelocity = nan}); }),
                         "WorldDef.linearSleepVelocity"));
    EXPECT_TRUE(contains(refusal([] { World w(WorldDef{.angularSleepVelocity = -1}); }),
                         "WorldDef.angularSleepVelocity"));
    EXPECT_TRUE(contains(refusal([&] { World w(WorldDef{.angularSleepVelocity = inf}); }),
                         "WorldDef.angularSleepVelocity"));
    for (const Real bad : {0.0, -1.0, inf, nan}) {
        EXPECT_TRUE(contains(refusal([&] { World w(WorldDef{.timeToSleep = bad}); }),
                             "WorldDef.timeToSleep"))
            << bad;
    }
    // Zero thresholds are allowed: only bodies exactly at rest sleep.
    EXPECT_EQ(refusal([] { World w(WorldDef{.linearSleepVelocity = 0}); }), "");

    World world;
    EXPECT_TRUE(contains(refusal([&] {
                             world.createBody(
                                 BodyDef{.linearVelocity = Vec3(1, 0, 0), .awake = false});
                         }),
                         "BodyDef.awake = false"));
    EXPECT_TRUE(contains(
        refusal([&] { world.createBody(BodyDef{.type = BodyType::Kinematic, .awake = false}); }),
        "only a dynamic body"));
    EXPECT_TRUE(
        contains(refusal([&] { world.createBody(BodyDef{.allowSleep = false, .awake = false}); }),
                 "allowSleep"));
    EXPECT_EQ(world.bodyCount(), 0) << "refused definitions create nothing";
}

}  // namespace
}  // namespace tumble
