/// The libccd adapter and the general convex query: for overlapping cores the separating-axis
/// depth of two polytopes, else libccd's EPA/MPR, refined by GJK (gjk.cpp). See ccd_adapter.h.

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

/// Cores of a pair with a cylinder that are closer than this (m) are measured like touching ones
/// (penetrationContact: least overlap over the candidate axes, refined by GJK on the pair moved
/// kWitnessShift apart). GJK's closest points on a curved rim are right to about 1e-12 m, so
/// their direction is off by about that over the distance: 5e-4 rad was measured at 2.8e-9 m,
/// which put a tilted cap's deepest rim point 1.2e-6 m off. Polytope cores are exact as they are.
constexpr Real kCurvedCoreNear = 1e-6;
/// libccd's EPA stops when a new support point gains less than this (m) on the nearest face.
constexpr Real kEpaTolerance = 1e-10;
constexpr Real kMprTolerance = 1e-10;
constexpr unsigned long kCcdMaxIterations = 200;
/// After EPA, B is moved out along the normal by depth + this (m), and GJK on the now separated
/// pair gives exact witness points (libccd's `pos` is only an average of simplex supports).
constexpr Real kWitnessShift = 1e-3;
constexpr int kMaxNormalRefinements = 8;

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
