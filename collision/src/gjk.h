#pragma once
/// GJK distance between the cores of two posed convex shapes (internal to collision/).
///
/// Every shape is seen as a core plus a rounding radius: a sphere is its centre plus its radius, a
/// capsule its segment plus its radius, the others themselves (radius 0). GJK runs on the cores,
/// which are polytopes except for cylinders, so it ends exactly on a face of the Minkowski
/// difference and the distance of rounded shapes is exact: separation = core distance - radii.
/// When the cores touch or overlap, queryConvex (ccd_adapter.h) measures the penetration.

#include "tumble/collision/shape.h"

namespace tumble::detail {

struct PosedCore;

/// Cores closer than this (m) count as touching: their closest-point direction is no longer a
/// trustworthy normal, so the full shapes go to EPA.
inline constexpr Real kCoreTouch = 1e-9;

/// GJK distance between the cores of two posed shapes.
struct CoreDistance {
    Real distance = 0;           ///< (m), 0 when the cores touch or overlap
    Vec3 pointA = Vec3::Zero();  ///< world, closest point of A's core (m)
    Vec3 pointB = Vec3::Zero();  ///< world, closest point of B's core (m)
    bool overlapping =
        false;           ///< the origin lies in (or within rounding of) the Minkowski difference
    int iterations = 0;  ///< GJK iterations used
};

/// The rounding radius of a shape's core (m): the radius of a sphere or capsule, else 0.
Real roundingRadius(const Shape& shape);

/// The point of the shape's core farthest along `direction` (local frame, need not be unit). A
/// sphere's core is its centre, a capsule's its segment. Half-spaces are not convex queries'
/// shapes.
Vec3 coreSupport(const Shape& shape, const Vec3& direction);

/// GJK distance between two posed cores (see gjk.cpp).
CoreDistance gjk(const PosedCore& a, const PosedCore& b);

/// GJK distance between the cores of `a` at `poseA` and `b` at `poseB`.
CoreDistance coreDistance(const Shape& a, const Transform& poseA, const Shape& b,
                          const Transform& poseB);

}  // namespace tumble::detail
