// A convex shape against a triangle mesh or height field.
//
// Everything runs in the surface's local frame (the shape is moved there once), so triangles are
// read as stored. The triangles under the shape's box grown by the margin (mesh_triangles.h) are
// each collided with the shape as a thin convex polytope: a prism of kPrismThickness behind the
// triangle, so the general convex path (GJK, separating axes, clipping in collide_convex.cpp)
// sees proper side faces and edge arcs, and the surface is two-sided.
//
// Ghost contacts: where a shape slides from one triangle to its flat neighbour, the neighbour's
// nearest feature is the shared edge, and the pair routine's normal there points sideways: a
// bump. When the feature the contact lies on (the triangle's vertices farthest toward the shape:
// one vertex or an edge) has only internal edges (mesh_shape.h), the contact is redone along the
// triangle's face normal: the shape's points below the triangle's plane (the half-space routine)
// that lie over the triangle itself. Over the neighbour they are dropped; the neighbour's own
// contact holds them. A contact on the face gets those points too, beside the clipped ones
// (which reach the triangle's edges, e.g. at the rim of a table): the half-space routine's
// depth is exact where clipping approximates (a cylinder's rim by a polygon). So does a triangle
// for which the pair routine found nothing: the half-space routine is closed-form and cheap, and
// catches what an iterative query (EPA on a cylinder against a prism this thin) may miss. This is
// the active-edge idea of Jolt and Bullet's internal-edge utility, with the depth measured along
// the replaced normal.
//
// The per-triangle manifolds then make one manifold: the normal of the deepest point, and the
// points of every triangle whose normal lies within kMergeCos of it, reduced to 4 (deepest plus
// largest area, clipping.h). Feature ids mix the triangle index into the pair routine's ids, so a
// point keeps its id while the same triangle and features touch.

#include <array>
#include <vector>

#include "clipping.h"
#include "mesh_triangles.h"
#include "pair_routines.h"

namespace tumble::detail {
namespace {

/// Depth of the prism behind each triangle (m): enough for well-defined side faces and edge
/// directions, too thin to be felt.
constexpr Real kPrismThickness = 1e-6;
/// A shape counts as behind a triangle when its origin lies behind the plane by more than this
/// fraction of its bounding radius.
constexpr Real kBackReach = 0.5;
/// Vertices within this (m) of the farthest one along a direction belong to the same feature.
constexpr Real kFeatureTolerance = 1e-9;
/// Points of triangles whose normal makes more than acos(kMergeCos) (about 18 degrees) with the
/// deepest normal are left out of the manifold.
constexpr Real kMergeCos = 0.95;
/// Mixes a triangle's index into feature ids (Knuth's multiplicative hash constant).
constexpr std::uint32_t kTriangleMix = 0x9E3779B1u;
/// Marks the ids of points redone along a face normal.
constexpr std::uint32_t kFaceRedoTag = 0x5BD1E995u;
/// The id of the shape's deepest point along a face normal.
constexpr std::uint32_t kDeepestId = 0x7FFFFFFFu;

/// A triangle as a hull: front face, back face kPrismThickness behind, and three side faces.
/// One per thread, refilled for each triangle; the Shape points at it without owning it, so
/// nothing is allocated after the first call.
class TrianglePrism {
public:
    TrianglePrism() {
        data_.vertices.resize(6);
        data_.faces.resize(5);
        data_.faceVertices = {0, 1, 2, 5, 4, 3, 1, 0, 3, 4, 2, 1, 4, 5, 0, 2, 5, 3};
        data_.edges = {{0, 1}, {0, 2}, {0, 3}, {1, 2}, {1, 4}, {2, 5}, {3, 4}, {3, 5}, {4, 5}};
        for (std::uint32_t f = 0; f < 5; ++f)
            data_.faces[f] = {Vec3::UnitZ(), 0, f < 2 ? 3 * f : 6 + 4 * (f - 2), f < 2 ? 3u : 4u};
        shape_ =
            ConvexHull{std::shared_ptr<const HullData>(std::shared_ptr<const HullData>(), &data_)};
    }

