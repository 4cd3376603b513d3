#pragma once
/// The narrowphase pair routines behind the dispatch table in narrowphase.cpp. Every routine has
/// the signature of CollideFn and handles its two types in the order of its name (A's type <=
/// B's type in ShapeType order); the manifold normal points from A to B.

#include <utility>

#include "tumble/collision/manifold.h"
#include "tumble/collision/shape.h"

namespace tumble::detail {

struct Segment {
    Vec3 start = Vec3::Zero();  ///< (m)
    Vec3 end = Vec3::Zero();    ///< (m)
    Vec3 direction() const { return end - start; }
};

/// Parameters (s on a, t on b, both in [0, 1]) of the closest points of two segments
/// (collide_spheres.cpp).
std::pair<Real, Real> closestParameters(const Segment& a, const Segment& b);

using CollideFn = void (*)(const Shape& a, const Transform& poseA, const Shape& b,
                           const Transform& poseB, Real margin, Manifold& out);

// Closed forms (collide_spheres.cpp, collide_box.cpp, collide_half_space.cpp).
void collideSpheres(const Shape&, const Transform&, const Shape&, const Transform&, Real,
                    Manifold&);
void collideSphereCapsule(const Shape&, const Transform&, const Shape&, const Transform&, Real,
                          Manifold&);
void collideCapsules(const Shape&, const Transform&, const Shape&, const Transform&, Real,
                     Manifold&);
void collideSphereBox(const Shape&, const Transform&, const Shape&, const Transform&, Real,
                      Manifold&);
void collideBoxes(const Shape&, const Transform&, const Shape&, const Transform&, Real, Manifold&);
/// Any convex shape (A) against a half-space (B).
void collideConvexHalfSpace(const Shape&, const Transform&, const Shape&, const Transform&, Real,
                            Manifold&);

/// Any convex shape (A) against a triangle mesh or height field (B) (collide_mesh.cpp): one
/// manifold per group of like normals, deepest first.
void collideConvexMesh(const Shape&, const Transform&, const Shape&, const Transform&, Real,
                       ManifoldSet&);
/// The same, keeping the first (deepest) manifold only: the dispatch table's entry.
void collideConvexMeshDeepest(const Shape&, const Transform&, const Shape&, const Transform&, Real,
                              Manifold&);

// General convex pairs through libccd, then clipping (collide_convex.cpp).
void collideConvex(const Shape&, const Transform&, const Shape&, const Transform&, Real, Manifold&);

}  // namespace tumble::detail
