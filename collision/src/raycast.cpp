// Ray casts and point queries against one posed shape. Each query moves the ray or point into the
// shape's local frame (the fraction t is the same in both frames, since a rigid transform keeps
// origin + t * direction affine in t), answers it there in closed form and turns the result back.
//
// Ray casts clip the whole line origin + t * direction, t in R, against the solid: every shape is
// convex, so the line meets it in one interval [enter, exit] (possibly empty). Then
//   enter >= 0            the ray starts outside (or on the surface heading in): hit at enter;
//   enter < 0 <= exit     the ray starts inside: hit at 0 with normal -direction;
//   exit < 0 or empty     miss.
// Nothing here allocates or iterates beyond a hull's faces.

#include "tumble/collision/raycast.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <variant>

#include "mesh_queries.h"
#include "tumble/core/error.h"

namespace tumble {
namespace {

constexpr Real kInfinity = std::numeric_limits<Real>::infinity();

/// The interval of t for which the line o + t d lies in a solid (local frame), and the outward
/// normal of the surface where it enters.
struct LineClip {
    Real enter = -kInfinity;
    Real exit = kInfinity;
    Vec3 normal = Vec3::Zero();  ///< at `enter`, local frame, unit
    bool empty = false;

    bool isEmpty() const { return empty || enter > exit; }
};

/// Clips to the half-space {x : n . x <= offset}: n . (o + t d) <= offset <=> t (n . d) <= gap with
/// gap = offset - n . o. The sign of n . d says whether t = gap / (n . d) bounds t from below (the
/// line enters, n . d < 0) or from above (it leaves).
void clipPlane(LineClip& clip, const Vec3& o, const Vec3& d, const Vec3& n, Real offset) {
    const Real gap = offset - n.dot(o);
    const Real rate = n.dot(d);
    if (rate == 0) {
        if (gap < 0)
            clip.empty = true;
        return;
    }
    const Real t = gap / rate;
    if (rate < 0) {
        if (t > clip.enter) {
            clip.enter = t;
            clip.normal = n;
        }
    } else {
        clip.exit = std::min(clip.exit, t);
    }
}

/// The roots of |p + t v|^2 = r^2 for the 2-d or 3-d offset p from a centre (or axis) and the
/// direction v: [mid - half, mid + half], or false when the line passes by. Instead of the
/// textbook discriminant b^2 - ac, which cancels when the line is far from the centre, the
/// squared half-chord comes from the closest approach p + mid v (Haines et al., "Precision
/// Improvements for Ray/Sphere Intersection", Ray Tracing Gems, 2019):
///   mid = -(p . v) / (v . v),  half^2 = (r^2 - |p + mid v|^2) / (v . v).
template <typename Vector>
bool roundRoots(const Vector& p, const Vector& v, Real radius, Real& first, Real& second) {
    const Real vv = v.squaredNorm();
    const Real mid = -p.dot(v) / vv;
    const Vector nearest = p + mid * v;
    const Real halfSquared = (radius * radius - nearest.squaredNorm()) / vv;
    if (halfSquared < 0)
        return false;
    const Real half = std::sqrt(halfSquared);
    first = mid - half;
    second = mid + half;
    return true;
}

/// Clips to the infinite solid cylinder x^2 + y^2 <= r^2 (local z axis).
void clipRound(LineClip& clip, const Vec3& o, const Vec3& d, Real radius) {
    const Eigen::Matrix<Real, 2, 1> p = o.head<2>();
    const Eigen::Matrix<Real, 2, 1> v = d.head<2>();
    if (v.squaredNorm() == 0) {  // parallel to the axis: all of the line or none of it
        if (p.squaredNorm() > radius * radius)
            clip.empty = true;
        return;
    }
    Real first = 0;
    Real second = 0;
    if (!roundRoots(p, v, radius, first, second)) {
        clip.empty = true;
        return;
    }
    if (first > clip.enter) {
        clip.enter = first;
        const Vec3 q = o + first * d;
        clip.normal = Vec3(q.x(), q.y(), 0).normalized();
    }
    clip.exit = std::min(clip.exit, second);
}

/// The line against a solid sphere of `radius` about `center`; `d` is nonzero.
LineClip clipSphere(const Vec3& o, const Vec3& d, const Vec3& center, Real radius) {
    LineClip clip;
    const Vec3 p = o - center;
    if (!roundRoots(p, d, radius, clip.enter, clip.exit)) {
        clip.empty = true;
        return clip;
    }
    clip.normal = (p + clip.enter * d).normalized();
    return clip;
}

/// Clips the line in the local frame; `d` is nonzero.
struct ClipLine {
    const Vec3& o;
    const Vec3& d;