    const Shape& shape(const MeshTriangle& t) {
        const Vec3& n = t.normal;
        for (std::size_t k = 0; k < 3; ++k) {
            data_.vertices[k] = t.vertices[k];
            data_.vertices[k + 3] = t.vertices[k] - kPrismThickness * n;
        }
        data_.faces[0].normal = n;
        data_.faces[0].offset = n.dot(t.vertices[0]);
        data_.faces[1].normal = -n;
        data_.faces[1].offset = -n.dot(data_.vertices[3]);
        for (std::size_t k = 0; k < 3; ++k) {
            const Vec3 side = (t.vertices[(k + 1) % 3] - t.vertices[k]).cross(n).normalized();
            data_.faces[2 + k].normal = side;
            data_.faces[2 + k].offset = side.dot(t.vertices[k]);
        }
        data_.centroid =
            (t.vertices[0] + t.vertices[1] + t.vertices[2]) / 3 - (kPrismThickness / 2) * n;
        return shape_;
    }

private:
    HullData data_;
    Shape shape_;
};

/// Edge bits of the triangle's feature farthest along `toward`: the edge of two vertices, the two
/// edges of one vertex; 0 for the whole face.
std::uint8_t featureEdges(const MeshTriangle& t, const Vec3& toward) {
    std::array<Real, 3> height;
    for (std::size_t k = 0; k < 3; ++k)
        height[k] = toward.dot(t.vertices[k]);
    const Real top = std::max({height[0], height[1], height[2]});
    std::uint8_t vertices = 0;
    for (std::size_t k = 0; k < 3; ++k)
        if (height[k] >= top - kFeatureTolerance)
            vertices |= static_cast<std::uint8_t>(1u << k);
    switch (vertices) {
        case 0b001:
            return 0b101;  // vertex 0: edges 2 (2 -> 0) and 0 (0 -> 1)
        case 0b010:
            return 0b011;
        case 0b100:
            return 0b110;
        case 0b011:
            return 0b001;  // edge 0
        case 0b110:
            return 0b010;
        case 0b101:
            return 0b100;
        default:
            return 0;
    }
}

/// Whether p (on or near the triangle's plane) projects into the triangle.
bool overTriangle(const MeshTriangle& t, const Vec3& p) {
    for (std::size_t k = 0; k < 3; ++k) {
        const Vec3& a = t.vertices[k];
        const Vec3& b = t.vertices[(k + 1) % 3];
        if ((b - a).cross(p - a).dot(t.normal) < -kFeatureTolerance * (b - a).norm())
            return false;
    }
    return true;
}

/// The face normal pointing from the shape into the triangle. The shape is in front unless its
/// origin lies behind the plane by more than `backReach`: a shape pressed into a surface past its
/// centre (a fast capsule into terrain) is still pushed out of the front, while one touching a
/// thin wall from behind is pushed back out behind. A sideways contact normal's tilt says
/// nothing of the side.
Vec3 intoTriangle(const Transform& pose, const MeshTriangle& t, Real backReach) {
    const bool front = t.normal.dot(pose.position - t.vertices[0]) >= -backReach;
    return front ? Vec3(-t.normal) : t.normal;
}

/// Redoes a contact along the face normal `normal` (from the shape into the triangle; see the
/// file comment).
void alongFace(const Shape& shape, const Transform& pose, const MeshTriangle& t, const Vec3& normal,
               Real margin, Manifold& m) {
    const Shape plane = HalfSpace{-normal, -normal.dot(t.vertices[0])};
    Manifold below;
    collideConvexHalfSpace(shape, pose, plane, Transform{}, margin, below);
    m.clear();
    m.normal = normal;
    // The half-space routine reduces to 4 points over the whole shape, and may keep one within
    // kDepthTolerance of the deepest instead of it; the support point along the normal is the
    // exact deepest, so it goes first.
    const Vec3 deepest = pose.apply(support(shape, pose.rotation.conjugate() * normal));
    const Real separation = normal.dot(t.vertices[0] - deepest);
    const Vec3 middle = deepest + (separation / 2) * normal;
    if (separation <= margin && overTriangle(t, middle))
        m.add(middle, separation, kDeepestId);
    for (int k = 0; k < below.pointCount; ++k) {
        const ContactPoint& c = below.points[static_cast<std::size_t>(k)];
        if (overTriangle(t, c.position))
            m.add(c.position, c.separation, c.featureId ^ kFaceRedoTag);
    }
}

struct TriangleManifold {
    Manifold manifold;
    std::uint32_t triangle;
};

/// Per-thread buffers, grown on first use and kept: no allocation in a warm step.
struct Scratch {
    TrianglePrism prism;
    std::vector<TriangleManifold> manifolds;
    std::array<ContactPoint, kMaxClipVertices> candidates;
};

Scratch& scratch() {
    thread_local Scratch s;
    return s;
}

/// reduceContacts may keep a point within kDepthTolerance of the deepest instead of it (for
/// stable ids); the manifold's depth should be exact, so the deepest candidate replaces the
/// kept point nearest to it.
void keepDeepest(const std::array<ContactPoint, kMaxClipVertices>& candidates, std::size_t count,
                 Manifold& out) {
    std::size_t deepest = 0;
    for (std::size_t k = 1; k < count; ++k)
        if (candidates[k].separation < candidates[deepest].separation)
            deepest = k;
    std::size_t nearest = 0;
    for (std::size_t k = 0; k < static_cast<std::size_t>(out.pointCount); ++k) {
        if (out.points[k].separation <= candidates[deepest].separation)
            return;
        if ((out.points[k].position - candidates[deepest].position).squaredNorm() <
            (out.points[nearest].position - candidates[deepest].position).squaredNorm())
            nearest = k;
    }
    if (out.pointCount > 0)
        out.points[nearest] = candidates[deepest];
}

/// One manifold from the triangles' (see the file comment), in the surface's frame.
void merge(const std::vector<TriangleManifold>& manifolds, Manifold& out) {
    Real deepest = INFINITY;
    Vec3 normal = Vec3::UnitZ();
    for (const TriangleManifold& tm : manifolds) {
        for (int k = 0; k < tm.manifold.pointCount; ++k) {
            if (tm.manifold.points[static_cast<std::size_t>(k)].separation < deepest) {
                deepest = tm.manifold.points[static_cast<std::size_t>(k)].separation;
                normal = tm.manifold.normal;
            }
        }
    }
    auto& candidates = scratch().candidates;
    std::size_t count = 0;
    for (const TriangleManifold& tm : manifolds) {
        if (tm.manifold.normal.dot(normal) < kMergeCos)
            continue;
        for (int k = 0; k < tm.manifold.pointCount; ++k) {
            if (count == candidates.size()) {  // full: keep the best 4 and go on
                reduceContacts(std::span<const ContactPoint>(candidates.data(), count), normal,
                               out);
                count = static_cast<std::size_t>(out.pointCount);
                std::copy_n(out.points.begin(), count, candidates.begin());
            }
            ContactPoint c = tm.manifold.points[static_cast<std::size_t>(k)];
            c.featureId ^= tm.triangle * kTriangleMix;
            candidates[count++] = c;
        }
    }
    reduceContacts(std::span<const ContactPoint>(candidates.data(), count), normal, out);
    keepDeepest(candidates, count, out);
}

}  // namespace

void collideConvexMesh(const Shape& a, const Transform& poseA, const Shape& b,
                       const Transform& poseB, Real margin, Manifold& out) {
    out.clear();
    const Transform pose{poseB.applyInverse(poseA.position),
                         (poseB.rotation.conjugate() * poseA.rotation).normalized()};
    const Aabb box = boundsOf(a, pose).fattened(margin);
    const Real backReach = kBackReach * boundingRadius(a);
    Scratch& s = scratch();
    s.manifolds.clear();
    forEachTriangle(b, box, [&](const MeshTriangle& t) {
        TriangleManifold tm{{}, t.index};
        collideConvex(a, pose, s.prism.shape(t), Transform{}, margin, tm.manifold);
        const Vec3 normal = intoTriangle(pose, t, backReach);
        if (tm.manifold.pointCount > 0) {
            const std::uint8_t edges = featureEdges(t, -tm.manifold.normal);
            if (edges != 0 && (edges & t.activeEdges) != 0) {
                s.manifolds.push_back(tm);  // an active edge or vertex: its own normal
                return;
            }
            // On the face from the shape's side: clipped points reach the triangle's edges.
            if (edges == 0 && tm.manifold.normal.dot(normal) > 0)
                s.manifolds.push_back(tm);
        }
        alongFace(a, pose, t, normal, margin, tm.manifold);
        if (tm.manifold.pointCount > 0)
            s.manifolds.push_back(tm);
    });
    if (s.manifolds.empty())
        return;
    merge(s.manifolds, out);
    out.normal = poseB.rotation * out.normal;
    for (int k = 0; k < out.pointCount; ++k) {
        ContactPoint& c = out.points[static_cast<std::size_t>(k)];
        c.position = poseB.apply(c.position);
    }
}

}  // namespace tumble::detail
