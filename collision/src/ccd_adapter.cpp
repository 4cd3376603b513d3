/// GJK distance on shape cores (our own: libccd 2.1 has no distance query); for overlapping
/// cores the separating-axis depth of two polytopes, else libccd's EPA/MPR. See ccd_adapter.h
/// for the core + radius split.
///
/// GJK (Gilbert, Johnson, Keerthi 1988; as in van den Bergen, "Collision Detection in Interactive
/// 3D Environments", ch. 4) searches the Minkowski difference D = A - B for its point v closest to
/// the origin. Each iteration adds w = s_D(-v) to a simplex and replaces v by the simplex's closest
/// point to the origin (Ericson, "Real-Time Collision Detection", 5.1.5 and 5.1.6), dropping the
/// vertices that do not support it. |v| bounds the distance from above and v.w / |v| from below,
/// so the loop stops when |v|^2 - v.w <= kRelativeGap |v|^2: the distance is then known to a
/// relative 1e-13. On polytopes the loop ends exactly on the closest face after a few iterations.

#include "ccd_adapter.h"

#include "polytope_sat.h"
#include "posed_core.h"

#include <ccd/ccd.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <initializer_list>
#include <limits>

namespace tumble::detail {
namespace {

constexpr int kMaxGjkIterations = 64;
constexpr Real kRelativeGap = 1e-13;  ///< GJK stop: |v|^2 - v.w <= this |v|^2
/// Cores closer than this (m) count as touching: their closest-point direction is no longer a
/// trustworthy normal, so the full shapes go to EPA.
constexpr Real kCoreTouch = 1e-9;
/// Cores of a pair with a cylinder that are closer than this (m) are measured like touching ones
/// (penetrationContact: least overlap over the candidate axes, refined by GJK on the pair moved
/// kWitnessShift apart). GJK's closest points on a curved rim are right to about 1e-12 m, so
/// their direction is off by about that over the distance: 5e-4 rad was measured at 2.8e-9 m,
/// which put a tilted cap's deepest rim point 1.2e-6 m off. Polytope cores are exact as they are.
constexpr Real kCurvedCoreNear = 1e-6;
/// A simplex face with |ab x ac|^2 below this times (longest edge)^4 -- the sine of its widest
/// angle below 1e-10 -- has collinear vertices to within rounding: its normal is noise.
constexpr Real kCollinear = 1e-20;
/// libccd's EPA stops when a new support point gains less than this (m) on the nearest face.
constexpr Real kEpaTolerance = 1e-10;
constexpr Real kMprTolerance = 1e-10;
constexpr unsigned long kCcdMaxIterations = 200;
/// After EPA, B is moved out along the normal by depth + this (m), and GJK on the now separated
/// pair gives exact witness points (libccd's `pos` is only an average of simplex supports).
constexpr Real kWitnessShift = 1e-3;
constexpr int kMaxNormalRefinements = 8;

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

// ---- libccd callbacks -------------------------------------------------------------------------

Vec3 fromCcd(const ccd_vec3_t& v) {
    return {v.v[0], v.v[1], v.v[2]};
}

void toCcd(const Vec3& v, ccd_vec3_t* out) {
    out->v[0] = v.x();
    out->v[1] = v.y();
    out->v[2] = v.z();
}

/// The full (rounded) shape's farthest point along `d` (world, need not be unit).
Vec3 roundedSupport(const PosedCore& o, const Vec3& d) {
    Vec3 point = o.support(d);
    const Real length = d.norm();
    if (o.radius > 0 && length > 0)
        point += (o.radius / length) * d;
    return point;
}

/// What libccd holds as one object: a posed core, plus, for the first object, the other one and
/// a count of support queries. libccd's EPA loop has no iteration cap: it stops only when a new
/// support point gains less than the tolerance, which on a curved boundary seen from near its
/// centre takes thousands of queries (a sphere on a capsule's axis: 70 ms for one pair) or, with
/// rounding, never ends (the fuzzer's sphere around a millimetre cylinder). Past the budget the
/// first object answers so that the Minkowski support equals the query direction, which is the
/// nearest polytope point EPA asks from: no gain, so EPA stops on its best face so far, and
/// penetrationContact refines that normal by GJK.
struct CcdObject {
    const PosedCore* core;
    bool rounded;                      ///< the full shape, else the core alone
    const PosedCore* other = nullptr;  ///< set on the first object only
    int* supportQueries = nullptr;     ///< set on the first object only

