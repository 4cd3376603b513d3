#pragma once
// Test geometry for triangle meshes, shared by the collision and engine tests.

#include <cstdint>
#include <random>
#include <set>
#include <vector>

#include "mesh_triangles.h"
#include "tumble/collision/mesh_data.h"
#include "tumble/collision/mesh_shape.h"

namespace tumble::testing {

/// A flat square of n x n cells of side `cell` centred on the origin at z = 0, two triangles per
/// cell (2 n^2 triangles), normals +z.
inline TriangleMeshData flatGrid(int n, Real cell) {
    TriangleMeshData data;
    const Real half = n * cell / 2;
    for (int j = 0; j <= n; ++j)
        for (int i = 0; i <= n; ++i)
            data.vertices.emplace_back(i * cell - half, j * cell - half, 0);
    const auto at = [&](int i, int j) { return static_cast<std::uint32_t>(j * (n + 1) + i); };
    for (int j = 0; j < n; ++j) {
        for (int i = 0; i < n; ++i) {
            data.triangles.push_back({at(i, j), at(i + 1, j), at(i + 1, j + 1)});
            data.triangles.push_back({at(i, j), at(i + 1, j + 1), at(i, j + 1)});
        }
    }
    return data;
}

/// A height field of columns x rows samples at the given spacings (m), sample (i, j) at height
/// `height(i, j)` (m); no holes.
template <typename Height>
HeightFieldData heightGrid(std::uint32_t columns, std::uint32_t rows, Real spacingX, Real spacingY,
                           Height&& height) {
    HeightFieldData grid;
    grid.columns = columns;
    grid.rows = rows;
    grid.spacingX = spacingX;
    grid.spacingY = spacingY;
    for (std::uint32_t j = 0; j < rows; ++j)
        for (std::uint32_t i = 0; i < columns; ++i)
            grid.heights.push_back(height(i, j));
    return grid;
}

/// A random convex shape of about 0.3-0.6 m: kind 0 sphere, 1 capsule, 2 box, 3 cylinder, else
/// a hull.
inline Shape randomConvex(std::mt19937& rng, int kind) {
    std::uniform_real_distribution<Real> size(0.15, 0.3);
    switch (kind) {
        case 0:
            return Sphere{size(rng)};
        case 1:
            return Capsule{size(rng), size(rng)};
        case 2:
            return Box{Vec3(size(rng), size(rng), size(rng))};
        case 3:
            return Cylinder{size(rng), size(rng)};
        default: {
            std::vector<Vec3> points;
            std::uniform_real_distribution<Real> unit(-1, 1);
            for (int k = 0; k < 12; ++k)
                points.push_back(0.25 * Vec3(unit(rng), unit(rng), unit(rng)));
            return ConvexHull::fromPoints(points);
        }
    }
}

inline Quat randomRotation(std::mt19937& rng) {
    std::normal_distribution<Real> n;
    return Quat(n(rng), n(rng), n(rng), n(rng)).normalized();
}

/// The triangles the hierarchy offers for `box`, and those a test of every triangle finds.
struct Candidates {
    std::set<std::uint32_t> walked, brute;
};

inline Candidates candidatesFor(const MeshGeometry& mesh, const Aabb& box) {
    Candidates c;
    detail::forEachTriangle(mesh, box, [&](const MeshTriangle& t) { c.walked.insert(t.index); });
    for (std::uint32_t k = 0; k < mesh.triangles.size(); ++k) {
        const MeshTriangle t = detail::meshTriangle(mesh, k);
        const Aabb triangleBox{t.vertices[0].cwiseMin(t.vertices[1]).cwiseMin(t.vertices[2]),
                               t.vertices[0].cwiseMax(t.vertices[1]).cwiseMax(t.vertices[2])};
        if (triangleBox.overlaps(box))
            c.brute.insert(k);
    }
    return c;
}

}  // namespace tumble::testing
