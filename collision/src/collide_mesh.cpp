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
// contact holds them; where no face's projection reaches, see offerGap and onFaceNormal. A contact
// on the face gets those points too, beside the clipped ones (which reach the triangle's edges,
// e.g. at the rim of a table): the half-space routine's depth is exact where clipping approximates
// (a cylinder's rim by a polygon). So does a triangle for which the pair routine found nothing: the
// half-space routine is closed-form and cheap, and catches what an iterative query (EPA on a
// cylinder against a prism this thin) may miss. This is the active-edge idea of Jolt and Bullet's
// internal-edge utility, with the depth measured along the replaced normal.
//
// The per-triangle manifolds then make up to ManifoldSet::kMaxManifolds manifolds, one per group
// of like normals (as Jolt keeps a manifold per sub-shape pair and merges those of near normals):
// the deepest point not yet grouped seeds a group with its triangle manifold's normal, and every
// ungrouped triangle whose normal lies within kMergeCos of it joins; past the limit, the rest
// join the group of the nearest normal. Each group's points are reduced to 4 (deepest plus
// largest area, clipping.h). So a box in a V-shaped crease gets a manifold on each face, each
// the one a half-space in that face's plane gives. Feature ids mix the triangle index into the
// pair routine's ids, so a point keeps its id while the same triangle and features touch.

#include <algorithm>
#include <array>
#include <cmath>
#include <vector>

#include "clipping.h"
#include "gjk.h"
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
/// Triangles whose normals lie within acos(kMergeCos) (5 degrees) of a group's share its
/// manifold: a curved surface's neighbours (internal edges are flat within 3 degrees), but not
/// the two faces of a crease (a V of 170 degrees folds by 10).
constexpr Real kMergeCos = 0.99619469809174555;
/// cos(kFlatEdgeAngle): an internal edge's contact normal within this of the face normal may lie
/// between the face normals of a convex fold (onFaceNormal).
constexpr Real kWedgeCos = 0.99862953475457383;
/// Points of one group closer than this (m) are one contact point.
constexpr Real kSamePoint = 1e-6;
/// Depths this close (m) are equal but for rounding: far below what the solver or a caller sees.
constexpr Real kDepthNoise = 1e-10;
/// Mixes a triangle's index into feature ids (Knuth's multiplicative hash constant).
constexpr std::uint32_t kTriangleMix = 0x9E3779B1u;
/// Marks the ids of points redone along a face normal.
constexpr std::uint32_t kFaceRedoTag = 0x5BD1E995u;
/// Marks the ids of points kept with the face normal though the redo dropped them (onFaceNormal).
constexpr std::uint32_t kUnclaimedTag = 0x68E31DA4u;
/// Marks the ids of points kept below an internal edge (offerGap).
constexpr std::uint32_t kGapTag = 0x2545F491u;
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

/// Adds the shape's exact deepest point `c` to `m`. The half-space routine reduces to 4 points over
/// the whole shape and may keep one within kDepthTolerance of the deepest instead of it. Where
/// `c` is one of the points (an edge lying flat, whose support point rounding moves from end to
/// end), that point takes its depth and keeps its id; else `c` replaces the point nearest to it
/// if `m` is full.
void addDeepest(Manifold& m, const ContactPoint& c) {
    std::size_t nearest = 0;
    for (std::size_t k = 0; k < static_cast<std::size_t>(m.pointCount); ++k) {
        const Real distance = (m.points[k].position - c.position).squaredNorm();
        if (distance < kSamePoint * kSamePoint) {
            m.points[k].separation = std::min(m.points[k].separation, c.separation);
            return;
        }
        if (distance < (m.points[nearest].position - c.position).squaredNorm())
            nearest = k;
    }
    if (m.pointCount < Manifold::kMaxPoints)
        m.add(c.position, c.separation, c.featureId);
    else
        m.points[nearest] = c;
}

/// A point below a triangle's plane that the redo along its face normal dropped as lying over a
/// neighbour, while it may lie where no triangle's projection reaches (gapPoint).
struct GapPoint {
    ContactPoint point;
    Vec3 normal;      ///< the triangle's face normal, from the shape into it
    Vec3 shapePoint;  ///< the point on the shape it stands for
    Vec3 core;        ///< the centre of the shape's rounding there (shapePoint if none)
    bool inside;      ///< whether `core` lies below the triangle's plane
    std::uint32_t triangle;
};

