#pragma once
/// Contacts as the world reports them after a step.

#include <array>

#include "tumble/body.h"
#include "tumble/collision/manifold.h"
#include "tumble/shape.h"

namespace tumble {

/// A pair of shapes whose fat bounding boxes overlap, with the manifold of the last step
/// (pointCount 0 when the shapes are apart by more than the speculative margin). The normal
/// points from shape A to shape B. A pair touching along several normals (a shape on a mesh in a
/// crease) has one Contact per normal, listed together.
struct Contact {
    ShapeId shapeA;
    ShapeId shapeB;
    BodyId bodyA;
    BodyId bodyB;
    Manifold manifold;
    /// Accumulated normal impulse of each manifold point from the last solve (N s); carried to
    /// the next step by feature id for warm starting.
    std::array<Real, Manifold::kMaxPoints> normalImpulse{};
    /// Accumulated friction impulse of each point (N s), world frame. (Spelled out: an Eigen
    /// vector's default constructor leaves it uninitialised.)
    std::array<Vec3, Manifold::kMaxPoints> tangentImpulse{Vec3::Zero(), Vec3::Zero(), Vec3::Zero(),
                                                          Vec3::Zero()};
    static_assert(Manifold::kMaxPoints == 4, "tangentImpulse lists one zero per point");
    /// Accumulated torsion and rolling-resistance impulse on body B (N m s), world frame; the
    /// manifold's, carried while it keeps points.
    Vec3 angularImpulse = Vec3::Zero();
};

}  // namespace tumble
