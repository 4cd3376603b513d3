#pragma once
/// Ray casts and point queries against one shape at a pose: the per-shape half of scene queries,
/// called by the engine for the candidates its broadphase finds. Everything is in world
/// coordinates; the shape's local frame sits at `pose`. Closed forms for every convex shape type
/// (no iteration, no allocation), so these may run in hot paths.
///
/// Shapes are solids, closed (their surface belongs to them). A ray that starts inside a solid
/// (or on its surface heading out) hits it at fraction 0: the reported point is the origin and the
/// normal is -direction / |direction|. A ray starting on the surface heading in hits at fraction 0
/// with the surface normal. A ray of zero direction is a point query: it hits at fraction 0 with a
/// zero normal if its origin is inside, and misses otherwise.
///
/// Triangle meshes and height fields are surfaces, not solids, hit from either side: a ray hits
/// the first triangle it crosses (through the mesh's hierarchy or the cells under the ray) with
/// the face normal turned against the ray; nothing contains a point, and the closest point is the
/// nearest point of the surface.

#include <optional>

#include "tumble/collision/shape.h"
#include "tumble/core/math.h"

namespace tumble {

/// The segment of points origin + t * direction for t in [0, maxFraction].
struct Ray {
    Vec3 origin = Vec3::Zero();      ///< (m), world frame
    Vec3 direction = Vec3::UnitX();  ///< (m per unit fraction), world frame; need not be unit
    Real maxFraction = 1;            ///< upper end of t (dimensionless), >= 0; +infinity allowed
};

/// Where a ray first meets a solid.
struct RayHit {
    Real fraction = 0;           ///< t at the hit (dimensionless), in [0, Ray::maxFraction]
    Vec3 point = Vec3::Zero();   ///< origin + fraction * direction (m), world frame
    Vec3 normal = Vec3::Zero();  ///< outward unit surface normal there, world frame (see the
                                 ///< file comment for rays starting inside)
};

/// Refuses (InvalidArgument) a ray with a non-finite origin or direction, or a maxFraction that is
/// NaN or negative. `where` prefixes the message (e.g. "World::raycast ray"). The query functions
/// below trust their input; call this at the boundary.
void checkRay(const Ray& ray, const char* where);

/// The first point of `shape` at `pose` on the ray, or nothing when the ray misses it within
/// [0, maxFraction]. On an edge or vertex the normal is that of one of the faces meeting there.
std::optional<RayHit> raycast(const Shape& shape, const Transform& pose, const Ray& ray);

/// The point of the solid nearest to `point` (m, world frame): `point` itself when inside.
Vec3 closestPoint(const Shape& shape, const Transform& pose, const Vec3& point);

/// Whether `point` (m, world frame) lies in the closed solid.
bool containsPoint(const Shape& shape, const Transform& pose, const Vec3& point);

}  // namespace tumble
