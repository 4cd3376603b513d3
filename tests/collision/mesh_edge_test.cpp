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

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <random>
#include <tuple>
#include <vector>

#include "ccd_adapter.h"
#include "collision/mesh_fixtures.h"
#include "tumble/collision/narrowphase.h"

namespace tumble {
namespace {

/// Smooth bumps: at scale 1, neighbouring triangles of a 0.25 m grid fold by under 3 degrees; at
/// scale 4, by up to ~20 degrees (active edges, convex and concave).
Real bump(Real x, Real y, Real scale) {
    return scale * 0.06 * std::sin(1.5 * x + 0.3) * std::cos(1.3 * y) + 0.03 * x;
}

constexpr Real kCell = 0.25;
constexpr std::uint32_t kSamples = 25;

Shape bumpyField(Real scale = 1) {
    return HeightField::fromData(testing::heightGrid(
        kSamples, kSamples, kCell, kCell,
        [&](std::uint32_t i, std::uint32_t j) { return bump(i * kCell, j * kCell, scale); }));
}

Shape bumpyMesh(Real scale = 1) {
    TriangleMeshData data = testing::flatGrid(static_cast<int>(kSamples) - 1, kCell);
    for (Vec3& v : data.vertices)
        v.z() = bump(v.x(), v.y(), scale);
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

/// A random shape of `kind` whose deepest point along a direction up to `maxTilt` (rad) off the
/// face normal of a random edge (an active one if `active`) lies 0-5 cm below a point of it.
struct EdgePose {
    MeshTriangle triangle;
    int edge;
    Shape shape;
    Transform pose;
};

EdgePose poseOverEdge(const Shape& surface, std::mt19937& rng, int kind, Real maxTilt,
                      bool active) {
    std::uniform_real_distribution<Real> u(0, 1);
    auto [t, edge] = randomEdge(surface, rng);
    while (active && ((t.activeEdges >> edge) & 1u) == 0)
        std::tie(t, edge) = randomEdge(surface, rng);
    const Vec3 a = t.vertices[static_cast<std::size_t>(edge)];
    const Vec3 b = t.vertices[static_cast<std::size_t>((edge + 1) % 3)];
    const Vec3 point = a + (0.05 + 0.9 * u(rng)) * (b - a);
    const Real tilt = (2 * u(rng) - 1) * maxTilt;
    const Vec3 along = Eigen::AngleAxis<Real>(tilt, (b - a).normalized()) * t.normal;
    EdgePose p{t, edge, testing::randomConvex(rng, kind),
               Transform{Vec3::Zero(), testing::randomRotation(rng)}};
    const Real depth = 0.05 * u(rng);
    p.pose.position = point - depth * along -
                      p.pose.rotation * support(p.shape, p.pose.rotation.conjugate() * -along);
    return p;
}

/// The triangles under `box`, and each as the column 1 m deep below it (see depthAlong).
void trianglesUnder(const Shape& surface, const Aabb& box, std::vector<MeshTriangle>& triangles,
                    std::vector<Shape>& columns) {
    detail::forEachTriangle(surface, box, [&](const MeshTriangle& c) {
        std::vector<Vec3> corners(c.vertices.begin(), c.vertices.end());
        for (const Vec3& v : c.vertices)
            corners.push_back(v - Vec3::UnitZ());
        columns.push_back(ConvexHull::fromPoints(corners));
        triangles.push_back(c);
    });
}

struct EdgeFigures {
    int poses = 0, touching = 0, exact = 0;
    Real worstDepth = 0, worstRelative = 0, worstNormal = 0;
};

/// One random pose over an internal edge of `surface` (see the file comment), checked.
void checkPose(const Shape& surface, std::mt19937& rng, int kind, EdgeFigures& f) {
    const EdgePose p = poseOverEdge(surface, rng, kind == 3 ? 4 : kind, kFlatEdgeAngle, false);
    ASSERT_EQ(p.triangle.activeEdges, 0) << "the surface's folds are within kFlatEdgeAngle";
    const Shape& shape = p.shape;
    const Transform& pose = p.pose;
    const MeshTriangle& t = p.triangle;
    Manifold m;
    collide(shape, pose, surface, Transform{}, 0.02, m);
    std::vector<Shape> columns;
    std::vector<MeshTriangle> near;
    trianglesUnder(surface, boundsOf(shape, pose).fattened(0.35), near, columns);
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
    for (const MeshTriangle& c : near)
        nearest = std::min(nearest, (c.normal - up).norm());
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

// Boxes and hulls over the active edges of steeper surfaces (the same bumps 8 times higher: folds
// up to 18.6 degrees, convex and concave), 0-5 cm deep along a normal up to 29 degrees off the
// face's. The pair routine's normal on an active edge or vertex is kept only inside that feature's
// normal cone (a thin prism's least way out of a shape deep below an edge is its side face, 90
// degrees off: the terrain pile's hulls were pushed sideways and sank 2 cm deeper than on a
// half-space); outside it the contact is redone along the face normal. Asserted: every touching
// pose gets a point; the deepest manifold's normal lies in the normal cone of the surface under the
// shape (a face normal, an edge's wedge between its faces' normals, or a direction no neighbour of
// some vertex rises above) within kConeAllowance; where that manifold is the pair's only one and
// its normal is an edge's, its depth equals the depth along the normal (depthAlong) within 1e-9 m +
// (1 / cos 5 deg - 1) of it. Before the cone, 235 and 221 of 1,000 poses (boxes, hulls, spheres,
// capsules) had normals off it.
// The depth is printed for every pose, not asserted (97 % within the allowance, worst 3.6 cm):
// with several manifolds each holds its own triangles, and clearing all of them along one normal
// takes more; and a face normal's redo near a concave valley counts points of the shape below the
// face's plane but above the rising neighbour (over-reports, as before the cone).

constexpr Real kSteep = 8;
constexpr Real kConeAllowance = 1e-9;

/// Whether `d` (unit, from the surface toward the shape) is a face normal of one of `faces`, lies
/// in the wedge of one of their edges, or in the normal cone of one of their vertices (the
/// neighbours of an edge or vertex: the vertices of the triangles of `ring` that share it).
bool inNormalCone(const Vec3& d, const std::vector<MeshTriangle>& faces,
                  const std::vector<MeshTriangle>& ring) {
    const auto shares = [](const MeshTriangle& r, const Vec3& v) {
        return std::any_of(r.vertices.begin(), r.vertices.end(),
                           [&](const Vec3& p) { return p == v; });
    };
    for (const MeshTriangle& f : faces) {
        if ((f.normal - d).norm() <= kConeAllowance)
            return true;
        for (std::size_t k = 0; k < 3; ++k) {  // the wedge of edge a-b, across it
            const Vec3 &a = f.vertices[k], &b = f.vertices[(k + 1) % 3];
            const Vec3 e = (b - a).normalized();
            const auto below = [&](const Vec3& p) {
                const Vec3 across = p - a - (p - a).dot(e) * e;
                return d.dot(across) <= kConeAllowance * across.norm();
            };
            bool inWedge = std::abs(d.dot(e)) <= kConeAllowance;
            for (const MeshTriangle& r : ring)
                if (shares(r, a) && shares(r, b))
                    for (const Vec3& x : r.vertices)
                        inWedge = inWedge && below(x);
            if (inWedge)
                return true;
        }
        for (const Vec3& v : f.vertices) {
            bool below = true;
            for (const MeshTriangle& r : ring) {
                if (!shares(r, v))
                    continue;
                for (const Vec3& x : r.vertices)
                    below = below && d.dot(x - v) <= kConeAllowance * (x - v).norm();
            }
            if (below)
                return true;
        }
    }
    return false;
}

struct ActiveFigures {
    int poses = 0, touching = 0, exact = 0, offCone = 0, edgeNormals = 0, withinAllowance = 0;
    Real worstDepth = 0, worstRelative = 0, worstEdgeDepth = 0;
};

/// One random pose over an active edge of `surface`, checked (see above).
void checkActivePose(const Shape& surface, std::mt19937& rng, int kind, ActiveFigures& f) {
    const EdgePose p = poseOverEdge(surface, rng, kind, 0.5, true);  // up to 29 degrees
    const Shape& shape = p.shape;
    const Transform& pose = p.pose;
    ManifoldSet set;
    collide(shape, pose, surface, Transform{}, 0.02, set);
    const Manifold& m = set.manifolds[0];
    std::vector<Shape> columns;
    std::vector<MeshTriangle> faces, ring;
    const Aabb box = boundsOf(shape, pose);
    trianglesUnder(surface, box.fattened(0.35), ring, columns);
    detail::forEachTriangle(surface, box.fattened(0.02),
                            [&](const MeshTriangle& c) { faces.push_back(c); });
    ++f.poses;
    if (m.pointCount == 0) {
        EXPECT_LE(depthAlong(shape, pose, p.triangle.normal, columns), 0)
            << "pose " << f.poses - 1 << " kind " << kind << " has no point";
        return;
    }
    const Vec3 up = -m.normal;
    const Real reference = depthAlong(shape, pose, up, columns);
    if (reference <= 0)
        return;
    ++f.touching;
    const bool inCone = inNormalCone(up, faces, ring);
    f.offCone += inCone ? 0 : 1;
    EXPECT_TRUE(inCone) << "pose " << f.poses - 1 << " kind " << kind << " normal "
                        << up.transpose();
    Real deepest = INFINITY;
    for (int k = 0; k < m.pointCount; ++k)
        deepest = std::min(deepest, m.points[static_cast<std::size_t>(k)].separation);
    const Real error = std::abs(deepest + reference);
    const Real allowed = 1e-9 + (1 / std::cos(5 * std::numbers::pi / 180) - 1) * reference;
    const bool onFace = std::any_of(faces.begin(), faces.end(), [&](const MeshTriangle& c) {
        return (c.normal - up).norm() <= kConeAllowance;
    });
    if (!onFace && set.count == 1) {
        ++f.edgeNormals;
        f.worstEdgeDepth = std::max(f.worstEdgeDepth, error);
        EXPECT_LE(error, allowed) << "pose " << f.poses - 1 << " kind " << kind << " depth "
                                  << reference << " reported " << -deepest << " manifolds "
                                  << set.count;
    }
    f.withinAllowance += error <= allowed ? 1 : 0;
    f.exact += error <= 1e-9 ? 1 : 0;
    f.worstDepth = std::max(f.worstDepth, error);
    f.worstRelative = std::max(f.worstRelative, error / reference);
}

void expectConeNormalsOverActiveEdges(const Shape& surface, const char* what) {
    std::mt19937 rng(2627);
    ActiveFigures f;
    for (int trial = 0; trial < 1000; ++trial)
        checkActivePose(surface, rng, trial % 2 == 0 ? 2 : 4, f);  // boxes and hulls
    std::printf(
        "%s, active edges: %d poses, %d touching, %d normals off the cone; %d alone with an "
        "edge normal, worst depth error %.3g m; all: depth exact within 1e-9 m at %d, within the "
        "allowance at %d, worst depth error %.3g m (%.3g of the depth)\n",
        what, f.poses, f.touching, f.offCone, f.edgeNormals, f.worstEdgeDepth, f.exact,
        f.withinAllowance, f.worstDepth, f.worstRelative);
    EXPECT_GE(f.touching, 900);
}

TEST(MeshActiveEdges, NormalsOverActiveEdgesOfASteepHeightFieldLieInTheirCone) {
    expectConeNormalsOverActiveEdges(bumpyField(kSteep), "steep height field");
}

TEST(MeshActiveEdges, NormalsOverActiveEdgesOfASteepMeshLieInTheirCone) {
    expectConeNormalsOverActiveEdges(bumpyMesh(kSteep), "steep mesh");
}

}  // namespace
}  // namespace tumble
