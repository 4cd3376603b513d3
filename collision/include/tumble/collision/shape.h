#pragma once
/// Collision shapes, each in its own local frame. A body carries one or more shapes at local poses
/// (a compound). Conventions: capsules and cylinders are aligned with local z; a half-space is the
/// solid {x : normal . x <= offset} and may only sit on a static body.

#include <array>
#include <cstdint>
#include <memory>
#include <span>
#include <variant>
#include <vector>

#include "tumble/collision/aabb.h"
#include "tumble/core/mass.h"
#include "tumble/core/math.h"

namespace tumble {

struct Sphere {
    Real radius = 0.5;  ///< (m), > 0
};

/// The points within `radius` of the segment from (0, 0, -halfLength) to (0, 0, +halfLength).
struct Capsule {
    Real radius = 0.5;      ///< (m), > 0
    Real halfLength = 0.5;  ///< half the segment length (m), >= 0
};

struct Box {
    Vec3 halfExtents = Vec3::Constant(0.5);  ///< (m), each > 0
};

/// A solid circular cylinder about local z, from z = -halfLength to +halfLength.
struct Cylinder {
    Real radius = 0.5;      ///< (m), > 0
    Real halfLength = 0.5;  ///< (m), > 0
};

/// One face of a convex hull: its outward plane and its vertices, counter-clockwise seen from
/// outside (indices into HullData::vertices, as the range [first, first + count) of
/// HullData::faceVertices).
struct HullFace {
    Vec3 normal = Vec3::UnitZ();  ///< outward, unit length
    Real offset = 0;              ///< plane: normal . x = offset (m)
    std::uint32_t first = 0;
    std::uint32_t count = 0;
};

/// Immutable geometry of a convex polyhedron, shared between the shapes that use it. Coplanar
/// facets are merged, so a box's hull has 6 quadrilateral faces.
struct HullData {
    std::vector<Vec3> vertices;  ///< (m), local frame
    std::vector<HullFace> faces;
    std::vector<std::uint32_t> faceVertices;          ///< see HullFace
    std::vector<std::array<std::uint32_t, 2>> edges;  ///< unique edges as vertex index pairs
    Vec3 centroid = Vec3::Zero();                     ///< of the solid (m)
};

/// A convex hull of a point cloud, built with Qhull. Refuses (InvalidArgument) fewer than 4
/// non-coplanar points and non-finite coordinates.
struct ConvexHull {
    std::shared_ptr<const HullData> data;

    static ConvexHull fromPoints(std::span<const Vec3> points);
};

/// The solid {x : normal . x <= offset} in the local frame. Static bodies only.
struct HalfSpace {
    Vec3 normal = Vec3::UnitZ();  ///< outward, unit length
    Real offset = 0;              ///< (m)
};

struct TriangleMeshData;
struct HeightFieldData;
struct MeshGeometry;
struct HeightFieldGeometry;

/// A static triangle mesh (mesh_shape.h): a two-sided surface, not a solid, with a bounding volume
/// hierarchy and per-edge "active" flags built once and shared. Static and kinematic bodies only.
struct TriangleMesh {
    std::shared_ptr<const MeshGeometry> data;

    /// Refuses (InvalidArgument) no triangles, non-finite vertices and indices out of range;
    /// drops degenerate triangles (counted in MeshGeometry::droppedTriangles).
    static TriangleMesh fromData(const TriangleMeshData& data);
};

/// A regular grid of heights (mesh_shape.h), two triangles per cell made on demand, holes
/// optional. A surface, not a solid. Static and kinematic bodies only.
struct HeightField {
    std::shared_ptr<const HeightFieldGeometry> data;

    /// Refuses (InvalidArgument) fewer than 2 x 2 samples, non-positive spacing, non-finite
    /// heights and a height or hole list of the wrong size.
    static HeightField fromData(const HeightFieldData& data);
};

/// The order of the alternatives is the order of ShapeType and of the narrowphase table.
using Shape =
    std::variant<Sphere, Capsule, Box, Cylinder, ConvexHull, HalfSpace, TriangleMesh, HeightField>;

enum class ShapeType : std::uint8_t {
    Sphere,
    Capsule,
    Box,
    Cylinder,
    ConvexHull,
    HalfSpace,
    TriangleMesh,
    HeightField,
    Count
};

inline ShapeType typeOf(const Shape& shape) {
    return static_cast<ShapeType>(shape.index());
}

/// Whether the shape is a triangle mesh or a height field: a massless surface of triangles that
/// static and kinematic bodies may carry, dynamic ones not.
inline bool isTriangleSurface(const Shape& shape) {
    return typeOf(shape) == ShapeType::TriangleMesh || typeOf(shape) == ShapeType::HeightField;
}

/// Refuses (InvalidArgument) a shape with a non-finite, zero or negative dimension, a non-unit
/// half-space normal, or an empty hull. `where` prefixes the message (e.g. "ShapeDef.shape").
void checkShape(const Shape& shape, const char* where);

/// Mass properties of the solid shape at `density` (kg/m^3), in the shape's frame. A half-space
/// has no finite mass and is refused.
MassProperties massOf(const Shape& shape, Real density);

/// Mass properties of several parts (each in the compound's frame) combined by the
/// parallel-axis theorem.
MassProperties combine(std::span<const MassProperties> parts);

/// Moves mass properties given in a frame F into the frame in which F sits at `pose`.
MassProperties transformed(const MassProperties& mass, const Transform& pose);

/// Stands for "unbounded" in a half-space's box (m): finite, so box centres, sizes and sums stay
/// finite where +-infinity would give NaN.
inline constexpr Real kHalfSpaceBound = 1e30;

/// The tight bounding box of the shape at `pose`. A half-space is unbounded: its box reaches
/// +-kHalfSpaceBound on every side, except that when its world normal lies exactly along a world
/// axis (e.g. an unrotated ground plane) the box ends at the plane on that axis.
Aabb boundsOf(const Shape& shape, const Transform& pose);

/// The point of the shape farthest along `direction` (local frame, need not be unit). Ties go
/// to a fixed choice (a zero component counts as positive; a hull's lowest vertex index). A
/// half-space has no support point and is refused (InvalidArgument): pair it through the
/// half-space routines instead.
Vec3 support(const Shape& shape, const Vec3& direction);

/// The largest distance from the shape's local origin to any of its points (m): the radius of
/// the smallest sphere about the origin that holds it. Infinite for a half-space.
Real boundingRadius(const Shape& shape);

}  // namespace tumble
