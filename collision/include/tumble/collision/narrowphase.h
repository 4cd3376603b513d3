#pragma once
/// Narrowphase: the contact manifold of two shapes at given poses.
///
/// Dispatch is a [ShapeType][ShapeType] table of functions. Each pair routine is written for one
/// order (A's type <= B's type); `collide` swaps the arguments for the other order and flips the
/// normal. Closed-form routines serve sphere-sphere, sphere-capsule, capsule-capsule, sphere-box,
/// box-box, and every convex shape against a half-space; a convex shape against a triangle mesh or
/// height field collides with each triangle under it (collide_mesh.cpp); the rest go through libccd
/// (GJK for separation, EPA/MPR for penetration) followed by face clipping to a full manifold.

#include "tumble/collision/manifold.h"
#include "tumble/collision/shape.h"

namespace tumble {

/// Writes into `out` the manifold of shape a at poseA and shape b at poseB: every contact point
/// whose separation is at most `margin` (m, >= 0), at most 4 points; pointCount 0 when the shapes
/// are farther apart than the margin. Half-spaces, meshes and height fields give no contact with
/// each other.
void collide(const Shape& a, const Transform& poseA, const Shape& b, const Transform& poseB,
             Real margin, Manifold& out);

/// Every manifold of the pair (ManifoldSet): as above for most pairs (count 0 or 1), one per
/// group of like normals for a convex shape against a mesh or height field, where the single
/// `collide` keeps only the first (deepest). `out.manifolds[0]` is always written: the one
/// manifold (possibly empty) the single `collide` gives.
void collide(const Shape& a, const Transform& poseA, const Shape& b, const Transform& poseB,
             Real margin, ManifoldSet& out);

/// Where the segment from a to b (world) passes through a triangle of a mesh `surface` at
/// `pose` (a thread through a thin wall between nodes on its two sides): the contact, for a
/// capsule of `radius` on that segment, that lifts it out over the nearest border edge
/// (mesh_crossing.cpp): normal (unit, from the surface to the segment) normal to both the
/// segment and the edge and pointing past the edge, the point on the edge, separation (m,
/// negative: how far along the normal the capsule must move to clear the edge). False when the
/// segment passes through no triangle, the mesh has no border edge near or `surface` is no mesh.
struct SheetCrossing {
    Vec3 normal = Vec3::UnitZ();
    Vec3 point = Vec3::Zero();
    Real separation = 0;
};
bool crossingOverBorder(const Shape& surface, const Transform& pose, const Vec3& a, const Vec3& b,
                        Real radius, SheetCrossing& out);

}  // namespace tumble
