#pragma once
/// Plain geometry of static triangle meshes and height fields, as given inline in a scene or read
/// from a file (OBJ, PNG). These are the loaders' output and the mesh shapes' input; they carry no
/// acceleration structure. Units are metres in the frame of the body that will carry the shape.

#include <array>
#include <cstdint>
#include <vector>

#include "tumble/core/math.h"

namespace tumble {

/// Triangles as vertex index triples, counter-clockwise seen from the side the normal points to.
/// Non-manifold edges are allowed; degenerate triangles are dropped by the loaders with a warning.
struct TriangleMeshData {
    std::vector<Vec3> vertices;                           ///< (m)
    std::vector<std::array<std::uint32_t, 3>> triangles;  ///< indices into vertices
};

/// A regular grid of heights over the local x-y plane, z up. Sample (i, j) sits at
/// (i * spacingX, j * spacingY, heights[j * columns + i]); cell (i, j) spans samples i..i+1,
/// j..j+1. Memory is proportional to the samples: no triangle list is stored.
struct HeightFieldData {
    std::uint32_t columns = 0;  ///< samples along x, >= 2
    std::uint32_t rows = 0;     ///< samples along y, >= 2
    Real spacingX = 1;          ///< (m), > 0
    Real spacingY = 1;          ///< (m), > 0
    std::vector<Real> heights;  ///< (m), rows * columns, row-major in j
    /// Empty (no holes) or (rows - 1) * (columns - 1) flags, row-major in j; 1 marks a hole.
    std::vector<std::uint8_t> holes;
};

}  // namespace tumble