/// How far (m, in the plane) p lies outside the triangle (0 over it); `pastActive` tells whether
/// one of the edges it lies beyond is active.
Real outsideDistance(const MeshTriangle& t, const Vec3& p, bool& pastActive) {
    int outside = 0;
    Real farthest = 0;
    pastActive = false;
    for (std::size_t k = 0; k < 3; ++k) {
        const Vec3& a = t.vertices[k];
        const Vec3 edge = t.vertices[(k + 1) % 3] - a;
        const Real out = -edge.cross(p - a).dot(t.normal) / edge.norm();
        if (out <= kFeatureTolerance)
            continue;
        pastActive = pastActive || ((t.activeEdges >> k) & 1u) != 0;
        ++outside;
        farthest = std::max(farthest, out);
    }
    if (outside < 2)
        return farthest;
    Real nearest = INFINITY;  // beyond two edges: the distance to their vertex
    for (const Vec3& v : t.vertices) {
        const Vec3 d = p - v;
        nearest = std::min(nearest, Vec3(d - d.dot(t.normal) * t.normal).norm());
    }
    return nearest;
}

/// Offers `c` (a point the redo along `normal` dropped) to the gap points: below the plane and
/// beyond internal edges by no more than its depth (45 degrees). Below a concave internal edge
/// (a valley), a point of the shape within the edge's wedge projects onto neither face, so each
/// face's redo drops it; a box corner there had no contact. Its depth is its distance to this
/// triangle (to the edge: the exact distance to the surface in the wedge). Kept only if no
/// triangle keeps the same point of the shape (collideConvexMesh): over a convex fold of
/// kFlatEdgeAngle the thin sliver between the plane and the neighbour lies beyond the edge by
/// 1 / tan(kFlatEdgeAngle) times its depth, so no point there qualifies.
void offerGap(const MeshTriangle& t, const ContactPoint& c, const Vec3& normal, Real rounding,
              std::vector<GapPoint>& gaps) {
    if (!(c.separation < 0))
        return;
    bool pastActive;
    const Real beyond = outsideDistance(t, c.position, pastActive);
    if (pastActive || beyond > -c.separation)
        return;
    const Vec3 shapePoint = c.position - (c.separation / 2) * normal;
    for (const GapPoint& g : gaps)
        if (g.triangle == t.index && (g.shapePoint - shapePoint).norm() < kSamePoint)
            return;
    gaps.push_back({{c.position, c.separation, c.featureId ^ kGapTag},
                    normal,
                    shapePoint,
                    shapePoint - rounding * normal,
                    rounding + c.separation < 0,
                    t.index});
}

/// The distance (m) from p to the triangle.
Real distanceTo(const MeshTriangle& t, const Vec3& p) {
    bool pastActive;
    return std::hypot(t.normal.dot(p - t.vertices[0]), outsideDistance(t, p, pastActive));
}

/// Sets the gap points' depths: a point of the shape in an edge's wedge is nearest to an edge or
/// vertex, so its depth is its distance to the nearest of `triangles` (a rounded shape's: its
/// core point's, less or plus the rounding), not its depth below its own triangle's plane.
void measureGaps(std::vector<GapPoint>& gaps, const std::vector<MeshTriangle>& triangles,
                 Real rounding) {
    for (GapPoint& g : gaps) {
        Real nearest = INFINITY;
        for (const MeshTriangle& t : triangles)
            nearest = std::min(nearest, distanceTo(t, g.core));
        g.point.separation = g.inside ? -(nearest + rounding) : nearest - rounding;
    }
}

/// Redoes a contact along the face normal `normal` (from the shape into the triangle; see the
/// file comment). Points dropped as lying over a neighbour are offered to `gaps`.
void alongFace(const Shape& shape, const Transform& pose, const MeshTriangle& t, const Vec3& normal,
               Real margin, Manifold& m, std::vector<GapPoint>& gaps) {
    const Shape plane = HalfSpace{-normal, -normal.dot(t.vertices[0])};
    Manifold below;
    collideConvexHalfSpace(shape, pose, plane, Transform{}, margin, below);
    m.clear();
    m.normal = normal;
    for (int k = 0; k < below.pointCount; ++k) {
        const ContactPoint& c = below.points[static_cast<std::size_t>(k)];
        if (overTriangle(t, c.position))
            m.add(c.position, c.separation, c.featureId ^ kFaceRedoTag);
        else
            offerGap(t, {c.position, c.separation, c.featureId ^ kFaceRedoTag}, normal,
                     roundingRadius(shape), gaps);
    }
    const Vec3 deepest = pose.apply(support(shape, pose.rotation.conjugate() * normal));
    const Real separation = normal.dot(t.vertices[0] - deepest);
    const Vec3 middle = deepest + (separation / 2) * normal;
    if (separation > margin)
        return;
    if (overTriangle(t, middle))
        addDeepest(m, {middle, separation, kDeepestId});
    else
        offerGap(t, {middle, separation, kDeepestId}, normal, roundingRadius(shape), gaps);
}

