// Bodies and shapes changed after creation (type, damping, user data, a shape's material and
// collision filter), each asserted by what the body then does; and listing the world's bodies
// and what a body carries (shapes, joints, springs).

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

constexpr Real kH = 1.0 / 60;

void steps(World& world, int count) {
    for (int i = 0; i < count; ++i)
        ASSERT_TRUE(world.step().ok());
}

// A world with a static floor (a half-space at z = 0) and the floor's id.
struct Floor {
    World world;
    BodyId floor;
    explicit Floor(const WorldDef& def = {}) : world(def) {
        floor = world.createBody(BodyDef{.type = BodyType::Static});
        world.createShape(floor, ShapeDef{.geometry = HalfSpace{}});
    }
    /// A 1 m cube resting on the floor at (x, 0), its mass from its shape (1000 kg).
    BodyId cube(Real x, BodyType type = BodyType::Dynamic, Real z = 0.5) {
        const BodyId body = world.createBody(BodyDef{.type = type, .position = Vec3(x, 0, z)});
        world.createShape(body, ShapeDef{.geometry = Box{Vec3(0.5, 0.5, 0.5)}});
        return body;
    }
};

// --- listing ----------------------------------------------------------------------------------

TEST(BodyLists, ShapesInAttachOrderJointsAndSpringsOfEitherEnd) {
    World world(WorldDef{.gravity = Vec3::Zero()});
    const BodyId a = world.createBody({});
    const BodyId b = world.createBody(BodyDef{.position = Vec3(2, 0, 0)});
    const BodyId c = world.createBody(BodyDef{.position = Vec3(4, 0, 0)});
    std::vector<ShapeId> shapes;
    for (int i = 0; i < 3; ++i) {
        const ShapeDef def{.geometry = Sphere{0.2},
                           .localPose = Transform{Vec3(0, 0, 0.5 * i), Quat::Identity()}};
        shapes.push_back(world.createShape(a, def));
    }
    EXPECT_EQ(world.bodyShapes(a), shapes);
    world.destroyShape(shapes[1]);
    EXPECT_EQ(world.bodyShapes(a), (std::vector<ShapeId>{shapes[0], shapes[2]}));
    EXPECT_TRUE(world.bodyShapes(b).empty());

    const JointId ab = world.createJoint(JointDef{.bodyA = a, .bodyB = b, .anchor = Vec3(1, 0, 0)});
    const JointId bc = world.createJoint(JointDef{.bodyA = b, .bodyB = c, .anchor = Vec3(3, 0, 0)});
    const SpringId ca = world.createSpring(SpringDef{.bodyA = c, .bodyB = a, .restLength = 4});
    const SpringId toWorld =
        world.createSpring(SpringDef{.bodyA = a, .bodyB = {}, .restLength = 1});
    EXPECT_EQ(world.bodyJoints(a), (std::vector<JointId>{ab}));
    EXPECT_EQ(world.bodyJoints(b), (std::vector<JointId>{ab, bc}));
    EXPECT_EQ(world.bodySprings(a), (std::vector<SpringId>{ca, toWorld}));
    EXPECT_TRUE(world.bodySprings(b).empty());

    EXPECT_EQ(world.bodies(), (std::vector<BodyId>{a, b, c}));
    world.destroyBody(a);  // c, the last, takes a's place; a's joint and springs go with it
    EXPECT_EQ(world.bodies(), (std::vector<BodyId>{c, b}));
    EXPECT_EQ(world.bodyJoints(b), (std::vector<JointId>{bc}));
    EXPECT_TRUE(world.bodySprings(c).empty());
    EXPECT_TRUE(contains(refusal([&] { world.bodyShapes(a); }), "does not name a live body"));
}

// --- body type --------------------------------------------------------------------------------

TEST(SetBodyType, AStaticBoxMadeDynamicFallsWithTheMassOfItsShape) {
    Floor scene;
    const BodyId box = scene.cube(0, BodyType::Static, 3);
    steps(scene.world, 30);
    EXPECT_EQ(scene.world.position(box).z(), 3) << "static: does not move";
    scene.world.setBodyType(box, BodyType::Dynamic);
    EXPECT_EQ(scene.world.bodyType(box), BodyType::Dynamic);
    EXPECT_TRUE(scene.world.isAwake(box));
    EXPECT_NEAR(scene.world.massProperties(box).mass, 1000, 1e-9);
    steps(scene.world, 30);  // 0.5 s of free fall: 1.23 m (semi-implicit Euler: a little more)
    const Real fallen = 3 - scene.world.position(box).z();
    EXPECT_NEAR(fallen, 0.5 * 9.81 * 0.5 * 0.5, 0.05);
    steps(scene.world, 120);
    EXPECT_NEAR(scene.world.position(box).z(), 0.5, 0.01) << "it lands on the floor";
}

