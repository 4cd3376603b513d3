// STL files, ASCII and binary. STL repeats every vertex in each triangle that uses it; equal
// coordinates are merged into one vertex so the mesh has the shared edges its adjacency needs.

#include <cmath>
#include <cstring>
#include <map>

#include "mesh_io_parts.h"

namespace tumble {
namespace {

constexpr std::size_t kBinaryHeader = 84;    // 80 bytes of text, then a little-endian uint32 count
constexpr std::size_t kBinaryTriangle = 50;  // normal, 3 vertices (12 floats), 2 attribute bytes

/// Builds the mesh, merging vertices with equal coordinates.
class MeshBuilder {
public:
    std::uint32_t vertex(const Vec3& p) {
        const auto [it, added] = index_.try_emplace({p.x(), p.y(), p.z()}, 0);
        if (added) {
            it->second = static_cast<std::uint32_t>(mesh.vertices.size());
            mesh.vertices.push_back(p);
        }
        return it->second;
    }
    TriangleMeshData mesh;

private:
    std::map<std::array<Real, 3>, std::uint32_t> index_;
};

bool isBinary(const std::string& bytes) {
    if (bytes.size() < kBinaryHeader)
        return false;
    std::uint32_t count = 0;
    std::memcpy(&count, bytes.data() + 80, 4);  // little-endian hosts only (x86-64, arm64)
    return bytes.size() == kBinaryHeader + kBinaryTriangle * std::size_t{count};
}

TriangleMeshData readBinary(const std::string& bytes, const std::string& path,
                            std::vector<std::size_t>& lines) {
    MeshBuilder builder;
    const std::size_t count = (bytes.size() - kBinaryHeader) / kBinaryTriangle;
    for (std::size_t t = 0; t < count; ++t) {
        float values[12];
        std::memcpy(values, bytes.data() + kBinaryHeader + t * kBinaryTriangle, sizeof values);
        std::array<std::uint32_t, 3> triangle{};
        for (int k = 0; k < 3; ++k) {
            const float* p = values + 3 + 3 * k;  // after the normal
            if (!std::isfinite(p[0]) || !std::isfinite(p[1]) || !std::isfinite(p[2]))
                fail(path, ": triangle ", t + 1, " of ", count, ": vertex ", k + 1,
                     " has a coordinate that is not finite (", p[0], ", ", p[1], ", ", p[2], ")");
            triangle[k] = builder.vertex(Vec3(p[0], p[1], p[2]));
        }
        builder.mesh.triangles.push_back(triangle);
        lines.push_back(t + 1);
    }
    return std::move(builder.mesh);
}

/// Whitespace-separated words with their 1-based lines.
std::vector<std::pair<std::string_view, std::size_t>> words(const std::string& text) {
    std::vector<std::pair<std::string_view, std::size_t>> out;
    std::size_t line = 1;
    for (std::size_t at = 0; at < text.size();) {
        const char c = text[at];
        if (c == ' ' || c == '\t' || c == '\r' || c == '\n') {
            line += c == '\n';
            ++at;
            continue;
        }
        const std::size_t end = std::min(text.find_first_of(" \t\r\n", at), text.size());
        out.emplace_back(std::string_view(text).substr(at, end - at), line);
        at = end;
    }
    return out;
}

/// solid NAME (facet normal N N N outer loop (vertex X Y Z){3} endloop endfacet)* endsolid NAME.
/// The names are skipped to the end of their line; the normals are read and ignored.
TriangleMeshData readAscii(const std::string& text, const std::string& path,
                           std::vector<std::size_t>& lines) {
    const auto list = words(text);
    MeshBuilder builder;
    std::size_t i = 0;
    const auto where = [&](std::size_t k) {
        const std::size_t line = k < list.size() ? list[k].second
                                 : list.empty()  ? 1
                                                 : list.back().second;
        return path + ":" + std::to_string(line);
    };
    const auto expect = [&](std::string_view word) {
        if (i >= list.size())
            fail(where(i), ": the file ends where \"", word, "\" was expected");
        if (list[i].first != word)
            fail(where(i), ": expected \"", word, "\", got \"", list[i].first, "\"");
        ++i;
    };
    const auto skipLine = [&] {
        const std::size_t line = list[i - 1].second;
        while (i < list.size() && list[i].second == line)
            ++i;
    };
    const auto number = [&] {
        if (i >= list.size())
            fail(where(i), ": the file ends where a number was expected");
        const Real value = mesh_io::readCoordinate(list[i].first, where(i));
        ++i;
        return value;
    };
    expect("solid");
    skipLine();
    while (i < list.size() && list[i].first == "facet") {
        const std::size_t facetLine = list[i].second;
        ++i;
        expect("normal");
        for (int k = 0; k < 3; ++k)
            number();
        expect("outer");
        expect("loop");
        std::array<std::uint32_t, 3> triangle{};
        for (int k = 0; k < 3; ++k) {
            expect("vertex");
            const Real x = number(), y = number(), z = number();
            triangle[k] = builder.vertex(Vec3(x, y, z));
        }
        expect("endloop");
        expect("endfacet");
        builder.mesh.triangles.push_back(triangle);
        lines.push_back(facetLine);
    }
    expect("endsolid");
    skipLine();
    if (i < list.size())
        fail(where(i), ": \"", list[i].first, "\" after endsolid");
    return std::move(builder.mesh);
}

}  // namespace

TriangleMeshData loadStl(const std::string& path, std::vector<std::string>* warnings) {
    const std::string bytes = mesh_io::readFile(path);
    // A binary file may begin with "solid" too; its size, from its count, tells it apart.
    const bool binary = isBinary(bytes);
    if (!binary && bytes.compare(0, 5, "solid") != 0)
        fail(path, ": not an STL file (neither \"solid\" at the start nor a binary file of 84 + ",
             "50 * count bytes; got ", bytes.size(), " bytes)");
    std::vector<std::size_t> lines;  // per triangle: its facet's line, or its number (binary)
    TriangleMeshData mesh = binary ? readBinary(bytes, path, lines) : readAscii(bytes, path, lines);
    const auto where = [&](MeshElement, std::size_t index) {
        return binary ? path + ": triangle " + std::to_string(lines[index])
                      : path + ":" + std::to_string(lines[index]);
    };
    const DroppedTriangles dropped = mesh_io::checkNamed(mesh, path, where);
    mesh_io::warnDropped(warnings, path, dropped,
                         "at " + where(MeshElement::Triangle, dropped.first));
    return mesh;
}

}  // namespace tumble
