// Building a height field's geometry: checks, the height range and the active-edge flags of every
// cell's two triangles (see MeshTriangle::index for the split, detail::fieldAcross for which
// neighbour each edge borders). Edges on the border or next to a hole stay active.

#include <algorithm>
#include <cmath>

#include "mesh_triangles.h"
#include "tumble/collision/mesh_shape.h"
#include "tumble/core/error.h"

namespace tumble {
namespace {

void checkInput(const HeightFieldData& data) {
    if (data.columns < 2 || data.rows < 2)
        fail("HeightField: columns = ", data.columns, " and rows = ", data.rows,
             " must both be >= 2");
    if (!(std::isfinite(data.spacingX) && data.spacingX > 0))
        fail("HeightField: spacingX = ", data.spacingX, " m must be finite and > 0");
    if (!(std::isfinite(data.spacingY) && data.spacingY > 0))
        fail("HeightField: spacingY = ", data.spacingY, " m must be finite and > 0");
    const std::size_t samples = std::size_t{data.columns} * data.rows;
    if (data.heights.size() != samples)
        fail("HeightField: heights has ", data.heights.size(),
             " values; columns x rows = ", samples);
    for (std::size_t k = 0; k < samples; ++k) {
        if (!std::isfinite(data.heights[k]))
            fail("HeightField: heights[", k, "] (column ", k % data.columns, ", row ",
                 k / data.columns, ") = ", data.heights[k], " m must be finite");
    }
    const std::size_t cells = std::size_t{data.columns - 1} * (data.rows - 1);
    if (!data.holes.empty() && data.holes.size() != cells)
        fail("HeightField: holes has ", data.holes.size(),
             " flags; it must be empty or (rows - 1) x ", "(columns - 1) = ", cells);
}

/// Bit 1 << edge when the triangle's edge `edge` is active (fieldAcross finds its neighbour).
std::uint8_t edgeBit(const HeightFieldGeometry& field, const MeshTriangle& t, int edge) {
    Vec3 across;
    if (!detail::fieldAcross(field, t.index, edge, across))
        return static_cast<std::uint8_t>(1u << edge);
    const auto& v = t.vertices;
    const bool active =
        isActiveEdge(v[static_cast<std::size_t>(edge)], v[static_cast<std::size_t>((edge + 1) % 3)],
                     v[static_cast<std::size_t>((edge + 2) % 3)], across);
    return active ? static_cast<std::uint8_t>(1u << edge) : std::uint8_t{0};
}

std::uint8_t cellFlags(const HeightFieldGeometry& field, std::uint32_t i, std::uint32_t j) {
    const MeshTriangle lower = detail::fieldTriangle(field, i, j, 0);
    const MeshTriangle upper = detail::fieldTriangle(field, i, j, 1);
    std::uint8_t low = 0, up = 0;
    for (int edge = 0; edge < 3; ++edge) {
        low |= edgeBit(field, lower, edge);
        up |= edgeBit(field, upper, edge);
    }
    return static_cast<std::uint8_t>(low | up << 3);
}

}  // namespace

Aabb localBounds(const HeightFieldGeometry& field) {
    const HeightFieldData& grid = field.grid;
    return {Vec3(0, 0, field.minHeight), Vec3((grid.columns - 1) * grid.spacingX,
                                              (grid.rows - 1) * grid.spacingY, field.maxHeight)};
}

HeightField HeightField::fromData(const HeightFieldData& data) {
    checkInput(data);
    auto field = std::make_shared<HeightFieldGeometry>();
    field->grid = data;
    const auto [low, high] = std::minmax_element(data.heights.begin(), data.heights.end());
    field->minHeight = *low;
    field->maxHeight = *high;
    const std::uint32_t cellColumns = data.columns - 1;
    // fieldTriangle reads the flags while they are built: start from all active.
    field->activeEdges.assign(std::size_t{cellColumns} * (data.rows - 1), 0b111111);
    std::vector<std::uint8_t> flags(field->activeEdges.size());
    for (std::uint32_t j = 0; j + 1 < data.rows; ++j)
        for (std::uint32_t i = 0; i < cellColumns; ++i)
            flags[j * cellColumns + i] = cellFlags(*field, i, j);
    field->activeEdges = std::move(flags);
    return HeightField{std::move(field)};
}

}  // namespace tumble
