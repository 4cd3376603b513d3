// Shape checks, bounding boxes and support points. boundsOf and support run every step: they
// trust shapes that passed checkShape and allocate nothing.

#include <algorithm>
#include <cmath>
#include <limits>
#include <variant>

#include "tumble/collision/mesh_shape.h"
#include "tumble/collision/shape.h"
#include "tumble/core/error.h"

namespace tumble {
namespace {

/// How far a half-space normal's length may stray from 1.
constexpr Real kUnitTolerance = 1e-6;

void checkPositive(const char* where, const char* field, Real value) {
    if (!std::isfinite(value) || value <= 0)
        fail(where, ": ", field, " = ", value, " m must be finite and > 0");
}

struct CheckShape {
    const char* where;

    void operator()(const Sphere& sphere) const {
        checkPositive(where, "Sphere.radius", sphere.radius);
    }
    void operator()(const Capsule& capsule) const {
        checkPositive(where, "Capsule.radius", capsule.radius);
        if (!std::isfinite(capsule.halfLength) || capsule.halfLength < 0)
            fail(where, ": Capsule.halfLength = ", capsule.halfLength,
                 " m must be finite and >= 0");
    }
    void operator()(const Box& box) const {
        const char* fields[] = {"Box.halfExtents.x", "Box.halfExtents.y", "Box.halfExtents.z"};
        for (int i = 0; i < 3; ++i)
            checkPositive(where, fields[i], box.halfExtents[i]);
    }
    void operator()(const Cylinder& cylinder) const {
        checkPositive(where, "Cylinder.radius", cylinder.radius);
        checkPositive(where, "Cylinder.halfLength", cylinder.halfLength);
    }
    void operator()(const ConvexHull& hull) const {
        if (hull.data == nullptr)
            fail(where, ": ConvexHull.data is null; build the hull with ConvexHull::fromPoints");
        if (hull.data->vertices.size() < 4 || hull.data->faces.size() < 4)
            fail(where, ": ConvexHull.data has ", hull.data->vertices.size(), " vertices and ",
                 hull.data->faces.size(), " faces; a solid needs at least 4 of each");
    }
    void operator()(const HalfSpace& halfSpace) const {
        const Vec3& n = halfSpace.normal;
        if (!isFinite(n) || std::abs(n.norm() - 1) > kUnitTolerance)
            fail(where, ": HalfSpace.normal = (", n.x(), ", ", n.y(), ", ", n.z(), ") has length ",
                 n.norm(), "; it must be unit length (to ", kUnitTolerance, ")");
        if (!std::isfinite(halfSpace.offset))
            fail(where, ": HalfSpace.offset = ", halfSpace.offset, " m must be finite");
    }
    void operator()(const TriangleMesh& mesh) const {
        if (mesh.data == nullptr)
            fail(where, ": TriangleMesh.data is null; build the mesh with TriangleMesh::fromData");
    }
    void operator()(const HeightField& field) const {
        if (field.data == nullptr)
            fail(where, ": HeightField.data is null; build it with HeightField::fromData");
    }
};

/// The box around a local box carried to `pose`.
Aabb posedBox(const Aabb& local, const Transform& pose) {
    const Transform centred{pose.apply(local.center()), pose.rotation};
    return Aabb::ofOrientedBox(centred, (local.upper - local.lower) / 2);
}

struct BoundsOf {
    const Transform& pose;

    Aabb operator()(const Sphere& sphere) const {
        return {pose.position.array() - sphere.radius, pose.position.array() + sphere.radius};
    }
    Aabb operator()(const Capsule& capsule) const {
        // The box of the segment's two ends, grown by the radius.
        const Vec3 end = pose.rotation * Vec3(0, 0, capsule.halfLength);
        const Vec3 extent = end.cwiseAbs().array() + capsule.radius;
        return {pose.position - extent, pose.position + extent};
    }
    Aabb operator()(const Box& box) const { return Aabb::ofOrientedBox(pose, box.halfExtents); }
    Aabb operator()(const Cylinder& cylinder) const {
        // Two discs of radius r about the unit axis a at +-h a. A disc's extent along world axis
        // e_i is r |e_i - (e_i . a) a| = r sqrt(1 - a_i^2); the centres add h |a_i|.
        const Vec3 axis = pose.rotation * Vec3::UnitZ();
        Vec3 extent;
        for (int i = 0; i < 3; ++i)
            extent[i] = cylinder.halfLength * std::abs(axis[i]) +
                        cylinder.radius * std::sqrt(std::max(Real(0), 1 - axis[i] * axis[i]));
        return {pose.position - extent, pose.position + extent};
    }
    Aabb operator()(const ConvexHull& hull) const {
        const Mat3 rotation = pose.rotation.toRotationMatrix();
        Vec3 lower = Vec3::Constant(std::numeric_limits<Real>::infinity());
        Vec3 upper = -lower;
        for (const Vec3& v : hull.data->vertices) {
            const Vec3 world = rotation * v;
            lower = lower.cwiseMin(world);
            upper = upper.cwiseMax(world);
        }
        return {lower + pose.position, upper + pose.position};
    }
    Aabb operator()(const HalfSpace& halfSpace) const {
        // Unbounded (+-kHalfSpaceBound) on every side, except when the world normal lies exactly
        // along a world axis (the common ground plane): then the solid ends at its plane there.
        Aabb box{Vec3::Constant(-kHalfSpaceBound), Vec3::Constant(kHalfSpaceBound)};
        const Vec3 normal = pose.rotation * halfSpace.normal;
        const Real offset = halfSpace.offset + normal.dot(pose.position);
        for (int i = 0; i < 3; ++i) {
            const int j = (i + 1) % 3;
            const int k = (i + 2) % 3;
            if (normal[i] == 0 || normal[j] != 0 || normal[k] != 0)
                continue;
            // normal_i x_i <= offset: an upper bound for a positive normal, lower for negative.
            if (normal[i] > 0)
                box.upper[i] = offset / normal[i];
            else
                box.lower[i] = offset / normal[i];
        }
        return box;
    }
    Aabb operator()(const TriangleMesh& mesh) const {
        return posedBox(localBounds(*mesh.data), pose);
    }
    Aabb operator()(const HeightField& field) const {
        return posedBox(localBounds(*field.data), pose);
    }
};

/// +1 for x >= 0, else -1: ties resolve to the positive side, deterministically.
Real signOf(Real x) {
    return x >= 0 ? Real(1) : Real(-1);
}

struct SupportOf {
    const Vec3& direction;

