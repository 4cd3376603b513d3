// The terrain scenes' ground (terrain.h).

#include "terrain.h"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace tumble::bench {

HeightFieldData rollingTerrain(const TerrainSpec& spec) {
    HeightFieldData field;
    field.columns = field.rows = static_cast<std::uint32_t>(spec.samples);
    field.spacingX = field.spacingY = spec.spacing;
    const Real half = 0.5 * (spec.samples - 1) * spec.spacing;
    const Real k = 2 * std::numbers::pi / spec.wavelength;
    for (int j = 0; j < spec.samples; ++j) {
        for (int i = 0; i < spec.samples; ++i) {
            const Real x = i * spec.spacing, y = j * spec.spacing;
            const Real r2 = (x - half) * (x - half) + (y - half) * (y - half);
            field.heights.push_back(spec.rise * r2 / (half * half) +
                                    spec.bump * std::sin(k * x) * std::sin(k * y));
        }
    }
    return field;
}

TriangleMeshData terrainMesh(const HeightFieldData& field) {
    TriangleMeshData mesh;
    for (std::uint32_t j = 0; j < field.rows; ++j) {
        for (std::uint32_t i = 0; i < field.columns; ++i)
            mesh.vertices.emplace_back(i * field.spacingX, j * field.spacingY,
                                       field.heights[j * field.columns + i]);
    }
    for (std::uint32_t j = 0; j + 1 < field.rows; ++j) {
        for (std::uint32_t i = 0; i + 1 < field.columns; ++i) {
            const std::uint32_t a = j * field.columns + i;  // (i, j)
            const std::uint32_t b = a + 1;                  // (i + 1, j)
            const std::uint32_t c = b + field.columns;      // (i + 1, j + 1)
            const std::uint32_t d = a + field.columns;      // (i, j + 1)
            mesh.triangles.push_back({a, b, c});
            mesh.triangles.push_back({a, c, d});
        }
    }
    return mesh;
}

Real terrainHeight(const HeightFieldData& field, Real x, Real y) {
    const Real u = std::clamp(x / field.spacingX, Real(0), Real(field.columns - 1));
    const Real v = std::clamp(y / field.spacingY, Real(0), Real(field.rows - 1));
    const auto i = std::min<std::uint32_t>(static_cast<std::uint32_t>(u), field.columns - 2);
    const auto j = std::min<std::uint32_t>(static_cast<std::uint32_t>(v), field.rows - 2);
    const Real s = u - i, t = v - j;  // in the cell, [0, 1]
    const auto h = [&](std::uint32_t di, std::uint32_t dj) {
        return field.heights[(j + dj) * field.columns + i + di];
    };
    // Below the diagonal (s >= t): triangle (i, j) (i+1, j) (i+1, j+1); above: (i, j) (i+1, j+1)
    // (i, j+1). Linear on each.
    if (s >= t)
        return h(0, 0) + s * (h(1, 0) - h(0, 0)) + t * (h(1, 1) - h(1, 0));
    return h(0, 0) + t * (h(0, 1) - h(0, 0)) + s * (h(1, 1) - h(0, 1));
}

}  // namespace tumble::bench
