// Closed forms for the round shapes: a sphere is a point plus a radius, a capsule a segment plus a
// radius, so every pair reduces to the closest points of two cores (point or segment) and
// separation = core distance - radiusA - radiusB, exact to rounding.

#include <algorithm>
#include <cmath>

#include "pair_routines.h"

namespace tumble::detail {
namespace {

Real clamp01(Real x) {
    return std::clamp(x, Real(0), Real(1));
}

}  // namespace

/// Parameters (s on a, t on b, both in [0, 1]) of the closest points of two segments.
/// Ericson, Real-Time Collision Detection, 5.1.9: minimise |a(s) - b(t)|^2 over the unit square;
/// the unconstrained minimum of s is clamped, t follows from s, and s is recomputed when t clamps.
std::pair<Real, Real> closestParameters(const Segment& a, const Segment& b) {
    const Vec3 da = a.direction();
    const Vec3 db = b.direction();
    const Vec3 r = a.start - b.start;
    const Real aa = da.squaredNorm();
    const Real bb = db.squaredNorm();
    const Real f = db.dot(r);
    if (aa <= 0 && bb <= 0)
        return {0, 0};
    if (aa <= 0)
        return {0, clamp01(f / bb)};
    const Real c = da.dot(r);
    if (bb <= 0)
        return {clamp01(-c / aa), 0};
    const Real ab = da.dot(db);
    const Real denominator = aa * bb - ab * ab;  // >= 0; 0 when parallel
    Real s = denominator > 0 ? clamp01((ab * f - c * bb) / denominator) : 0;
    Real t = (ab * s + f) / bb;
    if (t < 0) {
        t = 0;
        s = clamp01(-c / aa);
    } else if (t > 1) {
        t = 1;
        s = clamp01((ab - c) / aa);
    }
    return {s, t};
}

namespace {

/// Capsules whose axes make an angle with sine below this are treated as parallel and touch
/// along a line: two points, so a capsule lying on another does not rock about one point. As
/// collide_convex.cpp's kSegmentSin: at 1e-3 a capsule lying on another at 0.5 degrees was held
/// by one point that ran the overlap's length as it turned; the ends' sideways offset changes
/// their depth by its square over the radii only.
constexpr Real kParallelSine = 0.02;

Segment capsuleSegment(const Capsule& capsule, const Transform& pose) {
    const Vec3 half = pose.rotation * Vec3(0, 0, capsule.halfLength);
    return {pose.position - half, pose.position + half};
}

/// The contact of two spheres (centres, radii): normal from A to B, separation, midpoint. When
/// the centres coincide any direction is right; `fallbackNormal` (unit) is used.
void addSpherePair(const Vec3& centerA, Real radiusA, const Vec3& centerB, Real radiusB,
                   const Vec3& fallbackNormal, std::uint32_t featureId, Real margin,
                   Manifold& out) {
    const Vec3 delta = centerB - centerA;
    const Real distance = delta.norm();
    const Real separation = distance - radiusA - radiusB;
    if (separation > margin)
        return;
    out.normal = distance > 0 ? Vec3(delta / distance) : fallbackNormal;
    const Vec3 surfaceA = centerA + radiusA * out.normal;
    const Vec3 surfaceB = centerB - radiusB * out.normal;
    out.add((surfaceA + surfaceB) / 2, separation, featureId);
}

/// Parallel overlapping capsule cores: two points at the ends of the overlap of B's segment
/// projected on A's axis. Separations are measured along the common normal. Returns false when
/// the projections do not overlap (end-to-end), leaving the single closest point to the caller.
bool addParallelPair(const Segment& a, Real radiusA, const Segment& b, Real radiusB,
                     const Vec3& closestA, const Vec3& closestB, Real margin, Manifold& out) {
    const Vec3 axis = a.direction().normalized();
    const Real halfA = a.direction().norm() / 2;
    const Vec3 centerA = (a.start + a.end) / 2;
    const Real startB = axis.dot(b.start - centerA);
    const Real endB = axis.dot(b.end - centerA);
    const Real low = std::max(-halfA, std::min(startB, endB));
    const Real high = std::min(halfA, std::max(startB, endB));
    if (!(high - low > 1e-9 * (1 + halfA)))
        return false;

    // The normal is the part of the closest-point offset perpendicular to A's axis; for coaxial
    // cores any perpendicular does.
    const Vec3 offset = closestB - closestA;
    const Vec3 perpendicular = offset - axis.dot(offset) * axis;
    const Real length = perpendicular.norm();
    const Vec3 normal = length > 0 ? Vec3(perpendicular / length) : axis.unitOrthogonal();
    out.normal = normal;
    const std::array<Real, 2> ends{low, high};
    for (std::size_t i = 0; i < 2; ++i) {
        const Vec3 pointA = centerA + ends[i] * axis;
        const Real t = clamp01((ends[i] - startB) / (endB - startB));
        const Vec3 pointB = b.start + t * b.direction();
        const Real separation = normal.dot(pointB - pointA) - radiusA - radiusB;
        if (separation > margin)
            continue;
        const Vec3 surfaceA = pointA + radiusA * normal;
        const Vec3 surfaceB = pointB - radiusB * normal;
        out.add((surfaceA + surfaceB) / 2, separation, static_cast<std::uint32_t>(i + 1));
    }
    return true;
}

}  // namespace

void collideSpheres(const Shape& a, const Transform& poseA, const Shape& b, const Transform& poseB,
                    Real margin, Manifold& out) {
    out.clear();
    addSpherePair(poseA.position, std::get<Sphere>(a).radius, poseB.position,
                  std::get<Sphere>(b).radius, Vec3::UnitZ(), 0, margin, out);
}

void collideSphereCapsule(const Shape& a, const Transform& poseA, const Shape& b,
                          const Transform& poseB, Real margin, Manifold& out) {
    out.clear();
    const Capsule& capsule = std::get<Capsule>(b);
    const Vec3 axis = poseB.rotation * Vec3::UnitZ();
    const Real t = std::clamp(axis.dot(poseA.position - poseB.position), -capsule.halfLength,
                              capsule.halfLength);
    // A centre on the axis: push out sideways, along the capsule's local x.
    addSpherePair(poseA.position, std::get<Sphere>(a).radius, poseB.position + t * axis,
                  capsule.radius, poseB.rotation * Vec3::UnitX(), 0, margin, out);
}

void collideCapsules(const Shape& a, const Transform& poseA, const Shape& b, const Transform& poseB,
                     Real margin, Manifold& out) {
    out.clear();
    const Capsule& capsuleA = std::get<Capsule>(a);
    const Capsule& capsuleB = std::get<Capsule>(b);
    const Segment segmentA = capsuleSegment(capsuleA, poseA);
    const Segment segmentB = capsuleSegment(capsuleB, poseB);
    const auto [s, t] = closestParameters(segmentA, segmentB);
    const Vec3 closestA = segmentA.start + s * segmentA.direction();
    const Vec3 closestB = segmentB.start + t * segmentB.direction();
    if ((closestB - closestA).norm() - capsuleA.radius - capsuleB.radius > margin)
        return;

    const Vec3 axisA = poseA.rotation * Vec3::UnitZ();
    const Vec3 axisB = poseB.rotation * Vec3::UnitZ();
    const bool parallel = capsuleA.halfLength > 0 && capsuleB.halfLength > 0 &&
                          axisA.cross(axisB).norm() < kParallelSine;
    if (parallel && addParallelPair(segmentA, capsuleA.radius, segmentB, capsuleB.radius, closestA,
                                    closestB, margin, out))
        return;
    // Crossing cores touching in their middles: push out along the common perpendicular.
    const Vec3 across = axisA.cross(axisB);
    const Vec3 fallback = across.norm() > 0 ? Vec3(across.normalized()) : axisA.unitOrthogonal();
    addSpherePair(closestA, capsuleA.radius, closestB, capsuleB.radius, fallback, 0, margin, out);
}

}  // namespace tumble::detail
