// Any convex shape against a half-space, in closed form. A point x of the shape lies
// normal . x - offset above the boundary plane (world), so its separation is exact; the contact
// points are the shape's features nearest the plane: the sphere's lowest point, the capsule's two
// ends, the box's corners, the cylinder's rim points and the hull's vertices, each kept when its
// separation is within the margin. The manifold normal points from the shape (A) into the
// half-space (B), i.e. against the half-space's outward normal.
//
// Feature ids: sphere 0; capsule end 0 (-z) or 1 (+z); box corner 4 * (z > 0) + 2 * (y > 0) +
// (x > 0); cylinder see addCylinder; hull the vertex index.

#include <algorithm>
#include <cmath>
#include <numbers>

#include "clipping.h"
#include "pair_routines.h"

namespace tumble::detail {
namespace {

/// Below this sine of the angle between a cylinder's axis and the plane normal, the cylinder
/// stands flat: its rim points are taken at fixed angles, so they do not spin with the direction
/// of a vanishing tilt. They may miss the deepest rim point by radius * sine * (1 - cos 45 deg)
/// (0.3 mm for a 1 m radius), so that point is offered too: the reduction keeps it only when it
/// is more than kCapDepthTolerance deeper than all four (issue 20: the depth within 1e-6 m).
constexpr Real kFlatSine = 1e-3;

/// At and above this sine of the angle between a cylinder's axis and the plane normal (45
/// degrees), the cylinder faces the plane with its side: its contact is the line between the
/// caps' deepest rim points, and the rim's other points are not offered. They cannot come down
/// onto the plane without the cylinder turning onto its cap, yet its spin about its own axis
/// moves them along the normal: within a wide speculative margin (a fast roll), they held the
/// spinning rim off the plane and took the place of the line's far end in the reduction.
constexpr Real kSideSine = std::numbers::sqrt2 / 2;

/// The half-space's boundary in world coordinates: points x with normal . x = offset; the solid
/// is below.
struct Plane {
    Vec3 normal = Vec3::UnitZ();  ///< world, unit, out of the solid
    Real offset = 0;              ///< (m)
    Real height(const Vec3& x) const { return normal.dot(x) - offset; }
};

Plane worldPlane(const HalfSpace& halfSpace, const Transform& pose) {
    const Vec3 normal = pose.rotation * halfSpace.normal;
    return {normal, halfSpace.offset + normal.dot(pose.position)};
}

/// Collects candidate points; when the buffer fills, it is reduced to 4 in place so any number of
/// hull vertices can stream through without allocation.
class Candidates {
public:
    /// `depthTolerance`: the reduction's band (reduceContacts).
    Candidates(const Plane& plane, Real depthTolerance)
        : plane_(plane), depthTolerance_(depthTolerance), points_(storage()) {}

    /// Adds the shape's surface point `x` (world) if within `margin` of the plane.
    void offer(const Vec3& x, Real margin, std::uint32_t featureId) {
        const Real separation = plane_.height(x);
        if (separation > margin)
            return;
        if (count_ == points_.size())
            compact();
        points_[count_++] = {x - (separation / 2) * plane_.normal, separation, featureId};
    }

    void finish(Manifold& out) {
        reduceContacts(std::span<const ContactPoint>(points_.data(), count_), -plane_.normal, out,
                       false, depthTolerance_);
    }

private:
    void compact() {
        Manifold reduced;
        finish(reduced);
        count_ = static_cast<std::size_t>(reduced.pointCount);
        std::copy_n(reduced.points.begin(), count_, points_.begin());
    }

    // Per-thread storage: a local array would default-initialise all its points on every call.
    static std::array<ContactPoint, kMaxClipVertices>& storage() {
        thread_local std::array<ContactPoint, kMaxClipVertices> points;
        return points;
    }