struct TriangleManifold {
    Manifold manifold;
    std::uint32_t triangle;
    std::uint8_t group = 0;  ///< which of the pair's manifolds takes its points
};

/// A contact on an internal edge or vertex, kept with the face normal `normal` (as Jolt's inactive
/// edges keep theirs): its points and depths are the pair routine's, the true distance to this
/// triangle. Used only when no triangle kept a point: over a convex internal edge (a fold within
/// kFlatEdgeAngle) a rounded shape whose centre lies between the two face normals has its
/// deepest point along either normal over the other triangle, so the redo along each face
/// drops it (a band as wide as r times the fold). Only contacts whose normal lies within
/// kFlatEdgeAngle of the face normal qualify: further out the shape lies beyond the fold's
/// wedge, where a neighbour holds it. Taken when something else holds the shape, they would add
/// points off the exact ones (by up to r sin(kFlatEdgeAngle) on a flat mesh), so they are not.
TriangleManifold onFaceNormal(const TriangleManifold& edge, const Vec3& normal) {
    TriangleManifold out = edge;
    out.manifold.normal = normal;
    for (int k = 0; k < out.manifold.pointCount; ++k)
        out.manifold.points[static_cast<std::size_t>(k)].featureId ^= kUnclaimedTag;
    return out;
}

/// Per-thread buffers, grown on first use and kept: no allocation in a warm step.
struct Scratch {
    TrianglePrism prism;
    std::vector<TriangleManifold> manifolds;
    std::vector<TriangleManifold> unclaimed;  ///< see onFaceNormal
    std::vector<GapPoint> gaps;
    std::vector<MeshTriangle> triangles;  ///< all under the shape's box
    std::array<ContactPoint, kMaxClipVertices> candidates;
};

Scratch& scratch() {
    thread_local Scratch s;
    return s;
}

/// Whether another triangle than g's own holds g's point of the shape: one kept a point of the
/// same id (for a rounded shape, the same core: its point lies elsewhere along each normal); or
/// the point lies on or below one's plane and over it (inside the solid it bounds) and that one
/// kept points (among the first `kept` of `manifolds`); or a gap point of another triangle with
/// the same id is nearer, or as near and earlier (a point below a vertex is offered by every
/// triangle around it; one stands for it).
bool heldElsewhere(const std::vector<MeshTriangle>& triangles, const std::vector<GapPoint>& gaps,
                   const std::vector<TriangleManifold>& manifolds, std::size_t kept,
                   const GapPoint& g) {
    const auto end = manifolds.begin() + static_cast<std::ptrdiff_t>(kept);
    const auto keeps = [&](std::uint32_t triangle) {
        return std::any_of(manifolds.begin(), end,
                           [&](const TriangleManifold& tm) { return tm.triangle == triangle; });
    };
    const std::uint32_t redoId = g.point.featureId ^ kGapTag;
    const bool keptAsIs = std::any_of(manifolds.begin(), end, [&](const TriangleManifold& tm) {
        return std::any_of(tm.manifold.points.begin(),
                           tm.manifold.points.begin() + tm.manifold.pointCount,
                           [&](const ContactPoint& c) { return c.featureId == redoId; });
    });
    const bool under = std::any_of(triangles.begin(), triangles.end(), [&](const MeshTriangle& t) {
        return t.index != g.triangle && t.normal.dot(g.shapePoint - t.vertices[0]) <= 0 &&
               overTriangle(t, g.shapePoint) && keeps(t.index);
    });
    return keptAsIs || under || std::any_of(gaps.begin(), gaps.end(), [&](const GapPoint& other) {
               if (other.triangle == g.triangle || other.point.featureId != g.point.featureId)
                   return false;
               const Real nearer = other.point.separation - g.point.separation;
               return nearer > kDepthNoise || (nearer >= -kDepthNoise && &other < &g);
           });
}

