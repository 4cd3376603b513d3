// Ray casts and closest points against triangle surfaces. A mesh prunes its hierarchy by the
// best answer so far (the ray's current end, the nearest distance found). A ray walks a height
// field's grid cell by cell along its shadow on the x-y plane, nearest first, and stops at the
// first cell whose far side lies beyond a hit (a 2D DDA: Amanatides and Woo, "A fast voxel
// traversal algorithm", 1987): O(cells crossed), not O(cells under the ray's box). A closest
// point visits the cells under the box of the sphere that holds it. Triangles are two-sided.

#include "mesh_queries.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <optional>

#include "mesh_triangles.h"

namespace tumble::detail {
namespace {

constexpr Real kInfinity = std::numeric_limits<Real>::infinity();

/// The stretch [enter, exit] of o + t d, t in [enter, exit], inside `box`; false when empty.
bool clipToBox(const Aabb& box, const Vec3& o, const Vec3& d, Real& enter, Real& exit) {
    for (int i = 0; i < 3; ++i) {
        if (d[i] == 0) {
            if (o[i] < box.lower[i] || o[i] > box.upper[i])
                return false;
            continue;
        }
        Real t1 = (box.lower[i] - o[i]) / d[i], t2 = (box.upper[i] - o[i]) / d[i];
        if (t1 > t2)
            std::swap(t1, t2);
        enter = std::max(enter, t1);
        exit = std::min(exit, t2);
        if (enter > exit)
            return false;
    }
    return true;
}

/// The fraction at which o + t d crosses the triangle (either side), if in [0, limit]
/// (Moller-Trumbore: barycentric u, v and t from one 3x3 solve by Cramer's rule).
bool crossTriangle(const MeshTriangle& t, const Vec3& o, const Vec3& d, Real limit, Real& hit) {
    const Vec3 e1 = t.vertices[1] - t.vertices[0], e2 = t.vertices[2] - t.vertices[0];
    const Vec3 p = d.cross(e2);
    const Real det = e1.dot(p);
    if (det == 0)
        return false;  // the ray runs in the triangle's plane: it grazes, never crosses
    const Vec3 s = o - t.vertices[0];
    const Real u = s.dot(p) / det;
    if (u < 0 || u > 1)
        return false;
    const Vec3 q = s.cross(e1);
    const Real v = d.dot(q) / det;
    if (v < 0 || u + v > 1)
        return false;
    const Real fraction = e2.dot(q) / det;
    if (fraction < 0 || fraction > limit)
        return false;
    hit = fraction;
    return true;
}

struct BestHit {
    Real fraction;
    Vec3 normal = Vec3::Zero();
    bool found = false;

    void offer(const MeshTriangle& t, const Vec3& o, const Vec3& d) {
        Real hit = 0;
        if (crossTriangle(t, o, d, fraction, hit) && (!found || hit < fraction)) {
            fraction = hit;
            normal = t.normal.dot(d) <= 0 ? t.normal : Vec3(-t.normal);
            found = true;
        }
    }

    std::optional<RayHit> hit(const Transform& pose, const Ray& ray) const {
        if (!found)
            return std::nullopt;
        const Real f = fraction + Real(0);
        return RayHit{f, ray.origin + f * ray.direction, pose.rotation * normal};
    }
};

/// One axis of the walk: the step to the next cell (-1, 0, +1) and where the ray meets that
/// cell's side.
struct CellAxis {
    std::int64_t cell = 0;
    std::int64_t step = 0;
    Real spacing = 1;
    Real origin = 0, direction = 0;  ///< the ray's coordinate along this axis

