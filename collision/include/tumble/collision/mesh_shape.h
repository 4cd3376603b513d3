#pragma once
/// The built, immutable geometry behind the TriangleMesh and HeightField shapes: what the
/// narrowphase and the queries walk. Built once from the plain data of mesh_data.h and shared by
/// every shape that uses it.
///
/// Active edges (against "ghost" contacts): an edge between two triangles that lie in one plane
/// (within kFlatEdgeAngle) or fold concavely is internal: a contact on it, or on a vertex all of
/// whose edges in the triangle are internal, takes the triangle's face normal instead of the
/// edge's (collide_mesh_edges.cpp). Boundary edges, edges of more than two triangles and edges
/// between triangles of opposite winding stay active. The fold is judged from the side the normals
/// point to; seen from behind, a convex edge looks concave and is still flagged as seen from the
/// front.

#include <array>
#include <cstdint>
#include <vector>

#include "tumble/collision/aabb.h"
#include "tumble/collision/mesh_data.h"
#include "tumble/collision/shape.h"

namespace tumble {

/// Neighbouring triangles closer than this to coplanar make an internal edge (radians).
inline constexpr Real kFlatEdgeAngle = 3.0 * 3.14159265358979323846 / 180.0;

/// One node of a mesh's bounding volume hierarchy. Nodes lie in depth-first order in one array:
/// an inner node's first child follows it and its second child sits at `index`; a leaf holds the
/// triangles [index, index + count) of MeshGeometry::triangles.
struct MeshBvhNode {
    Aabb box;                 ///< (m), local frame
    std::uint32_t index = 0;  ///< second child (inner node) or first triangle (leaf)
    std::uint32_t count = 0;  ///< triangles of a leaf; 0 for an inner node
};

/// Bit k of a triangle's edge flags is edge k, from its vertex k to vertex (k + 1) mod 3.
inline constexpr std::uint8_t kAllEdgesActive = 0b111;
/// In MeshGeometry::across: the edge has no one neighbour (a border, a non-manifold edge or one
/// between triangles of opposite winding).
inline constexpr std::uint32_t kNoNeighbour = 0xFFFFFFFFu;

struct MeshGeometry {
    std::vector<Vec3> vertices;  ///< (m), local frame
    /// Triangles in the order of the hierarchy's leaves; a triangle's index here is its id in
    /// contact feature ids and query results.
    std::vector<std::array<std::uint32_t, 3>> triangles;
    std::vector<Vec3> normals;              ///< unit, per triangle, counter-clockwise side
    std::vector<std::uint8_t> activeEdges;  ///< per triangle (see kAllEdgesActive)
    /// Per triangle and edge k: the vertex (index into vertices) of the neighbour across it that
    /// is not on the edge, or kNoNeighbour. With the triangle's own third vertex it bounds the
    /// edge's normal cone (collide_mesh_edges.cpp).
    std::vector<std::array<std::uint32_t, 3>> across;
    std::vector<std::uint32_t> sourceIndex;  ///< per triangle: its index in the input data
    std::vector<MeshBvhNode> nodes;          ///< nodes[0] is the root
    std::uint32_t droppedTriangles = 0;      ///< degenerate input triangles left out
};

struct HeightFieldGeometry {
    HeightFieldData grid;
    Real minHeight = 0;  ///< (m)
    Real maxHeight = 0;  ///< (m)
    /// Per cell (row-major in j): bits 0-2 the edges of its lower triangle, 3-5 of its upper one.
    std::vector<std::uint8_t> activeEdges;
    // The neighbour across an edge is found from the grid (detail::fieldAcross): none is stored.
};

/// A triangle of a mesh or height field, in the shape's local frame.
struct MeshTriangle {
    std::array<Vec3, 3> vertices;  ///< (m), counter-clockwise seen from the normal's side
    Vec3 normal = Vec3::UnitZ();   ///< unit
    std::uint8_t activeEdges = kAllEdgesActive;
    /// Mesh: index in MeshGeometry::triangles. Height field: 2 * cell + (0 lower, 1 upper), cell
    /// = j * (columns - 1) + i. Cell (i, j) is split along its diagonal from sample (i, j) to
    /// (i + 1, j + 1); the lower triangle holds sample (i + 1, j).
    std::uint32_t index = 0;
};

/// The local bounding box of a mesh or height field (m).
Aabb localBounds(const MeshGeometry& mesh);
Aabb localBounds(const HeightFieldGeometry& field);

/// Whether the edge from a to b of the triangle (a, b, c) is active, given the third vertex d of
/// the neighbour (b, a, d) across it: true when the two fold convexly by more than kFlatEdgeAngle.
bool isActiveEdge(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d);

}  // namespace tumble