    Vec3 operator()(const Sphere& sphere) const { return sphere.radius * unit(); }
    Vec3 operator()(const Capsule& capsule) const {
        return Vec3(0, 0, signOf(direction.z()) * capsule.halfLength) + capsule.radius * unit();
    }
    Vec3 operator()(const Box& box) const {
        const Vec3& e = box.halfExtents;
        return {signOf(direction.x()) * e.x(), signOf(direction.y()) * e.y(),
                signOf(direction.z()) * e.z()};
    }
    Vec3 operator()(const Cylinder& cylinder) const {
        // A point of the rim of the cap facing `direction`; the cap centre when `direction` is
        // along the axis (every cap point is then farthest).
        const Real z = signOf(direction.z()) * cylinder.halfLength;
        const Real radial = std::hypot(direction.x(), direction.y());
        if (radial == 0)
            return {0, 0, z};
        return {cylinder.radius * (direction.x() / radial),
                cylinder.radius * (direction.y() / radial), z};
    }
    Vec3 operator()(const ConvexHull& hull) const {
        // Linear scan; ties go to the lowest index.
        const std::vector<Vec3>& vertices = hull.data->vertices;
        std::size_t best = 0;
        Real bestDot = vertices[0].dot(direction);
        for (std::size_t i = 1; i < vertices.size(); ++i) {
            const Real d = vertices[i].dot(direction);
            if (d > bestDot) {
                bestDot = d;
                best = i;
            }
        }
        return vertices[best];
    }
    Vec3 operator()(const HalfSpace&) const {
        fail(
            "support: a HalfSpace is unbounded and has no support point; pair it through "
            "collideConvexHalfSpace");
    }
    Vec3 operator()(const TriangleMesh&) const {
        fail("support: a TriangleMesh is not convex; pair it through collideConvexMesh");
    }
    Vec3 operator()(const HeightField&) const {
        fail("support: a HeightField is not convex; pair it through collideConvexMesh");
    }

    /// `direction` normalised; +x for a zero direction (every point is then farthest).
    Vec3 unit() const {
        const Real length = direction.norm();
        return length > 0 ? Vec3(direction / length) : Vec3(Vec3::UnitX());
    }
};

struct BoundingRadius {
    Real operator()(const Sphere& sphere) const { return sphere.radius; }
    Real operator()(const Capsule& capsule) const { return capsule.halfLength + capsule.radius; }
    Real operator()(const Box& box) const { return box.halfExtents.norm(); }
    Real operator()(const Cylinder& cylinder) const {
        return std::hypot(cylinder.radius, cylinder.halfLength);
    }
    Real operator()(const ConvexHull& hull) const {
        Real largest = 0;
        for (const Vec3& vertex : hull.data->vertices)
            largest = std::max(largest, vertex.norm());
        return largest;
    }
    Real operator()(const HalfSpace&) const { return std::numeric_limits<Real>::infinity(); }
    Real operator()(const TriangleMesh& mesh) const {
        return farthestCorner(localBounds(*mesh.data));
    }
    Real operator()(const HeightField& field) const {
        return farthestCorner(localBounds(*field.data));
    }

    /// Bounds the surface's distance from the origin by its box's farthest corner.
    static Real farthestCorner(const Aabb& box) {
        return box.lower.cwiseAbs().cwiseMax(box.upper.cwiseAbs()).norm();
    }
};

}  // namespace

void checkShape(const Shape& shape, const char* where) {
    std::visit(CheckShape{where}, shape);
}

Aabb boundsOf(const Shape& shape, const Transform& pose) {
    return std::visit(BoundsOf{pose}, shape);
}

Vec3 support(const Shape& shape, const Vec3& direction) {
    return std::visit(SupportOf{direction}, shape);
}

Real boundingRadius(const Shape& shape) {
    return std::visit(BoundingRadius{}, shape);
}

}  // namespace tumble