    /// The fraction at which the ray leaves the current cell along this axis (infinite if it
    /// runs parallel to it). From the cell index each time, not accumulated, so no drift.
    Real next() const {
        if (step == 0)
            return kInfinity;
        const Real side = static_cast<Real>(cell + (step > 0 ? 1 : 0)) * spacing;
        return (side - origin) / direction;
    }
};

CellAxis cellAxis(Real origin, Real direction, Real at, Real spacing, std::uint32_t samples) {
    const Real last = samples - 2;
    return {static_cast<std::int64_t>(std::clamp(std::floor(at / spacing), Real(0), last)),
            direction > 0 ? 1 : (direction < 0 ? -1 : 0), spacing, origin, direction};
}

/// Offers `best` the triangles of the cells the ray o + t d crosses for t in [enter, exit], in
/// the order it crosses them, until a hit lies before the current cell's far side.
void walkCells(const HeightFieldGeometry& field, const Vec3& o, const Vec3& d, Real enter,
               Real exit, BestHit& best) {
    const HeightFieldData& grid = field.grid;
    const Vec3 start = o + enter * d;
    CellAxis x = cellAxis(o.x(), d.x(), start.x(), grid.spacingX, grid.columns);
    CellAxis y = cellAxis(o.y(), d.y(), start.y(), grid.spacingY, grid.rows);
    const auto cellsX = static_cast<std::int64_t>(grid.columns - 1);
    const auto cellsY = static_cast<std::int64_t>(grid.rows - 1);
    while (x.cell >= 0 && x.cell < cellsX && y.cell >= 0 && y.cell < cellsY) {
        const auto i = static_cast<std::uint32_t>(x.cell), j = static_cast<std::uint32_t>(y.cell);
        if (grid.holes.empty() || grid.holes[j * (grid.columns - 1) + i] == 0) {
            best.offer(fieldTriangle(field, i, j, 0), o, d);
            best.offer(fieldTriangle(field, i, j, 1), o, d);
        }
        const Real nextX = x.next(), nextY = y.next();
        const Real leave = std::min(nextX, nextY);
        if (leave >= exit || (best.found && best.fraction <= leave))
            return;
        if (nextX < nextY)
            x.cell += x.step;
        else
            y.cell += y.step;
    }
}

}  // namespace

std::optional<RayHit> raycastSurface(const Shape& shape, const Transform& pose, const Vec3& o,
                                     const Vec3& d, const Ray& ray) {
    BestHit best{ray.maxFraction};
    if (const auto* mesh = std::get_if<TriangleMesh>(&shape)) {
        walkBvh(
            *mesh->data,
            [&](const Aabb& box) {
                Real enter = 0, exit = best.fraction;
                return clipToBox(box, o, d, enter, exit);
            },
            [&](const MeshBvhNode& leaf) {
                for (std::uint32_t k = leaf.index; k < leaf.index + leaf.count; ++k)
                    best.offer(meshTriangle(*mesh->data, k), o, d);
            });
    } else {
        const HeightFieldGeometry& field = *std::get<HeightField>(shape).data;
        Real enter = 0, exit = ray.maxFraction;
        if (clipToBox(localBounds(field), o, d, enter, exit))
            walkCells(field, o, d, enter, exit, best);
    }
    return best.hit(pose, ray);
}

std::optional<RayHit> raycastCellsUnderBox(const HeightFieldGeometry& field, const Transform& pose,
                                           const Vec3& o, const Vec3& d, const Ray& ray) {
    BestHit best{ray.maxFraction};
    Real enter = 0, exit = ray.maxFraction;
    if (clipToBox(localBounds(field), o, d, enter, exit)) {
        const Vec3 from = o + enter * d, to = o + exit * d;
        forEachTriangle(field, Aabb{from.cwiseMin(to), from.cwiseMax(to)},
                        [&](const MeshTriangle& t) { best.offer(t, o, d); });
    }
    return best.hit(pose, ray);
}

namespace {

/// The closest point when it is vertex v or on edge av (Ericson's vertex-b and edge-ab tests,
/// which serve vertex c and edge ac with b and c swapped): `along` = (v - a).(p - a), `onV` and
/// `other` the products of p - v with the edges to v and to the third vertex, `area` the
/// barycentric coordinate opposite the third vertex.
std::optional<Vec3> vertexOrEdge(const Vec3& a, const Vec3& v, const Vec3& av, Real along, Real onV,
                                 Real other, Real area) {
    if (onV >= 0 && other <= onV)
        return v;
    if (area <= 0 && along >= 0 && onV <= 0)
        return a + (along / (along - onV)) * av;
    return std::nullopt;
}

}  // namespace

Vec3 closestOnTriangle(const MeshTriangle& t, const Vec3& p) {
    // Voronoi regions of the vertices, then the edges, then the face (Ericson, Real-Time
    // Collision Detection, 5.1.5).
    const Vec3 &a = t.vertices[0], &b = t.vertices[1], &c = t.vertices[2];
    const Vec3 ab = b - a, ac = c - a, ap = p - a;
    const Real d1 = ab.dot(ap), d2 = ac.dot(ap);
    if (d1 <= 0 && d2 <= 0)
        return a;
    // Vertex b and edge ab, then (the same test with b, c swapped) vertex c and edge ac.
    const Vec3 bp = p - b, cp = p - c;
    const Real d3 = ab.dot(bp), d4 = ac.dot(bp), d5 = ab.dot(cp), d6 = ac.dot(cp);
    const Real vc = d1 * d4 - d3 * d2, vb = d5 * d2 - d1 * d6;
    if (const auto q = vertexOrEdge(a, b, ab, d1, d3, d4, vc))
        return *q;
    if (const auto q = vertexOrEdge(a, c, ac, d2, d6, d5, vb))
        return *q;
    const Real va = d3 * d6 - d5 * d4;
    if (va <= 0 && (d4 - d3) >= 0 && (d5 - d6) >= 0)
        return b + ((d4 - d3) / ((d4 - d3) + (d5 - d6))) * (c - b);
    const Real denominator = 1 / (va + vb + vc);
    return a + ab * (vb * denominator) + ac * (vc * denominator);
}

namespace {

/// Squared distance from p to the box (0 inside).
Real squaredDistance(const Aabb& box, const Vec3& p) {
    return (p - p.cwiseMax(box.lower).cwiseMin(box.upper)).squaredNorm();
}

struct Nearest {
    const Vec3& p;
    Vec3 point = Vec3::Zero();
    Real squared = kInfinity;

