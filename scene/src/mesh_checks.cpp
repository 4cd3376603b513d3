// The one set of checks behind every mesh and height-field loader (mesh_io.h), and the inline
// arrays. Checks run before anything is changed, so a refused input leaves nothing half-made.

#include <algorithm>
#include <charconv>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <sstream>

#include "mesh_io_parts.h"

namespace tumble {
namespace {

const char* listName(MeshElement element) {
    switch (element) {
        case MeshElement::Vertex:
            return "vertices";
        case MeshElement::Triangle:
            return "triangles";
        case MeshElement::Height:
        default:
            return "heights";
    }
}

std::string elementMessage(MeshElement element, std::size_t index, const std::string& rule) {
    return std::string(listName(element)) + "[" + std::to_string(index) + "]: " + rule;
}

bool degenerate(const TriangleMeshData& mesh, const std::array<std::uint32_t, 3>& t) {
    if (t[0] == t[1] || t[1] == t[2] || t[0] == t[2])
        return true;
    const Vec3& a = mesh.vertices[t[0]];
    const Vec3& b = mesh.vertices[t[1]];
    const Vec3& c = mesh.vertices[t[2]];
    const Real longest =
        std::max({(b - a).squaredNorm(), (c - b).squaredNorm(), (a - c).squaredNorm()});
    return (b - a).cross(c - a).norm() <= kDegenerateTriangleArea * longest;
}

}  // namespace

MeshElementError::MeshElementError(MeshElement element, std::size_t index, const std::string& rule)
    : InvalidArgument(elementMessage(element, index, rule)),
      element_(element),
      index_(index),
      rule_(rule) {}

DroppedTriangles checkTriangleMesh(TriangleMeshData& mesh) {
    const std::size_t vertexCount = mesh.vertices.size();
    if (vertexCount > std::numeric_limits<std::uint32_t>::max())
        fail("a mesh has at most 2^32 - 1 vertices (got ", vertexCount, ")");
    for (std::size_t i = 0; i < vertexCount; ++i) {
        const Vec3& v = mesh.vertices[i];
        if (!v.allFinite()) {
            std::ostringstream rule;
            rule << "coordinates must be finite (got " << v.x() << ", " << v.y() << ", " << v.z()
                 << ")";
            throw MeshElementError(MeshElement::Vertex, i, rule.str());
        }
    }
    for (std::size_t i = 0; i < mesh.triangles.size(); ++i) {
        for (const std::uint32_t index : mesh.triangles[i]) {
            if (index >= vertexCount)
                throw MeshElementError(MeshElement::Triangle, i,
                                       "vertex index " + std::to_string(index) +
                                           " is out of range (the mesh has " +
                                           std::to_string(vertexCount) + " vertices)");
        }
    }
    DroppedTriangles dropped;
    std::vector<bool> drop(mesh.triangles.size(), false);
    for (std::size_t i = 0; i < mesh.triangles.size(); ++i) {
        if (degenerate(mesh, mesh.triangles[i])) {
            drop[i] = true;
            dropped.first = dropped.count == 0 ? i : dropped.first;
            ++dropped.count;
        }
    }
    if (dropped.count == mesh.triangles.size())
        fail(mesh.triangles.empty() ? "a mesh needs at least one triangle (got none)"
                                    : "every triangle is degenerate (zero area or a repeated "
                                      "index): no triangle is left");
    std::size_t kept = 0;
    for (std::size_t i = 0; i < mesh.triangles.size(); ++i) {
        if (!drop[i])
            mesh.triangles[kept++] = mesh.triangles[i];
    }
    mesh.triangles.resize(kept);
    return dropped;
}

void checkHeightField(const HeightFieldData& field) {
    if (field.columns < 2 || field.rows < 2)
        fail("a height field needs at least 2 x 2 samples (got columns = ", field.columns,
             ", rows = ", field.rows, ")");
    const std::size_t samples = std::size_t{field.columns} * field.rows;
    if (field.heights.size() != samples)
        fail("heights has ", field.heights.size(), " samples; columns * rows = ", field.columns,
             " * ", field.rows, " = ", samples);
    for (const auto& [name, spacing] :
         {std::pair{"spacingX", field.spacingX}, {"spacingY", field.spacingY}}) {
        if (!(spacing > 0) || !std::isfinite(spacing))
            fail(name, " = ", spacing, " must be finite and > 0 (m)");
    }
    for (std::size_t k = 0; k < samples; ++k) {
        if (!std::isfinite(field.heights[k])) {
            std::ostringstream rule;
            rule << "must be finite (got " << field.heights[k] << ")";
            throw MeshElementError(MeshElement::Height, k, rule.str());
        }
    }
    const std::size_t cells = std::size_t{field.columns - 1} * (field.rows - 1);
    if (!field.holes.empty() && field.holes.size() != cells)
        fail("holes has ", field.holes.size(), " flags; a ", field.columns, " x ", field.rows,
             " height field has ", cells, " cells (or give none)");
    const auto bad =
        std::find_if(field.holes.begin(), field.holes.end(), [](std::uint8_t h) { return h > 1; });
    if (bad != field.holes.end())
        fail("holes[", bad - field.holes.begin(), "] = ", int{*bad}, " must be 0 or 1");
}

TriangleMeshData meshFromArrays(std::vector<Vec3> vertices,
                                std::vector<std::array<std::uint32_t, 3>> triangles,
                                std::vector<std::string>* warnings) {
    TriangleMeshData mesh{std::move(vertices), std::move(triangles)};
    const DroppedTriangles dropped = checkTriangleMesh(mesh);
    mesh_io::warnDropped(warnings, "mesh", dropped,
                         "triangles[" + std::to_string(dropped.first) + "]");
    return mesh;
}

HeightFieldData heightFieldFromArray(std::uint32_t columns, std::uint32_t rows, Real spacingX,
                                     Real spacingY, std::vector<Real> heights,
                                     std::vector<std::uint8_t> holes) {
    HeightFieldData field{columns, rows, spacingX, spacingY, std::move(heights), std::move(holes)};
    checkHeightField(field);
    return field;
}

TriangleMeshData loadMeshFile(const std::string& path, std::vector<std::string>* warnings) {
    std::string extension = path.substr(std::min(path.size(), path.rfind('.')));
    std::transform(extension.begin(), extension.end(), extension.begin(),
                   [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
    if (extension == ".obj")
        return loadObj(path, warnings);
    if (extension == ".stl")
        return loadStl(path, warnings);
    fail(path, ": a mesh file must end in .obj or .stl (got \"", extension, "\")");
}

namespace mesh_io {

std::string readFile(const std::string& path) {
    // Not a device or a pipe: a scene naming /dev/zero must be refused, not read for ever.
    std::error_code error;
    if (std::filesystem::exists(path, error) && !std::filesystem::is_regular_file(path, error))
        fail(path, ": not a regular file");
    std::ifstream in(path, std::ios::binary);
    if (!in)
        fail(path, ": cannot open the file");
    std::ostringstream buffer;
    buffer << in.rdbuf();
    if (in.bad())
        fail(path, ": cannot read the file");
    return buffer.str();
}

double readCoordinate(std::string_view text, const std::string& where) {
    if (!text.empty() && text.front() == '+')  // from_chars takes no '+'; some writers give one
        text.remove_prefix(1);
    double value = 0;
    const auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), value);
    if (error == std::errc::result_out_of_range)
        fail(where, ": coordinate \"", text, "\" is out of a double's range");
    if (error != std::errc() || end != text.data() + text.size())
        fail(where, ": coordinate \"", text, "\" is not a number");
    if (!std::isfinite(value))
        fail(where, ": coordinate \"", text, "\" is not finite (NaN and infinities are refused)");
    return value;
}

void warnDropped(std::vector<std::string>* warnings, const std::string& source,
                 const DroppedTriangles& dropped, const std::string& first) {
    if (warnings == nullptr || dropped.count == 0)
        return;
    warnings->push_back(source + ": dropped " + std::to_string(dropped.count) +
                        " degenerate triangle" + (dropped.count == 1 ? "" : "s") +
                        " (zero area or a repeated index), the first " + first);
}

}  // namespace mesh_io
}  // namespace tumble