/// Adds the gap points (offerGap) no other triangle holds, each to a manifold of its triangle
/// with that face normal.
void addGaps(const std::vector<GapPoint>& gaps, const std::vector<MeshTriangle>& triangles,
             std::vector<TriangleManifold>& manifolds) {
    const std::size_t kept = manifolds.size();
    for (const GapPoint& g : gaps) {
        if (!(g.point.separation < 0) || heldElsewhere(triangles, gaps, manifolds, kept, g))
            continue;
        if (manifolds.size() == kept || manifolds.back().triangle != g.triangle ||
            manifolds.back().manifold.pointCount == Manifold::kMaxPoints) {
            manifolds.push_back({{}, g.triangle});
            manifolds.back().manifold.normal = g.normal;
        }
        manifolds.back().manifold.add(g.point.position, g.point.separation, g.point.featureId);
    }
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

constexpr std::uint8_t kUngrouped = 0xFF;

/// Sorts the triangles' manifolds into groups of like normal (see the file comment) and writes
/// each group's normal into `normals`; returns the number of groups.
int groupManifolds(std::vector<TriangleManifold>& manifolds,
                   std::array<Vec3, ManifoldSet::kMaxManifolds>& normals) {
    for (TriangleManifold& tm : manifolds)
        tm.group = kUngrouped;
    int groups = 0;
    while (groups < ManifoldSet::kMaxManifolds) {
        Real deepest = INFINITY;
        const TriangleManifold* seed = nullptr;
        for (const TriangleManifold& tm : manifolds) {
            for (int k = 0; k < tm.manifold.pointCount && tm.group == kUngrouped; ++k) {
                if (tm.manifold.points[static_cast<std::size_t>(k)].separation < deepest) {
                    deepest = tm.manifold.points[static_cast<std::size_t>(k)].separation;
                    seed = &tm;
                }
            }
        }
        if (seed == nullptr)
            return groups;
        const Vec3 normal = seed->manifold.normal;
        normals[static_cast<std::size_t>(groups)] = normal;
        for (TriangleManifold& tm : manifolds)
            if (tm.group == kUngrouped && tm.manifold.normal.dot(normal) >= kMergeCos)
                tm.group = static_cast<std::uint8_t>(groups);
        ++groups;
    }
    // More directions than manifolds: the rest join the group of the nearest normal.
    for (TriangleManifold& tm : manifolds) {
        if (tm.group != kUngrouped)
            continue;
        int nearest = 0;
        for (int g = 1; g < groups; ++g)
            if (tm.manifold.normal.dot(normals[static_cast<std::size_t>(g)]) >
                tm.manifold.normal.dot(normals[static_cast<std::size_t>(nearest)]))
                nearest = g;
        tm.group = static_cast<std::uint8_t>(nearest);
    }
    return groups;
}

/// Whether `c` lies where one of the first `count` candidates does: one point found twice (by the
/// clipping and by the half-space routine, or as the exact deepest point). The first keeps its
/// id and takes the deeper separation: the reduction then never chooses between two ids for one
/// point by rounding noise (a box edge's ids flipped every step), and the depth stays exact.
bool sameAsCandidate(ContactPoint* candidates, std::size_t count, const ContactPoint& c) {
    for (std::size_t k = 0; k < count; ++k) {
        if ((candidates[k].position - c.position).squaredNorm() < kSamePoint * kSamePoint) {
            candidates[k].separation = std::min(candidates[k].separation, c.separation);
            return true;
        }
    }
    return false;
}

/// Removes the candidates that lie between two others on a segment (seen along `normal`) and are
/// no deeper than both; returns the count left. A line contact across several triangles (a
/// capsule or cylinder on its side) gives points where it crosses every triangle edge, all
/// equally deep and in line: the reduction weighed their zero areas by rounding noise, and the
/// kept ones (and their ids) changed from step to step. The segment's ends carry the contact.
/// Up to kBetweenLimit candidates (cubic); beyond, the reduction takes them as they are.
std::size_t dropBetween(ContactPoint* candidates, std::size_t count, const Vec3& normal) {
    constexpr std::size_t kBetweenLimit = 24;
    if (count > kBetweenLimit)
        return count;
    const auto flat = [&](std::size_t k) {
        return Vec3(candidates[k].position - normal.dot(candidates[k].position) * normal);
    };
    const auto between = [&](std::size_t c) {
        const Vec3 p = flat(c);
        for (std::size_t a = 0; a < count; ++a) {
            for (std::size_t b = a + 1; b < count; ++b) {
                if (a == c || b == c ||
                    candidates[c].separation <
                        std::min(candidates[a].separation, candidates[b].separation) - kDepthNoise)
                    continue;
                const Vec3 pa = flat(a), ab = flat(b) - pa;
                const Real t = (p - pa).dot(ab) / ab.squaredNorm();
                if (t > 0 && t < 1 && (pa + t * ab - p).squaredNorm() < kSamePoint * kSamePoint)
                    return true;
            }
        }
        return false;
    };
    std::array<bool, kBetweenLimit> drop;
    for (std::size_t c = 0; c < count; ++c)
        drop[c] = between(c);
    std::size_t kept = 0;
    for (std::size_t c = 0; c < count; ++c) {
        if (!drop[c])
            candidates[kept++] = candidates[c];
    }
    return kept;
}

/// The manifold of one group (see the file comment), in the surface's frame.
void merge(const std::vector<TriangleManifold>& manifolds, int group, const Vec3& normal,
           Manifold& out) {
    auto& candidates = scratch().candidates;
    std::size_t count = 0;
    for (const TriangleManifold& tm : manifolds) {
        if (tm.group != group)
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
            if (!sameAsCandidate(candidates.data(), count, c))
                candidates[count++] = c;
        }
    }
    if (count > static_cast<std::size_t>(Manifold::kMaxPoints))
        count = dropBetween(candidates.data(), count, normal);
    reduceContacts(std::span<const ContactPoint>(candidates.data(), count), normal, out);
    keepDeepest(candidates, count, out);
}

}  // namespace

