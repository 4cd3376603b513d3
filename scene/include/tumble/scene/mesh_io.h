#pragma once
/// Triangle meshes and height fields from files (OBJ, STL, greyscale PNG) and from plain arrays.
/// Every path ends in the same checks (checkTriangleMesh, checkHeightField): a bad input is
/// refused with an InvalidArgument naming the file (or list) and what is wrong, and nothing is
/// returned half-made. Degenerate triangles are dropped, not refused: each loader appends one
/// line saying how many it dropped to `warnings` (when given). Non-manifold edges are allowed.

#include <cstddef>
#include <string>
#include <vector>

#include "tumble/collision/mesh_data.h"
#include "tumble/core/error.h"

namespace tumble {

/// Which list an element refused by the checks belongs to.
enum class MeshElement { Vertex, Triangle, Height };

/// A refusal of one element: InvalidArgument "vertices[3]: ..." that also says which list and
/// index, so a caller can point at where the element came from (a file's line, a JSON path).
class MeshElementError : public InvalidArgument {
public:
    MeshElementError(MeshElement element, std::size_t index, const std::string& rule);
    MeshElement element() const { return element_; }
    std::size_t index() const { return index_; }
    /// The message without the element's name: "index 9 is out of range (4 vertices)".
    const std::string& rule() const { return rule_; }

private:
    MeshElement element_;
    std::size_t index_;
    std::string rule_;
};

/// Triangles whose area is at most this fraction of their longest edge squared are degenerate:
/// their normal (a cross product) has lost nearly all its digits to rounding.
inline constexpr Real kDegenerateTriangleArea = 1e-12;

/// What checkTriangleMesh dropped.
struct DroppedTriangles {
    std::size_t count = 0;
    std::size_t first = 0;  ///< index of the first one in the list given (valid when count > 0)
};

/// The checks every mesh passes: finite vertices, indices in range, at least one triangle left
/// after dropping the degenerate ones (zero area, a repeated index), fewer than 2^32 vertices.
/// Drops the degenerate triangles in place; throws MeshElementError for the first bad element
/// (InvalidArgument when the mesh as a whole is refused). `mesh` is unchanged when it throws.
DroppedTriangles checkTriangleMesh(TriangleMeshData& mesh);

/// The checks every height field passes: columns, rows >= 2, heights.size() == rows * columns,
/// spacings finite and > 0, heights finite, holes empty or one 0/1 flag per cell. Throws
/// MeshElementError for a non-finite height, InvalidArgument otherwise.
void checkHeightField(const HeightFieldData& field);

/// A mesh from arrays, checked. Messages name the lists "vertices[i]" and "triangles[i]".
TriangleMeshData meshFromArrays(std::vector<Vec3> vertices,
                                std::vector<std::array<std::uint32_t, 3>> triangles,
                                std::vector<std::string>* warnings = nullptr);

/// A height field from `heights` (rows * columns, row-major in j as HeightFieldData), checked.
HeightFieldData heightFieldFromArray(std::uint32_t columns, std::uint32_t rows, Real spacingX,
                                     Real spacingY, std::vector<Real> heights,
                                     std::vector<std::uint8_t> holes = {});

/// A Wavefront OBJ file's `v` and `f` lines (tinyobjloader); polygons are split into fans from
/// their first vertex (give convex polygons or triangles). Normals, texture coordinates, groups
/// and materials are ignored; no .mtl file is read. Messages name "path:line".
TriangleMeshData loadObj(const std::string& path, std::vector<std::string>* warnings = nullptr);

/// An STL file, ASCII ("solid ...") or binary; vertices shared by triangles are merged when their
/// coordinates are bitwise equal. Messages name "path:line" (ASCII) or the triangle (binary).
TriangleMeshData loadStl(const std::string& path, std::vector<std::string>* warnings = nullptr);

/// loadObj or loadStl by the file's extension (.obj, .stl, any case); others refused.
TriangleMeshData loadMeshFile(const std::string& path,
                              std::vector<std::string>* warnings = nullptr);

/// Most samples a PNG height field may have (2^24): 128 MB of heights, far above a useful
/// terrain, far below what a hostile file's header could make the loader allocate.
inline constexpr std::size_t kMaxHeightFieldSamples = std::size_t{1} << 24;

/// A height field from an 8- or 16-bit greyscale PNG (libpng): pixel (x, y) of a W x H image is
/// sample (i, j) = (x, H - 1 - y), so the image seen on a screen is the terrain seen from above
/// with x right and y up; its height is heightOffset + heightScale * value / (2^bits - 1) (m).
HeightFieldData loadHeightFieldPng(const std::string& path, Real spacingX, Real spacingY,
                                   Real heightScale, Real heightOffset = 0);

/// Are the OBJ and PNG loaders compiled in? (tinyobjloader and libpng are optional at configure
/// time; without them those loaders refuse every file, saying which package is missing.)
bool haveObjLoader();
bool havePngLoader();

}  // namespace tumble
