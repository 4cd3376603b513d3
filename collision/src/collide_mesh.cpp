// A convex shape against a triangle mesh or height field.
//
// Everything runs in the surface's local frame (the shape is moved there once), so triangles are
// read as stored. The triangles under the shape's box grown by the margin (mesh_triangles.h) are
// each collided with the shape as a thin convex polytope: a prism of kPrismThickness behind the
// triangle, so the general convex path (GJK, separating axes, clipping in collide_convex.cpp)
// sees proper side faces and edge arcs, and the surface is two-sided.
//
// Ghost contacts (a sideways normal on an internal edge, a bump) are kept away by the internal-
// edge rules of collide_mesh_edges.cpp: each triangle's contact is filed there, and what they
// keep is merged here.
//
// The per-triangle manifolds then make up to ManifoldSet::kMaxManifolds manifolds, one per group
// of like normals (as Jolt keeps a manifold per sub-shape pair and merges those of near normals):
// the deepest point not yet grouped seeds a group with its triangle manifold's normal, and every
// ungrouped triangle whose normal lies within kMergeCos of it joins; past the limit, the rest
// join the group of the nearest normal. Each group's points are reduced to 4 (deepest plus
// largest area, clipping.h). So a box in a V-shaped crease gets a manifold on each face, each
// the one a half-space in that face's plane gives. Feature ids mix the triangle index into the
// pair routine's ids, so a point keeps its id while the same triangle and features touch.

#include <algorithm>
#include <array>
#include <cmath>
#include <vector>

#include "clipping.h"
#include "collide_mesh_edges.h"
#include "gjk.h"
#include "mesh_triangles.h"
#include "pair_routines.h"

namespace tumble::detail {
namespace {

/// Depth of the prism behind each triangle (m): enough for well-defined side faces and edge
/// directions, too thin to be felt.
constexpr Real kPrismThickness = 1e-6;
/// Triangles whose normals lie within acos(kMergeCos) (5 degrees) of a group's share its
/// manifold: a curved surface's neighbours (internal edges are flat within 3 degrees), but not
/// the two faces of a crease (a V of 170 degrees folds by 10).
constexpr Real kMergeCos = 0.99619469809174555;
/// Mixes a triangle's index into feature ids (Knuth's multiplicative hash constant).
constexpr std::uint32_t kTriangleMix = 0x9E3779B1u;

/// A triangle as a hull: front face, back face kPrismThickness behind, and three side faces.
/// One per thread, refilled for each triangle; the Shape points at it without owning it, so
/// nothing is allocated after the first call.
class TrianglePrism {
public:
    TrianglePrism() {
        data_.vertices.resize(6);
        data_.faces.resize(5);
        data_.faceVertices = {0, 1, 2, 5, 4, 3, 1, 0, 3, 4, 2, 1, 4, 5, 0, 2, 5, 3};
        data_.edges = {{0, 1}, {0, 2}, {0, 3}, {1, 2}, {1, 4}, {2, 5}, {3, 4}, {3, 5}, {4, 5}};
        for (std::uint32_t f = 0; f < 5; ++f)
            data_.faces[f] = {Vec3::UnitZ(), 0, f < 2 ? 3 * f : 6 + 4 * (f - 2), f < 2 ? 3u : 4u};
        shape_ =
            ConvexHull{std::shared_ptr<const HullData>(std::shared_ptr<const HullData>(), &data_)};
    }

