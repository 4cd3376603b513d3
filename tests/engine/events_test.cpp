// Events: contact begin and end, impacts with their impulse, joint breaks, sleep and wake --
// each reported exactly once, readable after the step and gone after the next.

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <vector>

#include "refusal.h"
#include "testkit/scenes.h"
#include "tumble/world.h"

namespace tumble {
namespace {

using test::contains;
using test::refusal;

constexpr Real kGravity = 9.81;

using testkit::addBox;  // a unit cube
using testkit::addGround;
using testkit::quietWorld;

// Everything the steps reported, gathered step by step.
struct Tally {
    std::vector<ContactEvent> begins;
    std::vector<ContactEvent> ends;
    std::vector<ImpactEvent> impacts;
    std::vector<JointBreakEvent> breaks;
    std::vector<SleepEvent> sleeps;

    void take(const World& world) {
        begins.insert(begins.end(), world.contactBeginEvents().begin(),
                      world.contactBeginEvents().end());
        ends.insert(ends.end(), world.contactEndEvents().begin(), world.contactEndEvents().end());
        impacts.insert(impacts.end(), world.impactEvents().begin(), world.impactEvents().end());
        breaks.insert(breaks.end(), world.jointBreakEvents().begin(),
                      world.jointBreakEvents().end());
        sleeps.insert(sleeps.end(), world.sleepEvents().begin(), world.sleepEvents().end());
    }
};

Tally run(World& world, int steps) {
    Tally tally;
    for (int i = 0; i < steps; ++i) {
        EXPECT_TRUE(world.step().ok());
        tally.take(world);
    }
    return tally;
}

// A box dropped 1 m flat onto the ground: one begin, one impact, no end. Without restitution
// the contact takes the box's momentum plus its weight over the two steps the speculative
// contact stops it in (see ImpactEvent): J = m (v + 2 g h), v the approach speed at the start
// of the step the impulse began. That identity is momentum balance, so it holds to the
// solver's convergence (1e-6 relative asked).
//
// Which v: semi-implicit Euler falling from rest has v_n = n g h after a drop of
// s_n = g h^2 n (n + 1) / 2, and the impulse begins in the step k that would carry the box
// past the ground, s_k <= d < s_(k+1). Solving for v_k = k g h with w = sqrt((g h / 2)^2 + 2 g d)
// (the exact impact speed sqrt(2 g d) to O(h^2)): w - 3 g h / 2 < v_k <= w - g h / 2. So the
// impulse lies between m (w + g h / 2) and m (w + 3 g h / 2).
TEST(Events, DroppedBoxBeginsOnceAndImpactsOnceWithItsMomentum) {
    for (const Real h : {1.0 / 60.0, 1.0 / 240.0}) {
        SCOPED_TRACE(h);
        World world(quietWorld(h));
        const BodyId ground = addGround(world);
        const Real drop = 1;
        const BodyId box = addBox(world, Vec3(0, 0, 0.5 + drop));
        const Real mass = world.massProperties(box).mass;
        const Tally tally = run(world, static_cast<int>(std::lround(2 / h)));

        ASSERT_EQ(tally.begins.size(), 1u);
        EXPECT_TRUE((tally.begins[0].bodyA == ground && tally.begins[0].bodyB == box) ||
                    (tally.begins[0].bodyA == box && tally.begins[0].bodyB == ground));
        EXPECT_TRUE(tally.ends.empty());
        ASSERT_EQ(tally.impacts.size(), 1u);
        const ImpactEvent& impact = tally.impacts[0];
        const Real gh = kGravity * h;
        const Real w = std::sqrt(gh * gh / 4 + 2 * kGravity * drop);
        EXPECT_GT(impact.approachSpeed, w - 1.5 * gh);
        EXPECT_LE(impact.approachSpeed, w - 0.5 * gh + 1e-12);
        EXPECT_NEAR(impact.normalImpulse, mass * (impact.approachSpeed + 2 * gh), 1e-6 * mass * w);
        EXPECT_GT(impact.normalImpulse, mass * (w + 0.5 * gh));
        EXPECT_LE(impact.normalImpulse, mass * (w + 1.5 * gh) * (1 + 1e-6));
        EXPECT_NEAR(std::abs(impact.normal.z()), 1, 1e-9);
        // In the gap the box closed in that step.
        EXPECT_GE(impact.point.z(), -1e-9);
        EXPECT_LE(impact.point.z(), (impact.approachSpeed + gh) * h);
        EXPECT_NEAR(impact.point.x(), 0, 1e-6);  // centre of pressure under the centre
    }
}

// Lifting the resting box (an upward velocity) ends its contact exactly once; it comes back
// down and begins again, with a second impact.
TEST(Events, LiftedBoxEndsOnce) {
    const Real h = 1.0 / 60.0;
    World world(quietWorld(h));
    addGround(world);
    const BodyId box = addBox(world, Vec3(0, 0, 0.5));  // resting
    run(world, 30);
    world.setLinearVelocity(box, Vec3(0, 0, 3));
    const Tally rise = run(world, 15);  // 0.25 s: still rising (apex at 0.31 s)
    EXPECT_EQ(rise.ends.size(), 1u);
    EXPECT_TRUE(rise.begins.empty());
    EXPECT_TRUE(rise.impacts.empty());
    const Tally fall = run(world, 60);
    EXPECT_EQ(fall.begins.size(), 1u);
    EXPECT_EQ(fall.impacts.size(), 1u);
    EXPECT_TRUE(fall.ends.empty());
}

// A teleport away ends the contact once (the pair separates in the broadphase).
TEST(Events, TeleportedBoxEndsOnce) {
    World world(quietWorld(1.0 / 60.0));
    addGround(world);
    const BodyId box = addBox(world, Vec3(0, 0, 0.5));
    run(world, 10);
    world.setTransform(box, Vec3(0, 0, 5), Quat::Identity());
    world.setLinearVelocity(box, Vec3::Zero());
    const Tally tally = run(world, 5);
    EXPECT_EQ(tally.ends.size(), 1u);
    EXPECT_TRUE(tally.begins.empty());
}

// Destroying a touching box between steps ends its contact; the event comes with the next
// step and names the destroyed ids.
TEST(Events, DestroyedShapeEndsItsContactAtTheNextStep) {
    World world(quietWorld(1.0 / 60.0));
    addGround(world);
    const BodyId box = addBox(world, Vec3(0, 0, 0.5));
    run(world, 10);
    world.destroyBody(box);
    EXPECT_TRUE(world.contactEndEvents().empty());  // not published before the step
    ASSERT_TRUE(world.step().ok());
    ASSERT_EQ(world.contactEndEvents().size(), 1u);
    const ContactEvent& end = world.contactEndEvents()[0];
    EXPECT_TRUE(end.bodyA == box || end.bodyB == box);
    EXPECT_FALSE(world.isValid(box));
}

// Events are the last step's only: a quiet step publishes empty arrays.
TEST(Events, ClearedByTheNextStep) {
    World world(quietWorld(1.0 / 60.0));
    addGround(world);
    addBox(world, Vec3(0, 0, 0.5));
    ASSERT_TRUE(world.step().ok());
    EXPECT_EQ(world.contactBeginEvents().size(), 1u);
    ASSERT_TRUE(world.step().ok());
    EXPECT_TRUE(world.contactBeginEvents().empty());
    EXPECT_TRUE(world.contactEndEvents().empty());
    EXPECT_TRUE(world.impactEvents().empty());
}

// Resting and sliding contacts make no impacts; an infinite threshold turns impacts off.
TEST(Events, NoImpactsFromRestingOrSlidingOrWhenDisabled) {
    World world(quietWorld(1.0 / 60.0));
    addGround(world);
    const BodyId box = addBox(world, Vec3(0, 0, 0.5));
    world.setLinearVelocity(box, Vec3(3, 0, 0));
    const Tally tally = run(world, 120);
    EXPECT_TRUE(tally.impacts.empty());

    WorldDef quiet = quietWorld(1.0 / 60.0);
    quiet.impactSpeedThreshold = std::numeric_limits<Real>::infinity();
    World silent(quiet);
    addGround(silent);
    addBox(silent, Vec3(0, 0, 1.5));
    const Tally dropped = run(silent, 120);
    EXPECT_TRUE(dropped.impacts.empty());
    EXPECT_EQ(dropped.begins.size(), 1u);

    WorldDef bad;
    bad.impactSpeedThreshold = 0;
    EXPECT_TRUE(contains(refusal([&] { World w(bad); }), "WorldDef.impactSpeedThreshold"));
}

// A breakable joint breaks once, reported in the step it broke with the reaction that broke
// it, and never again.
TEST(Events, JointBreakReportedOnce) {
    World world(quietWorld(1.0 / 60.0));
    BodyDef def;
    def.position = Vec3(0, 0, -1);
    def.mass.mass = 1;
    def.mass.inertia = Mat3::Identity() * 0.1;
    const BodyId body = world.createBody(def);
    const JointId joint = world.createJoint(JointDef{.type = JointType::Ball,
                                                     .bodyA = body,
                                                     .bodyB = {},
                                                     .anchor = Vec3::Zero(),
                                                     .breakForce = 5});
    ASSERT_TRUE(world.step().ok());
    ASSERT_EQ(world.jointBreakEvents().size(), 1u);
    const JointBreakEvent& event = world.jointBreakEvents()[0];
    EXPECT_EQ(event.joint, joint);
    EXPECT_EQ(event.bodyA, body);
    EXPECT_TRUE(event.bodyB.isNull());
    EXPECT_GT(event.force.norm(), 5);
    const Tally later = run(world, 30);
    EXPECT_TRUE(later.breaks.empty());
}

// A box settles and its island sleeps: one sleep event. A push between steps wakes it (the
// wake is published by the next step); a box dropped on a sleeping one wakes it in the step.
TEST(Events, SleepAndWake) {
    World world;
    addGround(world);
    const BodyId box = addBox(world, Vec3(0, 0, 0.5));
    const Tally settle = run(world, 120);
    ASSERT_FALSE(world.isAwake(box));
    ASSERT_EQ(settle.sleeps.size(), 1u);
    EXPECT_EQ(settle.sleeps[0].body, box);
    EXPECT_TRUE(settle.sleeps[0].asleep);

    world.applyLinearImpulse(box, Vec3(0.1, 0, 0), world.centerOfMass(box));
    EXPECT_TRUE(world.sleepEvents().empty());
    ASSERT_TRUE(world.step().ok());
    ASSERT_EQ(world.sleepEvents().size(), 1u);
    EXPECT_EQ(world.sleepEvents()[0].body, box);
    EXPECT_FALSE(world.sleepEvents()[0].asleep);

    run(world, 120);
    ASSERT_FALSE(world.isAwake(box));
    addBox(world, Vec3(0, 0, 2));
    const Tally hit = run(world, 60);
    int wakes = 0;
    for (const SleepEvent& e : hit.sleeps)
        wakes += (e.body == box && !e.asleep) ? 1 : 0;
    EXPECT_EQ(wakes, 1);
}

// The same scene gives the same events, in the same order.
TEST(Events, Deterministic) {
    const auto record = [] {
        World world;
        addGround(world);
        for (int i = 0; i < 5; ++i)
            addBox(world, Vec3(0.3 * i, 0.1 * i, 0.6 + 1.1 * i));
        std::vector<Real> trace;
        for (int step = 0; step < 300; ++step) {
            EXPECT_TRUE(world.step().ok());
            for (const ContactEvent& e : world.contactBeginEvents())
                trace.push_back(e.shapeA.index * 1000.0 + e.shapeB.index);
            for (const ImpactEvent& e : world.impactEvents())
                trace.push_back(e.normalImpulse);
            for (const SleepEvent& e : world.sleepEvents())
                trace.push_back(e.body.index + (e.asleep ? 0.5 : 0));
        }
        return trace;
    };
    const std::vector<Real> first = record();
    EXPECT_FALSE(first.empty());
    EXPECT_EQ(first, record());
}

}  // namespace
}  // namespace tumble
