#pragma once
/// Enumerating the triangles of a mesh or height field that a box (local frame) may touch
/// (internal to collision/). A mesh walks its hierarchy depth first with a fixed stack, so the
/// order is the same on every run; a height field walks the cells under the box row by row and
/// makes their two triangles on the fly (holes skipped). Nothing here allocates.

#include <algorithm>
#include <array>
#include <cmath>

#include "tumble/collision/mesh_shape.h"

namespace tumble::detail {

/// Deeper than any hierarchy the median split builds (its depth is log2 of the triangle count).
constexpr int kBvhStackSize = 64;

inline MeshTriangle meshTriangle(const MeshGeometry& mesh, std::uint32_t index) {
    const auto& t = mesh.triangles[index];
    return {{mesh.vertices[t[0]], mesh.vertices[t[1]], mesh.vertices[t[2]]},
            mesh.normals[index],
            mesh.activeEdges[index],
            index};
}

/// Calls visit(node) for every hierarchy leaf whose box passes `accept(box)`, depth first.
template <typename Accept, typename Visit>
void walkBvh(const MeshGeometry& mesh, Accept&& accept, Visit&& visit) {
    std::array<std::uint32_t, kBvhStackSize> stack;
    int top = 0;
    stack[top++] = 0;
    while (top > 0) {
        const MeshBvhNode& node = mesh.nodes[stack[--top]];
        if (!accept(node.box))
            continue;
        if (node.count > 0) {
            visit(node);
            continue;
        }
        const auto self = static_cast<std::uint32_t>(&node - mesh.nodes.data());
        stack[top++] = node.index;  // second child, visited after the first
        stack[top++] = self + 1;
    }
}

/// Calls visit(const MeshTriangle&) for each triangle whose box overlaps `box` (local frame).
template <typename Visit>
void forEachTriangle(const MeshGeometry& mesh, const Aabb& box, Visit&& visit) {
    walkBvh(
        mesh, [&](const Aabb& nodeBox) { return nodeBox.overlaps(box); },
        [&](const MeshBvhNode& leaf) {
            for (std::uint32_t k = leaf.index; k < leaf.index + leaf.count; ++k) {
                const MeshTriangle triangle = meshTriangle(mesh, k);
                const Aabb triangleBox{triangle.vertices[0]
                                           .cwiseMin(triangle.vertices[1])
                                           .cwiseMin(triangle.vertices[2]),
                                       triangle.vertices[0]
                                           .cwiseMax(triangle.vertices[1])
                                           .cwiseMax(triangle.vertices[2])};
                if (triangleBox.overlaps(box))
                    visit(triangle);
            }
        });
}

inline Vec3 samplePoint(const HeightFieldData& grid, std::uint32_t i, std::uint32_t j) {
    return {i * grid.spacingX, j * grid.spacingY, grid.heights[j * grid.columns + i]};
}

/// Triangle k (0 lower, 1 upper) of cell (i, j); see MeshTriangle::index.
inline MeshTriangle fieldTriangle(const HeightFieldGeometry& field, std::uint32_t i,
                                  std::uint32_t j, int k) {
    const HeightFieldData& grid = field.grid;
    const Vec3 p00 = samplePoint(grid, i, j), p11 = samplePoint(grid, i + 1, j + 1);
    const Vec3 corner = k == 0 ? samplePoint(grid, i + 1, j) : samplePoint(grid, i, j + 1);
    MeshTriangle t;
    t.vertices =
        k == 0 ? std::array<Vec3, 3>{p00, corner, p11} : std::array<Vec3, 3>{p00, p11, corner};
    t.normal = (t.vertices[1] - t.vertices[0]).cross(t.vertices[2] - t.vertices[0]).normalized();
    const std::uint32_t cell = j * (grid.columns - 1) + i;
    t.activeEdges = static_cast<std::uint8_t>((field.activeEdges[cell] >> (3 * k)) & 0b111);
    t.index = 2 * cell + static_cast<std::uint32_t>(k);
    return t;
}

/// Whether cell (i, j) exists: inside the grid and not a hole.
inline bool isCell(const HeightFieldData& grid, std::int64_t i, std::int64_t j) {
    if (i < 0 || j < 0 || i >= grid.columns - 1 || j >= grid.rows - 1)
        return false;
    return grid.holes.empty() ||
           grid.holes[static_cast<std::size_t>(j * (grid.columns - 1) + i)] == 0;
}

/// The vertex of the triangle across edge `edge` of the height field's triangle `index` (see
/// MeshTriangle::index) that is not on the edge; false on the border or next to a hole. Edges of
/// the lower triangle (00, 10, 11) border, in order, the cell below (j - 1), the cell to the
/// right (i + 1) and the diagonal; of the upper one (00, 11, 01), the diagonal, the cell above
/// (j + 1) and the cell to the left (i - 1).
inline bool fieldAcross(const HeightFieldGeometry& field, std::uint32_t index, int edge,
                        Vec3& out) {
    struct Across {
        int cellI, cellJ, sampleI, sampleJ;  // offsets from cell (i, j)
    };
    static constexpr std::array<std::array<Across, 3>, 2> kAcross{
        {{{{0, -1, 0, -1}, {1, 0, 2, 1}, {0, 0, 0, 1}}},
         {{{0, 0, 1, 0}, {0, 1, 1, 2}, {-1, 0, -1, 0}}}}};
    const HeightFieldData& grid = field.grid;
    const std::uint32_t cell = index / 2;
    const auto i = static_cast<std::int64_t>(cell % (grid.columns - 1));
    const auto j = static_cast<std::int64_t>(cell / (grid.columns - 1));
    const Across& a = kAcross[index % 2][static_cast<std::size_t>(edge)];
    if (!isCell(grid, i + a.cellI, j + a.cellJ))
        return false;
    out = samplePoint(grid, static_cast<std::uint32_t>(i + a.sampleI),
                      static_cast<std::uint32_t>(j + a.sampleJ));
    return true;
}

/// The same for a mesh (MeshGeometry::across).
inline bool meshAcross(const MeshGeometry& mesh, std::uint32_t index, int edge, Vec3& out) {
    const std::uint32_t vertex = mesh.across[index][static_cast<std::size_t>(edge)];
    if (vertex == kNoNeighbour)
        return false;
    out = mesh.vertices[vertex];
    return true;
}

/// The cells [first, last] along one axis of n samples at `spacing` whose span meets
/// [low, high]; false when none does.
inline bool cellRange(Real low, Real high, Real spacing, std::uint32_t samples,
                      std::uint32_t& first, std::uint32_t& last) {
    const Real cells = samples - 1;
    if (!(high >= 0 && low <= cells * spacing))
        return false;
    first = static_cast<std::uint32_t>(std::clamp(std::floor(low / spacing), Real(0), cells - 1));
    last = static_cast<std::uint32_t>(std::clamp(std::floor(high / spacing), Real(0), cells - 1));
    return true;
}

/// Calls visit(const MeshTriangle&) for both triangles of every cell under `box` (local frame)
/// whose heights reach it, holes skipped.
template <typename Visit>
void forEachTriangle(const HeightFieldGeometry& field, const Aabb& box, Visit&& visit) {
    const HeightFieldData& grid = field.grid;
    if (box.upper.z() < field.minHeight || box.lower.z() > field.maxHeight)
        return;
    std::uint32_t i0, i1, j0, j1;
    if (!cellRange(box.lower.x(), box.upper.x(), grid.spacingX, grid.columns, i0, i1) ||
        !cellRange(box.lower.y(), box.upper.y(), grid.spacingY, grid.rows, j0, j1))
        return;
    for (std::uint32_t j = j0; j <= j1; ++j) {
        for (std::uint32_t i = i0; i <= i1; ++i) {
            const std::uint32_t cell = j * (grid.columns - 1) + i;
            if (!grid.holes.empty() && grid.holes[cell] != 0)
                continue;
            const Real h00 = grid.heights[j * grid.columns + i];
            const Real h10 = grid.heights[j * grid.columns + i + 1];
            const Real h01 = grid.heights[(j + 1) * grid.columns + i];
            const Real h11 = grid.heights[(j + 1) * grid.columns + i + 1];
            if (std::max({h00, h10, h01, h11}) < box.lower.z() ||
                std::min({h00, h10, h01, h11}) > box.upper.z())
                continue;
            visit(fieldTriangle(field, i, j, 0));
            visit(fieldTriangle(field, i, j, 1));
        }
    }
}

/// The vertex across edge `edge` of triangle t of either kind of surface (fieldAcross).
inline bool acrossVertex(const Shape& shape, const MeshTriangle& t, int edge, Vec3& out) {
    if (const auto* mesh = std::get_if<TriangleMesh>(&shape))
        return meshAcross(*mesh->data, t.index, edge, out);
    return fieldAcross(*std::get<HeightField>(shape).data, t.index, edge, out);
}

/// Either kind of triangle surface: the mesh or height field behind `shape`.
template <typename Visit>
void forEachTriangle(const Shape& shape, const Aabb& box, Visit&& visit) {
    if (const auto* mesh = std::get_if<TriangleMesh>(&shape))
        forEachTriangle(*mesh->data, box, visit);
    else if (const auto* field = std::get_if<HeightField>(&shape))
        forEachTriangle(*field->data, box, visit);
}

}  // namespace tumble::detail