    LineClip operator()(const Sphere& sphere) const {
        return clipSphere(o, d, Vec3::Zero(), sphere.radius);
    }
    LineClip operator()(const Capsule& capsule) const;
    LineClip operator()(const Box& box) const {
        LineClip clip;
        for (int i = 0; i < 3; ++i) {
            clipPlane(clip, o, d, Vec3::Unit(i), box.halfExtents[i]);
            clipPlane(clip, o, d, -Vec3::Unit(i), box.halfExtents[i]);
        }
        return clip;
    }
    LineClip operator()(const Cylinder& cylinder) const {
        LineClip clip;
        clipPlane(clip, o, d, Vec3::UnitZ(), cylinder.halfLength);
        clipPlane(clip, o, d, -Vec3::UnitZ(), cylinder.halfLength);
        clipRound(clip, o, d, cylinder.radius);
        return clip;
    }
    LineClip operator()(const ConvexHull& hull) const {
        LineClip clip;
        for (const HullFace& face : hull.data->faces)
            clipPlane(clip, o, d, face.normal, face.offset);
        return clip;
    }
    LineClip operator()(const HalfSpace& halfSpace) const {
        LineClip clip;
        clipPlane(clip, o, d, halfSpace.normal, halfSpace.offset);
        return clip;
    }
    // Surfaces of triangles are not convex solids: raycast sends them to raycastSurface.
    LineClip operator()(const TriangleMesh&) const { return {.empty = true}; }
    LineClip operator()(const HeightField&) const { return {.empty = true}; }
};

/// A capsule is the union of its two end spheres and the finite cylinder between them; being
/// convex, its chord is the hull of the pieces' chords: enter = min of their entries, exit = max
/// of their exits. The cylinder only counts where it meets the line on its side (|z| <= h): where
/// the line crosses a cap disc instead, that disc lies inside an end sphere, whose chord already
/// reaches at least as far. Taking the spheres first and the side only when strictly earlier
/// gives the sphere's normal on the seam, where both agree anyway.
LineClip ClipLine::operator()(const Capsule& capsule) const {
    const Real h = capsule.halfLength;
    const LineClip top = clipSphere(o, d, Vec3(0, 0, h), capsule.radius);
    const LineClip bottom = clipSphere(o, d, Vec3(0, 0, -h), capsule.radius);
    LineClip clip;
    clip.enter = kInfinity;
    clip.exit = -kInfinity;
    for (const LineClip* piece : {&top, &bottom}) {
        if (piece->isEmpty())
            continue;
        if (piece->enter < clip.enter) {
            clip.enter = piece->enter;
            clip.normal = piece->normal;
        }
        clip.exit = std::max(clip.exit, piece->exit);
    }
    LineClip side;
    clipRound(side, o, d, capsule.radius);
    if (!side.isEmpty() && std::isfinite(side.enter)) {
        if (std::abs(o.z() + side.enter * d.z()) <= h && side.enter < clip.enter) {
            clip.enter = side.enter;
            clip.normal = side.normal;
        }
        if (std::abs(o.z() + side.exit * d.z()) <= h)
            clip.exit = std::max(clip.exit, side.exit);
    }
    // Nothing met: enter = +inf > exit = -inf, so the clip reads as empty.
    return clip;
}

/// Point queries in the local frame.
struct Contains {
    const Vec3& p;

