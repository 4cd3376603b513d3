// Building a triangle mesh's geometry: checks, degenerate triangles dropped, the bounding volume
// hierarchy and the active-edge flags.
//
// The hierarchy splits the triangles at the median of their centroids along the longest axis of
// the centroids' box, down to leaves of at most kLeafSize. A median split is not the cheapest tree
// for ray casts (a surface-area split is), but its depth is log2(n / kLeafSize) whatever the
// input, so the traversal stack is fixed, and sorting with the input index as the tie-break makes
// the tree the same on every platform.
//
// Adjacency: vertices at equal coordinates count as one (loaders that do not weld their vertices
// still get internal edges), and an edge is shared when exactly two triangles run along it in
// opposite directions.

#include <algorithm>
#include <cmath>
#include <numeric>

#include "tumble/collision/mesh_shape.h"
#include "tumble/core/error.h"

namespace tumble {
namespace {

constexpr std::uint32_t kLeafSize = 4;
/// A triangle whose doubled area is below this fraction of its longest edge squared is degenerate
/// (its normal would be noise).
constexpr Real kDegenerateRatio = 1e-12;

void checkInput(const TriangleMeshData& data) {
    if (data.triangles.empty())
        fail("TriangleMesh: the mesh has no triangles");
    for (std::size_t i = 0; i < data.vertices.size(); ++i) {
        const Vec3& v = data.vertices[i];
        if (!isFinite(v))
            fail("TriangleMesh: vertex ", i, " = (", v.x(), ", ", v.y(), ", ", v.z(),
                 ") m must be finite");
    }
    for (std::size_t t = 0; t < data.triangles.size(); ++t) {
        for (int k = 0; k < 3; ++k) {
            if (data.triangles[t][static_cast<std::size_t>(k)] >= data.vertices.size())
                fail("TriangleMesh: triangle ", t, " vertex index ", k, " = ",
                     data.triangles[t][static_cast<std::size_t>(k)], " must be < the ",
                     data.vertices.size(), " vertices");
        }
    }
}

bool isDegenerate(const Vec3& a, const Vec3& b, const Vec3& c) {
    const Real longest =
        std::max({(b - a).squaredNorm(), (c - b).squaredNorm(), (a - c).squaredNorm()});
    return !((b - a).cross(c - a).norm() > kDegenerateRatio * longest) || longest == 0;
}

struct Builder {
    const std::vector<Vec3>& vertices;
    std::vector<std::array<std::uint32_t, 3>>& triangles;
    std::vector<std::uint32_t>& source;
    std::vector<MeshBvhNode>& nodes;
    std::vector<Vec3> centroids;

    Aabb boxOf(std::uint32_t first, std::uint32_t count) const {
        Aabb box{Vec3::Constant(INFINITY), Vec3::Constant(-INFINITY)};
        for (std::uint32_t k = first; k < first + count; ++k)
            for (const std::uint32_t v : triangles[k])
                box = box.merged({vertices[v], vertices[v]});
        return box;
    }

    /// Builds the subtree of triangles [first, first + count) at node `self`.
    void build(std::uint32_t self, std::uint32_t first, std::uint32_t count) {
        nodes[self].box = boxOf(first, count);
        if (count <= kLeafSize) {
            nodes[self].index = first;
            nodes[self].count = count;
            return;
        }
        Vec3 low = Vec3::Constant(INFINITY), high = -low;
        for (std::uint32_t k = first; k < first + count; ++k) {
            low = low.cwiseMin(centroids[k]);
            high = high.cwiseMax(centroids[k]);
        }
        Eigen::Index axis = 0;
        (high - low).maxCoeff(&axis);
        std::vector<std::uint32_t> order(count);
        std::iota(order.begin(), order.end(), first);
        std::sort(order.begin(), order.end(), [&](std::uint32_t p, std::uint32_t q) {
            const Real cp = centroids[p][axis], cq = centroids[q][axis];
            return cp < cq || (cp == cq && source[p] < source[q]);
        });
        permute(order, first);
        const std::uint32_t half = count / 2;
        const auto left = static_cast<std::uint32_t>(nodes.size());
        nodes.emplace_back();
        build(left, first, half);
        const auto right = static_cast<std::uint32_t>(nodes.size());
        nodes.emplace_back();
        build(right, first + half, count - half);
        nodes[self].index = right;
        nodes[self].count = 0;
    }

