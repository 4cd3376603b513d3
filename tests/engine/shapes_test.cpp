// Shapes on bodies: mass from geometry, contacts through the world, the contact cache.

#include <gtest/gtest.h>

#include <numbers>

#include "testkit/scenes.h"
#include "tumble/core/error.h"
#include "tumble/world.h"

namespace tumble {
namespace {

using testkit::addGround;

TEST(Shapes, BodyMassComesFromItsShapes) {
    World world;
    const BodyId body = world.createBody({});
    ShapeDef box{.geometry = Box{Vec3(0.5, 1.0, 1.5)}};
    box.material.density = 10;
    world.createShape(body, box);
    const MassProperties single = world.massProperties(body);
    EXPECT_NEAR(single.mass, 10 * 1 * 2 * 3, 1e-12);
    EXPECT_NEAR(single.inertia(0, 0), 60.0 / 12 * (4 + 9), 1e-9);

    // A second, offset box: the compound's centre moves to the midpoint, parallel-axis inertia.
    box.localPose.position = Vec3(2, 0, 0);
    world.createShape(body, box);
    const MassProperties both = world.massProperties(body);
    EXPECT_NEAR(both.mass, 120, 1e-12);
    EXPECT_TRUE(both.localCenter.isApprox(Vec3(1, 0, 0)));
    EXPECT_NEAR(both.inertia(1, 1), 2 * (60.0 / 12 * (1 + 9) + 60 * 1), 1e-9);
    EXPECT_NEAR(world.position(body).norm(), 0, 1e-15) << "the origin stays where it was";
}

TEST(Shapes, BadShapeDefinitionsAreRefused) {
    World world;
    const BodyId body = world.createBody({});
    EXPECT_THROW(world.createShape(body, ShapeDef{.geometry = Box{Vec3(1, 0, 1)}}),
                 InvalidArgument);
    EXPECT_THROW(world.createShape(body, ShapeDef{.geometry = Sphere{-1}}), InvalidArgument);
    EXPECT_THROW(world.createShape(body, ShapeDef{.geometry = HalfSpace{}}), InvalidArgument)
        << "half-spaces belong on static bodies";
    ShapeDef slippery;
    slippery.material.friction = -0.1;
    EXPECT_THROW(world.createShape(body, slippery), InvalidArgument);
    ShapeDef bouncy;
    bouncy.material.restitution = 1.5;
    EXPECT_THROW(world.createShape(body, bouncy), InvalidArgument);
    EXPECT_EQ(world.massProperties(body).mass, MassProperties{}.mass) << "nothing changed";
}

TEST(Shapes, RestingBoxHasFourContactPointsWithStableIds) {
    World world(WorldDef{.gravity = Vec3::Zero()});
    addGround(world);
    BodyDef def;
    def.position = Vec3(0, 0, 0.5);
    const BodyId box = world.createBody(def);
    world.createShape(box, ShapeDef{.geometry = Box{}});
    ASSERT_TRUE(world.step().ok());
    ASSERT_EQ(world.contacts().size(), 1u);
    const Contact first = world.contacts()[0];
    EXPECT_TRUE(first.bodyA == box || first.bodyB == box);
    ASSERT_EQ(first.manifold.pointCount, 4);
    for (int i = 0; i < 4; ++i) {
        EXPECT_NEAR(first.manifold.points[i].separation, 0, 1e-9);
        EXPECT_NEAR(std::abs(first.manifold.points[i].position.x()), 0.5, 1e-9);
        EXPECT_NEAR(std::abs(first.manifold.points[i].position.y()), 0.5, 1e-9);
    }
    for (int s = 0; s < 100; ++s)
        ASSERT_TRUE(world.step().ok());
    const Contact later = world.contacts()[0];
    ASSERT_EQ(later.manifold.pointCount, 4);
    for (int i = 0; i < 4; ++i)
        EXPECT_EQ(later.manifold.points[i].featureId, first.manifold.points[i].featureId);
}

TEST(Shapes, CompoundPartsDoNotCollideAndStaticPairsAreSkipped) {
    World world(WorldDef{.gravity = Vec3::Zero()});
    addGround(world);
    BodyDef wallDef;
    wallDef.type = BodyType::Static;
    const BodyId wall = world.createBody(wallDef);
    world.createShape(wall, ShapeDef{.geometry = Box{}});  // overlaps the ground: static-static
    const BodyId body = world.createBody({});
    world.createShape(
        body, ShapeDef{.geometry = Sphere{1}, .localPose = {Vec3(0, 0, 5), Quat::Identity()}});
    world.createShape(
        body, ShapeDef{.geometry = Sphere{1}, .localPose = {Vec3(0, 0, 5.5), Quat::Identity()}});
    world.step();
    EXPECT_TRUE(world.contacts().empty());
}

TEST(Shapes, DestroyingABodyRemovesItsShapesAndContacts) {
    World world(WorldDef{.gravity = Vec3::Zero()});
    addGround(world);
    BodyDef def;
    def.position = Vec3(0, 0, 0.4);
    const BodyId body = world.createBody(def);
    const ShapeId shape = world.createShape(body, ShapeDef{.geometry = Sphere{0.5}});
    world.step();
    EXPECT_EQ(world.contacts().size(), 1u);
    world.destroyBody(body);
    EXPECT_FALSE(world.isValid(shape));
    world.step();
    EXPECT_TRUE(world.contacts().empty());
}

TEST(Shapes, FastBodyIsCaughtBySpeculativeContactAndDoesNotTunnel) {
    // 200 m/s toward a 2 cm wall 2 m away at h = 1/60: it would cover 3.3 m in one step.
    World world(WorldDef{.gravity = Vec3::Zero()});
    BodyDef wallDef;
    wallDef.type = BodyType::Static;
    wallDef.position = Vec3(2, 0, 0);
    const BodyId wall = world.createBody(wallDef);
    world.createShape(wall, ShapeDef{.geometry = Box{Vec3(0.01, 1, 1)}});
    BodyDef ballDef;
    ballDef.linearVelocity = Vec3(200, 0, 0);
    const BodyId ball = world.createBody(ballDef);
    world.createShape(ball, ShapeDef{.geometry = Sphere{0.05}});
    world.step();
    ASSERT_EQ(world.contacts().size(), 1u) << "the pair is found before the ball gets there";
    EXPECT_GT(world.contacts()[0].manifold.pointCount, 0);
    for (int i = 0; i < 60; ++i)
        world.step();
    EXPECT_LT(world.position(ball).x(), 2 - 0.01 - 0.05 + 1e-3) << "stopped at the wall's face";
}

}  // namespace
}  // namespace tumble