    bool operator()(const Sphere& sphere) const {
        return p.squaredNorm() <= sphere.radius * sphere.radius;
    }
    bool operator()(const Capsule& capsule) const {
        const Vec3 axisPoint(0, 0, std::clamp(p.z(), -capsule.halfLength, capsule.halfLength));
        return (p - axisPoint).squaredNorm() <= capsule.radius * capsule.radius;
    }
    bool operator()(const Box& box) const {
        return (p.cwiseAbs().array() <= box.halfExtents.array()).all();
    }
    bool operator()(const Cylinder& cylinder) const {
        return std::abs(p.z()) <= cylinder.halfLength &&
               p.head<2>().squaredNorm() <= cylinder.radius * cylinder.radius;
    }
    bool operator()(const ConvexHull& hull) const {
        for (const HullFace& face : hull.data->faces)
            if (face.normal.dot(p) > face.offset)
                return false;
        return true;
    }
    bool operator()(const HalfSpace& halfSpace) const {
        return halfSpace.normal.dot(p) <= halfSpace.offset;
    }
    // A surface encloses no volume.
    bool operator()(const TriangleMesh&) const { return false; }
    bool operator()(const HeightField&) const { return false; }
};

Vec3 closestOnSegment(const Vec3& a, const Vec3& b, const Vec3& p) {
    const Vec3 ab = b - a;
    const Real lengthSquared = ab.squaredNorm();
    if (lengthSquared == 0)
        return a;
    const Real s = std::clamp(ab.dot(p - a) / lengthSquared, Real(0), Real(1));
    return a + s * ab;
}

/// The nearest point of one face's polygon to p, whose height above the face's plane is
/// `height` > 0, if nearer than `best`: p's projection when that falls inside the polygon (then
/// returns true), else the nearest point of an edge the projection lies beyond -- for a convex
/// polygon the nearest boundary point to an outside point of its plane lies on such an edge.
bool nearestOnFace(const HullData& hull, const HullFace& face, const Vec3& p, Real height,
                   Vec3& best, Real& bestSquared) {
    const Vec3 projected = p - height * face.normal;
    bool inPolygon = true;
    for (std::uint32_t k = 0; k < face.count; ++k) {
        const Vec3& a = hull.vertices[hull.faceVertices[face.first + k]];
        const Vec3& b = hull.vertices[hull.faceVertices[face.first + (k + 1) % face.count]];
        if ((b - a).cross(projected - a).dot(face.normal) >= 0)
            continue;
        inPolygon = false;
        const Vec3 candidate = closestOnSegment(a, b, p);
        const Real distanceSquared = (p - candidate).squaredNorm();
        if (distanceSquared < bestSquared) {
            bestSquared = distanceSquared;
            best = candidate;
        }
    }
    if (inPolygon) {
        bestSquared = height * height;
        best = projected;
    }
    return inPolygon;
}

/// The nearest point to an outside point p of a convex polyhedron lies on a face that p sees
/// (n . p > offset): at that point x, p - x is a non-negative mix of the normals of the faces
/// through x, and its square is positive, so one of those faces has n . (p - x) > 0. When p's
/// projection falls inside a seen face's polygon, no point of the solid, which lies behind that
/// face's plane, is nearer: done. A face's plane distance bounds the distance to all its points
/// from below, so after trying the highest face first most others are skipped on that bound.
Vec3 closestOnHull(const HullData& hull, const Vec3& p) {
    const HullFace* highest = nullptr;
    Real highestHeight = 0;
    for (const HullFace& face : hull.faces) {
        const Real height = face.normal.dot(p) - face.offset;
        if (height > highestHeight) {
            highestHeight = height;
            highest = &face;
        }
    }
    if (highest == nullptr)
        return p;  // behind every face: inside
    Vec3 best = p;
    Real bestSquared = kInfinity;
    if (nearestOnFace(hull, *highest, p, highestHeight, best, bestSquared))
        return best;
    for (const HullFace& face : hull.faces) {
        const Real height = face.normal.dot(p) - face.offset;
        if (&face == highest || height <= 0 || height * height >= bestSquared)
            continue;
        if (nearestOnFace(hull, face, p, height, best, bestSquared))
            return best;
    }
    return best;
}

/// Nearest points in the local frame. Sphere, capsule, box and cylinder are products or
/// Minkowski sums of simple sets, so their projections are clamps.
struct Closest {
    const Vec3& p;