    void permute(const std::vector<std::uint32_t>& order, std::uint32_t first) {
        std::vector<std::array<std::uint32_t, 3>> t(order.size());
        std::vector<std::uint32_t> s(order.size());
        std::vector<Vec3> c(order.size());
        for (std::size_t k = 0; k < order.size(); ++k) {
            t[k] = triangles[order[k]];
            s[k] = source[order[k]];
            c[k] = centroids[order[k]];
        }
        std::copy(t.begin(), t.end(), triangles.begin() + first);
        std::copy(s.begin(), s.end(), source.begin() + first);
        std::copy(c.begin(), c.end(), centroids.begin() + first);
    }
};

/// One side of an edge: triangle t runs from vertex `from` to `to` (welded ids) as its edge k.
struct EdgeSide {
    std::uint32_t low, high, triangle;
    std::uint8_t k;
    bool forward;  ///< from < to
};

/// Welded vertex ids: equal coordinates share the lowest index among them.
std::vector<std::uint32_t> weld(const std::vector<Vec3>& vertices) {
    std::vector<std::uint32_t> order(vertices.size()), id(vertices.size());
    std::iota(order.begin(), order.end(), 0u);
    const auto less = [&](std::uint32_t p, std::uint32_t q) {
        const Vec3 &a = vertices[p], &b = vertices[q];
        if (a.x() != b.x())
            return a.x() < b.x();
        if (a.y() != b.y())
            return a.y() < b.y();
        if (a.z() != b.z())
            return a.z() < b.z();
        return p < q;
    };
    std::sort(order.begin(), order.end(), less);
    for (std::size_t k = 0; k < order.size(); ++k) {
        const bool same = k > 0 && vertices[order[k]] == vertices[order[k - 1]];
        id[order[k]] = same ? id[order[k - 1]] : order[k];
    }
    return id;
}

void flagActiveEdges(MeshGeometry& mesh) {
    const std::vector<std::uint32_t> id = weld(mesh.vertices);
    std::vector<EdgeSide> sides;
    sides.reserve(3 * mesh.triangles.size());
    for (std::uint32_t t = 0; t < mesh.triangles.size(); ++t) {
        for (std::uint8_t k = 0; k < 3; ++k) {
            const std::uint32_t from = id[mesh.triangles[t][k]];
            const std::uint32_t to = id[mesh.triangles[t][(k + 1) % 3]];
            sides.push_back({std::min(from, to), std::max(from, to), t, k, from < to});
        }
    }
    std::sort(sides.begin(), sides.end(), [](const EdgeSide& p, const EdgeSide& q) {
        return std::tie(p.low, p.high, p.triangle, p.k) < std::tie(q.low, q.high, q.triangle, q.k);
    });
    mesh.activeEdges.assign(mesh.triangles.size(), kAllEdgesActive);
    mesh.across.assign(mesh.triangles.size(), {kNoNeighbour, kNoNeighbour, kNoNeighbour});
    for (std::size_t s = 0; s < sides.size();) {
        std::size_t end = s + 1;
        while (end < sides.size() && sides[end].low == sides[s].low &&
               sides[end].high == sides[s].high)
            ++end;
        const EdgeSide &p = sides[s], &q = sides[end - 1];
        if (end - s == 2 && p.forward != q.forward) {
            const auto vertex = [&](const EdgeSide& side, int offset) {
                return mesh.vertices[mesh.triangles[side.triangle][(side.k + offset) % 3]];
            };
            const auto clear = [&](const EdgeSide& side, const EdgeSide& other) {
                mesh.across[side.triangle][side.k] =
                    mesh.triangles[other.triangle][(other.k + 2) % 3];
                if (!isActiveEdge(vertex(side, 0), vertex(side, 1), vertex(side, 2),
                                  vertex(other, 2)))
                    mesh.activeEdges[side.triangle] &= static_cast<std::uint8_t>(~(1u << side.k));
            };
            clear(p, q);
            clear(q, p);
        }
        s = end;
    }
}

}  // namespace

bool isActiveEdge(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d) {
    const Vec3 n = (b - a).cross(c - a).normalized();
    const Vec3 m = (a - b).cross(d - b).normalized();
    if (n.dot(m) >= std::cos(kFlatEdgeAngle))
        return false;         // flat: internal
    return n.dot(d - a) < 0;  // the neighbour bends away below this plane: convex
}

Aabb localBounds(const MeshGeometry& mesh) {
    return mesh.nodes[0].box;
}

TriangleMesh TriangleMesh::fromData(const TriangleMeshData& data) {
    checkInput(data);
    auto mesh = std::make_shared<MeshGeometry>();
    mesh->vertices = data.vertices;
    for (std::uint32_t t = 0; t < data.triangles.size(); ++t) {
        const auto& tri = data.triangles[t];
        if (isDegenerate(data.vertices[tri[0]], data.vertices[tri[1]], data.vertices[tri[2]])) {
            ++mesh->droppedTriangles;
            continue;
        }
        mesh->triangles.push_back(tri);
        mesh->sourceIndex.push_back(t);
    }
    if (mesh->triangles.empty())
        fail("TriangleMesh: all ", data.triangles.size(), " triangles are degenerate");
    Builder builder{mesh->vertices, mesh->triangles, mesh->sourceIndex, mesh->nodes, {}};
    for (const auto& tri : mesh->triangles)
        builder.centroids.push_back(
            (mesh->vertices[tri[0]] + mesh->vertices[tri[1]] + mesh->vertices[tri[2]]) / 3);
    mesh->nodes.emplace_back();
    builder.build(0, 0, static_cast<std::uint32_t>(mesh->triangles.size()));
    for (const auto& tri : mesh->triangles) {
        const Vec3 &a = mesh->vertices[tri[0]], &b = mesh->vertices[tri[1]],
                   &c = mesh->vertices[tri[2]];
        mesh->normals.push_back((b - a).cross(c - a).normalized());
    }
    flagActiveEdges(*mesh);
    return TriangleMesh{std::move(mesh)};
}

}  // namespace tumble