TEST(SetBodyType, AFallingBoxMadeStaticStopsAndCarriesAnother) {
    Floor scene;
    const BodyId shelf = scene.cube(0, BodyType::Dynamic, 3);
    steps(scene.world, 10);
    ASSERT_LT(scene.world.linearVelocity(shelf).z(), -1);
    const int awake = scene.world.awakeBodyCount();
    scene.world.setBodyType(shelf, BodyType::Static);
    EXPECT_EQ(scene.world.linearVelocity(shelf), Vec3::Zero());
    EXPECT_FALSE(scene.world.isAwake(shelf));
    EXPECT_EQ(scene.world.awakeBodyCount(), awake - 1);
    const Real height = scene.world.position(shelf).z();
    const BodyId top = scene.cube(0, BodyType::Dynamic, height + 1.5);
    steps(scene.world, 120);
    EXPECT_EQ(scene.world.position(shelf).z(), height);
    EXPECT_NEAR(scene.world.position(top).z(), height + 1, 0.01) << "rests on the shelf";
}

TEST(SetBodyType, AKinematicBodyKeepsItsVelocityAndIgnoresGravity) {
    Floor scene;
    const BodyId body = scene.cube(0, BodyType::Dynamic, 3);
    scene.world.setLinearVelocity(body, Vec3(1, 0, 0));
    scene.world.setBodyType(body, BodyType::Kinematic);
    EXPECT_EQ(scene.world.massProperties(body).mass, 1000) << "kept for reporting";
    EXPECT_EQ(scene.world.kineticEnergy(body), 0) << "no mass in the dynamics";
    steps(scene.world, 60);
    EXPECT_NEAR(scene.world.position(body).x(), 1, 1e-9);
    EXPECT_EQ(scene.world.position(body).z(), 3);
    EXPECT_TRUE(scene.world.isAwake(body));
}

TEST(SetBodyType, RefusalsNameTheReasonAndChangeNothing) {
    Floor scene;
    EXPECT_TRUE(contains(refusal([&] { scene.world.setBodyType(scene.floor, BodyType::Dynamic); }),
                         "half-space"));
    EXPECT_EQ(scene.world.bodyType(scene.floor), BodyType::Static);
    const BodyId bob = scene.cube(0, BodyType::Dynamic, 3);
    scene.world.createJoint(JointDef{.bodyA = bob, .bodyB = {}, .anchor = Vec3(0, 0, 4)});
    EXPECT_TRUE(contains(refusal([&] { scene.world.setBodyType(bob, BodyType::Static); }),
                         "would join no dynamic body"));
    EXPECT_EQ(scene.world.bodyType(bob), BodyType::Dynamic);
    const BodyId bare = scene.world.createBody(
        BodyDef{.type = BodyType::Static, .mass = MassProperties{.mass = -1}});
    EXPECT_TRUE(contains(refusal([&] { scene.world.setBodyType(bare, BodyType::Dynamic); }),
                         "setBodyType: the body's mass.mass = -1"));
    EXPECT_EQ(scene.world.bodyType(bare), BodyType::Static);
}

// --- shape material and filter ----------------------------------------------------------------

TEST(SetShapeMaterial, AFrictionlessBoxSlidesOnWhileTheOtherStops) {
    Floor scene(WorldDef{.enableSleep = false});
    const BodyId rough = scene.cube(0);
    const BodyId smooth = scene.cube(3);
    steps(scene.world, 30);  // settle
    const ShapeId shape = scene.world.bodyShapes(smooth).front();
    Material ice = scene.world.shapeDef(shape).material;
    ice.friction = 0;
    scene.world.setShapeMaterial(shape, ice);
    EXPECT_EQ(scene.world.shapeDef(shape).material.friction, 0);
    for (const BodyId b : {rough, smooth})
        scene.world.setLinearVelocity(b, Vec3(2, 0, 0));
    steps(scene.world, 60);  // mu g = 4.9 m/s^2 stops the rough box within 0.41 s
    EXPECT_NEAR(scene.world.linearVelocity(rough).x(), 0, 1e-3);
    EXPECT_NEAR(scene.world.linearVelocity(smooth).x(), 2, 1e-6);
}

