// No body tunnels through the terrain: a 1,000-body pile of boxes, spheres, capsules, cylinders
// and hulls dropped in layers onto the benchmark's rolling bowl (bench/harness/terrain.h) as a
// height field, stepped at h = 1/60 s. At every step, every body's lowest point lies above the
// exact surface under it (terrainHeight: the same triangles as the height field), less the
// solver's slop and a tolerance.
//
// The tolerance, 0.05 m, was set before measuring: a quarter of the thinnest body (a box 0.2 m
// tall), so a body whose lowest point passes it is on its way through, while the soft contact of
// a pile seven layers deep (resolved a fraction per step beyond the slop) stays well inside it.

#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <vector>

#include "bench/harness/terrain.h"
#include "tumble/world.h"

namespace tumble::bench {
namespace {

constexpr int kBodies = 1000;
constexpr int kPerSide = 12;       // bodies per layer side
constexpr Real kPitch = 0.45;      // (m) between bodies in a layer
constexpr Real kTolerance = 0.05;  // (m) beyond the slop; see the file comment

Shape pileShape(int k) {
    switch (k % 5) {
        case 0:
            return Box{Vec3(0.15, 0.12, 0.1)};
        case 1:
            return Sphere{0.15};
        case 2:
            return Capsule{0.1, 0.1};
        case 3:
            return Cylinder{0.12, 0.1};
        default:
            return ConvexHull::fromPoints(std::vector<Vec3>{
                Vec3(0.15, 0, -0.1), Vec3(-0.1, 0.13, -0.1), Vec3(-0.1, -0.13, -0.1),
                Vec3(0.1, 0.08, 0.1), Vec3(-0.05, -0.1, 0.12), Vec3(0, 0, -0.14)});
    }
}

/// The lowest point of `shape` at `pose` (world, z up).
Vec3 lowestPoint(const Shape& shape, const Transform& pose) {
    const Vec3 down = -Vec3::UnitZ();
    const auto lowest = [&](const auto& points) {
        Vec3 best = pose.apply(points.front());
        for (const Vec3& p : points)
            if (pose.apply(p).z() < best.z())
                best = pose.apply(p);
        return best;
    };
    if (const auto* sphere = std::get_if<Sphere>(&shape))
        return pose.position + sphere->radius * down;
    if (const auto* box = std::get_if<Box>(&shape)) {
        std::vector<Vec3> corners;
        for (int c = 0; c < 8; ++c)
            corners.push_back(box->halfExtents.cwiseProduct(
                Vec3(c & 1 ? 1 : -1, c & 2 ? 1 : -1, c & 4 ? 1 : -1)));
        return lowest(corners);
    }
    if (const auto* capsule = std::get_if<Capsule>(&shape)) {
        const std::vector<Vec3> ends = {Vec3(0, 0, capsule->halfLength),
                                        Vec3(0, 0, -capsule->halfLength)};
        return lowest(ends) + capsule->radius * down;
    }
    if (const auto* cylinder = std::get_if<Cylinder>(&shape)) {
        // On each cap's rim, the point furthest down: along the downward direction projected
        // onto the cap's plane.
        const Vec3 axis = pose.rotation * Vec3::UnitZ();
        const Vec3 along = down - down.dot(axis) * axis;
        const Vec3 rim =
            along.norm() > 1e-12 ? Vec3(cylinder->radius * along.normalized()) : Vec3::Zero();
        const Vec3 a = pose.position + cylinder->halfLength * axis + rim;
        const Vec3 b = pose.position - cylinder->halfLength * axis + rim;
        return a.z() < b.z() ? a : b;
    }
    return lowest(std::get<ConvexHull>(shape).data->vertices);
}

TEST(TerrainTunnel, ThousandBodyPileNeverSinksBelowTheHeightField) {
    const HeightFieldData field = rollingTerrain();
    WorldDef def;
    def.timeStep = 1.0 / 60;
    World world(def);
    const BodyId ground = world.createBody(BodyDef{.type = BodyType::Static});
    world.createShape(
        ground, ShapeDef{.geometry = HeightField::fromData(field), .material = {.friction = 0.5}});
    const Real middle = 0.5 * (field.columns - 1) * field.spacingX;
    std::vector<ShapeId> shapes;
    for (int k = 0; k < kBodies; ++k) {
        const int cell = k % (kPerSide * kPerSide), layer = k / (kPerSide * kPerSide);
        const Real x = middle + kPitch * (cell % kPerSide - 0.5 * (kPerSide - 1));
        const Real y = middle + kPitch * (cell / kPerSide - 0.5 * (kPerSide - 1));
        BodyDef body;
        body.position = Vec3(x, y, terrainHeight(field, x, y) + 0.4 + kPitch * layer);
        body.orientation = Quat(Eigen::AngleAxis<Real>(0.6 * k, Vec3(1, 2, 3).normalized()));
        const BodyId b = world.createBody(body);
        shapes.push_back(world.createShape(
            b, ShapeDef{.geometry = pileShape(k), .material = {.friction = 0.5, .density = 700}}));
    }
    const Real side = (field.columns - 1) * field.spacingX;
    const Real allowed = world.settings().solver.slop + kTolerance;
    constexpr int kSteps = 120;  // 2 s: the top layer (3.1 m up) lands by ~0.8 s, then settles
    Real worst = -INFINITY;
    int worstStep = 0, sunk = 0;
    const auto start = std::chrono::steady_clock::now();
    for (int step = 1; step <= kSteps; ++step) {
        ASSERT_TRUE(world.step().ok()) << "step " << step;
        for (const ShapeId s : shapes) {
            const Vec3 p = lowestPoint(world.shapeDef(s).geometry, world.shapeTransform(s));
            ASSERT_TRUE(p.x() > 0 && p.y() > 0 && p.x() < side && p.y() < side)
                << "a body left the terrain at step " << step;
            const Real depth = terrainHeight(field, p.x(), p.y()) - p.z();
            if (depth > worst) {
                worst = depth;
                worstStep = step;
            }
            sunk += depth > allowed ? 1 : 0;
        }
    }
    const std::chrono::duration<double> took = std::chrono::steady_clock::now() - start;
    std::printf(
        "terrain tunnel: %d bodies x %d steps, deepest lowest point %.4f m below the surface "
        "(step %d; allowed slop + %.2f = %.3f m), %.2f s\n",
        kBodies, kSteps, worst, worstStep, kTolerance, allowed, took.count());
    EXPECT_EQ(sunk, 0) << "body-steps deeper than " << allowed << " m";
    EXPECT_LE(worst, allowed);
}

}  // namespace
}  // namespace tumble::bench
