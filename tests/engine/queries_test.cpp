// World queries answered through the broadphase agree with brute force over every shape.

#include <gtest/gtest.h>

#include <algorithm>
#include <random>
#include <vector>

#include "tumble/collision/narrowphase.h"
#include "tumble/collision/raycast.h"
#include "tumble/world.h"

namespace tumble {
namespace {

struct Scene {
    World world{WorldDef{.gravity = Vec3::Zero()}};
    std::vector<ShapeId> shapes;
};

// 300 mixed shapes scattered in a 20 m cube, some on dynamic bodies, some filtered out.
void build(Scene& scene, std::mt19937& rng) {
    std::uniform_real_distribution<Real> coordinate(-10, 10);
    std::uniform_real_distribution<Real> size(0.1, 1.0);
    std::uniform_real_distribution<Real> unit(-1, 1);
    for (int i = 0; i < 300; ++i) {
        BodyDef def;
        def.type = i % 3 == 0 ? BodyType::Dynamic : BodyType::Static;
        def.position = Vec3(coordinate(rng), coordinate(rng), coordinate(rng));
        def.orientation = Quat(unit(rng), unit(rng), unit(rng), unit(rng)).normalized();
        const BodyId body = scene.world.createBody(def);
        ShapeDef shape;
        switch (i % 3) {
            case 0:
                shape.geometry = Sphere{size(rng)};
                break;
            case 1:
                shape.geometry = Box{Vec3(size(rng), size(rng), size(rng))};
                break;
            default:
                shape.geometry = Capsule{size(rng) / 2, size(rng)};
                break;
        }
        shape.filter.category = i % 7 == 0 ? 2u : 1u;
        scene.shapes.push_back(scene.world.createShape(body, shape));
    }
    scene.world.step();  // gravity is off: nothing moves, but the broadphase settles
}

TEST(Queries, ClosestRayHitEqualsBruteForce) {
    std::mt19937 rng(7);
    Scene scene;
    build(scene, rng);
    std::uniform_real_distribution<Real> coordinate(-12, 12);
    int hits = 0;
    for (int r = 0; r < 500; ++r) {
        const Vec3 origin(coordinate(rng), coordinate(rng), coordinate(rng));
        const Vec3 translation = Vec3(coordinate(rng), coordinate(rng), coordinate(rng)) - origin;
        const QueryFilter filter{.mask = 1};
        std::optional<RayCastHit> expected;
        for (ShapeId id : scene.shapes) {
            if ((scene.world.shapeDef(id).filter.category & filter.mask) == 0)
                continue;
            const std::optional<RayHit> hit =
                raycast(scene.world.shapeDef(id).geometry, scene.world.shapeTransform(id),
                        Ray{origin, translation, 1});
            if (hit && (!expected || hit->fraction < expected->fraction)) {
                expected = RayCastHit{id, scene.world.shapeBody(id), hit->fraction, hit->point,
                                      hit->normal};
            }
        }
        const std::optional<RayCastHit> got =
            scene.world.castRayClosest(origin, translation, filter);
        ASSERT_EQ(got.has_value(), expected.has_value()) << "ray " << r;
        if (!got)
            continue;
        ++hits;
        EXPECT_EQ(got->shape, expected->shape) << "ray " << r;
        EXPECT_NEAR(got->fraction, expected->fraction, 1e-12);
        const std::vector<RayCastHit> all = scene.world.castRayAll(origin, translation, filter);
        ASSERT_FALSE(all.empty());
        EXPECT_EQ(all.front().shape, got->shape);
        EXPECT_TRUE(std::is_sorted(
            all.begin(), all.end(),
            [](const RayCastHit& a, const RayCastHit& b) { return a.fraction < b.fraction; }));
    }
    EXPECT_GT(hits, 50) << "the test must exercise hits, not only misses";
}

TEST(Queries, AabbAndShapeOverlapEqualBruteForce) {
    std::mt19937 rng(11);
    Scene scene;
    build(scene, rng);
    std::uniform_real_distribution<Real> coordinate(-10, 10);
    for (int q = 0; q < 200; ++q) {
        const Vec3 center(coordinate(rng), coordinate(rng), coordinate(rng));
        const Aabb box{center - Vec3::Constant(2), center + Vec3::Constant(2)};
        std::vector<ShapeId> expected;
        for (ShapeId id : scene.shapes) {
            if (scene.world.shapeBounds(id).overlaps(box))
                expected.push_back(id);
        }
        std::sort(expected.begin(), expected.end(),
                  [](ShapeId a, ShapeId b) { return a.index < b.index; });
        EXPECT_EQ(scene.world.overlapAabb(box), expected);

        const Sphere probe{1.5};
        const Transform pose{center, Quat::Identity()};
        std::vector<ShapeId> touching;
        Manifold manifold;
        for (ShapeId id : scene.shapes) {
            collide(probe, pose, scene.world.shapeDef(id).geometry, scene.world.shapeTransform(id),
                    0, manifold);
            if (manifold.pointCount > 0)
                touching.push_back(id);
        }
        std::sort(touching.begin(), touching.end(),
                  [](ShapeId a, ShapeId b) { return a.index < b.index; });
        EXPECT_EQ(scene.world.overlapShape(probe, pose), touching);
    }
}

TEST(Queries, ClosestPointOnAShape) {
    World world;
    BodyDef def;
    def.type = BodyType::Static;
    def.position = Vec3(1, 2, 3);
    const BodyId body = world.createBody(def);
    const ShapeId sphere = world.createShape(body, ShapeDef{.geometry = Sphere{0.5}});
    EXPECT_TRUE(world.closestPoint(sphere, Vec3(1, 2, 10)).isApprox(Vec3(1, 2, 3.5)));
    EXPECT_TRUE(world.closestPoint(sphere, Vec3(1.1, 2, 3)).isApprox(Vec3(1.1, 2, 3))) << "inside";
}

}  // namespace
}  // namespace tumble