    Vec3 support(const PosedCore& o, const Vec3& d) const {
        return rounded ? roundedSupport(o, d) : o.support(d);
    }
};

/// Support queries allowed per libccd call: EPA on polytopes and on off-centre curved contacts
/// settles in tens; the budget only ends the loops that would not.
constexpr int kCcdSupportBudget = 512;

void ccdSupport(const void* object, const ccd_vec3_t* direction, ccd_vec3_t* out) {
    const auto& o = *static_cast<const CcdObject*>(object);
    const Vec3 d = fromCcd(*direction);
    if (o.supportQueries != nullptr && ++*o.supportQueries > kCcdSupportBudget) {
        toCcd(d + o.support(*o.other, -d), out);
        return;
    }
    toCcd(o.support(*o.core, d), out);
}

/// An interior point (world), which MPR starts from.
void ccdCenter(const void* object, ccd_vec3_t* out) {
    const auto& o = *static_cast<const CcdObject*>(object)->core;
    Vec3 local = Vec3::Zero();
    if (const auto* hull = std::get_if<ConvexHull>(o.shape))
        local = hull->data->centroid;
    toCcd(o.rotation * local + o.position, out);
}

/// libccd's GJK starts along x by default; on symmetric configurations (a box centred on another)
/// its simplex then holds the origin on a face and EPA returns depth 0 with a NaN direction. A
/// start direction off every axis avoids those ties.
void ccdFirstDirection(const void* objectA, const void* objectB, ccd_vec3_t* out) {
    const auto& a = *static_cast<const CcdObject*>(objectA)->core;
    const auto& b = *static_cast<const CcdObject*>(objectB)->core;
    const Vec3 generic(0.2672612419124244, 0.5345224838248488, 0.8017837257372732);
    const Vec3 between = b.position - a.position;
    toCcd(between + (1e-3 * between.norm() + 1e-6) * generic, out);
}

/// The penetration direction libccd finds for the full shapes (world, unit, from A to B). Returns
/// false when libccd finds them apart. libccd's depth is not used: see penetrationAlong.
bool ccdPenetrationNormal(const PosedCore& a, const PosedCore& b, PenetrationMethod method,
                          Vec3& normal) {
    ccd_t ccd;
    CCD_INIT(&ccd);
    ccd.first_dir = ccdFirstDirection;
    ccd.support1 = ccdSupport;
    ccd.support2 = ccdSupport;
    ccd.center1 = ccdCenter;
    ccd.center2 = ccdCenter;
    ccd.max_iterations = kCcdMaxIterations;
    ccd.epa_tolerance = kEpaTolerance;
    ccd.mpr_tolerance = kMprTolerance;
    // A rounded shape is its core swollen by a ball, so the cores' penetration direction is the
    // shapes' (the depth grows by the radii, which penetrationAlong adds). EPA on a core is far
    // cheaper: a sphere's core is a point, where its full surface is curved everywhere. Two
    // rounded cores (point, segment) may have a flat Minkowski difference, which EPA cannot
    // start from, so those pairs keep their full shapes.
    const bool rounded = a.radius > 0 && b.radius > 0;
    int supportQueries = 0;
    const CcdObject first{&a, rounded, &b, &supportQueries}, second{&b, rounded};
    ccd_real_t depth = 0;
    ccd_vec3_t direction, position;
    const int status =
        method == PenetrationMethod::Epa
            ? ccdGJKPenetration(&first, &second, &ccd, &depth, &direction, &position)
            : ccdMPRPenetration(&first, &second, &ccd, &depth, &direction, &position);
    if (status != 0)
        return false;
    // libccd's direction is the one to move B along to separate it from A: from A to B.
    normal = fromCcd(direction);
    const Real length = normal.norm();
    if (!(length > 0) || !normal.allFinite())
        return false;
    normal /= length;
    return true;
}

/// How far B must move along the unit `normal` to separate from A (m): the overlap of the two
/// shapes' extents on that axis, h_A(n) + h_B(-n) with h the support function. Exact for any
/// direction and never below the true penetration depth (the minimum over directions), so a
/// direction from EPA or MPR that misses the minimum gives a valid, if deeper, contact. libccd's
/// own depth can fall short of it (its EPA sometimes stops on a face that is not the nearest).
Real penetrationAlong(const PosedCore& a, const PosedCore& b, const Vec3& normal) {
    return normal.dot(a.support(normal) - b.support(-normal)) + a.radius + b.radius;
}

/// Fills `out` for B penetrating A, starting from libccd's `normal`, and refines that normal.
///
/// Moving B out along n by its exact overlap plus kWitnessShift leaves the pair apart, and GJK on
/// it gives exact closest points and their direction n'. If n were the minimum translation
/// direction, n' = n; otherwise the overlap along n' is smaller (the boundary of the Minkowski
/// difference is nearer in that direction), so n' replaces n while it helps. This settles EPA's
/// tolerance on curved shapes (cylinders, rounded cores) and costs one GJK when EPA was exact.
/// The witness points come from the last GJK (libccd's `pos` is only an average of supports).
void penetrationContact(const PosedCore& a, const PosedCore& b, Vec3 normal, ConvexContact& out) {
    const Real radiusA = a.radius, radiusB = b.radius;
    Real depth = penetrationAlong(a, b, normal);
    // EPA on two flat faces that barely overlap (cylinders stacked end to end) can return the
    // opposite axis, along which the overlap is measured the long way through (1.2 m for two
    // 0.6 m cylinders, where the real overlap was millimetres), and the refinement below cannot
    // leave it. Any axis gives a valid contact at its exact overlap, so the reverse and the
    // axis between the centres are tried too and the shallowest kept.
    //
    // EPA started from cores that touch (the origin on the boundary of the Minkowski difference)
    // returns an arbitrary face: a cylinder lying on a long box exactly got the box's side normal
    // at 5.5 m. So the flat faces' normals (a box's, a hull's, a cylinder's caps) are tried as
    // well: exact whenever a face takes part in the deepest contact, as on any face resting
    // contact, and otherwise an upper bound the refinement below starts from.
    const Vec3 between = b.position - a.position;
    Vec3 face = normal;
    Real faceDepth = depth;
    leastFaceOverlap(a, b, face, faceDepth);
    for (const Vec3& candidate :
         {Vec3(-normal), between.norm() > 0 ? Vec3(between.normalized()) : normal, face}) {
        const Real along = penetrationAlong(a, b, candidate);
        if (along < depth) {
            depth = along;
            normal = candidate;
        }
    }
    out.pointA = a.support(normal) + radiusA * normal;
    out.pointB = b.support(-normal) - radiusB * normal;
    for (int refinement = 0; refinement < kMaxNormalRefinements; ++refinement) {
        PosedCore moved = b;
        const Vec3 shift = (depth + kWitnessShift) * normal;
        moved.position += shift;
        const CoreDistance apart = gjk(a, moved);
        if (apart.overlapping || !(apart.distance > kCoreTouch))
            break;
        const Vec3 direction = (apart.pointB - apart.pointA) / apart.distance;
        out.pointA = apart.pointA + radiusA * direction;
        out.pointB = apart.pointB - radiusB * direction - shift;
        const Real depthAlong = penetrationAlong(a, b, direction);
        if (!(depthAlong < depth))
            break;
        depth = depthAlong;
        normal = direction;
    }
    out.normal = normal;
    out.separation = -depth;
}

}  // namespace

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

ConvexContact queryConvex(const Shape& a, const Transform& poseA, const Shape& b,
                          const Transform& poseB, PenetrationMethod method) {
    const PosedCore coreA(a, poseA), coreB(b, poseB);
    const Real radiusA = coreA.radius, radiusB = coreB.radius;
    const CoreDistance core = gjk(coreA, coreB);
    ConvexContact out;
    const bool polytopes = isPolytopeCore(a) && isPolytopeCore(b);
    if (!polytopes && !core.overlapping && core.distance > kCoreTouch &&
        core.distance <= kCurvedCoreNear) {
        penetrationContact(coreA, coreB, (core.pointB - core.pointA) / core.distance, out);
        return out;
    }
    if (!core.overlapping && core.distance > kCoreTouch) {
        // Exact for rounded shapes: their surfaces are the cores pushed out by the radii.
        out.normal = (core.pointB - core.pointA) / core.distance;
        out.separation = core.distance - radiusA - radiusB;
        out.pointA = core.pointA + radiusA * out.normal;
        out.pointB = core.pointB - radiusB * out.normal;
        return out;
    }
    if (method == PenetrationMethod::Auto && polytopes && polytopePenetration(coreA, coreB, out)) {
        return out;
    }
    const PenetrationMethod first =
        method == PenetrationMethod::Mpr ? method : PenetrationMethod::Epa;
    const PenetrationMethod other =
        first == PenetrationMethod::Epa ? PenetrationMethod::Mpr : PenetrationMethod::Epa;
    for (const PenetrationMethod tried : {first, other}) {
        Vec3 normal = Vec3::Zero();
        if (ccdPenetrationNormal(coreA, coreB, tried, normal)) {
            penetrationContact(coreA, coreB, normal, out);
            return out;
        }
    }
    // Touching to within rounding (libccd sees no overlap) or both routines failed: the closest
    // points' direction (noise when they meet) or the centres' starts the same search for the
    // least overlap as an EPA direction would.
    Vec3 normal = core.pointB - core.pointA;
    if (!(normal.norm() > kCoreTouch))
        normal = poseB.position - poseA.position;
    if (!(normal.norm() > 0))
        normal = Vec3::UnitZ();
    penetrationContact(coreA, coreB, normal.normalized(), out);
    return out;
}

}  // namespace tumble::detail
