// Bad input to the core API is refused with an InvalidArgument whose message names the field,
// and nothing is created or changed.

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <string>

#include "tumble/core/error.h"
#include "tumble/world.h"

namespace tumble {
namespace {

const Real kNaN = std::numeric_limits<Real>::quiet_NaN();
const Real kInf = std::numeric_limits<Real>::infinity();

// Expects `call` to throw InvalidArgument with `fragment` in its message.
template <typename Call>
void expectRefused(Call call, const std::string& fragment) {
    try {
        call();
        FAIL() << "accepted; expected a refusal mentioning '" << fragment << "'";
    } catch (const InvalidArgument& e) {
        EXPECT_NE(std::string(e.what()).find(fragment), std::string::npos) << e.what();
    }
}

void expectBodyRefused(const BodyDef& def, const std::string& fragment) {
    World world;
    expectRefused([&] { world.createBody(def); }, fragment);
    EXPECT_EQ(world.bodyCount(), 0) << "nothing is created";
}

TEST(InputChecks, ZeroOrNegativeMassOnDynamicBody) {
    for (Real mass : {0.0, -1.0, kNaN, kInf}) {
        BodyDef def;
        def.mass.mass = mass;
        expectBodyRefused(def, "BodyDef.mass.mass");
    }
}

TEST(InputChecks, MassIsIgnoredOnStaticBody) {
    World world;
    BodyDef def;
    def.type = BodyType::Static;
    def.mass.mass = 0;
    EXPECT_NO_THROW(world.createBody(def));
}

// createBody applies the rule World::setLinearVelocity does: a static body never moves. It used to
// take the velocity and drop it unseen (and so did scene files, which go through createBody).
TEST(InputChecks, StaticBodyWithAVelocity) {
    expectBodyRefused(BodyDef{.type = BodyType::Static, .linearVelocity = Vec3(1, 0, 0)},
                      "BodyDef.linearVelocity = ");
    expectBodyRefused(BodyDef{.type = BodyType::Static, .angularVelocity = Vec3(0, 0, 1)},
                      "BodyDef.angularVelocity = ");
    World world;
    EXPECT_NO_THROW(world.createBody(BodyDef{.type = BodyType::Static}));
    EXPECT_NO_THROW(
        world.createBody(BodyDef{.type = BodyType::Kinematic, .linearVelocity = Vec3(1, 0, 0)}));
}

TEST(InputChecks, UnphysicalInertia) {
    BodyDef def;
    def.mass.inertia = Vec3(1, 1, -1).asDiagonal();
    expectBodyRefused(def, "principal moment");
    def.mass.inertia = Vec3(1, 1, 3).asDiagonal();
    expectBodyRefused(def, "exceeds the sum");
    def.mass.inertia = Mat3::Identity();
    def.mass.inertia(0, 1) = 0.5;
    expectBodyRefused(def, "symmetric");
}

TEST(InputChecks, NonFinitePositionOrVelocity) {
    BodyDef def;
    def.position = Vec3(0, kNaN, 0);
    expectBodyRefused(def, "BodyDef.position");
    def = {};
    def.linearVelocity = Vec3(kInf, 0, 0);
    expectBodyRefused(def, "BodyDef.linearVelocity");
    def = {};
    def.angularVelocity = Vec3(0, 0, kNaN);
    expectBodyRefused(def, "BodyDef.angularVelocity");
}

TEST(InputChecks, NonUnitOrZeroQuaternion) {
    BodyDef def;
    def.orientation = Quat(0, 0, 0, 0);
    expectBodyRefused(def, "BodyDef.orientation");
    def.orientation = Quat(1, 1, 0, 0);
    expectBodyRefused(def, "unit quaternion");
    def.orientation = Quat(kNaN, 0, 0, 0);
    expectBodyRefused(def, "finite");
}

TEST(InputChecks, NegativeDamping) {
    BodyDef def;
    def.linearDamping = -0.1;
    expectBodyRefused(def, "BodyDef.linearDamping");
    def = {};
    def.angularDamping = -1;
    expectBodyRefused(def, "BodyDef.angularDamping");
}

TEST(InputChecks, NonPositiveTimeStep) {
    for (Real h : {0.0, -0.01, kNaN, kInf}) {
        expectRefused([&] { World world(WorldDef{.timeStep = h}); }, "WorldDef.timeStep");
        World world;
        expectRefused([&] { world.setTimeStep(h); }, "timeStep");
        EXPECT_EQ(world.settings().timeStep, WorldDef{}.timeStep) << "unchanged after a refusal";
    }
}

TEST(InputChecks, BadWorldSettings) {
    expectRefused([] { World world(WorldDef{.gravity = Vec3(0, 0, kNaN)}); }, "WorldDef.gravity");
    expectRefused([] { World world(WorldDef{.maxStepsPerAdvance = 0}); }, "maxStepsPerAdvance");
    World world;
    expectRefused([&] { world.advance(-1); }, "frameTime");
    expectRefused([&] { world.advance(kNaN); }, "frameTime");
}

TEST(InputChecks, NonFiniteForcesAndSetters) {
    World world;
    const BodyId body = world.createBody({});
    expectRefused([&] { world.applyForceToCenter(body, Vec3(kNaN, 0, 0)); }, "force");
    expectRefused([&] { world.applyForce(body, Vec3::Zero(), Vec3(kInf, 0, 0)); }, "point");
    expectRefused([&] { world.applyTorque(body, Vec3(0, kNaN, 0)); }, "torque");
    expectRefused([&] { world.applyLinearImpulse(body, Vec3(kNaN, 0, 0), Vec3::Zero()); },
                  "impulse");
    expectRefused([&] { world.setTransform(body, Vec3::Zero(), Quat(2, 0, 0, 0)); }, "orientation");
    expectRefused([&] { world.setLinearVelocity(body, Vec3(kNaN, 0, 0)); }, "velocity");
    MassProperties bad;
    bad.mass = -2;
    expectRefused([&] { world.setMassProperties(body, bad); }, "mass");
    EXPECT_EQ(world.massProperties(body).mass, MassProperties{}.mass);
    world.step();
    EXPECT_TRUE(world.position(body).allFinite());
}

TEST(InputChecks, StaleAndNullIds) {
    World world;
    const BodyId body = world.createBody({});
    world.destroyBody(body);
    expectRefused([&] { world.linearVelocity(body); }, "does not name a live body");
    expectRefused([&] { world.applyForceToCenter(BodyId{}, Vec3::Zero()); }, "null");
}

}  // namespace
}  // namespace tumble
