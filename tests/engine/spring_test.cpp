// Spring-dampers (explicit and implicit) and drag: the physics each promises, the refusals, the
// report of an unstable explicit spring, sleeping and determinism.

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <numbers>
#include <string>
#include <vector>

#include "refusal.h"
#include "testkit/scenes.h"
#include "tumble/world.h"

namespace tumble {
namespace {

using test::contains;
using test::refusal;

MassProperties pointMass(Real m) {
    MassProperties p;
    p.mass = m;
    p.inertia = Mat3::Identity() * 1e-3 * m;
    return p;
}

BodyId addMass(World& world, const Vec3& position, Real m = 1,
               const Vec3& velocity = Vec3::Zero()) {
    BodyDef def;
    def.position = position;
    def.linearVelocity = velocity;
    def.mass = pointMass(m);
    return world.createBody(def);
}

using testkit::quietWorld;
using testkit::weightlessWorld;

SpringId hang(World& world, BodyId body, Real k, Real c, SpringFormulation f, Real rest = 1) {
    SpringDef def;
    def.bodyA = body;
    def.localAnchorB = Vec3::Zero();  // world point: the origin
    def.restLength = rest;
    def.stiffness = k;
    def.damping = c;
    def.formulation = f;
    return world.createSpring(def);
}

class BothFormulations : public ::testing::TestWithParam<SpringFormulation> {};

// A damped mass hanging on a spring settles where k (L - L0) = m g, and the reported tension is
// the weight. Implicit Euler's fixed point is exact; the explicit spring's too.
TEST_P(BothFormulations, HangingMassSettlesAtStaticStretch) {
    World world(quietWorld(1.0 / 240.0));
    const BodyId body = addMass(world, Vec3(0, 0, -1), 2);
    const SpringId spring = hang(world, body, 400, 20, GetParam());
    for (int i = 0; i < 240 * 10; ++i)
        ASSERT_TRUE(world.step().ok());
    const SpringState s = world.springState(spring);
    EXPECT_NEAR(s.length, 1 + 2 * 9.81 / 400, 1e-9);
    EXPECT_NEAR(s.tension, 2 * 9.81, 1e-6);
    EXPECT_FALSE(s.slack);
    EXPECT_NEAR(world.position(body).z(), -(1 + 2 * 9.81 / 400), 1e-9);
}

// Two free bodies joined by a spring, anchors off their centres: no external force, so the total
// momentum stays what it was, to rounding.
TEST_P(BothFormulations, SpringBetweenBodiesConservesMomentum) {
    World world(weightlessWorld());
    const BodyId a = addMass(world, Vec3(0, 0, 0), 1, Vec3(0.3, 0.1, 0));
    const BodyId b = addMass(world, Vec3(1.5, 0, 0), 3, Vec3(-0.2, 0, 0.4));
    SpringDef def;
    def.bodyA = a;
    def.bodyB = b;
    def.localAnchorA = Vec3(0.1, 0.05, 0);
    def.localAnchorB = Vec3(-0.1, 0, 0.02);
    def.restLength = 1;
    def.stiffness = 50;
    def.damping = 0.5;
    def.formulation = GetParam();
    world.createSpring(def);
    const Vec3 p0 = world.linearVelocity(a) + 3 * world.linearVelocity(b);
    for (int i = 0; i < 600; ++i)
        ASSERT_TRUE(world.step().ok());
    const Vec3 p1 = world.linearVelocity(a) + 3 * world.linearVelocity(b);
    EXPECT_LT((p1 - p0).norm(), 1e-12);
    EXPECT_GT(world.angularVelocity(a).norm(), 0) << "an off-centre anchor turns the body";
}

// A slack thread pushes nothing: a mass moving inside the rest length keeps its velocity and the
// element reports itself slack.
TEST_P(BothFormulations, TensionOnlyThreadPushesNothing) {
    World world(weightlessWorld());
    const BodyId body = addMass(world, Vec3(0.5, 0, 0), 1, Vec3(-0.2, 0.1, 0));
    SpringDef def;
    def.bodyA = body;
    def.restLength = 1;
    def.stiffness = 1000;
    def.damping = 10;
    def.tensionOnly = true;
    def.formulation = GetParam();
    const SpringId spring = world.createSpring(def);
    for (int i = 0; i < 60; ++i)
        ASSERT_TRUE(world.step().ok());
    EXPECT_EQ(world.linearVelocity(body), Vec3(-0.2, 0.1, 0));
    EXPECT_TRUE(world.springState(spring).slack);
    EXPECT_EQ(world.springState(spring).tension, 0);
}

INSTANTIATE_TEST_SUITE_P(Spring, BothFormulations,
                         ::testing::Values(SpringFormulation::Explicit, SpringFormulation::Implicit,
                                           SpringFormulation::BackwardEuler));

TEST(Spring, NumericalDampingOutsideItsRangeIsRefused) {
    World world(weightlessWorld());
    const BodyId body = addMass(world, Vec3(1.1, 0, 0));
    SpringDef def;
    def.bodyA = body;
    def.stiffness = 10;
    for (const Real bad : {-0.1, 1.5, std::numeric_limits<Real>::quiet_NaN()}) {
        def.numericalDamping = bad;
        try {
            world.createSpring(def);
            ADD_FAILURE() << "numericalDamping = " << bad << " was accepted";
        } catch (const InvalidArgument& e) {
            EXPECT_NE(std::string(e.what()).find("SpringDef.numericalDamping"), std::string::npos);
        }
    }
}

// Implicit at omega h = 100 (k = 10^4 N/m, m = 1 kg, h = 1 s): bounded, and the energy only
// falls (implicit Euler dissipates what the step cannot resolve).
TEST(Spring, ImplicitIsStableFarBeyondTheExplicitLimit) {
    World world(weightlessWorld(1.0));
    const BodyId body = addMass(world, Vec3(1.1, 0, 0));
    hang(world, body, 1e4, 0, SpringFormulation::Implicit);
    Real energy = world.kineticEnergy() + world.springPotentialEnergy();
    for (int i = 0; i < 200; ++i) {
        ASSERT_TRUE(world.step().ok());
        const Real now = world.kineticEnergy() + world.springPotentialEnergy();
        EXPECT_LE(now, energy * (1 + 1e-12));
        energy = now;
    }
    EXPECT_LT(std::abs(world.position(body).x() - 1), 1e-3);
}

// Resolved implicit oscillation (omega h = 0.05): the period is 2 pi / omega to O(h^2) plus
// implicit Euler's O(h) damping, which shows as a slow decay.
TEST(Spring, ImplicitOscillatesWithTheSpringPeriod) {
    const Real h = 0.005;
    World world(weightlessWorld(h));
    const BodyId body = addMass(world, Vec3(1.01, 0, 0));
    hang(world, body, 100, 0, SpringFormulation::Implicit);  // omega = 10 rad/s
    std::vector<Real> crossings;
    Real previous = world.position(body).x() - 1;
    for (int i = 1; i <= 2000; ++i) {
        ASSERT_TRUE(world.step().ok());
        const Real x = world.position(body).x() - 1;
        if (previous > 0 && x <= 0)
            crossings.push_back(h * (i - 1 + previous / (previous - x)));
        previous = x;
    }
    ASSERT_GE(crossings.size(), 10u);
    const Real period =
        (crossings.back() - crossings.front()) / static_cast<Real>(crossings.size() - 1);
    EXPECT_NEAR(period, 2 * std::numbers::pi / 10, 0.01 * 2 * std::numbers::pi / 10);
}

// E A / L0, and its refusals.
TEST(Spring, AxialStiffnessFromMaterial) {
    EXPECT_DOUBLE_EQ(axialStiffness(2e9, 1e-6, 0.5), 4000);
    EXPECT_TRUE(contains(refusal([] { axialStiffness(0, 1e-6, 1); }), "youngsModulus"));
    EXPECT_TRUE(contains(refusal([] { axialStiffness(1e9, -1, 1); }), "area"));
    EXPECT_TRUE(contains(refusal([] { axialStiffness(1e9, 1e-6, 0); }), "restLength"));
}

TEST(Spring, BadDefinitionsAreRefusedAndCreateNothing) {
    World world(weightlessWorld());
    const BodyId a = addMass(world, Vec3::Zero());
    const BodyId b = addMass(world, Vec3(1, 0, 0));
    const BodyId dead = addMass(world, Vec3(2, 0, 0));
    world.destroyBody(dead);
    SpringDef good;
    good.bodyA = a;
    good.bodyB = b;
    good.stiffness = 10;
    const Real nan = std::numeric_limits<Real>::quiet_NaN();
    auto refused = [&](auto edit, const std::string& part) {
        SpringDef def = good;
        edit(def);
        EXPECT_TRUE(contains(refusal([&] { world.createSpring(def); }), part));
        EXPECT_EQ(world.springCount(), 0);
    };
    refused([](SpringDef& d) { d.stiffness = -1; }, "stiffness");
    refused([](SpringDef& d) { d.damping = -0.1; }, "damping");
    refused([](SpringDef& d) { d.restLength = 0; }, "restLength");
    refused([](SpringDef& d) { d.restLength = -1; }, "restLength");
    refused([&](SpringDef& d) { d.stiffness = nan; }, "stiffness");
    refused([&](SpringDef& d) { d.localAnchorA.x() = nan; }, "localAnchorA");
    refused([&](SpringDef& d) { d.bodyA = BodyId{}; }, "bodyA is null");
    refused([&](SpringDef& d) { d.bodyA = dead; }, "bodyA");
    refused([&](SpringDef& d) { d.bodyB = dead; }, "bodyB");
    refused([&](SpringDef& d) { d.bodyB = a; }, "same body");
    EXPECT_NO_THROW(world.createSpring(good));
}

TEST(Spring, BadDragIsRefused) {
    World world(weightlessWorld());
    const BodyId a = addMass(world, Vec3::Zero());
    EXPECT_TRUE(contains(refusal([&] { world.setDrag(a, {.linear = -1}); }), "Drag.linear"));
    EXPECT_TRUE(contains(refusal([&] { world.setDrag(a, {.quadratic = -1}); }), "Drag.quadratic"));
    Drag bad;
    bad.linear = 1;
    bad.projection(0, 0) = std::numeric_limits<Real>::infinity();
    EXPECT_TRUE(contains(refusal([&] { world.setDrag(a, bad); }), "projection"));
    EXPECT_EQ(world.drag(a).linear, 0);
}

// Ids: a destroyed body takes its springs with it; their ids are refused afterwards.
TEST(Spring, DestroyingABodyDestroysItsSprings) {
    World world(weightlessWorld());
    const BodyId a = addMass(world, Vec3::Zero());
    const BodyId b = addMass(world, Vec3(1, 0, 0));
    const BodyId c = addMass(world, Vec3(2, 0, 0));
    SpringDef def;
    def.bodyA = a;
    def.bodyB = b;
    const SpringId ab = world.createSpring(def);
    def.bodyA = b;
    def.bodyB = c;
    const SpringId bc = world.createSpring(def);
    def.bodyA = c;
    def.bodyB = BodyId{};
    const SpringId cWorld = world.createSpring(def);
    world.destroyBody(b);
    EXPECT_FALSE(world.isValid(ab));
    EXPECT_FALSE(world.isValid(bc));
    EXPECT_TRUE(world.isValid(cWorld));
    EXPECT_EQ(world.springCount(), 1);
    EXPECT_TRUE(contains(refusal([&] { world.springState(ab); }), "SpringId"));
    EXPECT_TRUE(world.step().ok());
}

// Drag restricted to the horizontal, as in the study: the fall is untouched, the horizontal
// speed decays as (1 - h b / m)^n (explicit drag).
TEST(Drag, HorizontalOnlyLeavesTheFallAlone) {
    const Real h = 0.01;
    World world(quietWorld(h));
    const BodyId body = addMass(world, Vec3::Zero(), 2, Vec3(3, 0, 0));
    Drag drag;
    drag.linear = 0.5;
    drag.projection = Vec3(1, 1, 0).asDiagonal();
    world.setDrag(body, drag);
    for (int i = 0; i < 100; ++i)
        ASSERT_TRUE(world.step().ok());
    EXPECT_NEAR(world.linearVelocity(body).z(), -9.81 * 100 * h, 1e-12);
    EXPECT_NEAR(world.linearVelocity(body).x(), 3 * std::pow(1 - h * 0.5 / 2, 100), 1e-12);
}

// Quadratic drag while falling: terminal speed sqrt(m g / b2).
TEST(Drag, QuadraticDragReachesTerminalSpeed) {
    World world(quietWorld(0.01));
    const BodyId body = addMass(world, Vec3::Zero(), 0.5);
    world.setDrag(body, {.quadratic = 0.2});
    for (int i = 0; i < 2000; ++i)
        ASSERT_TRUE(world.step().ok());
    EXPECT_NEAR(world.linearVelocity(body).z(), -std::sqrt(0.5 * 9.81 / 0.2), 1e-9);
}

// An explicit spring far past its limit (omega h = 20) blows up; the step that goes non-finite is
// rolled back and names the body and the spring that drove it.
TEST(Spring, UnstableExplicitSpringIsNamed) {
    World world(weightlessWorld(0.1));
    const BodyId quiet = addMass(world, Vec3(5, 0, 0));
    hang(world, quiet, 1, 0, SpringFormulation::Explicit, 4.9);  // stable, nearby
    const BodyId body = addMass(world, Vec3(1.1, 0, 0));
    hang(world, body, 0.1, 0, SpringFormulation::Explicit);  // weak, also on the body
    const SpringId culprit = hang(world, body, 4e4, 0, SpringFormulation::Explicit);
    StepStatus status;
    int steps = 0;
    for (; steps < 10000 && status.ok(); ++steps)
        status = world.step();
    ASSERT_EQ(status.code, StepStatus::Code::NonFiniteState);
    EXPECT_EQ(status.body, body);
    EXPECT_EQ(status.spring, culprit);
    EXPECT_EQ(world.stepCount(), static_cast<std::uint64_t>(steps - 1)) << "rolled back";
    EXPECT_TRUE(world.position(body).allFinite());
    EXPECT_TRUE(std::isfinite(world.springState(culprit).tension));
}

// Springs join islands: two bodies on a spring fall asleep together, and pushing one wakes the
// other.
TEST(Spring, SpringJoinsIslands) {
    WorldDef settings = weightlessWorld();
    settings.enableSleep = true;
    World world(settings);
    const BodyId a = addMass(world, Vec3::Zero());
    const BodyId b = addMass(world, Vec3(1, 0, 0));
    SpringDef def;
    def.bodyA = a;
    def.bodyB = b;
    def.stiffness = 10;
    def.damping = 1;
    world.createSpring(def);
    for (int i = 0; i < 60; ++i)
        world.step();
    EXPECT_FALSE(world.isAwake(a));
    EXPECT_FALSE(world.isAwake(b));
    world.applyForceToCenter(a, Vec3(10, 0, 0));
    world.step();
    EXPECT_TRUE(world.isAwake(b)) << "the spring carries the push";
    EXPECT_GT(world.linearVelocity(b).x(), 0);
}

// The same string, built twice, steps to bitwise the same state.
TEST(Spring, Deterministic) {
    auto run = [](SpringFormulation f) {
        World world(quietWorld(1.0 / 60.0));
        BodyId previous;
        std::vector<BodyId> masses;
        for (int i = 1; i <= 20; ++i) {
            const BodyId body = addMass(world, Vec3(0.1 * i, 0, 0.01 * std::sin(i)), 0.01);
            SpringDef def;
            def.bodyA = body;
            def.bodyB = previous;
            def.localAnchorB = previous.isNull() ? Vec3::Zero() : Vec3::Zero();
            def.restLength = 0.1;
            def.stiffness = 50;
            def.damping = 0.01;
            def.tensionOnly = true;
            def.formulation = f;
            world.createSpring(def);
            previous = body;
            masses.push_back(body);
        }
        for (int i = 0; i < 300; ++i)
            world.step();
        std::vector<Real> out;
        for (const BodyId m : masses) {
            for (int k = 0; k < 3; ++k)
                out.push_back(world.position(m)(k));
        }
        return out;
    };
    for (const SpringFormulation f : {SpringFormulation::Explicit, SpringFormulation::Implicit}) {
        const std::vector<Real> first = run(f);
        const std::vector<Real> second = run(f);
        ASSERT_EQ(first.size(), second.size());
        for (std::size_t i = 0; i < first.size(); ++i)
            EXPECT_EQ(first[i], second[i]);
    }
}

}  // namespace
}  // namespace tumble
