// Closed forms involving boxes: sphere-box by clamping the centre into the box, box-box by the
// separating-axis test followed by face clipping (face contacts) or the closest points of two
// edges (edge contacts).
//
// Feature ids (box-box): a face is 2 * axis + (1 if its outward normal is -axis); an incident
// corner is 4 * face + corner; an edge is 4 * axis + the signs of the two other axes (bit 0 for
// the next axis, bit 1 for the one after). Face contacts take their ids from clipToManifold; an
// edge contact is (511 << 22) | (edgeA << 11) | edgeB, which clipping never produces.

#include <algorithm>
#include <cmath>

#include "clipping.h"
#include "pair_routines.h"
#include "tumble/core/lane_kernel.h"

namespace tumble::detail {
namespace {

/// A face axis keeps the contact unless another face axis separates more by this much (m) plus
/// kRelativeAxisTolerance of the best face's |separation|: jitter then never flips the reference
/// face of a resting box, which keeps feature ids and points steady.
constexpr Real kFaceAxisTolerance = 1e-4;
/// An edge axis must beat the best face axis by this much (m) plus the relative part below,
/// since face contacts give full manifolds and edge contacts a single point.
constexpr Real kEdgeAxisTolerance = 1e-4;
constexpr Real kRelativeAxisTolerance = 0.05;
/// Edge pairs closer to parallel than this (sine of their angle) give no axis of their own: the
/// face axes then already bound the separation.
constexpr Real kParallelEdgeSine = 1e-6;

struct OrientedBox {
    Vec3 center = Vec3::Zero();       ///< world (m)
    Mat3 axes = Mat3::Identity();     ///< world directions of the local axes (columns)
    Vec3 halfExtents = Vec3::Zero();  ///< (m)
};

OrientedBox orientedBox(const Shape& shape, const Transform& pose) {
    return {pose.position, pose.rotation.toRotationMatrix(), std::get<Box>(shape).halfExtents};
}

Real signOf(Real x) {
    return x < 0 ? Real(-1) : Real(1);
}

/// Corners (+-1, +-1) of the face of `box` with outward normal sign * axis `axis`, in counter-
/// clockwise order seen from outside. The face's centre and the two half edges are computed
/// once for the four corners (a corner's sum is ((centre + a) +- b) +- c as before: kNext and
/// kAfter are +-1, so (+-h) col = +-(h col) and x + (-y) = x - y to the bit); one corner at a
/// time they were 1.4 % of pyramid-20's step.
std::array<Vec3, 4> faceCorners(const OrientedBox& box, int axis, Real sign) {
    // (next, after) signs for corners 0..3: counter-clockwise about +axis, since
    // axes.col(next) x axes.col(after) = axes.col(axis) for a rotation.
    static constexpr Real kNext[4] = {1, -1, -1, 1};
    static constexpr Real kAfter[4] = {1, 1, -1, -1};
    const int next = (axis + 1) % 3;
    const int after = (axis + 2) % 3;
    const Vec3 centre = box.center + sign * box.halfExtents[axis] * box.axes.col(axis);
    const Vec3 halfNext = box.halfExtents[next] * box.axes.col(next);
    const Vec3 halfAfter = box.halfExtents[after] * box.axes.col(after);
    const Vec3 plusNext = centre + halfNext;
    const Vec3 minusNext = centre - halfNext;
    std::array<Vec3, 4> corners;
    for (int corner = 0; corner < 4; ++corner) {
        // Seen from -axis the order reverses: walk the corners backwards.
        const int k = sign > 0 ? corner : 3 - corner;
        const Vec3& edge = kNext[k] > 0 ? plusNext : minusNext;
        corners[static_cast<std::size_t>(corner)] =
            kAfter[k] > 0 ? Vec3(edge + halfAfter) : Vec3(edge - halfAfter);
    }
    return corners;
}

std::uint32_t faceId(int axis, Real sign) {
    return static_cast<std::uint32_t>(2 * axis + (sign < 0 ? 1 : 0));
}

struct Axis {
    Real separation = -1e300;     ///< (m)
    Vec3 normal = Vec3::UnitZ();  ///< world, unit, from A to B
    int indexA = -1;              ///< A's face axis, or A's edge axis for an edge pair
    int indexB = -1;              ///< B's face axis, or B's edge axis for an edge pair
};

/// The three kinds of candidate separating axes: the best of each (largest separation).
struct AxisSearch {
    Axis faceA, faceB, edge;
};

/// SAT over the 15 axes (Gottschalk et al., OBBTree, 1996): along a unit axis L the boxes'
/// projections are intervals of radius sum_k h_k |L . u_k| about their centres, so the gap is
/// |L . (cB - cA)| minus both radii. Computed in A's frame, where B's axes are the columns of
/// C = RA^T RB.
AxisSearch searchAxes(const OrientedBox& a, const OrientedBox& b) {
    const Mat3 c = a.axes.transpose() * b.axes;
    const Mat3 absC = c.cwiseAbs();
    const Vec3 t = a.axes.transpose() * (b.center - a.center);
    AxisSearch search;
    for (int i = 0; i < 3; ++i) {
        const Real gap = std::abs(t[i]) - a.halfExtents[i] - absC.row(i).dot(b.halfExtents);
        if (gap > search.faceA.separation)
            search.faceA = {gap, signOf(t[i]) * a.axes.col(i), i, -1};
    }
    for (int j = 0; j < 3; ++j) {
        const Real distance = t.dot(c.col(j));
        const Real gap = std::abs(distance) - b.halfExtents[j] - absC.col(j).dot(a.halfExtents);
        if (gap > search.faceB.separation)
            search.faceB = {gap, signOf(distance) * b.axes.col(j), -1, j};
    }
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) {
            const Vec3 axis = Vec3::Unit(i).cross(c.col(j));  // A's frame
            const Real length = axis.norm();
            if (length < kParallelEdgeSine)
                continue;
            const Real radiusA = axis.cwiseAbs().dot(a.halfExtents);
            const Real radiusB = (c.transpose() * axis).cwiseAbs().dot(b.halfExtents);
            const Real distance = t.dot(axis);
            const Real gap = (std::abs(distance) - radiusA - radiusB) / length;
            if (gap > search.edge.separation)
                search.edge = {gap, signOf(distance) * (a.axes * axis) / length, i, j};
        }
    return search;
}

/// The face of `reference` whose outward normal is `normal` (along axis `axis`) clips the face of
/// `incident` most anti-parallel to it.
void clipFaces(const OrientedBox& reference, int axis, const Vec3& normal,
               const OrientedBox& incident, bool referenceIsA, Real margin, Manifold& out) {
    const Real referenceSign = signOf(normal.dot(reference.axes.col(axis)));
    const std::array<Vec3, 4> referenceVertices = faceCorners(reference, axis, referenceSign);

    const Vec3 alignment = (incident.axes.transpose() * normal);
    int incidentAxis = 0;
    alignment.cwiseAbs().maxCoeff(&incidentAxis);
    const Real incidentSign = -signOf(alignment[incidentAxis]);
    const std::uint32_t incidentFace = faceId(incidentAxis, incidentSign);
    const std::array<Vec3, 4> corners = faceCorners(incident, incidentAxis, incidentSign);
    std::array<ClipVertex, 4> incidentVertices;
    for (int k = 0; k < 4; ++k)
        incidentVertices[static_cast<std::size_t>(k)] = {
            corners[static_cast<std::size_t>(k)], 4 * incidentFace + static_cast<std::uint32_t>(k)};

    const ReferenceFace face{referenceVertices, normal, faceId(axis, referenceSign)};
    clipToManifold(face, incidentVertices, referenceIsA, margin, out);
}

/// The edge of `box` along `axis` farthest along `direction`: its midpoint and its id.
std::pair<Vec3, std::uint32_t> supportEdge(const OrientedBox& box, int axis,
                                           const Vec3& direction) {
    Vec3 midpoint = box.center;
    std::uint32_t id = static_cast<std::uint32_t>(4 * axis);
    for (int step = 1; step <= 2; ++step) {
        const int k = (axis + step) % 3;
        const Real sign = signOf(direction.dot(box.axes.col(k)));
        midpoint += sign * box.halfExtents[k] * box.axes.col(k);
        if (sign > 0)
            id |= static_cast<std::uint32_t>(step);
    }
    return {midpoint, id};
}

/// One point midway between the closest points of the two edges named by `axis`.
void edgeContact(const OrientedBox& a, const OrientedBox& b, const Axis& axis, Real margin,
                 Manifold& out) {
    const auto [midA, edgeA] = supportEdge(a, axis.indexA, axis.normal);
    const auto [midB, edgeB] = supportEdge(b, axis.indexB, -axis.normal);
    const Vec3 uA = a.axes.col(axis.indexA);
    const Vec3 uB = b.axes.col(axis.indexB);
    // Minimise |midA + s uA - midB - t uB|^2: s - k t + dA = 0 and t - k s - dB = 0 with
    // k = uA . uB, dA = uA . r, dB = uB . r, r = midA - midB; the edges are not parallel here.
    const Vec3 r = midA - midB;
    const Real k = uA.dot(uB);
    const Real dA = uA.dot(r);
    const Real dB = uB.dot(r);
    const Real halfA = a.halfExtents[axis.indexA];
    const Real halfB = b.halfExtents[axis.indexB];
    const Real s = std::clamp((k * dB - dA) / (1 - k * k), -halfA, halfA);
    const Real t = std::clamp(dB + k * s, -halfB, halfB);
    const Vec3 pointA = midA + s * uA;
    const Vec3 pointB = midB + t * uB;
    const Real separation = axis.normal.dot(pointB - pointA);
    out.normal = axis.normal;
    if (separation > margin)
        return;
    out.add((pointA + pointB) / 2, separation, 511u << 22 | edgeA << 11 | edgeB);
}

}  // namespace

