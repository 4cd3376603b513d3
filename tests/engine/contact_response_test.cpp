// The world's contact response end to end: shapes -> manifolds -> solver -> motion.

#include <gtest/gtest.h>

#include <cmath>

#include "refusal.h"
#include "testkit/scenes.h"
#include "tumble/world.h"

namespace tumble {
namespace {

using testkit::addGround;

TEST(ContactResponse, DroppedBoxComesToRestOnTheGround) {
    World world;
    addGround(world);
    BodyDef def;
    def.position = Vec3(0, 0, 1.5);
    def.orientation = Quat(Eigen::AngleAxis<Real>(0.3, Vec3(1, 1, 0).normalized()));
    const BodyId box = world.createBody(def);
    world.createShape(box, ShapeDef{.geometry = Box{}});
    for (int i = 0; i < 180; ++i)
        ASSERT_TRUE(world.step().ok());
    // Resting on a face: centre at half the height, less what the slop lets sink.
    const Real slop = world.settings().solver.slop;
    EXPECT_NEAR(world.position(box).z(), 0.5, slop + 1e-3);
    EXPECT_LT(world.linearVelocity(box).norm(), 1e-3);
    EXPECT_LT(world.angularVelocity(box).norm(), 1e-3);
    EXPECT_LE(world.solverStats().deepestPenetration, slop + 1e-3);
}

// The first apex, r + (H - r) e^2, at a coarse step: the bounce is placed at the time of impact
// within the step, on the parabola the integrator's positions follow, so the apex is right to
// O(h^2) (measured -0.27 % at h = 1/60, -0.02 % at 1/240). Taking the end-of-step speed as the
// impact speed gave +4.4 % at 1/60.
Real firstApex(Real h) {
    World world(WorldDef{.timeStep = h});
    addGround(world);
    BodyDef def;
    def.position = Vec3(0, 0, 1);
    const BodyId ball = world.createBody(def);
    ShapeDef shape{.geometry = Sphere{0.1}};
    shape.material.restitution = 0.8;
    world.createShape(ball, shape);
    bool bounced = false;
    for (int i = 0; i < static_cast<int>(3 / h); ++i) {
        world.step();
        const Real vz = world.linearVelocity(ball).z();
        if (vz > 0)
            bounced = true;
        if (bounced && vz <= 0)
            return world.position(ball).z();
    }
    return 0;
}

TEST(ContactResponse, SphereBouncesWithNewtonsRestitution) {
    const Real expected = 0.1 + 0.9 * 0.64;
    for (const Real h : {1.0 / 60, 1.0 / 240, 1.0 / 1000}) {
        const Real apex = firstApex(h);
        EXPECT_NEAR(apex, expected, 0.005 * expected) << "h = " << h;
        EXPECT_LE(apex, expected * 1.001) << "no energy created at the impact, h = " << h;
    }
}

// A ball (e = 1) strikes a row of touching balls: however the impulse spreads, no step may add
// kinetic energy. Approach speeds measured after other contacts' warm-start impulses had been
// applied once raised it from 0.26 J to 1.9 J.
TEST(ContactResponse, ElasticRowOfTouchingBallsCreatesNoEnergy) {
    World world(WorldDef{.gravity = Vec3::Zero(), .enableSleep = false});
    for (int i = 0; i < 5; ++i) {
        BodyDef def;
        def.position = Vec3(i == 0 ? -0.3 : 0.1 * i, 0, 0);
        def.linearVelocity = Vec3(i == 0 ? 1 : 0, 0, 0);
        const BodyId ball = world.createBody(def);
        ShapeDef shape{.geometry = Sphere{0.05}};
        shape.material.restitution = 1;
        shape.material.friction = 0;
        world.createShape(ball, shape);
    }
    const Real initial = world.kineticEnergy();
    for (int i = 0; i < 120; ++i) {
        ASSERT_TRUE(world.step().ok());
        ASSERT_LE(world.kineticEnergy(), initial * (1 + 1e-9)) << "step " << i;
    }
}

// Bad solver settings are refused where the world takes them, naming the field, and leave the
// world's settings as they were.
TEST(ContactResponse, BadSolverSettingsAreRefusedByTheWorld) {
    WorldDef def;
    def.solver.iterations = -1;
    EXPECT_TRUE(test::contains(test::refusal([&] { World{def}; }), "iterations"));

    World world;
    const SolverSettings before = world.settings().solver;
    SolverSettings bad = before;
    bad.relaxation = 2.5;
    EXPECT_TRUE(test::contains(test::refusal([&] { world.setSolverSettings(bad); }), "relaxation"));
    bad = before;
    bad.slop = -0.001;
    EXPECT_TRUE(test::contains(test::refusal([&] { world.setSolverSettings(bad); }), "slop"));
    bad = before;
    bad.relaxIterations = -2;
    EXPECT_TRUE(
        test::contains(test::refusal([&] { world.setSolverSettings(bad); }), "relaxIterations"));
    bad = before;
    bad.linkIterations = 0;
    EXPECT_TRUE(
        test::contains(test::refusal([&] { world.setSolverSettings(bad); }), "linkIterations"));
    bad = before;
    bad.linkRelaxIterations = -1;
    EXPECT_TRUE(test::contains(test::refusal([&] { world.setSolverSettings(bad); }),
                               "linkRelaxIterations"));
    EXPECT_EQ(world.settings().solver.iterations, before.iterations);
    EXPECT_EQ(world.settings().solver.slop, before.slop);
    EXPECT_EQ(world.settings().solver.relaxIterations, before.relaxIterations);
    EXPECT_EQ(world.settings().solver.linkIterations, before.linkIterations);
}

// A solve of rigid contacts runs the contacts' budget; one holding a link -- a spring, a joint --
// runs the links' where it is the larger, and the contacts' where that is (SolverSettings::
// linkIterations). The physics the links' budget buys is asserted where it matters:
// Joints.HingeLimitStopsTheSwing and ThreadRestThinWall.LandsWithoutKicks fail at 8 + 4.
TEST(ContactResponse, ASolveWithLinksRunsTheLinksBudget) {
    const auto sweeps = [](SolverSettings settings, bool spring, bool joint) {
        WorldDef worldDef;
        worldDef.enableSleep = false;
        worldDef.solver = settings;
        World world(worldDef);
        const BodyId box = world.createBody(BodyDef{.position = Vec3(0, 0, 0.49)});
        world.createShape(box, ShapeDef{.geometry = Box{Vec3(0.5, 0.5, 0.5)}});
        const BodyId ground = world.createBody(BodyDef{.type = BodyType::Static});
        world.createShape(ground, ShapeDef{.geometry = HalfSpace{}});
        const BodyId bob = world.createBody(BodyDef{.position = Vec3(3, 0, 2)});
        world.createShape(bob, ShapeDef{.geometry = Sphere{0.1}});
        if (spring) {
            SpringDef def;
            def.bodyA = bob;
            def.localAnchorB = Vec3(3, 0, 3);
            def.stiffness = 100;
            world.createSpring(def);
        }
        if (joint) {
            world.createJoint(JointDef{
                .type = JointType::Ball, .bodyA = bob, .bodyB = {}, .anchor = Vec3(3, 0, 3)});
        }
        EXPECT_TRUE(world.step().ok());
        return world.solverStats().iterations;
    };
    // Contacts cheaper than links (the defaults are 10 + 8 against 10 + 10).
    SolverSettings cheap;
    cheap.iterations = 8;
    cheap.relaxIterations = 4;
    EXPECT_EQ(sweeps(cheap, false, false), 8);
    EXPECT_EQ(sweeps(cheap, true, false), cheap.linkIterations);
    EXPECT_EQ(sweeps(cheap, false, true), cheap.linkIterations);
    SolverSettings more = cheap;
    more.iterations = 15;  // the contacts' budget, larger, is the budget of every solve
    EXPECT_EQ(sweeps(more, false, false), 15);
    EXPECT_EQ(sweeps(more, true, false), 15);
    SolverSettings fewer = cheap;
    fewer.linkIterations = 3;  // links cheaper than contacts: the contacts' budget
    EXPECT_EQ(sweeps(fewer, true, true), 8);
}

}  // namespace
}  // namespace tumble
