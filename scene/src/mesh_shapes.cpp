// Scene-file meshes and height fields (docs/scene-format.md): inline arrays or a file beside the
// scene, read into the plain data of collision/mesh_data.h through the loaders of mesh_io.h, whose
// refusals are re-thrown at the JSON path of the value they refuse (so the file's line is named).

#include <filesystem>

#include "scene_parts.h"
#include "tumble/collision/mesh_shape.h"
#include "tumble/scene/mesh_io.h"

namespace tumble::cli {

// The one place a mesh or height field becomes a Shape. The loaders already dropped the
// triangles they saw as degenerate; fromData may drop more by its own (area) rule, so those are
// reported too.
Shape meshShape(const TriangleMeshData& mesh, const ShapeSource& source, const std::string& path) {
    try {
        TriangleMesh shape = TriangleMesh::fromData(mesh);
        if (source.warnings != nullptr && shape.data->droppedTriangles > 0)
            source.warnings->push_back(path + ": dropped " +
                                       std::to_string(shape.data->droppedTriangles) +
                                       " degenerate triangles");
        return shape;
    } catch (const InvalidArgument& e) {
        failAt(path, e.what());
    }
}
Shape heightFieldShape(const HeightFieldData& field, const std::string& path) {
    try {
        return HeightField::fromData(field);
    } catch (const InvalidArgument& e) {
        failAt(path, e.what());
    }
}

namespace {

std::string elementPath(const std::string& list, std::size_t index) {
    return list + "[" + std::to_string(index) + "]";
}

/// The member `key`, required to be an array.
const Json& arrayAt(JsonObject& o, const std::string& key, const char* expected) {
    const Json* value = o.find(key);
    if (value == nullptr || !value->is_array())
        failAt(o.pathOf(key), "expected ", expected,
               value == nullptr ? std::string(", got nothing") : ", got " + typeName(*value));
    return *value;
}

std::uint32_t readIndex(const Json& value, const std::string& path) {
    if (!value.is_number_integer() || value.get<long long>() < 0 ||
        value.get<long long>() > 0xFFFFFFFFll)
        failAt(path, "expected a vertex index (an integer in [0, 4294967295]), got ",
               value.is_number() ? value.dump() : typeName(value));
    return static_cast<std::uint32_t>(value.get<long long>());
}

std::string resolve(const std::string& file, const ShapeSource& source) {
    const std::filesystem::path path(file);
    return path.is_absolute() || source.directory.empty()
               ? file
               : (std::filesystem::path(source.directory) / path).string();
}

/// The member "file" read with `load`; a refusal names the key (and so the scene's line) and
/// then the file's own message.
template <typename Load>
auto loadFile(JsonObject& o, const ShapeSource& source, Load&& load) {
    const std::string file = o.string("file", "");
    if (file.empty())
        failAt(o.pathOf("file"), "expected a file name");
    try {
        return load(resolve(file, source));
    } catch (const InvalidArgument& e) {
        failAt(o.pathOf("file"), e.what());
    }
}

}  // namespace

TriangleMeshData parseMeshData(JsonObject& o, const ShapeSource& source) {
    std::vector<std::string> warnings;
    TriangleMeshData mesh;
    if (o.has("file")) {
        for (const char* key : {"vertices", "triangles"}) {
            if (o.has(key))
                failAt(o.pathOf(key), "give either \"file\" or \"vertices\" and \"triangles\"");
        }
        mesh = loadFile(o, source,
                        [&](const std::string& path) { return loadMeshFile(path, &warnings); });
    } else {
        const Json& vertices = arrayAt(o, "vertices", "an array of [x, y, z] vertices (m)");
        const Json& triangles = arrayAt(o, "triangles", "an array of [i, j, k] vertex indices");
        for (std::size_t i = 0; i < vertices.size(); ++i)
            mesh.vertices.push_back(readVec3(vertices[i], elementPath(o.pathOf("vertices"), i)));
        for (std::size_t t = 0; t < triangles.size(); ++t) {
            const std::string path = elementPath(o.pathOf("triangles"), t);
            if (!triangles[t].is_array() || triangles[t].size() != 3)
                failAt(path, "expected an array of 3 vertex indices, got ", typeName(triangles[t]));
            mesh.triangles.push_back({readIndex(triangles[t][0], elementPath(path, 0)),
                                      readIndex(triangles[t][1], elementPath(path, 1)),
                                      readIndex(triangles[t][2], elementPath(path, 2))});
        }
        try {
            mesh = meshFromArrays(std::move(mesh.vertices), std::move(mesh.triangles), &warnings);
        } catch (const MeshElementError& e) {
            const char* list = e.element() == MeshElement::Vertex ? "vertices" : "triangles";
            failAt(elementPath(o.pathOf(list), e.index()), e.rule());
        } catch (const InvalidArgument& e) {
            failAt(o.pathOf("triangles"), e.what());
        }
    }
    if (source.warnings != nullptr) {
        for (const std::string& w : warnings)
            source.warnings->push_back(o.path() + ": " + w);
    }
    return mesh;
}

namespace {

/// "heights": rows of samples, row j at y = j * spacingY, all of one length.
std::vector<Real> readHeights(JsonObject& o, std::uint32_t& columns, std::uint32_t& rows) {
    const std::string path = o.pathOf("heights");
    const Json& list = arrayAt(o, "heights", "an array of rows [[h, h, ...], ...] (m)");
    std::vector<Real> heights;
    for (std::size_t j = 0; j < list.size(); ++j) {
        const Json& row = list[j];
        if (!row.is_array() || (j > 0 && row.size() != list[0].size()))
            failAt(elementPath(path, j), "expected a row of ", j > 0 ? list[0].size() : 2,
                   j > 0 ? " heights (as row 0)" : " or more heights", ", got ",
                   row.is_array() ? std::to_string(row.size()) + " values" : typeName(row));
        for (std::size_t i = 0; i < row.size(); ++i) {
            if (!row[i].is_number())
                failAt(elementPath(elementPath(path, j), i), "expected a height (m), got ",
                       typeName(row[i]));
            heights.push_back(row[i].get<Real>());
        }
    }
    rows = static_cast<std::uint32_t>(std::min<std::size_t>(list.size(), 0xFFFFFFFF));
    columns = list.empty() ? 0 : static_cast<std::uint32_t>(list[0].size());
    return heights;
}

/// "holes": one row of 0/1 flags per row of cells (optional).
std::vector<std::uint8_t> readHoles(JsonObject& o) {
    std::vector<std::uint8_t> holes;
    const Json* list = o.find("holes");
    if (list == nullptr)
        return holes;
    if (!list->is_array())
        failAt(o.pathOf("holes"), "expected rows of 0/1 flags, one per cell, got ",
               typeName(*list));
    for (std::size_t j = 0; j < list->size(); ++j) {
        const Json& row = (*list)[j];
        for (std::size_t i = 0; row.is_array() && i < row.size(); ++i) {
            if (!row[i].is_number_integer() || (row[i] != 0 && row[i] != 1))
                failAt(elementPath(elementPath(o.pathOf("holes"), j), i),
                       "expected 0 or 1 (1: a hole)");
            holes.push_back(row[i].get<std::uint8_t>());
        }
        if (!row.is_array())
            failAt(elementPath(o.pathOf("holes"), j), "expected a row of 0/1 flags");
    }
    return holes;
}

}  // namespace

HeightFieldData parseHeightFieldData(JsonObject& o, const ShapeSource& source) {
    const Json* spacing = o.find("spacing");
    if (spacing == nullptr || !spacing->is_array() || spacing->size() != 2 ||
        !(*spacing)[0].is_number() || !(*spacing)[1].is_number())
        failAt(o.pathOf("spacing"), "expected [dx, dy], the samples' spacing along x and y (m)");
    const Real dx = (*spacing)[0].get<Real>(), dy = (*spacing)[1].get<Real>();
    if (o.has("file")) {
        for (const char* key : {"heights", "holes"}) {
            if (o.has(key))
                failAt(o.pathOf(key), "give either \"file\" or \"heights\"");
        }
        const Real scale = o.number("heightScale", 1);
        const Real offset = o.number("heightOffset", 0);
        return loadFile(o, source, [&](const std::string& path) {
            return loadHeightFieldPng(path, dx, dy, scale, offset);
        });
    }
    for (const char* key : {"heightScale", "heightOffset"}) {
        if (o.has(key))
            failAt(o.pathOf(key),
                   "only with \"file\" (a PNG's samples are scaled; inline heights "
                   "are metres)");
    }
    std::uint32_t columns = 0, rows = 0;
    std::vector<Real> heights = readHeights(o, columns, rows);
    std::vector<std::uint8_t> holes = readHoles(o);
    try {
        return heightFieldFromArray(columns, rows, dx, dy, std::move(heights), std::move(holes));
    } catch (const InvalidArgument& e) {
        const std::string what = e.what();
        failAt(o.pathOf(what.rfind("spacing", 0) == 0 ? "spacing"
                        : what.rfind("holes", 0) == 0 ? "holes"
                                                      : "heights"),
               what);
    }
}

}  // namespace tumble::cli
