// Wavefront OBJ files through tinyobjloader (Debian's libtinyobjloader-dev, double precision).
// tinyobjloader is lenient: a vertex coordinate it cannot read becomes 0 and NaN is not a number
// to it, so a scan of our own first checks every `v` line's numbers and records the line of each
// `v` and `f` line; then a refused vertex or face (from the shared checks) can name its line.

#include <sstream>
#include <string_view>

#include "mesh_io_parts.h"

#ifdef TUMBLE_HAVE_TINYOBJLOADER
#include <tiny_obj_loader.h>
#endif

namespace tumble {

#ifdef TUMBLE_HAVE_TINYOBJLOADER
namespace {

/// The 1-based line of every `v` and `f` line, in file order.
struct ObjLines {
    std::vector<std::size_t> vertices;
    std::vector<std::size_t> faces;
};

/// Whitespace-separated tokens as tinyobjloader splits them (space, tab, carriage return).
std::vector<std::string_view> tokens(std::string_view line) {
    std::vector<std::string_view> out;
    std::size_t at = 0;
    while (at < line.size()) {
        const std::size_t start = line.find_first_not_of(" \t\r", at);
        if (start == std::string_view::npos)
            break;
        const std::size_t end = std::min(line.find_first_of(" \t\r", start), line.size());
        out.push_back(line.substr(start, end - start));
        at = end;
    }
    return out;
}

/// Checks each `v` line has three finite numbers and each `f` line three or more vertices, and
/// records the lines. Lines end at \n, \r\n or a lone \r, as tinyobjloader reads them.
ObjLines scanObj(const std::string& text, const std::string& path) {
    ObjLines lines;
    std::size_t number = 0;
    for (std::size_t at = 0; at < text.size();) {
        std::size_t end = text.find_first_of("\r\n", at);
        end = end == std::string::npos ? text.size() : end;
        std::string_view line(text.data() + at, end - at);
        line = line.substr(0, line.find('\0'));  // tinyobjloader reads the line as a C string
        at = end + (text.compare(end, 2, "\r\n") == 0 ? 2 : 1);
        ++number;
        const std::size_t first = line.find_first_not_of(" \t");
        if (first == std::string_view::npos || first + 1 >= line.size())
            continue;
        const bool spaced = line[first + 1] == ' ' || line[first + 1] == '\t';
        const std::string where = path + ":" + std::to_string(number);
        if (line[first] == 'v' && spaced) {
            const std::vector<std::string_view> words = tokens(line.substr(first + 2));
            if (words.size() < 3)
                fail(where, ": a vertex needs three coordinates (got ", words.size(), ")");
            for (std::size_t k = 0; k < 3; ++k)
                mesh_io::readCoordinate(words[k], where);
            lines.vertices.push_back(number);
        } else if (line[first] == 'f' && spaced) {
            const std::size_t count = tokens(line.substr(first + 2)).size();
            if (count < 3)
                fail(where, ": a face needs at least three vertices (got ", count, ")");
            lines.faces.push_back(number);
        }
    }
    return lines;
}

/// "path:line" of element k of `list`, or "path: <name> k+1" if the scan saw fewer (a file the
/// scan and tinyobjloader split differently, which should not happen).
std::string located(const std::string& path, const std::vector<std::size_t>& list, std::size_t k,
                    const char* name) {
    return k < list.size() ? path + ":" + std::to_string(list[k])
                           : path + ": " + name + " " + std::to_string(k + 1);
}

/// The faces tinyobjloader read, split into fans from their first corner; faceOf[t] is the face
/// of triangle t. Refuses a corner outside the vertices (a relative index before the first one, a
/// number past the last), naming the face's line.
void triangulate(const std::vector<tinyobj::shape_t>& shapes, const ObjLines& lines,
                 const std::string& path, TriangleMeshData& mesh,
                 std::vector<std::size_t>& faceOf) {
    const std::size_t vertexCount = mesh.vertices.size();
    std::size_t face = 0;
    for (const tinyobj::shape_t& shape : shapes) {
        std::size_t offset = 0;
        for (const unsigned int corners : shape.mesh.num_face_vertices) {
            const tinyobj::index_t* corner = &shape.mesh.indices[offset];
            for (unsigned int k = 0; k < corners; ++k) {
                const int index = corner[k].vertex_index;
                if (index < 0 || static_cast<std::size_t>(index) >= vertexCount)
                    fail(located(path, lines.faces, face, "face"), ": corner ", k + 1,
                         " is outside the file's ", vertexCount,
                         " vertices (OBJ numbers them 1 to ", vertexCount, ", or -1 back to -",
                         vertexCount, " from the face)");
            }
            for (unsigned int k = 1; k + 1 < corners; ++k) {
                mesh.triangles.push_back({static_cast<std::uint32_t>(corner[0].vertex_index),
                                          static_cast<std::uint32_t>(corner[k].vertex_index),
                                          static_cast<std::uint32_t>(corner[k + 1].vertex_index)});
                faceOf.push_back(face);
            }
            offset += corners;
            ++face;
        }
    }
}

}  // namespace

bool haveObjLoader() {
    return true;
}

TriangleMeshData loadObj(const std::string& path, std::vector<std::string>* warnings) {
    const std::string text = mesh_io::readFile(path);
    const ObjLines lines = scanObj(text, path);
    tinyobj::attrib_t attrib;
    std::vector<tinyobj::shape_t> shapes;
    std::vector<tinyobj::material_t> materials;
    std::string warning;
    std::string error;
    std::istringstream in(text);
    // No material reader: `mtllib` is ignored. No triangulation: ours keeps each face's line.
    if (!tinyobj::LoadObj(&attrib, &shapes, &materials, &warning, &error, &in, nullptr, false))
        fail(path, ": OBJ parse error: ", error.substr(0, error.find_last_not_of('\n') + 1));
    TriangleMeshData mesh;
    for (std::size_t i = 0; i + 2 < attrib.vertices.size(); i += 3)
        mesh.vertices.emplace_back(attrib.vertices[i], attrib.vertices[i + 1],
                                   attrib.vertices[i + 2]);
    std::vector<std::size_t> faceOf;
    triangulate(shapes, lines, path, mesh, faceOf);
    const auto where = [&](MeshElement element, std::size_t index) {
        if (element == MeshElement::Vertex)
            return located(path, lines.vertices, index, "vertex");
        return located(path, lines.faces, faceOf[index], "face");
    };
    const DroppedTriangles dropped = mesh_io::checkNamed(mesh, path, where);
    mesh_io::warnDropped(warnings, path, dropped,
                         "at " + where(MeshElement::Triangle, dropped.first));
    return mesh;
}

#else

bool haveObjLoader() {
    return false;
}

TriangleMeshData loadObj(const std::string& path, std::vector<std::string>*) {
    fail(path, ": OBJ files need tinyobjloader, which this build was configured without ",
         "(apt install libtinyobjloader-dev, then configure again)");
}

#endif

}  // namespace tumble
