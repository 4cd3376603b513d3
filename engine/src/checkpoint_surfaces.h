#pragma once
/// The mesh section of a checkpoint (checkpoint.cpp): the triangle meshes and height fields the
/// shapes carry, each saved once as its builder's input, and a shape's reference to one.

#include <algorithm>
#include <cstdint>
#include <vector>

#include "checkpoint_io.h"
#include "shape_store.h"
#include "tumble/collision/mesh_shape.h"

namespace tumble::checkpoint_io {

// A checkpoint is self-contained: the meshes and height fields the shapes carry are saved in a
// section of their own, each once however many shapes share it, ahead of the shape records,
// which refer to them by their index in it. The section saves the builders' input, not what they
// built: the reader builds again, and since the builders are deterministic (mesh_bvh.cpp,
// height_field.cpp) it gets the same hierarchy, triangle order and edge flags, bit for bit. A
// mesh's input is its vertices and its triangles in their source order, a dropped (degenerate)
// triangle written as (0, 0, 0), which the builder drops again: every triangle keeps its index.

/// The section's own format version, checked before anything in it is read.
constexpr std::uint32_t kSurfaceSectionVersion = 1;

inline const void* surfaceData(const Shape& shape) {
    if (const auto* mesh = std::get_if<TriangleMesh>(&shape))
        return mesh->data.get();
    return std::get<HeightField>(shape).data.get();
}

inline TriangleMeshData builderInput(const MeshGeometry& mesh) {
    TriangleMeshData input{mesh.vertices, {}};
    input.triangles.assign(mesh.triangles.size() + mesh.droppedTriangles, {0, 0, 0});
    for (std::size_t k = 0; k < mesh.triangles.size(); ++k)
        input.triangles[mesh.sourceIndex[k]] = mesh.triangles[k];
    return input;
}

template <typename Ar>
void field(Ar& a, TriangleMeshData& x) {
    fields(a, x.vertices, x.triangles);
}
template <typename Ar>
void field(Ar& a, HeightFieldData& x) {
    fields(a, x.columns, x.rows, x.spacingX, x.spacingY, x.heights, x.holes);
}

inline void surfaceSection(Writer& a, const std::vector<ShapeRecord>& records) {
    for (const ShapeRecord& record : records) {
        const Shape& shape = record.def.geometry;
        if (!isTriangleSurface(shape))
            continue;
        if (surfaceData(shape) == nullptr)
            fail("checkpoint: a shape's triangle mesh or height field has no geometry");
        if (std::none_of(a.surfaces.begin(), a.surfaces.end(), [&](const Shape& saved) {
                return surfaceData(saved) == surfaceData(shape);
            }))
            a.surfaces.push_back(shape);
    }
    std::uint32_t version = kSurfaceSectionVersion;
    field(a, version);
    a.count(a.surfaces.size());
    for (const Shape& shape : a.surfaces) {
        auto type = static_cast<std::uint8_t>(shape.index());
        field(a, type);
        if (const auto* mesh = std::get_if<TriangleMesh>(&shape)) {
            TriangleMeshData input = builderInput(*mesh->data);
            field(a, input);
        } else {
            HeightFieldData grid = std::get<HeightField>(shape).data->grid;
            field(a, grid);
        }
    }
}

/// Builds `data` into a shape with `build`; a refusal becomes a corrupt-payload error.
template <typename Data, typename Build>
Shape buildSurface(const Reader& a, std::size_t k, const Data& data, Build&& build) {
    try {
        return build(data);
    } catch (const InvalidArgument& e) {
        a.corrupt("mesh section: surface ", k, " does not build: ", e.what());
    }
}

inline void surfaceSection(Reader& a, const std::vector<ShapeRecord>&) {
    std::uint32_t version = 0;
    field(a, version);
    if (version != kSurfaceSectionVersion)
        a.corrupt("mesh section version ", version, ", this build reads version ",
                  kSurfaceSectionVersion);
    const std::size_t count = a.count(0);
    for (std::size_t k = 0; k < count; ++k) {
        std::uint8_t type = 0;
        field(a, type);
        if (type == static_cast<std::uint8_t>(ShapeType::TriangleMesh)) {
            TriangleMeshData input;
            field(a, input);
            a.surfaces.push_back(buildSurface(a, k, input, TriangleMesh::fromData));
        } else if (type == static_cast<std::uint8_t>(ShapeType::HeightField)) {
            HeightFieldData grid;
            field(a, grid);
            a.surfaces.push_back(buildSurface(a, k, grid, HeightField::fromData));
        } else {
            a.corrupt("mesh section: surface ", k, " has shape type ", int{type});
        }
    }
}

/// A mesh or height field shape as its index in the surface section.
template <typename Ar>
void surfaceReference(Ar& a, Shape& shape) {
    std::uint32_t index = 0;
    if constexpr (!Ar::kReading) {
        const auto saved = std::find_if(a.surfaces.begin(), a.surfaces.end(), [&](const Shape& s) {
            return surfaceData(s) == surfaceData(shape);
        });
        index = static_cast<std::uint32_t>(saved - a.surfaces.begin());
    }
    field(a, index);
    if constexpr (Ar::kReading) {
        if (!(index < a.surfaces.size() && a.surfaces[index].index() == shape.index()))
            a.corrupt("a shape refers to surface ", index, " of the mesh section (",
                      a.surfaces.size(), " surfaces), or to one of another type");
        shape = a.surfaces[index];
    }
}

}  // namespace tumble::checkpoint_io