TEST(SetShapeMaterial, DensityChangesAMassFromShapesAndBadValuesAreRefused) {
    Floor scene;
    const BodyId box = scene.cube(0);
    const ShapeId shape = scene.world.bodyShapes(box).front();
    scene.world.setShapeMaterial(shape, Material{.density = 250});
    EXPECT_NEAR(scene.world.massProperties(box).mass, 250, 1e-9);
    EXPECT_TRUE(
        contains(refusal([&] { scene.world.setShapeMaterial(shape, Material{.friction = -1}); }),
                 "setShapeMaterial material.friction = -1"));
    EXPECT_TRUE(
        contains(refusal([&] { scene.world.setShapeMaterial(shape, Material{.restitution = 2}); }),
                 "setShapeMaterial material.restitution = 2"));
    EXPECT_EQ(scene.world.shapeDef(shape).material.density, 250) << "refusals changed it";
}

TEST(SetShapeFilter, AMaskThatExcludesTheFloorLetsTheBoxFallThrough) {
    Floor scene;
    const BodyId kept = scene.cube(0);
    const BodyId dropped = scene.cube(3);
    steps(scene.world, 60);
    ASSERT_NEAR(scene.world.position(dropped).z(), 0.5, 0.01);
    const ShapeId shape = scene.world.bodyShapes(dropped).front();
    scene.world.setShapeFilter(shape, CollisionFilter{.category = 2, .mask = ~1u});
    EXPECT_EQ(scene.world.shapeDef(shape).filter.mask, ~1u);
    steps(scene.world, 30);
    EXPECT_LT(scene.world.position(dropped).z(), -0.5) << "passes through the floor";
    EXPECT_NEAR(scene.world.position(kept).z(), 0.5, 0.01);
    for (const Contact& contact : scene.world.contacts())
        EXPECT_FALSE(contact.bodyA == dropped || contact.bodyB == dropped);
}

// --- damping and user data --------------------------------------------------------------------

// v /= 1 + c k at each of the integrator's steps k (h, or h / n on the soft step's n substeps).
TEST(SetDamping, ActsFromTheNextStepAndBadValuesAreRefusedByName) {
    for (const testkit::StepChoice& step : testkit::kIntegratorStepChoices) {
        SCOPED_TRACE(testkit::stepName(step));
        WorldDef def{.gravity = Vec3::Zero()};
        testkit::applyStep(def.solver, step);
        World world(def);
        const BodyId body = world.createBody({});
        world.setLinearVelocity(body, Vec3(1, 0, 0));
        world.setAngularVelocity(body, Vec3(0, 0, 1));
        world.setLinearDamping(body, 2);
        world.setAngularDamping(body, 3);
        EXPECT_EQ(world.linearDamping(body), 2);
        EXPECT_EQ(world.angularDamping(body), 3);
        ASSERT_TRUE(world.step().ok());
        const int n = testkit::integratorStepsPerStep(step);
        const Real k = kH / n;
        EXPECT_NEAR(world.linearVelocity(body).x(), std::pow(1 + k * 2, -n), 1e-12);
        EXPECT_NEAR(world.angularVelocity(body).z(), std::pow(1 + k * 3, -n), 1e-12);
    }
    World world(WorldDef{.gravity = Vec3::Zero()});
    const BodyId body = world.createBody({});
    world.setLinearDamping(body, 2);
    EXPECT_TRUE(contains(refusal([&] { world.setLinearDamping(body, -1); }),
                         "setLinearDamping damping (1/s) = -1 must be finite and >= 0"));
    EXPECT_TRUE(contains(
        refusal([&] { world.setAngularDamping(body, std::numeric_limits<Real>::infinity()); }),
        "setAngularDamping damping (1/s) = inf"));
    EXPECT_EQ(world.linearDamping(body), 2);
}

TEST(SetUserData, IsHandedBack) {
    World world;
    const BodyId body = world.createBody(BodyDef{.userData = 7});
    world.setUserData(body, 0xFEEDu);
    EXPECT_EQ(world.userData(body), 0xFEEDu);
}

}  // namespace
}  // namespace tumble