    void offer(const MeshTriangle& t) {
        const Vec3 q = closestOnTriangle(t, p);
        const Real s = (q - p).squaredNorm();
        if (s < squared) {
            squared = s;
            point = q;
        }
    }
};

}  // namespace

Vec3 closestOnSurface(const MeshGeometry& mesh, const Vec3& p) {
    Nearest nearest{p};
    walkBvh(
        mesh, [&](const Aabb& box) { return squaredDistance(box, p) < nearest.squared; },
        [&](const MeshBvhNode& leaf) {
            for (std::uint32_t k = leaf.index; k < leaf.index + leaf.count; ++k)
                nearest.offer(meshTriangle(mesh, k));
        });
    return nearest.point;
}

Vec3 closestOnSurface(const HeightFieldGeometry& field, const Vec3& p) {
    // A first answer from the cells under p (clamped onto the field) bounds the search sphere;
    // every nearer point lies in that sphere's box. Holes may leave the first box empty: then the
    // whole field is searched.
    const Aabb bounds = localBounds(field);
    const Vec3 under = p.cwiseMax(bounds.lower).cwiseMin(bounds.upper);
    Nearest nearest{p};
    forEachTriangle(field,
                    Aabb{Vec3(under.x(), under.y(), bounds.lower.z()),
                         Vec3(under.x(), under.y(), bounds.upper.z())},
                    [&](const MeshTriangle& t) { nearest.offer(t); });
    const Real reach = std::sqrt(nearest.squared);
    const Aabb search = std::isfinite(reach) ? Aabb{p.array() - reach, p.array() + reach} : bounds;
    forEachTriangle(field, search, [&](const MeshTriangle& t) { nearest.offer(t); });
    return nearest.point;
}

}  // namespace tumble::detail
