#include "tumble/world.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <limits>
#include <numbers>
#include <vector>

#include "testkit/scenes.h"
#include "tumble/core/error.h"

namespace tumble {
namespace {

WorldDef zeroGravity() {
    return WorldDef{.gravity = Vec3::Zero()};
}

TEST(World, IdsStayValidUntilDestroyedAndAreNeverReused) {
    World world;
    const BodyId a = world.createBody({});
    const BodyId b = world.createBody({});
    EXPECT_TRUE(world.isValid(a));
    EXPECT_FALSE(world.isValid(BodyId{}));
    world.destroyBody(a);
    EXPECT_FALSE(world.isValid(a));
    EXPECT_TRUE(world.isValid(b));
    const BodyId c = world.createBody({});
    EXPECT_EQ(c.index, a.index) << "the freed slot is reused";
    EXPECT_NE(c.generation, a.generation) << "with a new generation";
    EXPECT_FALSE(world.isValid(a));
    EXPECT_THROW(world.position(a), InvalidArgument);
    EXPECT_THROW(world.destroyBody(a), InvalidArgument);
    EXPECT_EQ(world.bodyCount(), 2);
}

TEST(World, DestroyingMovesNoOtherBody) {
    World world;
    std::vector<BodyId> ids;
    for (int i = 0; i < 5; ++i) {
        BodyDef def;
        def.position = Vec3(i, 0, 0);
        def.userData = static_cast<std::uint64_t>(i);
        ids.push_back(world.createBody(def));
    }
    world.destroyBody(ids[1]);
    for (int i : {0, 2, 3, 4}) {
        EXPECT_EQ(world.position(ids[i]).x(), i);
        EXPECT_EQ(world.userData(ids[i]), static_cast<std::uint64_t>(i));
    }
}

TEST(World, StaticBodyNeverMovesAndKinematicIgnoresForces) {
    World world;
    BodyDef staticDef;
    staticDef.type = BodyType::Static;
    staticDef.position = Vec3(1, 2, 3);
    const BodyId ground = world.createBody(staticDef);

    BodyDef kinematicDef;
    kinematicDef.type = BodyType::Kinematic;
    kinematicDef.linearVelocity = Vec3(1, 0, 0);
    kinematicDef.angularVelocity = Vec3(0, 0, 1);
    const BodyId platform = world.createBody(kinematicDef);

    for (int i = 0; i < 60; ++i) {
        world.applyForceToCenter(ground, Vec3(100, 0, 0));
        world.applyForceToCenter(platform, Vec3(0, 100, 0));
        world.step();
    }
    EXPECT_EQ(world.position(ground), Vec3(1, 2, 3));
    EXPECT_NEAR(world.position(platform).x(), 1.0, 1e-12);
    EXPECT_NEAR(world.position(platform).y(), 0.0, 1e-12);
    EXPECT_NEAR(world.position(platform).z(), 0.0, 1e-12)
        << "gravity does not act on kinematic bodies";
    const Quat expected(Eigen::AngleAxis<Real>(1.0, Vec3::UnitZ()));
    EXPECT_NEAR(world.orientation(platform).angularDistance(expected), 0, 1e-12);
    EXPECT_THROW(world.setLinearVelocity(ground, Vec3(1, 0, 0)), InvalidArgument);
}

TEST(World, ForceAtPointGivesForceAndTorqueForOneStepOnly) {
    World world(zeroGravity());
    BodyDef def;
    def.mass.mass = 2;
    def.mass.inertia = Mat3::Identity();
    const BodyId body = world.createBody(def);
    const Real h = world.settings().timeStep;
    world.applyForce(body, Vec3(0, 4, 0), Vec3(1, 0, 0));
    world.step();
    EXPECT_TRUE(world.linearVelocity(body).isApprox(Vec3(0, 2 * h, 0)));
    EXPECT_TRUE(world.angularVelocity(body).isApprox(Vec3(0, 0, 4 * h)));
    const Vec3 v = world.linearVelocity(body);
    world.step();
    EXPECT_EQ(world.linearVelocity(body), v) << "forces are cleared after the step";
}

TEST(World, ImpulseAtPointChangesMomentumAtOnce) {
    World world(zeroGravity());
    BodyDef def;
    def.mass.mass = 4;
    def.mass.inertia = Vec3(1, 2, 2).asDiagonal();
    def.position = Vec3(5, 0, 0);
    const BodyId body = world.createBody(def);
    world.applyLinearImpulse(body, Vec3(0, 0, 8), Vec3(5, 1, 0));
    EXPECT_TRUE(world.linearVelocity(body).isApprox(Vec3(0, 0, 2)));
    // Angular momentum = r x p = (0,1,0) x (0,0,8) = (8,0,0).
    EXPECT_TRUE(world.angularMomentum(body).isApprox(Vec3(8, 0, 0)));
}

TEST(World, OffsetCentreOfMassKeepsTheOriginAsThePose) {
    World world(zeroGravity());
    BodyDef def;
    def.position = Vec3(1, 0, 0);
    def.mass.localCenter = Vec3(0, 0.5, 0);
    def.angularVelocity = Vec3(0, 0, 1);
    const BodyId body = world.createBody(def);
    EXPECT_TRUE(world.centerOfMass(body).isApprox(Vec3(1, 0.5, 0)));
    // Spinning about the centre of mass: after a quarter turn the origin has swung around it.
    const int steps = 600;
    world.setTimeStep(std::numbers::pi / 2 / steps);
    for (int i = 0; i < steps; ++i)
        world.step();
    EXPECT_TRUE(world.centerOfMass(body).isApprox(Vec3(1, 0.5, 0)));
    EXPECT_NEAR((world.position(body) - Vec3(1.5, 0.5, 0)).norm(), 0, 1e-12);
}

// v /= 1 + c k at each of the integrator's steps k: 1 / (1 + c h) on the default step,
// (1 + c h / n)^-n on the soft step's n substeps.
TEST(World, DampingDecaysVelocityImplicitly) {
    for (const testkit::StepChoice& step : testkit::kIntegratorStepChoices) {
        SCOPED_TRACE(testkit::stepName(step));
        WorldDef worldDef = zeroGravity();
        testkit::applyStep(worldDef.solver, step);
        World world(worldDef);
        BodyDef def;
        def.linearVelocity = Vec3(1, 0, 0);
        def.linearDamping = 2;
        const BodyId body = world.createBody(def);
        const int n = testkit::integratorStepsPerStep(step);
        const Real k = world.settings().timeStep / n;
        world.step();
        EXPECT_NEAR(world.linearVelocity(body).x(), std::pow(1 + 2 * k, -n), 1e-15);
    }
}

TEST(World, NonFiniteStepIsReportedAndRolledBack) {
    World world;
    const BodyId calm = world.createBody({});
    const BodyId wild = world.createBody({});
    world.step();
    const Vec3 before = world.position(wild);
    const Vec3 calmBefore = world.position(calm);
    const Real big = std::numeric_limits<Real>::max();
    world.applyForceToCenter(wild, Vec3(big, 0, 0));
    world.applyForceToCenter(wild, Vec3(big, 0, 0));  // the sum overflows to infinity
    const StepStatus status = world.step();
    EXPECT_EQ(status.code, StepStatus::Code::NonFiniteState);
    EXPECT_EQ(status.body, wild);
    EXPECT_EQ(world.position(wild), before) << "the world keeps its last finite state";
    EXPECT_EQ(world.position(calm), calmBefore);
    EXPECT_EQ(world.stepCount(), 1u);
}

// The same scene built the same way gives bitwise-identical states.
TEST(World, StepsAreDeterministic) {
    auto run = [] {
        World world;
        std::vector<BodyId> ids;
        for (int i = 0; i < 50; ++i) {
            BodyDef def;
            def.position = Vec3(i * 0.1, -i * 0.2, i);
            def.angularVelocity = Vec3(0.3 * i, 1, -0.7);
            def.mass.inertia = Vec3(1, 2, 2.5).asDiagonal();
            ids.push_back(world.createBody(def));
        }
        for (int s = 0; s < 300; ++s) {
            world.applyTorque(ids[s % 50], Vec3(0.1, 0, 0));
            world.step();
        }
        std::vector<Real> state;
        for (BodyId id : ids) {
            const Quat q = world.orientation(id);
            for (Real v : {world.position(id).x(), world.position(id).y(), world.position(id).z(),
                           q.w(), q.x(), q.y(), q.z()}) {
                state.push_back(v);
            }
        }
        return state;
    };
    const std::vector<Real> a = run();
    const std::vector<Real> b = run();
    ASSERT_EQ(a.size(), b.size());
    EXPECT_EQ(std::memcmp(a.data(), b.data(), a.size() * sizeof(Real)), 0);
}

}  // namespace
}  // namespace tumble
