#pragma once
/// The general convex query behind collideConvex: how far apart two posed convex shapes are, or
/// how deep they overlap, with the normal and a witness point on each surface.
///
/// Apart, the cores' GJK distance (gjk.h) gives it exactly. When the cores touch or overlap:
/// - both cores polytopes (box, hull, sphere centre, capsule segment): the least overlap over the
///   separating axes (face normals of both, and the cross products of the edge pairs whose
///   Gauss-map arcs cross) is the exact penetration depth and its axis the exact normal
///   (ccd_adapter.cpp). gjk_epa_test measures it against brute-force separating axes on 15,000
///   random box overlaps and 4,430 hull (and sphere/capsule-in-hull) overlaps, shallow and deep:
///   max error 2e-15 m. libccd's EPA, on the same deep box overlaps, is deeper than the minimum
///   in about 3 % of them, by up to 0.6 m. Cost: below EPA for boxes and hulls of up to about 20
///   vertices; the edge-pair loop is O(edges A x edges B), so for 50- and 100-point hulls it is
///   about 2x and 2.5x EPA's time.
/// - a cylinder in the pair (no finite axis set): libccd is asked (EPA by default) for the
///   direction, the depth is measured exactly along it (the overlap of the support extents),
///   the flat faces' normals (box and hull faces, cylinder caps) are measured too and the
///   shallowest kept -- at exact touch EPA's direction is arbitrary -- and that direction is
///   refined by GJK on the pair moved apart. Cores within 1e-6 m go the same way, as GJK's
///   closest-point direction on a curved rim is noise that close. The depth is then never
///   shallower than the true one, and deeper only when no start lies near the nearest face of
///   the Minkowski difference and the GJK refinement cannot reach it (measured only on faces,
///   face_touch_test: exact there; elsewhere there is no closed-form reference).
/// ccd_adapter.cpp is the only door to libccd: no other file includes its headers.
///
/// EPA over MPR (measured on 5,000 random shallow box overlaps, gjk_epa_test): EPA's depth matches
/// the separating-axis depth to 1e-12 m in every case; MPR's portal direction missed the minimum
/// in 18 cases, by up to 5 mm.

#include <cstdint>

#include "gjk.h"
#include "tumble/collision/shape.h"

namespace tumble::detail {

/// How penetration is measured when the cores overlap.
enum class PenetrationMethod : std::uint8_t {
    Auto,  ///< separating axes for two polytope cores, else libccd's EPA (default)
    Epa,   ///< always libccd's GJK + expanding polytope (comparison and tests)
    Mpr    ///< always libccd's Minkowski portal refinement: its direction may miss the minimum
};

/// The answer of queryConvex. On a touching or penetrating pair the witness points are the
/// deepest points of each shape along the normal.
struct ConvexContact {
    Vec3 normal = Vec3::UnitZ();  ///< world, unit, from A to B
    Real separation = 0;          ///< signed surface distance (m); negative = penetration depth
    Vec3 pointA = Vec3::Zero();   ///< world, on A's surface (m)
    Vec3 pointB = Vec3::Zero();   ///< world, on B's surface (m)
};

/// The separation (or penetration), normal and witness points of two convex shapes. Neither may
/// be a half-space. Allocation-free except when libccd runs (a cylinder in an overlapping pair,
/// or an explicit Epa/Mpr method): its EPA allocates.
ConvexContact queryConvex(const Shape& a, const Transform& poseA, const Shape& b,
                          const Transform& poseB,
                          PenetrationMethod method = PenetrationMethod::Auto);

}  // namespace tumble::detail