    const Shape& shape(const MeshTriangle& t) {
        const Vec3& n = t.normal;
        for (std::size_t k = 0; k < 3; ++k) {
            data_.vertices[k] = t.vertices[k];
            data_.vertices[k + 3] = t.vertices[k] - kPrismThickness * n;
        }
        data_.faces[0].normal = n;
        data_.faces[0].offset = n.dot(t.vertices[0]);
        data_.faces[1].normal = -n;
        data_.faces[1].offset = -n.dot(data_.vertices[3]);
        for (std::size_t k = 0; k < 3; ++k) {
            const Vec3 side = (t.vertices[(k + 1) % 3] - t.vertices[k]).cross(n).normalized();
            data_.faces[2 + k].normal = side;
            data_.faces[2 + k].offset = side.dot(t.vertices[k]);
        }
        data_.centroid =
            (t.vertices[0] + t.vertices[1] + t.vertices[2]) / 3 - (kPrismThickness / 2) * n;
        return shape_;
    }

private:
    HullData data_;
    Shape shape_;
};

/// Per-thread buffers, grown on first use and kept: no allocation in a warm step.
struct Scratch {
    TrianglePrism prism;
    EdgeContacts kept;
    std::array<ContactPoint, kMaxClipVertices> candidates;
};

Scratch& scratch() {
    thread_local Scratch s;
    return s;
}

/// reduceContacts may keep a point within kDepthTolerance of the deepest instead of it (for
/// stable ids); the manifold's depth should be exact, so the deepest candidate replaces the
/// kept point nearest to it.
void keepDeepest(const std::array<ContactPoint, kMaxClipVertices>& candidates, std::size_t count,
                 Manifold& out) {
    std::size_t deepest = 0;
    for (std::size_t k = 1; k < count; ++k)
        if (candidates[k].separation < candidates[deepest].separation)
            deepest = k;
    std::size_t nearest = 0;
    for (std::size_t k = 0; k < static_cast<std::size_t>(out.pointCount); ++k) {
        if (out.points[k].separation <= candidates[deepest].separation)
            return;
        if ((out.points[k].position - candidates[deepest].position).squaredNorm() <
            (out.points[nearest].position - candidates[deepest].position).squaredNorm())
            nearest = k;
    }
    if (out.pointCount > 0)
        out.points[nearest] = candidates[deepest];
}

constexpr std::uint8_t kUngrouped = 0xFF;

/// Sorts the triangles' manifolds into groups of like normal (see the file comment) and writes
/// each group's normal into `normals`; returns the number of groups.
int groupManifolds(std::vector<TriangleManifold>& manifolds,
                   std::array<Vec3, ManifoldSet::kMaxManifolds>& normals) {
    for (TriangleManifold& tm : manifolds)
        tm.group = kUngrouped;
    int groups = 0;
    while (groups < ManifoldSet::kMaxManifolds) {
        Real deepest = INFINITY;
        const TriangleManifold* seed = nullptr;
        for (const TriangleManifold& tm : manifolds) {
            for (int k = 0; k < tm.manifold.pointCount && tm.group == kUngrouped; ++k) {
                if (tm.manifold.points[static_cast<std::size_t>(k)].separation < deepest) {
                    deepest = tm.manifold.points[static_cast<std::size_t>(k)].separation;
                    seed = &tm;
                }
            }
        }
        if (seed == nullptr)
            return groups;
        const Vec3 normal = seed->manifold.normal;
        normals[static_cast<std::size_t>(groups)] = normal;
        for (TriangleManifold& tm : manifolds)
            if (tm.group == kUngrouped && tm.manifold.normal.dot(normal) >= kMergeCos)
                tm.group = static_cast<std::uint8_t>(groups);
        ++groups;
    }
    // More directions than manifolds: the rest join the group of the nearest normal.
    for (TriangleManifold& tm : manifolds) {
        if (tm.group != kUngrouped)
            continue;
        int nearest = 0;
        for (int g = 1; g < groups; ++g)
            if (tm.manifold.normal.dot(normals[static_cast<std::size_t>(g)]) >
                tm.manifold.normal.dot(normals[static_cast<std::size_t>(nearest)]))
                nearest = g;
        tm.group = static_cast<std::uint8_t>(nearest);
    }
    return groups;
}

/// The squared distance from the nearest of `manifolds`' points to the farthest of tm's.
Real farthestFrom(const std::vector<TriangleManifold>& manifolds, const TriangleManifold& tm) {
    Real farthest = 0;
    for (int k = 0; k < tm.manifold.pointCount; ++k) {
        Real nearest = INFINITY;
        for (const TriangleManifold& other : manifolds)
            for (int q = 0; q < other.manifold.pointCount; ++q)
                nearest =
                    std::min(nearest, (other.manifold.points[static_cast<std::size_t>(q)].position -
                                       tm.manifold.points[static_cast<std::size_t>(k)].position)
                                          .squaredNorm());
        farthest = std::max(farthest, nearest);
    }
    return farthest;
}

/// Groups the speculative manifolds of internal features (keepSpeculative,
/// collide_mesh_edges.cpp) after the others (`kept`, grouped into the first `groups`): each joins
/// a group of like normal; the rest seed the groups left, first the one that reaches farthest
/// from every kept point (the part of the shape nothing else holds); past the limit, none.
int groupSpeculative(std::vector<TriangleManifold>& speculative,
                     const std::vector<TriangleManifold>& kept,
                     std::array<Vec3, ManifoldSet::kMaxManifolds>& normals, int groups) {
    const auto join = [&](int first) {
        for (TriangleManifold& tm : speculative)
            for (int g = first; g < groups && tm.group == kUngrouped; ++g)
                if (tm.manifold.normal.dot(normals[static_cast<std::size_t>(g)]) >= kMergeCos)
                    tm.group = static_cast<std::uint8_t>(g);
    };
    for (TriangleManifold& tm : speculative)
        tm.group = kUngrouped;
    join(0);
    while (groups < ManifoldSet::kMaxManifolds) {
        const TriangleManifold* seed = nullptr;
        Real farthest = -1;
        for (const TriangleManifold& tm : speculative) {
            if (tm.group != kUngrouped)
                continue;
            const Real reach = farthestFrom(kept, tm);
            if (reach > farthest) {
                farthest = reach;
                seed = &tm;
            }
        }
        if (seed == nullptr)
            break;
        normals[static_cast<std::size_t>(groups++)] = seed->manifold.normal;
        join(groups - 1);
    }
    return groups;
}

/// Whether `c` lies where one of the first `count` candidates does: one point found twice (by the
/// clipping and by the half-space routine, or as the exact deepest point). The first keeps its
/// id and takes the deeper separation: the reduction then never chooses between two ids for one
/// point by rounding noise (a box edge's ids flipped every step), and the depth stays exact.
bool sameAsCandidate(ContactPoint* candidates, std::size_t count, const ContactPoint& c) {
    for (std::size_t k = 0; k < count; ++k) {
        if ((candidates[k].position - c.position).squaredNorm() < kSamePoint * kSamePoint) {
            candidates[k].separation = std::min(candidates[k].separation, c.separation);
            return true;
        }
    }
    return false;
}

/// Removes the candidates that lie between two others on a segment (seen along `normal`) and are
/// no deeper than both; returns the count left. A line contact across several triangles (a
/// capsule or cylinder on its side) gives points where it crosses every triangle edge, all
/// equally deep and in line: the reduction weighed their zero areas by rounding noise, and the
/// kept ones (and their ids) changed from step to step. The segment's ends carry the contact.
/// Up to kBetweenLimit candidates (cubic); beyond, the reduction takes them as they are.
std::size_t dropBetween(ContactPoint* candidates, std::size_t count, const Vec3& normal) {
    constexpr std::size_t kBetweenLimit = 24;
    if (count > kBetweenLimit)
        return count;
    const auto flat = [&](std::size_t k) {
        return Vec3(candidates[k].position - normal.dot(candidates[k].position) * normal);
    };
    const auto between = [&](std::size_t c) {
        const Vec3 p = flat(c);
        for (std::size_t a = 0; a < count; ++a) {
            for (std::size_t b = a + 1; b < count; ++b) {
                if (a == c || b == c ||
                    candidates[c].separation <
                        std::min(candidates[a].separation, candidates[b].separation) - kDepthNoise)
                    continue;
                const Vec3 pa = flat(a), ab = flat(b) - pa;
                const Real t = (p - pa).dot(ab) / ab.squaredNorm();
                if (t > 0 && t < 1 && (pa + t * ab - p).squaredNorm() < kSamePoint * kSamePoint)
                    return true;
            }
        }
        return false;
    };
    std::array<bool, kBetweenLimit> drop;
    for (std::size_t c = 0; c < count; ++c)
        drop[c] = between(c);
    std::size_t kept = 0;
    for (std::size_t c = 0; c < count; ++c) {
        if (!drop[c])
            candidates[kept++] = candidates[c];
    }
    return kept;
}

/// The manifold of one group (see the file comment), in the surface's frame.
void merge(const std::vector<TriangleManifold>& manifolds, int group, const Vec3& normal,
           Manifold& out) {
    auto& candidates = scratch().candidates;
    std::size_t count = 0;
    for (const TriangleManifold& tm : manifolds) {
        if (tm.group != group)
            continue;
        for (int k = 0; k < tm.manifold.pointCount; ++k) {
            if (count == candidates.size()) {  // full: keep the best 4 and go on
                reduceContacts(std::span<const ContactPoint>(candidates.data(), count), normal,
                               out);
                count = static_cast<std::size_t>(out.pointCount);
                std::copy_n(out.points.begin(), count, candidates.begin());
            }
            ContactPoint c = tm.manifold.points[static_cast<std::size_t>(k)];
            c.featureId ^= tm.triangle * kTriangleMix;
            if (!sameAsCandidate(candidates.data(), count, c))
                candidates[count++] = c;
        }
    }
    if (count > static_cast<std::size_t>(Manifold::kMaxPoints))
        count = dropBetween(candidates.data(), count, normal);
    reduceContacts(std::span<const ContactPoint>(candidates.data(), count), normal, out);
    keepDeepest(candidates, count, out);
    out.normal = normal;
}

/// Fills `out` (a group's manifold) up to Manifold::kMaxPoints with the group's speculative points
/// of internal features (keepSpeculative, collide_mesh_edges.cpp), each time the one farthest
/// from those kept. They only fill: the reduction weighs area, and a speculative point on a
/// triangle's edge, measured to that triangle, took the place of a box corner over the next one
/// at a tenth of its separation.
void fillSpeculative(const std::vector<TriangleManifold>& speculative, int group, Manifold& out) {
    while (out.pointCount < Manifold::kMaxPoints) {
        const ContactPoint* farthest = nullptr;
        std::uint32_t triangle = 0;
        Real far = kSamePoint * kSamePoint;
        for (const TriangleManifold& tm : speculative) {
            for (int k = 0; k < tm.manifold.pointCount && tm.group == group; ++k) {
                const ContactPoint& c = tm.manifold.points[static_cast<std::size_t>(k)];
                Real nearest = INFINITY;
                for (int q = 0; q < out.pointCount; ++q)
                    nearest = std::min(
                        nearest, (out.points[static_cast<std::size_t>(q)].position - c.position)
                                     .squaredNorm());
                if (nearest > far) {
                    far = nearest;
                    farthest = &c;
                    triangle = tm.triangle;
                }
            }
        }
        if (farthest == nullptr)
            return;
        out.add(farthest->position, farthest->separation,
                farthest->featureId ^ triangle * kTriangleMix);
    }
}

}  // namespace

void collideConvexMesh(const Shape& a, const Transform& poseA, const Shape& b,
                       const Transform& poseB, Real margin, ManifoldSet& out) {
    out.count = 0;
    out.manifolds[0] = Manifold{};
    const Transform pose{poseB.applyInverse(poseA.position),
                         (poseB.rotation.conjugate() * poseA.rotation).normalized()};
    const Aabb box = boundsOf(a, pose).fattened(margin);
    Scratch& s = scratch();
    s.kept.clear();
    forEachTriangle(b, box, [&](const MeshTriangle& t) { s.kept.triangles.push_back(t); });
    for (const MeshTriangle& t : s.kept.triangles) {
        TriangleManifold tm{{}, t.index};
        collideConvex(a, pose, s.prism.shape(t), Transform{}, margin, tm.manifold);
        fileTriangleContact(a, pose, b, t, margin, tm, s.kept);
    }
    finishEdgeContacts(roundingRadius(a), s.kept);
    std::array<Vec3, ManifoldSet::kMaxManifolds> normals;
    out.count = groupManifolds(s.kept.manifolds, normals);
    out.count = groupSpeculative(s.kept.speculative, s.kept.manifolds, normals, out.count);
    for (int g = 0; g < out.count; ++g) {
        Manifold& m = out.manifolds[static_cast<std::size_t>(g)];
        m = Manifold{};  // the pair's record copies all of it, unused points included
        merge(s.kept.manifolds, g, normals[static_cast<std::size_t>(g)], m);
        fillSpeculative(s.kept.speculative, g, m);
        m.normal = poseB.rotation * m.normal;
        for (int k = 0; k < m.pointCount; ++k) {
            ContactPoint& c = m.points[static_cast<std::size_t>(k)];
            c.position = poseB.apply(c.position);
        }
    }
}

void collideConvexMeshDeepest(const Shape& a, const Transform& poseA, const Shape& b,
                              const Transform& poseB, Real margin, Manifold& out) {
    thread_local ManifoldSet set;
    collideConvexMesh(a, poseA, b, poseB, margin, set);
    out = set.manifolds[0];
}

}  // namespace tumble::detail
