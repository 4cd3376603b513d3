#pragma once
/// The terrain scenes' ground, generated in one place so every engine -- and Tumble's height field
/// and mesh shapes -- collides with the same surface: a bowl with rolling bumps as a height field,
/// and the same surface as a triangle mesh split the same way.

#include "tumble/collision/mesh_data.h"

namespace tumble::bench {

/// A square bowl of rolling bumps: h(x, y) = rise r^2 / R^2 + bump sin(2 pi x / L) sin(2 pi y / L),
/// r the distance from the centre, R half the side; it keeps a pile from rolling off the edge.
struct TerrainSpec {
    int samples = 65;     ///< along each side (64 x 64 cells)
    Real spacing = 0.25;  ///< between samples (m): a 16 m square
    Real rise = 2;        ///< the bowl's height at the middle of each edge (m)
    Real bump = 0.3;      ///< the bumps' amplitude (m)
    Real wavelength = 3;  ///< the bumps' wavelength L (m)
};

/// The terrain as a height field: sample (i, j) at (i dx, j dy, h), x and y from 0 to the side.
HeightFieldData rollingTerrain(const TerrainSpec& spec = {});

/// The same surface as triangles: vertex j * columns + i is sample (i, j); each cell is split
/// along the diagonal from sample (i, j) to (i + 1, j + 1) into (i, j) (i+1, j) (i+1, j+1) and
/// (i, j) (i+1, j+1) (i, j+1), counter-clockwise seen from above (normals up).
TriangleMeshData terrainMesh(const HeightFieldData& field);

/// The surface's height at (x, y) on those triangles; clamped to the field at its edges (m).
Real terrainHeight(const HeightFieldData& field, Real x, Real y);

}  // namespace tumble::bench
