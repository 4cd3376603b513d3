#pragma once
// A V-shaped crease for the multi-manifold tests: two planes folding up from a crease along the
// y axis, as a triangle mesh and as the two half-spaces whose union is the same solid.

#include <array>
#include <cmath>
#include <cstdint>
#include <numbers>

#include "collision/mesh_fixtures.h"
#include "tumble/collision/mesh_data.h"
#include "tumble/collision/shape.h"

namespace tumble::testing {

/// A crease of `degrees` (the angle between its faces, < 180) along the y axis through the
/// origin: each face rises from it at (180 - degrees) / 2.
struct Crease {
    Real degrees = 90;

    Real tilt() const { return (180 - degrees) / 2 * std::numbers::pi / 180; }
    /// Outward normal of the face over x < 0 (side 0) or x > 0 (side 1).
    Vec3 normal(int side) const {
        const Real s = std::sin(tilt()), c = std::cos(tilt());
        return side == 0 ? Vec3(s, 0, c) : Vec3(-s, 0, c);
    }
    HalfSpace face(int side) const { return HalfSpace{normal(side), 0}; }

    /// Both faces as a mesh: `cells` cells of `cell` (m, along x) on each side of the crease and
    /// 2 `cells` along y, centred on the origin, two triangles per cell; the crease runs along
    /// triangle edges.
    TriangleMeshData mesh(int cells, Real cell) const {
        TriangleMeshData data = flatGrid(2 * cells, cell);
        for (Vec3& v : data.vertices)
            v.z() = std::abs(v.x()) * std::tan(tilt());
        return data;
    }

    /// Moves `pose` in the xz plane so that the shape's separation from face 0 is `first` and
    /// from face 1 is `second` (m; negative: penetrating).
    void place(const Shape& shape, Transform& pose, Real first, Real second) const {
        std::array<Real, 2> target{first, second}, now;
        for (int side = 0; side < 2; ++side) {
            const Vec3 n = normal(side);
            const Vec3 lowest = pose.apply(support(shape, pose.rotation.conjugate() * -n));
            now[static_cast<std::size_t>(side)] = n.dot(lowest);
        }
        // n0 . d = target0 - now0, n1 . d = target1 - now1, d = (dx, 0, dz).
        const Vec3 a = normal(0), b = normal(1);
        const Real r0 = target[0] - now[0], r1 = target[1] - now[1];
        const Real det = a.x() * b.z() - a.z() * b.x();
        pose.position.x() += (r0 * b.z() - r1 * a.z()) / det;
        pose.position.z() += (a.x() * r1 - b.x() * r0) / det;
    }
};

}  // namespace tumble::testing
