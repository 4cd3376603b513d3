// The internal-edge rules of the mesh narrowphase (see collide_mesh.cpp for the rest).
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

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <vector>

#include "clipping.h"
#include "collide_mesh_edges.h"
#include "gjk.h"
#include "mesh_triangles.h"
#include "pair_routines.h"

namespace tumble::detail {
namespace {

/// Vertices within this (m) of the farthest one along a direction belong to the same feature.
constexpr Real kFeatureTolerance = 1e-9;
/// A contact normal may point above a neighbouring vertex by this (dimensionless: of the
/// vertex's distance) and still count as within a feature's normal cone (withinCone).
constexpr Real kConeTolerance = 1e-12;
/// cos(kFlatEdgeAngle): an internal edge's contact normal within this of the face normal may lie
/// between the face normals of a convex fold (onFaceNormal).
constexpr Real kWedgeCos = 0.99862953475457383;
/// Marks the ids of points redone along a face normal.
constexpr std::uint32_t kFaceRedoTag = 0x5BD1E995u;
/// Marks the ids of points kept with the face normal though the redo dropped them (onFaceNormal).
constexpr std::uint32_t kUnclaimedTag = 0x68E31DA4u;
/// Marks the ids of speculative points kept from an internal edge or vertex (keepSpeculative).
constexpr std::uint32_t kSpeculativeTag = 0x1B873593u;
/// Marks the ids of points kept below an internal edge (offerGap).
constexpr std::uint32_t kGapTag = 0x2545F491u;
/// The id of the shape's deepest point along a face normal.
constexpr std::uint32_t kDeepestId = 0x7FFFFFFFu;

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

/// Whether `d` (unit, from the surface toward the shape in front of it) lies in the normal cone of
/// t's feature whose edges are `edges` (featureEdges; not the face): the plane through the
/// feature with normal d has no neighbouring vertex above it (by more than kConeTolerance of its
/// distance). Of an edge: t's third vertex and the one across the edge (acrossVertex), measured
/// across the edge (the wedge between the two face normals). Of a vertex: every vertex of the
/// `triangles` that share it; all of them are under the shape's box, as the vertex is (the
/// triangle's point nearest to or deepest in the shape). A thin prism's least way out of a shape
/// deep below an edge is often its side face, far outside the cone: such a normal pushes the
/// shape along the surface or into it.
bool withinCone(const Shape& surface, const std::vector<MeshTriangle>& triangles,
                const MeshTriangle& t, std::uint8_t edges, const Vec3& d) {
    const auto below = [&](const Vec3& offset) {
        return d.dot(offset) <= kConeTolerance * offset.norm();
    };
    for (std::size_t k = 0; k < 3; ++k) {
        const Vec3& a = t.vertices[k];
        if (edges == (1u << k)) {  // the edge from a: offsets across it
            const Vec3 e = (t.vertices[(k + 1) % 3] - a).normalized();
            const auto acrossEdge = [&](const Vec3& p) { return Vec3(p - a - (p - a).dot(e) * e); };
            Vec3 across;
            return below(acrossEdge(t.vertices[(k + 2) % 3])) &&
                   !(acrossVertex(surface, t, static_cast<int>(k), across) &&
                     !below(acrossEdge(across)));
        }
        if (edges != ((1u << k) | (1u << ((k + 2) % 3))))
            continue;
        for (const MeshTriangle& other : triangles) {  // vertex a: edges k and k - 1
            if (std::find(other.vertices.begin(), other.vertices.end(), a) == other.vertices.end())
                continue;
            for (const Vec3& p : other.vertices)
                if (!below(p - a))
                    return false;
        }
    }
    return true;
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

/// A shape counts as behind a triangle when it lies behind the plane by more than this fraction
/// of its reach (intoTriangle).
constexpr Real kBackReach = 0.5;

/// The face normal pointing from the shape into the triangle. The shape is in front unless it
/// lies behind the plane by more than kBackReach of its reach: a shape pressed into a surface
/// past its centre (a fast capsule into terrain) is still pushed out of the front, while one
/// touching a thin wall from behind is pushed back out behind. A sideways contact normal's tilt
/// says nothing of the side. A mesh may be a sheet with two open sides, so its reach is
/// measured along the face normal: the shape's middle there, against half its width. By its
/// origin and bounding radius a long shape lying along a thin wall behind it counted as in
/// front (a thread's capsule touching the wall, 1 cm behind it and 4 cm long), and its contact
/// pushed it through the wall by its whole thickness. A height field has solid below it: the
/// origin and bounding radius, the farther reach.
Vec3 intoTriangle(const Shape& shape, const Transform& pose, const Shape& surface,
                  const MeshTriangle& t) {
    Real behind, reach;
    if (std::holds_alternative<HeightField>(surface)) {
        behind = t.normal.dot(t.vertices[0] - pose.position);
        reach = boundingRadius(shape);
    } else {
        const Vec3 d = pose.rotation.conjugate() * t.normal;
        const Vec3 high = support(shape, d), low = support(shape, -d);
        behind = t.normal.dot(t.vertices[0] - pose.apply((high + low) / 2));
        reach = d.dot(high - low) / 2;
    }
    return behind <= kBackReach * reach ? Vec3(-t.normal) : t.normal;
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

/// How far (m, in the plane) p lies outside the triangle (0 over it): to the nearest point of
/// the edges it lies beyond; `pastActive` tells whether one of them is active. Beyond one edge
/// alone, p may lie past that edge's end, off an acute vertex: a wall panel's lower triangle
/// meets its top edge only at that vertex (11 degrees), and a thread's capsule above the edge,
/// 1.5 cm over the vertex, measured 3 mm from the diagonal's line, was taken nearer to that
/// internal edge than to the border and kept 2.4 cm deep along the face normal (dustbin-mesh:
/// pushed 1-2 cm sideways in one step, 1 J in a thread).
Real outsideDistance(const MeshTriangle& t, const Vec3& p, bool& pastActive) {
    Real nearest = INFINITY;
    pastActive = false;
    for (std::size_t k = 0; k < 3; ++k) {
        const Vec3& a = t.vertices[k];
        const Vec3 edge = t.vertices[(k + 1) % 3] - a;
        const Real out = -edge.cross(p - a).dot(t.normal) / edge.norm();
        if (out <= kFeatureTolerance)
            continue;
        pastActive = pastActive || ((t.activeEdges >> k) & 1u) != 0;
        const Real along = std::clamp((p - a).dot(edge) / edge.squaredNorm(), Real(0), Real(1));
        const Vec3 d = p - (a + along * edge);
        nearest = std::min(nearest, Vec3(d - d.dot(t.normal) * t.normal).norm());
    }
    return nearest == INFINITY ? 0 : nearest;
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

/// Sets the gap points' depths: a point of the shape in an edge's wedge is nearest to an edge or
/// vertex, so its depth is its distance to the nearest of `triangles` (a rounded shape's: its
/// core point's, less or plus the rounding), not its depth below its own triangle's plane. A
/// point nearest to an active edge or vertex (past it) lies in no wedge but past the surface's
/// border or a sharp fold, where that feature's own contact holds the shape: it is dropped. On a
/// thin wall of triangles a thread's end cap 4 cm behind the plane, past an internal diagonal
/// and over the wall's top edge, was taken 5 cm deep along the face normal, and one step of an
/// 8 x 8 net landing on the edge gained 0.6 J.
void measureGaps(std::vector<GapPoint>& gaps, const std::vector<MeshTriangle>& triangles,
                 Real rounding) {
    std::erase_if(gaps, [&](GapPoint& g) {
        Real nearest = INFINITY;
        bool pastBorder = false;
        for (const MeshTriangle& t : triangles) {
            bool pastActive;
            const Real outside = outsideDistance(t, g.core, pastActive);
            const Real distance = std::hypot(t.normal.dot(g.core - t.vertices[0]), outside);
            if (distance < nearest - kDepthNoise)
                pastBorder = false;
            if (distance <= nearest + kDepthNoise)
                pastBorder = pastBorder || pastActive;
            nearest = std::min(nearest, distance);
        }
        g.point.separation = g.inside ? -(nearest + rounding) : nearest - rounding;
        return pastBorder;
    });
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

/// The pair routine's speculative points (ahead of the shape, within the margin) on an internal
/// edge or vertex whose redo along the face normal `normal` kept nothing over the triangle: kept
/// with the face normal and the pair's separation, the distance to the triangle. Over a bump's
/// vertex, the part of a tilted cylinder's rim (or a hull's corner) nearest the vertex projects
/// along each face normal onto a neighbour, and the half-space routine's few points per plane lie
/// elsewhere: no triangle offered a point there, and a landing cylinder's rim swung 3 cm into the
/// terrain within one step (TerrainTunnel). Points below the plane are the gaps' (offerGap).
/// Not for rounded shapes: a rolling ball's point ahead, measured to the next triangle, nears
/// faster than its distance allows in a step, a bump of 0.19 m/s (MeshContact).
void keepSpeculative(const TriangleManifold& pair, const Vec3& normal,
                     std::vector<TriangleManifold>& out) {
    TriangleManifold kept{{}, pair.triangle};
    kept.manifold.normal = normal;
    for (int k = 0; k < pair.manifold.pointCount; ++k) {
        const ContactPoint& c = pair.manifold.points[static_cast<std::size_t>(k)];
        if (c.separation > 0)
            kept.manifold.add(c.position, c.separation, c.featureId ^ kSpeculativeTag);
    }
    if (kept.manifold.pointCount > 0)
        out.push_back(kept);
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
    // Kept a point as deep as g's: beside a valley's internal edge each face's deepest point of a
    // cylinder's rim lay over the other face, so each took the other as holding it, and the
    // rim went 2 cm into the terrain without a point (TerrainTunnel).
    const auto keeps = [&](std::uint32_t triangle) {
        return std::any_of(manifolds.begin(), end, [&](const TriangleManifold& tm) {
            return tm.triangle == triangle &&
                   std::any_of(tm.manifold.points.begin(),
                               tm.manifold.points.begin() + tm.manifold.pointCount,
                               [&](const ContactPoint& c) {
                                   return c.separation <= g.point.separation + kDepthTolerance;
                               });
        });
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

}  // namespace

void fileTriangleContact(const Shape& shape, const Transform& pose, const Shape& surface,
                         const MeshTriangle& t, Real margin, TriangleManifold tm,
                         EdgeContacts& out) {
    const Vec3 normal = intoTriangle(shape, pose, surface, t);
    const TriangleManifold pair = tm;
    if (tm.manifold.pointCount > 0) {
        const std::uint8_t edges = featureEdges(t, -tm.manifold.normal);
        // An active edge or vertex keeps its own normal if it lies in the feature's normal cone;
        // else the contact is redone along the face normal, as on an internal edge (the
        // neighbour's own contact holds what lies over it). Seen from behind, a convex edge is
        // concave: its normal is kept as it is. So is a rounded shape's: the direction from the
        // feature to its core may leave a neighbour above the plane (a saddle vertex) and still
        // be the one way out for a sphere of that radius (redone, the terrain pile's capsules went
        // 3.3 cm deep instead of 0.8).
        if (edges != 0 && (edges & t.activeEdges) != 0 &&
            (normal.dot(t.normal) > 0 || roundingRadius(shape) > 0 ||
             withinCone(surface, out.triangles, t, edges, -tm.manifold.normal))) {
            out.manifolds.push_back(tm);
            return;
        }
        // On the face from the shape's side: clipped points reach the triangle's edges.
        if (edges == 0 && tm.manifold.normal.dot(normal) > 0)
            out.manifolds.push_back(tm);
        if (edges != 0 && tm.manifold.normal.dot(normal) >= kWedgeCos)
            out.unclaimed.push_back(onFaceNormal(tm, normal));
    }
    alongFace(shape, pose, t, normal, margin, tm.manifold, out.gaps);
    if (tm.manifold.pointCount > 0)
        out.manifolds.push_back(tm);
    else if (pair.manifold.pointCount > 0 && roundingRadius(shape) == 0 &&
             featureEdges(t, -pair.manifold.normal) != 0)
        keepSpeculative(pair, normal, out.speculative);
}

void finishEdgeContacts(Real rounding, EdgeContacts& out) {
    measureGaps(out.gaps, out.triangles, rounding);
    addGaps(out.gaps, out.triangles, out.manifolds);
    if (out.manifolds.empty())
        std::swap(out.manifolds, out.unclaimed);  // see onFaceNormal
}

}  // namespace tumble::detail
