#pragma once
/// Ray casts and closest points against triangle meshes and height fields (internal to
/// collision/; raycast.cpp's entry points send surfaces here).

#include <optional>

#include "tumble/collision/mesh_shape.h"
#include "tumble/collision/raycast.h"

namespace tumble::detail {

/// The first triangle of the mesh or height field `shape` at `pose` on `ray`; `o` and `d` are the
/// ray's origin and direction (nonzero) in the shape's frame.
std::optional<RayHit> raycastSurface(const Shape& shape, const Transform& pose, const Vec3& o,
                                     const Vec3& d, const Ray& ray);

/// The reference answer for a height field: every cell under the box of the ray's stretch over
/// the field, which the grid walk of raycastSurface must match (tests, benchmark).
std::optional<RayHit> raycastCellsUnderBox(const HeightFieldGeometry& field, const Transform& pose,
                                           const Vec3& o, const Vec3& d, const Ray& ray);

/// The point of the surface nearest to `p` (local frame).
Vec3 closestOnSurface(const MeshGeometry& mesh, const Vec3& p);
Vec3 closestOnSurface(const HeightFieldGeometry& field, const Vec3& p);

/// The point of the triangle nearest to `p`.
Vec3 closestOnTriangle(const MeshTriangle& triangle, const Vec3& p);

}  // namespace tumble::detail
