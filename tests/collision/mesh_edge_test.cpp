// Shapes over the internal edges of bumpy surfaces (issue 26): a rounded shape whose centre lies
// between the face normals of a convex fold within kFlatEdgeAngle had no contact point (the redo
// along either face normal fell over the other triangle), so a sphere sank 4.6 cm into the
// terrain. Here spheres, capsules, boxes and hulls sit over random points of random internal
// edges of a bumpy height field and a bumpy mesh, every fold within 3 degrees (all internal edges
// inactive), at depths 0-5 cm along a normal up to 3 degrees off the face's, so the poses cover
// both folds' wedges. Every touching pose must get a point; the normal must be a face normal (no
// ghost: an edge normal); and the depth must equal the exact depth along that normal (the
// translation that clears every triangle, by conservative advancement against the columns under
// them) within 1e-9 m + (1 / cos 3 deg - 1) of it. That allowance, set before measuring, is how
// far a depth along one face normal may differ from one along a neighbour's within the
// threshold: over a fold's wedge the point is the pair routine's (the distance to the edge) and
// a crease's two faces share one manifold's normal.

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <random>
#include <vector>

#include "ccd_adapter.h"
#include "collision/mesh_fixtures.h"
#include "tumble/collision/narrowphase.h"

namespace tumble {
namespace {

/// Smooth bumps: neighbouring triangles of a 0.25 m grid fold by under 3 degrees.
Real bump(Real x, Real y) {
    return 0.06 * std::sin(1.5 * x + 0.3) * std::cos(1.3 * y) + 0.03 * x;
}

constexpr Real kCell = 0.25;
constexpr std::uint32_t kSamples = 25;

Shape bumpyField() {
    return HeightField::fromData(testing::heightGrid(
        kSamples, kSamples, kCell, kCell,
        [](std::uint32_t i, std::uint32_t j) { return bump(i * kCell, j * kCell); }));
}

Shape bumpyMesh() {
    TriangleMeshData data = testing::flatGrid(static_cast<int>(kSamples) - 1, kCell);
    for (Vec3& v : data.vertices)
        v.z() = bump(v.x(), v.y());
    return TriangleMesh::fromData(data);
}

/// A random triangle with an internal edge away from the border, and that edge's index.
std::pair<MeshTriangle, int> randomEdge(const Shape& surface, std::mt19937& rng) {
    std::uniform_int_distribution<std::uint32_t> cell(2, kSamples - 4);
    std::uniform_int_distribution<int> pick(0, 5);
    const int k = pick(rng);
    if (const auto* field = std::get_if<HeightField>(&surface))
        return {detail::fieldTriangle(*field->data, cell(rng), cell(rng), k / 3), k % 3};
    const MeshGeometry& mesh = *std::get<TriangleMesh>(surface).data;
    const Real half = (kSamples - 1) * kCell / 2;
    const Vec3 at(cell(rng) * kCell - half + 0.1, cell(rng) * kCell - half + 0.1, 0);
    MeshTriangle found;
    detail::forEachTriangle(mesh, Aabb{at - Vec3(0, 0, 1), at + Vec3(0, 0, 1)},
                            [&](const MeshTriangle& t) { found = t; });
    return {found, k % 3};
}

/// How far (m) `shape` at `pose` must move along `up` to clear every triangle near it, each as
/// the column 1 m deep below it (the solid under a height-field-like surface): conservative
/// advancement from 0.3 m up, each step the least distance to the columns.
Real depthAlong(const Shape& shape, const Transform& pose, const Vec3& up,
                const std::vector<Shape>& columns) {
    Real t = 0.3;
    for (int iteration = 0; iteration < 1000; ++iteration) {
        const Transform moved{pose.position + t * up, pose.rotation};
        Real gap = INFINITY;
        for (const Shape& column : columns)
            gap = std::min(gap, detail::queryConvex(shape, moved, column, Transform{}).separation);
        if (gap < 1e-13)
            break;
        t -= gap;
    }
    return t;
}

struct EdgeFigures {
    int poses = 0, touching = 0, exact = 0;
    Real worstDepth = 0, worstRelative = 0, worstNormal = 0;
};

/// One random pose over an internal edge of `surface` (see the file comment), checked.
void checkPose(const Shape& surface, std::mt19937& rng, int kind, EdgeFigures& f) {
    std::uniform_real_distribution<Real> u(0, 1);
    const auto [t, edge] = randomEdge(surface, rng);
    ASSERT_EQ(t.activeEdges, 0) << "the surface's folds are within kFlatEdgeAngle";
    const Vec3 a = t.vertices[static_cast<std::size_t>(edge)];
    const Vec3 b = t.vertices[static_cast<std::size_t>((edge + 1) % 3)];
    const Vec3 point = a + (0.05 + 0.9 * u(rng)) * (b - a);
    const Real tilt = (2 * u(rng) - 1) * kFlatEdgeAngle;
    const Vec3 along = Eigen::AngleAxis<Real>(tilt, (b - a).normalized()) * t.normal;
    const Shape shape = testing::randomConvex(rng, kind == 3 ? 4 : kind);  // not cylinders
    Transform pose{Vec3::Zero(), testing::randomRotation(rng)};
    // The shape's deepest point along -along lies `depth` below the edge point.
    const Real depth = 0.05 * u(rng);
    pose.position =
        point - depth * along - pose.rotation * support(shape, pose.rotation.conjugate() * -along);
    Manifold m;
    collide(shape, pose, surface, Transform{}, 0.02, m);
    std::vector<Shape> columns;
    std::vector<Vec3> normals;
    detail::forEachTriangle(surface, boundsOf(shape, pose).fattened(0.35),
                            [&](const MeshTriangle& c) {
                                std::vector<Vec3> corners(c.vertices.begin(), c.vertices.end());
                                for (const Vec3& v : c.vertices)
                                    corners.push_back(v - Vec3::UnitZ());
                                columns.push_back(ConvexHull::fromPoints(corners));
                                normals.push_back(c.normal);
                            });
    ++f.poses;
    const Vec3 up = m.pointCount > 0 ? Vec3(-m.normal) : t.normal;
    const Real reference = depthAlong(shape, pose, up, columns);
    if (reference <= 0)
        return;
    ++f.touching;
    ASSERT_GT(m.pointCount, 0) << "pose " << f.poses - 1 << " kind " << kind
                               << " depth along the normal " << reference;
    Real deepest = INFINITY;
    for (int k = 0; k < m.pointCount; ++k)
        deepest = std::min(deepest, m.points[static_cast<std::size_t>(k)].separation);
    const Real error = std::abs(deepest + reference);
    const Real allowed = 1e-9 + (1 / std::cos(kFlatEdgeAngle) - 1) * reference;
    EXPECT_LE(error, allowed) << "pose " << f.poses - 1 << " kind " << kind << " depth "
                              << reference << " reported " << -deepest;
    f.exact += error <= 1e-9 ? 1 : 0;
    f.worstDepth = std::max(f.worstDepth, error);
    f.worstRelative = std::max(f.worstRelative, error / reference);
    Real nearest = INFINITY;
    for (const Vec3& normal : normals)
        nearest = std::min(nearest, (normal - up).norm());
    f.worstNormal = std::max(f.worstNormal, nearest);
}

void expectContactsOverInternalEdges(const Shape& surface, const char* what) {
    std::mt19937 rng(2626);
    EdgeFigures f;
    for (int trial = 0; trial < 1000; ++trial)
        checkPose(surface, rng, trial % 4, f);
    std::printf(
        "%s: %d poses, %d touching, %d with the depth exact within 1e-9 m; worst depth error "
        "%.3g m (%.3g of the depth), normal off a face normal by %.3g\n",
        what, f.poses, f.touching, f.exact, f.worstDepth, f.worstRelative, f.worstNormal);
    EXPECT_GE(f.touching, 900);
    EXPECT_LT(f.worstNormal, 1e-9);
}

TEST(MeshInternalEdges, EveryShapeOverAnInternalEdgeOfABumpyHeightFieldGetsItsDepth) {
    expectContactsOverInternalEdges(bumpyField(), "bumpy height field");
}

TEST(MeshInternalEdges, EveryShapeOverAnInternalEdgeOfABumpyMeshGetsItsDepth) {
    expectContactsOverInternalEdges(bumpyMesh(), "bumpy mesh");
}

}  // namespace
}  // namespace tumble