    Plane plane_;
    Real depthTolerance_;
    std::array<ContactPoint, kMaxClipVertices>& points_;
    std::size_t count_ = 0;
};

/// Flat (axis within kFlatSine of the normal): four rim points of the lower cap at fixed angles,
/// ids 0-3, and its deepest rim point, id 12, when the axis is tilted at all. Tilted: on each cap
/// the deepest rim point and those at +90, 180 and -90 degrees from it, ids 4 + 4 * cap + k (cap 0
/// at -z); the deepest ones alone within the margin when the cylinder leans on its rim, all on the
/// lower cap as it comes to stand, both deepest when it lies on its side.
void addCylinder(const Cylinder& cylinder, const Transform& pose, const Plane& plane, Real margin,
                 Candidates& candidates) {
    const Vec3 down = pose.rotation.conjugate() * (-plane.normal);  // local
    const Real tilt = std::hypot(down.x(), down.y());
    const Vec3 axis = pose.rotation * Vec3::UnitZ();
    if (tilt < kFlatSine) {
        const Vec3 cap = pose.position + (down.z() < 0 ? -1 : 1) * cylinder.halfLength * axis;
        const Vec3 x = pose.rotation * Vec3::UnitX();
        const Vec3 y = pose.rotation * Vec3::UnitY();
        const std::array<Vec3, 4> rim{x, y, -x, -y};
        for (std::size_t k = 0; k < 4; ++k)
            candidates.offer(cap + cylinder.radius * rim[k], margin, static_cast<std::uint32_t>(k));
        if (tilt > 0) {
            const Vec3 deepest = pose.rotation * Vec3(down.x() / tilt, down.y() / tilt, 0);
            candidates.offer(cap + cylinder.radius * deepest, margin, 12);
        }
        return;
    }
    const Vec3 deepest = pose.rotation * Vec3(down.x() / tilt, down.y() / tilt, 0);
    const Vec3 side = axis.cross(deepest);
    const std::array<Vec3, 4> rim{deepest, side, -deepest, -side};
    // Lying nearer its side than its cap, the cylinder's supporting feature is the line between
    // the caps' deepest points.
    const std::size_t rimPoints = tilt < kSideSine ? 4 : 1;
    for (std::uint32_t cap = 0; cap < 2; ++cap) {
        const Vec3 center = pose.position + (cap == 0 ? -1 : 1) * cylinder.halfLength * axis;
        for (std::size_t k = 0; k < rimPoints; ++k)
            candidates.offer(center + cylinder.radius * rim[k], margin,
                             4 + 4 * cap + static_cast<std::uint32_t>(k));
    }
}

void addBox(const Box& box, const Transform& pose, Real margin, Candidates& candidates) {
    const Mat3 axes = pose.rotation.toRotationMatrix();
    for (std::uint32_t corner = 0; corner < 8; ++corner) {
        const Vec3 local((corner & 1) ? box.halfExtents.x() : -box.halfExtents.x(),
                         (corner & 2) ? box.halfExtents.y() : -box.halfExtents.y(),
                         (corner & 4) ? box.halfExtents.z() : -box.halfExtents.z());
        candidates.offer(axes * local + pose.position, margin, corner);
    }
}

void addHull(const HullData& hull, const Transform& pose, Real margin, Candidates& candidates) {
    const Mat3 axes = pose.rotation.toRotationMatrix();
    for (std::size_t i = 0; i < hull.vertices.size(); ++i)
        candidates.offer(axes * hull.vertices[i] + pose.position, margin,
                         static_cast<std::uint32_t>(i));
}

}  // namespace

void collideConvexHalfSpace(const Shape& a, const Transform& poseA, const Shape& b,
                            const Transform& poseB, Real margin, Manifold& out) {
    out.clear();
    const Plane plane = worldPlane(std::get<HalfSpace>(b), poseB);
    out.normal = -plane.normal;
    // A cylinder's rim points are exact only within the narrow band (issue 20: 1e-6 m); boxes
    // and hulls keep the wide one, which holds their flush points steady.
    Candidates candidates(plane,
                          typeOf(a) == ShapeType::Cylinder ? kCapDepthTolerance : kDepthTolerance);
    switch (typeOf(a)) {
        case ShapeType::Sphere:
            candidates.offer(poseA.position - std::get<Sphere>(a).radius * plane.normal, margin, 0);
            break;
        case ShapeType::Capsule: {
            const Capsule& capsule = std::get<Capsule>(a);
            const Vec3 half = poseA.rotation * Vec3(0, 0, capsule.halfLength);
            const Vec3 drop = capsule.radius * plane.normal;
            candidates.offer(poseA.position - half - drop, margin, 0);
            candidates.offer(poseA.position + half - drop, margin, 1);
            break;
        }
        case ShapeType::Box:
            addBox(std::get<Box>(a), poseA, margin, candidates);
            break;
        case ShapeType::Cylinder:
            addCylinder(std::get<Cylinder>(a), poseA, plane, margin, candidates);
            break;
        case ShapeType::ConvexHull:
            addHull(*std::get<ConvexHull>(a).data, poseA, margin, candidates);
            break;
        case ShapeType::HalfSpace:
        case ShapeType::TriangleMesh:
        case ShapeType::HeightField:
        case ShapeType::Count:
            return;  // no contact between static geometry
    }
    candidates.finish(out);
}

}  // namespace tumble::detail
