// Triangle meshes and height fields: building (checks, degenerate triangles, active edges), the
// hierarchy's candidates against brute force, and the narrowphase against the equivalent box and
// half-space.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <set>

#include "ccd_adapter.h"
#include "collision/mesh_fixtures.h"
#include "mesh_queries.h"
#include "tumble/collision/mesh_shape.h"
#include "tumble/collision/narrowphase.h"
#include "tumble/collision/raycast.h"
#include "tumble/core/error.h"

namespace tumble {
namespace {

using testing::flatGrid;
using testing::heightGrid;
using testing::randomConvex;
using testing::randomRotation;

/// The 12 triangles of a box's surface, outward normals.
TriangleMeshData boxMesh(const Vec3& e) {
    TriangleMeshData data;
    for (int k = 0; k < 8; ++k)
        data.vertices.emplace_back((k & 1) ? e.x() : -e.x(), (k & 2) ? e.y() : -e.y(),
                                   (k & 4) ? e.z() : -e.z());
    // Quads counter-clockwise from outside: -z, +z, -y, +y, -x, +x.
    const std::uint32_t quads[6][4] = {{0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4},
                                       {2, 6, 7, 3}, {0, 4, 6, 2}, {1, 3, 7, 5}};
    for (const auto& q : quads) {
        data.triangles.push_back({q[0], q[1], q[2]});
        data.triangles.push_back({q[0], q[2], q[3]});
    }
    return data;
}

TEST(TriangleMesh, RefusesNonFiniteVerticesAndBadIndicesNamingThem) {
    TriangleMeshData data = flatGrid(2, 1);
    data.vertices[3].y() = NAN;
    try {
        TriangleMesh::fromData(data);
        FAIL() << "NaN accepted";
    } catch (const InvalidArgument& e) {
        EXPECT_NE(std::string(e.what()).find("vertex 3"), std::string::npos) << e.what();
    }
    data = flatGrid(2, 1);
    data.triangles[5][2] = 99;
    try {
        TriangleMesh::fromData(data);
        FAIL() << "index out of range accepted";
    } catch (const InvalidArgument& e) {
        EXPECT_NE(std::string(e.what()).find("triangle 5"), std::string::npos) << e.what();
    }
    EXPECT_THROW(TriangleMesh::fromData(TriangleMeshData{}), InvalidArgument);
}

TEST(TriangleMesh, DropsDegenerateTrianglesAndCountsThem) {
    TriangleMeshData data = flatGrid(2, 1);
    data.triangles.push_back({0, 1, 2});  // three collinear vertices of the bottom row
    data.triangles.push_back({4, 4, 5});
    const TriangleMesh mesh = TriangleMesh::fromData(data);
    EXPECT_EQ(mesh.data->droppedTriangles, 2u);
    EXPECT_EQ(mesh.data->triangles.size(), 8u);
}

/// Counts of active edges over all triangles.
int activeEdgeCount(const MeshGeometry& mesh) {
    int count = 0;
    for (const std::uint8_t flags : mesh.activeEdges)
        count += std::popcount(static_cast<unsigned>(flags));
    return count;
}

TEST(TriangleMesh, FlatInteriorEdgesAreInactiveAndBorderEdgesActive) {
    const TriangleMesh mesh = TriangleMesh::fromData(flatGrid(4, 1));
    EXPECT_EQ(activeEdgeCount(*mesh.data), 16) << "only the 4 x 4 border edges";
    // A box's edges all fold convexly; its face diagonals are flat.
    const TriangleMesh box = TriangleMesh::fromData(boxMesh(Vec3(1, 2, 3)));
    EXPECT_EQ(activeEdgeCount(*box.data), 24) << "12 box edges, seen from both triangles";
}

TEST(TriangleMesh, ConvexRidgeIsActiveAndConcaveValleyIsNot) {
    // Two triangles folded along the y axis: a ridge (z = -|x|) and a valley (z = |x|).
    for (const Real sign : {-1.0, 1.0}) {
        TriangleMeshData data;
        data.vertices = {Vec3(0, 0, 0), Vec3(0, 1, 0), Vec3(1, 0.5, sign), Vec3(-1, 0.5, sign)};
        data.triangles = {{0, 2, 1}, {0, 1, 3}};
        const TriangleMesh mesh = TriangleMesh::fromData(data);
        const int shared = activeEdgeCount(*mesh.data) - 4;  // 4 border edges stay active
        EXPECT_EQ(shared, sign < 0 ? 2 : 0) << (sign < 0 ? "ridge" : "valley");
    }
}

TEST(TriangleMesh, WeldsVerticesAtEqualCoordinatesForAdjacency) {
    TriangleMeshData data = flatGrid(3, 1);
    TriangleMeshData unwelded;
    for (const auto& t : data.triangles) {
        const auto base = static_cast<std::uint32_t>(unwelded.vertices.size());
        for (const std::uint32_t v : t)
            unwelded.vertices.push_back(data.vertices[v]);
        unwelded.triangles.push_back({base, base + 1, base + 2});
    }
    EXPECT_EQ(activeEdgeCount(*TriangleMesh::fromData(unwelded).data), 12);
}

TEST(TriangleMesh, HierarchyCandidatesEqualBruteForceForRandomBoxes) {
    // A crumpled sheet: a grid with random heights, plus random loose triangles.
    std::mt19937 rng(26);
    std::uniform_real_distribution<Real> unit(-1, 1);
    TriangleMeshData data = flatGrid(24, 0.5);
    for (Vec3& v : data.vertices)
        v.z() = 0.3 * unit(rng);
    for (int k = 0; k < 300; ++k) {
        const auto base = static_cast<std::uint32_t>(data.vertices.size());
        const Vec3 centre(6 * unit(rng), 6 * unit(rng), 2 * unit(rng));
        for (int v = 0; v < 3; ++v)
            data.vertices.push_back(centre + 0.4 * Vec3(unit(rng), unit(rng), unit(rng)));
        data.triangles.push_back({base, base + 1, base + 2});
    }
    const TriangleMesh mesh = TriangleMesh::fromData(data);
    const MeshGeometry& g = *mesh.data;
    for (int trial = 0; trial < 2000; ++trial) {
        const Vec3 centre(7 * unit(rng), 7 * unit(rng), 2 * unit(rng));
        const Vec3 half = Vec3(unit(rng), unit(rng), unit(rng)).cwiseAbs() * 1.5;
        const Aabb box{centre - half, centre + half};
        const testing::Candidates c = testing::candidatesFor(g, box);
        ASSERT_EQ(c.walked, c.brute) << "trial " << trial;
    }
}

Real deepest(const Manifold& m) {
    Real d = INFINITY;
    for (int k = 0; k < m.pointCount; ++k)
        d = std::min(d, m.points[static_cast<std::size_t>(k)].separation);
    return d;
}

/// Every convex shape against a surface and against its solid equivalent, at random poses whose
/// contact lies away from the solid's edges: the deepest separation and the normal agree. Shapes
/// sit within `reach` (x, y) of `centre` (surface frame; its z is the top face's height).
void expectSameAsSolid(const Shape& surface, const Shape& solid, const Transform& surfacePose,
                       const Vec3& centre, Real reach, const char* what) {
    std::mt19937 rng(1026);
    std::uniform_real_distribution<Real> unit(-1, 1);
    const Real margin = 0.02;
    int compared = 0;
    Real worstDepth = 0, worstNormal = 0;
    for (int trial = 0; trial < 1200; ++trial) {
        const Shape shape = randomConvex(rng, trial % 5);
        Transform pose{centre + Vec3(reach * unit(rng), reach * unit(rng), 0), randomRotation(rng)};
        // The shape's lowest point from 0.05 m below to 0.015 m above the top face.
        const Real low = boundsOf(shape, pose).lower.z() - centre.z();
        pose.position.z() += -low - 0.05 + 0.065 * (unit(rng) + 1) / 2;
        const Transform world{surfacePose.apply(pose.position),
                              surfacePose.rotation * pose.rotation};
        Manifold onSurface, onSolid;
        collide(shape, world, surface, surfacePose, margin, onSurface);
        collide(shape, world, solid, surfacePose, margin, onSolid);
        ASSERT_EQ(onSurface.pointCount > 0, onSolid.pointCount > 0) << what << " trial " << trial;
        if (onSolid.pointCount == 0)
            continue;
        ++compared;
        // The solid's depth: its manifold's for a half-space (closed form, exact), the pair's
        // penetration for a box (the general path's manifold may clip to a face that misses the
        // deepest vertex of a hull).
        const Real solidDepth =
            typeOf(solid) == ShapeType::HalfSpace
                ? deepest(onSolid)
                : detail::queryConvex(shape, world, solid, surfacePose).separation;
        worstDepth = std::max(worstDepth, std::abs(deepest(onSurface) - solidDepth));
        worstNormal = std::max(worstNormal, (onSurface.normal - onSolid.normal).norm());
    }
    std::printf("%s: %d contacts compared, worst depth difference %.3g m, normal %.3g\n", what,
                compared, worstDepth, worstNormal);
    EXPECT_GE(compared, 1000);
    EXPECT_LT(worstDepth, 1e-9);
    EXPECT_LT(worstNormal, 1e-9);
}

Transform tilted() {
    return {Vec3(1, -2, 0.5), Quat(Eigen::AngleAxis<Real>(0.4, Vec3(1, 2, 3).normalized()))};
}

TEST(MeshNarrowphase, EveryConvexShapeOnAFlatMeshMatchesTheHalfSpace) {
    const Shape surface = TriangleMesh::fromData(flatGrid(20, 0.25));
    expectSameAsSolid(surface, HalfSpace{}, tilted(), Vec3::Zero(), 2.0, "flat mesh vs half-space");
}

TEST(MeshNarrowphase, EveryConvexShapeOnABoxMeshMatchesTheBox) {
    const Vec3 e(3, 3, 1);
    const Shape surface = TriangleMesh::fromData(boxMesh(e));
    expectSameAsSolid(surface, Box{e}, tilted(), Vec3(0, 0, e.z()), 2.0, "box mesh vs box");
}

TEST(MeshNarrowphase, EveryConvexShapeOnAFlatHeightFieldMatchesTheHalfSpace) {
    const HeightFieldData grid =
        heightGrid(41, 31, 0.2, 0.25, [](std::uint32_t, std::uint32_t) { return 0.0; });
    expectSameAsSolid(HeightField::fromData(grid), HalfSpace{}, tilted(), Vec3(4, 3.75, 0), 3.0,
                      "flat height field vs half-space");
}

TEST(MeshQueries, RaysAndClosestPointsOnABoxMeshMatchTheBox) {
    const Vec3 e(1.5, 1, 0.5);
    const Shape surface = TriangleMesh::fromData(boxMesh(e));
    const Shape solid = Box{e};
    const Transform pose = tilted();
    std::mt19937 rng(2626);
    std::uniform_real_distribution<Real> unit(-1, 1);
    int hits = 0;
    Real worstFraction = 0, worstNormal = 0, worstClosest = 0;
    for (int trial = 0; trial < 2000; ++trial) {
        // From a point outside towards a point in or near the box.
        const Vec3 from = pose.apply(Vec3(unit(rng), unit(rng), unit(rng)).normalized() * 4);
        const Vec3 to = pose.apply(Vec3(2 * unit(rng), 1.4 * unit(rng), 0.8 * unit(rng)));
        const Ray ray{from, to - from, 2};
        const auto onSurface = raycast(surface, pose, ray);
        const auto onSolid = raycast(solid, pose, ray);
        ASSERT_EQ(onSurface.has_value(), onSolid.has_value()) << "trial " << trial;
        worstClosest =
            std::max(worstClosest,
                     (closestPoint(surface, pose, from) - closestPoint(solid, pose, from)).norm());
        if (!onSolid)
            continue;
        ++hits;
        worstFraction = std::max(worstFraction, std::abs(onSurface->fraction - onSolid->fraction));
        // On an edge either face's normal is right; away from edges they must agree.
        const Vec3 local = pose.applyInverse(onSolid->point).cwiseAbs();
        const auto nearEdges = ((e - local).array() < 1e-6).count();
        if (nearEdges < 2)
            worstNormal = std::max(worstNormal, (onSurface->normal - onSolid->normal).norm());
    }
    std::printf(
        "rays on a box mesh: %d hits, worst fraction difference %.3g, normal %.3g, closest "
        "point %.3g m\n",
        hits, worstFraction, worstNormal, worstClosest);
    EXPECT_GE(hits, 500);
    EXPECT_LT(worstFraction, 1e-12);
    EXPECT_LT(worstNormal, 1e-12);
    EXPECT_LT(worstClosest, 1e-12);
}

TEST(MeshQueries, RaysOnAHeightFieldHitItsTrianglesAndPassThroughHoles) {
    HeightFieldData grid = heightGrid(
        5, 4, 1, 2, [](std::uint32_t i, std::uint32_t j) { return 0.1 * i + 0.05 * j * j; });
    grid.holes.assign(4 * 3, 0);
    grid.holes[1 * 4 + 2] = 1;  // cell (2, 1)
    const Shape field = HeightField::fromData(grid);
    const HeightFieldGeometry& g = *std::get<HeightField>(field).data;
    const Transform pose{Vec3(-1, 2, 0.3), Quat(Eigen::AngleAxis<Real>(0.2, Vec3::UnitX()))};
    std::mt19937 rng(7);
    std::uniform_real_distribution<Real> u(0, 1);
    int hits = 0, holes = 0;
    for (int trial = 0; trial < 500; ++trial) {
        const Vec3 local(4 * u(rng), 6 * u(rng), 0);
        const auto i = static_cast<std::uint32_t>(local.x()),
                   j = static_cast<std::uint32_t>(local.y() / 2);
        // Straight down along the field's -z from above: the hit's height is the triangle's.
        const Ray ray{pose.apply(Vec3(local.x(), local.y(), 5)), pose.rotation * Vec3(0, 0, -10),
                      1};
        const auto hit = raycast(field, pose, ray);
        if (grid.holes[j * 4 + i] != 0) {
            ++holes;
            EXPECT_FALSE(hit.has_value()) << "through the hole";
            continue;
        }
        ASSERT_TRUE(hit.has_value());
        ++hits;
        const Vec3 point = pose.applyInverse(hit->point);
        const Vec3 nearest = detail::closestOnSurface(g, point);
        EXPECT_LT((nearest - point).norm(), 1e-12) << "on the surface";
        EXPECT_GT((pose.rotation.conjugate() * hit->normal).z(), 0.9) << "faces the ray";
    }
    EXPECT_GT(holes, 10);
    EXPECT_GT(hits, 400);
}

TEST(MeshNarrowphase, BoxRestingOnMeshKeepsItsFeatureIdsUnderJitter) {
    const Shape surface = TriangleMesh::fromData(flatGrid(8, 0.25));
    const Shape box = Box{Vec3(0.3, 0.2, 0.1)};
    const Transform rest{Vec3(0.1, -0.05, 0.1 - 1e-3),
                         Quat(Eigen::AngleAxis<Real>(0.3, Vec3::UnitZ()))};
    Manifold first;
    collide(box, rest, surface, Transform{}, 0.01, first);
    ASSERT_EQ(first.pointCount, 4);
    std::mt19937 rng(3);
    std::uniform_real_distribution<Real> unit(-1, 1);
    for (int trial = 0; trial < 100; ++trial) {
        Transform jittered = rest;
        jittered.position += 1e-7 * Vec3(unit(rng), unit(rng), unit(rng));
        Manifold again;
        collide(box, jittered, surface, Transform{}, 0.01, again);
        ASSERT_EQ(again.pointCount, 4);
        std::set<std::uint32_t> a, b;
        for (int k = 0; k < 4; ++k) {
            a.insert(first.points[static_cast<std::size_t>(k)].featureId);
            b.insert(again.points[static_cast<std::size_t>(k)].featureId);
        }
        EXPECT_EQ(a, b) << "trial " << trial;
        EXPECT_NEAR(deepest(again), -1e-3, 2e-7);
    }
}

}  // namespace
}  // namespace tumble
