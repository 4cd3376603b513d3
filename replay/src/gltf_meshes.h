#pragma once
// Triangle meshes of the replay's shapes for the glTF export, in the shape's own frame: flat
// normals on boxes, hulls and caps, smooth ones on round surfaces. Degenerate triangles (at a
// sphere's poles) are left out, as glTF validators warn of them.

#include <cstdint>
#include <nlohmann/json.hpp>
#include <vector>

namespace tumble::gltf {

struct Mesh {
    std::vector<float> positions;  ///< x, y, z per vertex (m)
    std::vector<float> normals;    ///< unit, per vertex
    std::vector<std::uint32_t> indices;
};

/// The mesh of a shape of the replay description (docs/replay.md); a plane becomes a square of
/// side `planeSize` (m) about the point of the plane nearest the origin.
Mesh shapeMesh(const nlohmann::json& shape, float planeSize);

}  // namespace tumble::gltf
