#pragma once
/// Face clipping: the step that turns one contact normal into a full manifold, shared by the
/// closed-form box-box routine and the general libccd path.
///
/// Given a reference face (on one shape, its outward normal roughly along the contact normal) and
/// an incident polygon (the face, edge or vertex of the other shape most anti-parallel to it),
/// the incident polygon is clipped by the reference face's side planes (Sutherland-Hodgman), each
/// surviving point's separation is measured along the reference normal, points deeper than
/// `margin` is shallow are kept, and at most 4 are chosen: the deepest, then those spanning the
/// largest area, so the support polygon survives the reduction.

#include <array>
#include <cstdint>
#include <span>

#include "tumble/collision/manifold.h"
#include "tumble/core/math.h"

namespace tumble::detail {

/// A polygon vertex (world) with the id of the feature that produced it. The clipper gives a
/// point created by a side plane an id made from the incident edge and the reference side, so
/// ids stay stable while the configuration persists.
struct ClipVertex {
    Vec3 position = Vec3::Zero();
    std::uint32_t featureId = 0;
};

/// Largest polygon the clipper handles (incident vertices plus one per reference side).
constexpr int kMaxClipVertices = 64;

/// Candidates within this of the deepest separation count as equally deep in reduceContacts (m).
/// Wide enough that flush faces (boxes, hulls) whose points differ in depth by solver noise keep
/// the same 4 points, and ids, from step to step, so piles settle and sleep; their clipped points
/// are exact, and the reduction loses at most this of their depth only on faces tilted into the
/// contact.
constexpr Real kDepthTolerance = 1e-4;

/// The band where a cylinder's cap or rim takes part (m): half of issue 20's 1e-6 m depth bound.
/// A tilted cap (a polygon of up to 17 points, plus its exact deepest rim point) lost that point
/// to a wider set 9.95e-5 m shallower under kDepthTolerance. Used for boxes and hulls too, it kept
/// their flush piles awake: the deepest point, a solver-noise 1e-6 m lower, swapped in and out.
constexpr Real kCapDepthTolerance = 5e-7;

struct ReferenceFace {
    std::span<const Vec3> vertices;  ///< world, counter-clockwise seen from outside (along normal)
    Vec3 normal = Vec3::UnitZ();     ///< world, outward, unit
    std::uint32_t featureId = 0;     ///< id of the face on its shape (combined into point ids)
};

/// Clips `incident` (world, ordered around its boundary; 1 vertex = a point, 2 = a segment) by
/// `reference` and writes up to 4 points into `out`. `referenceIsA` says which shape owns the
/// reference face: the manifold normal is set to point from A to B. Each point's position is
/// midway between the incident point and its projection on the reference plane.
///
/// An incident vertex less than kClipTolerance outside a side plane counts as on it and is kept
/// unmoved (equal boxes stacked flush keep their corner points and ids under jitter). The result
/// may hold 0 points when the incident polygon lies wholly outside the reference face; a caller
/// that knows the shapes touch then falls back to its own witness point.
///
/// Point ids: bit 31 set when the reference face is B's; bits 22-30 the reference featureId
/// (mod 511; 511 is never produced, so callers may use it for non-clipped contacts); bits 11-21
/// and 0-10 the labels of the two polygon edges meeting at the point, each either an incident
/// edge (named by the featureId of its first vertex, mod 1024) or a reference side (1024 + side
/// index). A kept incident vertex is thus named by its two incident edges, a side crossing by the
/// edge and the side, a reference corner by its two sides.
///
/// `contactNormal` (world, unit, from A to B), when given, replaces the reference normal as the
/// manifold normal: each point's separation is then its distance to the reference plane along
/// that normal, and its position is midway along it. A caller whose reference face is a few
/// degrees off the true contact normal keeps the true normal (and the true depth) this way. The
/// reference normal must then make an angle well below 90 degrees with it. `depthTolerance` is
/// reduceContacts' band.
void clipToManifold(const ReferenceFace& reference, std::span<const ClipVertex> incident,
                    bool referenceIsA, Real margin, Manifold& out,
                    const Vec3* contactNormal = nullptr, Real depthTolerance = kDepthTolerance);

/// How far outside a reference side plane an incident vertex may lie and still be kept (m).
constexpr Real kClipTolerance = 1e-5;

/// Writes into `out` (normal set to `normal`) at most 4 of `candidates`: all when there are at
/// most 4; otherwise a deepest candidate (any within `depthTolerance` of the minimum separation)
/// plus those that make the largest contact area, measured in the plane perpendicular to
/// `normal`. Up to kExactReduceLimit candidates every 4-subset is tried (exact); beyond, a greedy
/// choice (deepest, farthest from it, largest triangle, largest quadrilateral) improved by
/// single swaps (worst measured: 90 % of the best area). A later subset
/// replaces an earlier one only when its area is larger by more than kAreaTieFraction, so
/// symmetric contacts keep the same points, and ids, under jitter.
///
/// `convexPolygon` promises that the candidates are the vertices of a convex polygon in boundary
/// order (as clipping produces): the hull of 4 of them is then the quadrilateral they form in
/// that order, and the exact search costs one cross product per subset instead of seven.
void reduceContacts(std::span<const ContactPoint> candidates, const Vec3& normal, Manifold& out,
                    bool convexPolygon = false, Real depthTolerance = kDepthTolerance);

/// Candidate count up to which reduceContacts searches every 4-subset.
constexpr int kExactReduceLimit = 8;

/// Relative area gain below which reduceContacts keeps the earlier choice.
constexpr Real kAreaTieFraction = 1e-3;

}  // namespace tumble::detail