void collideSphereBox(const Shape& a, const Transform& poseA, const Shape& b,
                      const Transform& poseB, Real margin, Manifold& out) {
    out.clear();
    const Real radius = std::get<Sphere>(a).radius;
    const Vec3& half = std::get<Box>(b).halfExtents;
    const Vec3 center = poseB.applyInverse(poseA.position);  // in the box's frame
    const Vec3 closest = center.cwiseMax(-half).cwiseMin(half);
    Vec3 outward;  // box's frame, from the box towards the sphere
    Vec3 surface;  // box's frame, on the box's surface
    Real separation = 0;
    if (closest != center) {
        const Vec3 delta = center - closest;
        const Real distance = delta.norm();
        outward = delta / distance;
        surface = closest;
        separation = distance - radius;
    } else {
        // Centre inside: leave through the nearest face.
        const Vec3 gaps = half - center.cwiseAbs();
        int axis = 0;
        gaps.minCoeff(&axis);
        const Real sign = signOf(center[axis]);
        outward = sign * Vec3::Unit(axis);
        surface = center;
        surface[axis] = sign * half[axis];
        separation = -gaps[axis] - radius;
    }
    if (separation > margin)
        return;
    out.normal = -(poseB.rotation * outward);
    const Vec3 surfaceB = poseB.apply(surface);
    const Vec3 surfaceA = poseA.position + radius * out.normal;
    out.add((surfaceA + surfaceB) / 2, separation, 0);
}

