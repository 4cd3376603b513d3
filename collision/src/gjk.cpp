/// GJK distance on shape cores (our own: libccd 2.1 has no distance query). See gjk.h for the
/// core + radius split.
///
/// GJK (Gilbert, Johnson, Keerthi 1988; as in van den Bergen, "Collision Detection in Interactive
/// 3D Environments", ch. 4) searches the Minkowski difference D = A - B for its point v closest to
/// the origin. Each iteration adds w = s_D(-v) to a simplex and replaces v by the simplex's closest
/// point to the origin (Ericson, "Real-Time Collision Detection", 5.1.5 and 5.1.6), dropping the
/// vertices that do not support it. |v| bounds the distance from above and v.w / |v| from below,
/// so the loop stops when |v|^2 - v.w <= kRelativeGap |v|^2: the distance is then known to a
/// relative 1e-13. On polytopes the loop ends exactly on the closest face after a few iterations.

#include "gjk.h"

#include "posed_core.h"

#include <array>
#include <cmath>
#include <initializer_list>
#include <limits>

namespace tumble::detail {
namespace {

constexpr int kMaxGjkIterations = 64;
constexpr Real kRelativeGap = 1e-13;  ///< GJK stop: |v|^2 - v.w <= this |v|^2
/// A simplex face with |ab x ac|^2 below this times (longest edge)^4 -- the sine of its widest
/// angle below 1e-10 -- has collinear vertices to within rounding: its normal is noise.
constexpr Real kCollinear = 1e-20;

/// A vertex of the GJK simplex: w = a - b with a on A's core and b on B's core (world).
struct SimplexVertex {
    Vec3 w, a, b;
};

struct Simplex {
    std::array<SimplexVertex, 4> vertices;
    std::array<Real, 4> weights{};  ///< barycentric weights of v
    int count = 0;
};

/// Keeps the simplex vertices listed in `keep` with their weights.
void reduce(Simplex& simplex, std::initializer_list<int> keep,
            std::initializer_list<Real> weights) {
    Simplex reduced;
    auto weight = weights.begin();
    for (int index : keep) {
        reduced.vertices[reduced.count] = simplex.vertices[index];
        reduced.weights[reduced.count++] = *weight++;
    }
    simplex = reduced;
}

/// Closest point to the origin on segment (i, j) of the simplex; reduces to the supporting part.
void closestOnSegment(Simplex& s, int i, int j) {
    const Vec3& a = s.vertices[i].w;
    const Vec3 ab = s.vertices[j].w - a;
    const Real length2 = ab.squaredNorm();
    const Real t = length2 > 0 ? -a.dot(ab) / length2 : 0;
    if (t <= 0) {
        reduce(s, {i}, {1});
    } else if (t >= 1) {
        reduce(s, {j}, {1});
    } else {
        reduce(s, {i, j}, {1 - t, t});
    }
}

/// Closest point to the origin on triangle (i, j, k) by Voronoi regions (Ericson 5.1.5 with p = 0).
void closestOnTriangle(Simplex& s, int i, int j, int k) {
    const Vec3& a = s.vertices[i].w;
    const Vec3& b = s.vertices[j].w;
    const Vec3& c = s.vertices[k].w;
    const Vec3 ab = b - a, ac = c - a;
    const Real d1 = -ab.dot(a), d2 = -ac.dot(a);
    if (d1 <= 0 && d2 <= 0)
        return reduce(s, {i}, {1});
    const Real d3 = -ab.dot(b), d4 = -ac.dot(b);
    if (d3 >= 0 && d4 <= d3)
        return reduce(s, {j}, {1});
    const Real vc = d1 * d4 - d3 * d2;
    if (vc <= 0 && d1 >= 0 && d3 <= 0) {
        const Real t = d1 / (d1 - d3);
        return reduce(s, {i, j}, {1 - t, t});
    }
    const Real d5 = -ab.dot(c), d6 = -ac.dot(c);
    if (d6 >= 0 && d5 <= d6)
        return reduce(s, {k}, {1});
    const Real vb = d5 * d2 - d1 * d6;
    if (vb <= 0 && d2 >= 0 && d6 <= 0) {
        const Real t = d2 / (d2 - d6);
        return reduce(s, {i, k}, {1 - t, t});
    }
    const Real va = d3 * d6 - d5 * d4;
    if (va <= 0 && d4 - d3 >= 0 && d5 - d6 >= 0) {
        const Real t = (d4 - d3) / ((d4 - d3) + (d5 - d6));
        return reduce(s, {j, k}, {1 - t, t});
    }
    const Real sum = va + vb + vc;
    if (!(sum > 0))
        return closestOnSegment(s, i, j);  // degenerate triangle: rounding only
    const Real v = vb / sum, w = vc / sum;
    reduce(s, {i, j, k}, {1 - v - w, v, w});
}

/// Closest point to the origin on the tetrahedron (Ericson 5.1.6): the best of the faces whose
/// plane separates the origin from the opposite vertex. Returns false when the origin is inside.
bool closestOnTetrahedron(Simplex& s) {
    static constexpr int kFaces[4][4] = {{0, 1, 2, 3}, {0, 2, 3, 1}, {0, 3, 1, 2}, {1, 3, 2, 0}};
    // Near convergence on a curved core (a cylinder's rim) the supports crowd together and the
    // simplex becomes a sliver whose face normals are rounding noise: a sign test on such a
    // face can call every face "inside" with the origin 0.2 m away. Two guards: a point inside
    // lies within the tetrahedron's longest edge of every vertex, and a face whose vertices are
    // collinear to within rounding decides nothing -- in either case every face is tested.
    Real longestEdge2 = 0;
    Real nearestVertex2 = std::numeric_limits<Real>::infinity();
    for (int i = 0; i < 4; ++i) {
        nearestVertex2 = std::min(nearestVertex2, s.vertices[i].w.squaredNorm());
        for (int j = i + 1; j < 4; ++j)
            longestEdge2 =
                std::max(longestEdge2, (s.vertices[j].w - s.vertices[i].w).squaredNorm());
    }
    const bool mayEnclose = nearestVertex2 <= longestEdge2;
    Simplex best;
    Real bestDistance2 = std::numeric_limits<Real>::infinity();
    bool outsideAny = false;
    for (const auto& face : kFaces) {
        const Vec3& a = s.vertices[face[0]].w;
        const Vec3 normal = (s.vertices[face[1]].w - a).cross(s.vertices[face[2]].w - a);
        const Real signOrigin = -normal.dot(a);
        const Real signOpposite = normal.dot(s.vertices[face[3]].w - a);
        const bool decisive = normal.squaredNorm() > kCollinear * longestEdge2 * longestEdge2;
        // A flat tetrahedron (signOpposite == 0) cannot enclose anything: test every face.
        if (mayEnclose && decisive && signOrigin * signOpposite > 0 && signOpposite != 0)
            continue;
        outsideAny = true;
        Simplex candidate = s;
        closestOnTriangle(candidate, face[0], face[1], face[2]);
        Vec3 v = Vec3::Zero();
        for (int n = 0; n < candidate.count; ++n)
            v += candidate.weights[n] * candidate.vertices[n].w;
        if (v.squaredNorm() < bestDistance2) {
            bestDistance2 = v.squaredNorm();
            best = candidate;
        }
    }
    if (outsideAny)
        s = best;
    return outsideAny;
}

Vec3 simplexPoint(const Simplex& s) {
    Vec3 v = Vec3::Zero();
    for (int n = 0; n < s.count; ++n)
        v += s.weights[n] * s.vertices[n].w;
    return v;
}

bool containsVertex(const Simplex& s, const Vec3& a, const Vec3& b) {
    for (int n = 0; n < s.count; ++n) {
        if (s.vertices[n].a == a && s.vertices[n].b == b)
            return true;
    }
    return false;
}

}  // namespace

/// GJK distance between two posed cores (see the file comment).
CoreDistance gjk(const PosedCore& a, const PosedCore& b) {
    Simplex simplex;
    Vec3 direction = b.position - a.position;  // search D = A - B towards -(cA - cB)
    if (!(direction.squaredNorm() > 0))
        direction = Vec3::UnitX();
    {
        const Vec3 pa = a.support(direction);
        const Vec3 pb = b.support(-direction);
        simplex.vertices[0] = {pa - pb, pa, pb};
        simplex.weights[0] = 1;
        simplex.count = 1;
    }
    Vec3 v = simplex.vertices[0].w;
    CoreDistance result;
    for (int iteration = 1; iteration <= kMaxGjkIterations; ++iteration) {
        result.iterations = iteration;
        const Real vv = v.squaredNorm();
        if (vv <= kCoreTouch * kCoreTouch) {
            result.overlapping = true;
            break;
        }
        const Vec3 pa = a.support(-v);
        const Vec3 pb = b.support(v);
        const Vec3 w = pa - pb;
        if (vv - v.dot(w) <= kRelativeGap * vv)
            break;  // no support point gets closer
        if (containsVertex(simplex, pa, pb))
            break;  // rounding: the same vertex again
        const Simplex previous = simplex;
        simplex.vertices[simplex.count++] = {w, pa, pb};
        if (simplex.count == 4) {
            if (!closestOnTetrahedron(simplex)) {
                result.overlapping = true;
                break;
            }
        } else if (simplex.count == 3) {
            closestOnTriangle(simplex, 0, 1, 2);
        } else {
            closestOnSegment(simplex, 0, 1);
        }
        const Vec3 next = simplexPoint(simplex);
        if (next.squaredNorm() >= vv) {  // no progress (rounding): keep the previous answer
            simplex = previous;
            break;
        }
        v = next;
    }
    result.pointA = Vec3::Zero();
    result.pointB = Vec3::Zero();
    for (int n = 0; n < simplex.count; ++n) {
        result.pointA += simplex.weights[n] * simplex.vertices[n].a;
        result.pointB += simplex.weights[n] * simplex.vertices[n].b;
    }
    result.distance = result.overlapping ? 0 : (result.pointA - result.pointB).norm();
    return result;
}

Real roundingRadius(const Shape& shape) {
    if (const auto* sphere = std::get_if<Sphere>(&shape))
        return sphere->radius;
    if (const auto* capsule = std::get_if<Capsule>(&shape))
        return capsule->radius;
    return 0;
}

Vec3 coreSupport(const Shape& shape, const Vec3& d) {
    switch (typeOf(shape)) {
        case ShapeType::Sphere:
            return Vec3::Zero();
        case ShapeType::Capsule: {
            const Real h = std::get<Capsule>(shape).halfLength;
            return {0, 0, d.z() >= 0 ? h : -h};
        }
        case ShapeType::Box: {
            const Vec3& e = std::get<Box>(shape).halfExtents;
            return {d.x() >= 0 ? e.x() : -e.x(), d.y() >= 0 ? e.y() : -e.y(),
                    d.z() >= 0 ? e.z() : -e.z()};
        }
        case ShapeType::Cylinder: {
            const auto& cylinder = std::get<Cylinder>(shape);
            const Real radial = std::hypot(d.x(), d.y());
            const Real z = d.z() >= 0 ? cylinder.halfLength : -cylinder.halfLength;
            if (!(radial > 0))
                return {0, 0, z};
            return {cylinder.radius * d.x() / radial, cylinder.radius * d.y() / radial, z};
        }
        case ShapeType::ConvexHull: {
            const HullData& hull = *std::get<ConvexHull>(shape).data;
            std::size_t best = 0;
            Real bestDot = -std::numeric_limits<Real>::infinity();
            for (std::size_t i = 0; i < hull.vertices.size(); ++i) {
                const Real dot = hull.vertices[i].dot(d);
                if (dot > bestDot) {
                    bestDot = dot;
                    best = i;
                }
            }
            return hull.vertices[best];
        }
        default:
            return Vec3::Zero();  // half-spaces never reach the convex query
    }
}

CoreDistance coreDistance(const Shape& a, const Transform& poseA, const Shape& b,
                          const Transform& poseB) {
    return gjk(PosedCore(a, poseA), PosedCore(b, poseB));
}

}  // namespace tumble::detail