    Vec3 operator()(const Sphere& sphere) const {
        const Real distance = p.norm();
        return distance <= sphere.radius ? p : Vec3(p * (sphere.radius / distance));
    }
    Vec3 operator()(const Capsule& capsule) const {
        const Vec3 axisPoint(0, 0, std::clamp(p.z(), -capsule.halfLength, capsule.halfLength));
        const Vec3 offset = p - axisPoint;
        const Real distance = offset.norm();
        if (distance <= capsule.radius)
            return p;
        return axisPoint + offset * (capsule.radius / distance);
    }
    Vec3 operator()(const Box& box) const {
        return p.cwiseMax(-box.halfExtents).cwiseMin(box.halfExtents);
    }
    Vec3 operator()(const Cylinder& cylinder) const {
        // A disc times an interval: clamp each factor on its own.
        Vec3 q(p.x(), p.y(), std::clamp(p.z(), -cylinder.halfLength, cylinder.halfLength));
        const Real radial = p.head<2>().norm();
        if (radial > cylinder.radius)
            q.head<2>() *= cylinder.radius / radial;
        return q;
    }
    Vec3 operator()(const ConvexHull& hull) const { return closestOnHull(*hull.data, p); }
    Vec3 operator()(const HalfSpace& halfSpace) const {
        const Real height = halfSpace.normal.dot(p) - halfSpace.offset;
        return height <= 0 ? p : Vec3(p - height * halfSpace.normal);
    }
    Vec3 operator()(const TriangleMesh& mesh) const {
        return detail::closestOnSurface(*mesh.data, p);
    }
    Vec3 operator()(const HeightField& field) const {
        return detail::closestOnSurface(*field.data, p);
    }
};

}  // namespace

void checkRay(const Ray& ray, const char* where) {
    const Vec3& o = ray.origin;
    const Vec3& d = ray.direction;
    if (!isFinite(o))
        fail(where, ": Ray.origin = (", o.x(), ", ", o.y(), ", ", o.z(), ") m must be finite");
    if (!isFinite(d))
        fail(where, ": Ray.direction = (", d.x(), ", ", d.y(), ", ", d.z(), ") m must be finite");
    if (std::isnan(ray.maxFraction) || ray.maxFraction < 0)
        fail(where, ": Ray.maxFraction = ", ray.maxFraction, " must be >= 0 (+infinity allowed)");
}

std::optional<RayHit> raycast(const Shape& shape, const Transform& pose, const Ray& ray) {
    if (ray.direction.squaredNorm() == 0) {
        if (!containsPoint(shape, pose, ray.origin))
            return std::nullopt;
        return RayHit{0, ray.origin, Vec3::Zero()};
    }
    const Vec3 o = pose.applyInverse(ray.origin);
    const Vec3 d = pose.rotation.conjugate() * ray.direction;
    if (isTriangleSurface(shape))
        return detail::raycastSurface(shape, pose, o, d, ray);
    const LineClip clip = std::visit(ClipLine{o, d}, shape);
    if (clip.isEmpty() || clip.exit < 0 || clip.enter > ray.maxFraction)
        return std::nullopt;
    if (clip.enter < 0)  // the origin is inside
        return RayHit{0, ray.origin, -ray.direction.normalized()};
    // + 0 turns the -0 of a ray starting on a face (gap -0 / rate) into +0.
    const Real fraction = clip.enter + Real(0);
    const Vec3 point = ray.origin + fraction * ray.direction;
    return RayHit{fraction, point, pose.rotation * clip.normal};
}

Vec3 closestPoint(const Shape& shape, const Transform& pose, const Vec3& point) {
    const Vec3 local = pose.applyInverse(point);
    const Vec3 nearest = std::visit(Closest{local}, shape);
    // Inside: hand back the caller's point untouched rather than a round trip through the frame.
    return nearest == local ? point : pose.apply(nearest);
}

bool containsPoint(const Shape& shape, const Transform& pose, const Vec3& point) {
    const Vec3 local = pose.applyInverse(point);
    return std::visit(Contains{local}, shape);
}

}  // namespace tumble