// Compiled for AVX2 and the baseline (lane_kernel.h: the same bits); with the clipping, 8.8 %
// of pyramid-20's instructions.
TUMBLE_LANE_KERNEL void collideBoxes(const Shape& a, const Transform& poseA, const Shape& b,
                                     const Transform& poseB, Real margin, Manifold& out) {
    out.clear();
    const OrientedBox boxA = orientedBox(a, poseA);
    const OrientedBox boxB = orientedBox(b, poseB);
    const AxisSearch search = searchAxes(boxA, boxB);
    const Real largest =
        std::max({search.faceA.separation, search.faceB.separation, search.edge.separation});
    if (largest > margin)
        return;

    // Prefer A's face, then B's face, then an edge pair: the bias keeps the contact type steady.
    const Axis* best = &search.faceA;
    if (search.faceB.separation > search.faceA.separation + kFaceAxisTolerance +
                                      kRelativeAxisTolerance * std::abs(search.faceA.separation))
        best = &search.faceB;
    if (search.edge.separation > best->separation + kEdgeAxisTolerance +
                                     kRelativeAxisTolerance * std::abs(best->separation)) {
        edgeContact(boxA, boxB, search.edge, margin, out);
        return;
    }
    if (best == &search.faceA)
        clipFaces(boxA, best->indexA, best->normal, boxB, true, margin, out);
    else
        clipFaces(boxB, best->indexB, -best->normal, boxA, false, margin, out);
}

}  // namespace tumble::detail