void collideConvexMesh(const Shape& a, const Transform& poseA, const Shape& b,
                       const Transform& poseB, Real margin, ManifoldSet& out) {
    out.count = 0;
    out.manifolds[0] = Manifold{};
    const Transform pose{poseB.applyInverse(poseA.position),
                         (poseB.rotation.conjugate() * poseA.rotation).normalized()};
    const Aabb box = boundsOf(a, pose).fattened(margin);
    const Real backReach = kBackReach * boundingRadius(a);
    Scratch& s = scratch();
    s.manifolds.clear();
    s.unclaimed.clear();
    s.gaps.clear();
    s.triangles.clear();
    forEachTriangle(b, box, [&](const MeshTriangle& t) {
        TriangleManifold tm{{}, t.index};
        s.triangles.push_back(t);
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
            if (edges != 0 && tm.manifold.normal.dot(normal) >= kWedgeCos)
                s.unclaimed.push_back(onFaceNormal(tm, normal));
        }
        alongFace(a, pose, t, normal, margin, tm.manifold, s.gaps);
        if (tm.manifold.pointCount > 0)
            s.manifolds.push_back(tm);
    });
    measureGaps(s.gaps, s.triangles, roundingRadius(a));
    addGaps(s.gaps, s.triangles, s.manifolds);
    if (s.manifolds.empty())
        std::swap(s.manifolds, s.unclaimed);  // see onFaceNormal
    std::array<Vec3, ManifoldSet::kMaxManifolds> normals;
    out.count = groupManifolds(s.manifolds, normals);
    for (int g = 0; g < out.count; ++g) {
        Manifold& m = out.manifolds[static_cast<std::size_t>(g)];
        m = Manifold{};  // the pair's record copies all of it, unused points included
        merge(s.manifolds, g, normals[static_cast<std::size_t>(g)], m);
        m.normal = poseB.rotation * m.normal;
        for (int k = 0; k < m.pointCount; ++k) {
            ContactPoint& c = m.points[static_cast<std::size_t>(k)];
            c.position = poseB.apply(c.position);
        }
    }
}

void collideConvexMeshDeepest(const Shape& a, const Transform& poseA, const Shape& b,
                              const Transform& poseB, Real margin, Manifold& out) {
    thread_local ManifoldSet set;
    collideConvexMesh(a, poseA, b, poseB, margin, set);
    out = set.manifolds[0];
}

}  // namespace tumble::detail
