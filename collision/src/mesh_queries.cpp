// Ray casts and closest points against triangle surfaces. A mesh prunes its hierarchy by the
// best answer so far (the ray's current end, the nearest distance found); a height field visits
// the cells under the box of the ray's stretch over the field, or of the sphere that holds the
// nearest point. Triangles are two-sided.

#include "mesh_queries.h"

#include <algorithm>
#include <cmath>
#include <limits>

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
};

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
        if (!clipToBox(localBounds(field), o, d, enter, exit))
            return std::nullopt;
        const Vec3 from = o + enter * d, to = o + exit * d;
        forEachTriangle(field, Aabb{from.cwiseMin(to), from.cwiseMax(to)},
                        [&](const MeshTriangle& t) { best.offer(t, o, d); });
    }
    if (!best.found)
        return std::nullopt;
    const Real fraction = best.fraction + Real(0);
    return RayHit{fraction, ray.origin + fraction * ray.direction, pose.rotation * best.normal};
}

Vec3 closestOnTriangle(const MeshTriangle& t, const Vec3& p) {
    // Voronoi regions of the vertices, then the edges, then the face (Ericson, Real-Time
    // Collision Detection, 5.1.5).
    const Vec3 &a = t.vertices[0], &b = t.vertices[1], &c = t.vertices[2];
    const Vec3 ab = b - a, ac = c - a, ap = p - a;
    const Real d1 = ab.dot(ap), d2 = ac.dot(ap);
    if (d1 <= 0 && d2 <= 0)
        return a;
    const Vec3 bp = p - b;
    const Real d3 = ab.dot(bp), d4 = ac.dot(bp);
    if (d3 >= 0 && d4 <= d3)
        return b;
    const Real vc = d1 * d4 - d3 * d2;
    if (vc <= 0 && d1 >= 0 && d3 <= 0)
        return a + (d1 / (d1 - d3)) * ab;
    const Vec3 cp = p - c;
    const Real d5 = ab.dot(cp), d6 = ac.dot(cp);
    if (d6 >= 0 && d5 <= d6)
        return c;
    const Real vb = d5 * d2 - d1 * d6;
    if (vb <= 0 && d2 >= 0 && d6 <= 0)
        return a + (d2 / (d2 - d6)) * ac;
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
