// Building a height field's geometry: checks, the height range and the active-edge flags of every
// cell's two triangles (see MeshTriangle::index for the split). A cell's edges border, in order,
// for the lower triangle (00, 10, 11): the cell below (j - 1), the cell to the right (i + 1) and
// the diagonal; for the upper one (00, 11, 01): the diagonal, the cell above (j + 1) and the cell
// to the left (i - 1). Edges on the border or next to a hole stay active.

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

bool isCell(const HeightFieldData& grid, std::int64_t i, std::int64_t j) {
    if (i < 0 || j < 0 || i >= grid.columns - 1 || j >= grid.rows - 1)
        return false;
    return grid.holes.empty() ||
           grid.holes[static_cast<std::size_t>(j * (grid.columns - 1) + i)] == 0;
}

/// Bit 1 << edge when the triangle's edge `edge` is active, its neighbour's third vertex being
/// sample (ni, nj) of a cell that exists.
std::uint8_t edgeBit(const HeightFieldData& grid, const MeshTriangle& t, int edge, bool neighbour,
                     std::uint32_t ni, std::uint32_t nj) {
    if (!neighbour)
        return static_cast<std::uint8_t>(1u << edge);
    const auto& v = t.vertices;
    const bool active = isActiveEdge(
        v[static_cast<std::size_t>(edge)], v[static_cast<std::size_t>((edge + 1) % 3)],
        v[static_cast<std::size_t>((edge + 2) % 3)], detail::samplePoint(grid, ni, nj));
    return active ? static_cast<std::uint8_t>(1u << edge) : std::uint8_t{0};
}

std::uint8_t cellFlags(const HeightFieldGeometry& field, std::uint32_t i, std::uint32_t j) {
    const HeightFieldData& grid = field.grid;
    const auto si = static_cast<std::int64_t>(i), sj = static_cast<std::int64_t>(j);
    const MeshTriangle lower = detail::fieldTriangle(field, i, j, 0);
    const MeshTriangle upper = detail::fieldTriangle(field, i, j, 1);
    std::uint8_t low = 0, up = 0;
    low |= edgeBit(grid, lower, 0, isCell(grid, si, sj - 1), i, j - 1);
    low |= edgeBit(grid, lower, 1, isCell(grid, si + 1, sj), i + 2, j + 1);
    low |= edgeBit(grid, lower, 2, true, i, j + 1);
    up |= edgeBit(grid, upper, 0, true, i + 1, j);
    up |= edgeBit(grid, upper, 1, isCell(grid, si, sj + 1), i + 1, j + 2);
    up |= edgeBit(grid, upper, 2, isCell(grid, si - 1, sj), i - 1, j);
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
