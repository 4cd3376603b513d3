#pragma once
/// Exact penetration of two polytope cores by separating axes (internal to collision/): the least
/// overlap over both shapes' face normals and the edge pairs whose Gauss-map arcs cross. See
/// polytope_sat.cpp for the argument and the source (Gregorius, GDC 2013).

#include "ccd_adapter.h"
#include "posed_core.h"

namespace tumble::detail {

/// Box and hull, and the point and segment cores of sphere and capsule: shapes whose core is a
/// polytope with known faces and edges.
bool isPolytopeCore(const Shape& shape);

/// For overlapping polytope cores: fills `out` (normal from A to B, separation = -(depth + radii),
/// witness points) from the minimum-overlap axis and returns true; false when there is no axis at
/// all (two point cores).
bool polytopePenetration(const PosedCore& a, const PosedCore& b, ConvexContact& out);

/// For overlapping or touching cores of which at least one has flat faces (box, hull, and here
/// also a cylinder's caps): the least overlap of the full shapes (m, radii included) over those
/// faces' normals, and that normal (from A to B). An upper bound of the penetration depth, and
/// the exact depth and normal whenever a face takes part in the deepest contact. False when
/// neither core has a flat face.
bool leastFaceOverlap(const PosedCore& a, const PosedCore& b, Vec3& normal, Real& depth);

}  // namespace tumble::detail
