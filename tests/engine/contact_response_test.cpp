// The world's contact response end to end: shapes -> manifolds -> solver -> motion.

#include <gtest/gtest.h>

#include <cmath>

#include "tumble/world.h"

namespace tumble {
namespace {

BodyId addGround(World& world, Real friction = 0.5) {
    const BodyId ground = world.createBody(BodyDef{.type = BodyType::Static});
    ShapeDef def{.geometry = HalfSpace{}};
    def.material.friction = friction;
    world.createShape(ground, def);
    return ground;
}

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

TEST(ContactResponse, SphereBouncesWithNewtonsRestitution) {
    World world(WorldDef{.timeStep = 1.0 / 1000});
    addGround(world);
    BodyDef def;
    def.position = Vec3(0, 0, 1);
    const BodyId ball = world.createBody(def);
    ShapeDef shape{.geometry = Sphere{0.1}};
    shape.material.restitution = 0.8;
    world.createShape(ball, shape);
    // First apex: r + (H - r) e^2.
    Real apex = 0;
    bool bounced = false;
    for (int i = 0; i < 3000; ++i) {
        world.step();
        const Real vz = world.linearVelocity(ball).z();
        if (vz > 0)
            bounced = true;
        if (bounced && vz <= 0) {
            apex = world.position(ball).z();
            break;
        }
    }
    const Real expected = 0.1 + 0.9 * 0.64;
    EXPECT_NEAR(apex, expected, 0.02 * expected);
    EXPECT_LE(apex, expected * 1.005) << "no energy created at the impact";
}

}  // namespace
}  // namespace tumble
