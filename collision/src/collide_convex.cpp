/// The general convex pair: queryConvex (GJK; on overlap the separating-axis depth for polytope
/// pairs, libccd EPA otherwise) gives one normal and the separation; the manifold then comes from
/// the features of both shapes along that normal.
///
/// Each shape offers the feature most aligned with the normal (A along +n, B along -n): a box or
/// hull face, a cylinder cap polygon (a regular kCapVertexCount-gon inscribed in the rim, plus
/// the rim's deepest point when the cap is tilted), a
/// cylinder side line or a capsule segment (when nearly perpendicular to the normal), else a
/// single point. Two nearly parallel segments touch at the ends of their overlap
/// (addParallelSegments). When a face lies within kFaceCos of the normal (kCapCos when a cylinder
/// cap takes part), the better aligned face is the reference and the other feature is clipped
/// against it (clipToManifold); otherwise the contact is the single pair of witness points
/// (edge-edge, a rim or a sphere touching anything). Where a cap takes part in the clipping, the
/// lowest point found on its true disc joins the clipped points (addLowestOnDisc).
///
/// Feature ids: vertex ids are fixed per shape (box corner by its signs, hull vertex index,
/// cylinder rim vertex index, segment end), and face ids are the face index, so the ids stay the
/// same while the same features touch.

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <numbers>

#include "ccd_adapter.h"
#include "clipping.h"
#include "pair_routines.h"

namespace tumble::detail {
namespace {

constexpr int kCapVertexCount = 16;
/// A face counts as facing the normal when cos(angle) >= this (about 1.1 degrees). Within it a
/// face is clipped; beyond it the contact is a point, because clipping would set the manifold
/// normal to a face normal that differs from the true one.
constexpr Real kFaceCos = 0.9998;
/// A cylinder cap is offered as a polygon when cos(angle to the direction) >= this (15 degrees),
/// and when a cap takes part, faces within this angle of the normal are clipped too. Stacked
/// cylinders whose caps are tilted a few degrees against each other (and against the normal)
/// then keep a supporting polygon instead of rocking on one rim point. The manifold keeps the
/// query normal, and each point's separation is measured along it (clipToManifold's
/// contactNormal), so the looser face test does not tilt the normal or change the depth. The
/// inscribed cap polygon alone would make a rim contact shallower by up to
/// r (1 - cos(pi / kCapVertexCount)) sin(15 deg) = 0.5 % of r, so the rim's deepest point joins
/// it (capFeature).
constexpr Real kCapCos = 0.9659;
/// A cap's deepest rim point along the normal joins its polygon when it lies more than this (m)
/// beyond the chord of its two neighbouring vertices: the manifold then has the true depth to
/// this. Below it, near-parallel caps keep the fixed polygon, whose vertices do not wander with
/// rounding in the tilt's direction (stable ids for warm starting a stack).
constexpr Real kRimDepthGain = 1e-8;
/// A segment (capsule core, cylinder side line) counts as lying across the normal when
/// |sin(angle to the plane)| <= this.
constexpr Real kSegmentSin = 0.02;
/// Reference faces within this alignment of each other go to A, so the choice does not flicker.
constexpr Real kReferenceTie = 1e-6;
/// Marks the ids of single-point contacts. They may rarely equal a clipped point's id of another
/// step; the cost is one warm start from a neighbouring point.
constexpr std::uint32_t kSinglePointTag = 0x40000000u;

/// The feature of one shape along a direction, in world coordinates.
struct Feature {
    std::array<Vec3, kMaxClipVertices> vertices;
    std::array<std::uint32_t, kMaxClipVertices> ids{};
    int count = 0;
    bool isFace = false;            ///< a polygon of >= 3 vertices, counter-clockwise from outside
    bool isCap = false;             ///< a cylinder cap
    Vec3 capCenter = Vec3::Zero();  ///< world, when isCap
    Real capRadius = 0;             ///< (m), when isCap
    Vec3 normal = Vec3::UnitZ();    ///< outward face normal (world), when isFace
    Real alignment = -1;            ///< normal . direction, when isFace
    std::uint32_t id = 0;           ///< face (or feature) id on its shape

    void add(const Transform& pose, const Vec3& local, std::uint32_t vertexId) {
        vertices[static_cast<std::size_t>(count)] = pose.apply(local);
        ids[static_cast<std::size_t>(count++)] = vertexId;
    }
    void setFace(const Transform& pose, const Vec3& localNormal, const Vec3& localDirection,
                 std::uint32_t faceId) {
        isFace = true;
        normal = pose.rotation * localNormal;
        alignment = localNormal.dot(localDirection);
        id = faceId;
    }
};

void capsuleFeature(const Capsule& capsule, const Transform& pose, const Vec3& d, Feature& f) {
    const Vec3 offset = capsule.radius * d;
    if (std::abs(d.z()) <= kSegmentSin) {
        f.add(pose, Vec3(0, 0, -capsule.halfLength) + offset, 0);
        f.add(pose, Vec3(0, 0, capsule.halfLength) + offset, 1);
        f.id = 2;
        return;
    }
    const bool top = d.z() > 0;
    f.add(pose, Vec3(0, 0, top ? capsule.halfLength : -capsule.halfLength) + offset, top ? 1 : 0);
    f.id = top ? 1 : 0;
}

/// The box face whose normal is closest to d; corners counter-clockwise seen from outside.
void boxFeature(const Box& box, const Transform& pose, const Vec3& d, Feature& f) {
    Eigen::Index maxIndex = 0;
    d.cwiseAbs().maxCoeff(&maxIndex);
    const int axis = static_cast<int>(maxIndex);
    const Real sign = d[axis] >= 0 ? 1 : -1;
    const int u = (axis + 1) % 3, v = (axis + 2) % 3;  // e_u x e_v = e_axis
    // (u, v) signs in counter-clockwise order about +e_axis; reversed for the -e_axis face.
    static constexpr Real kSquare[4][2] = {{1, 1}, {-1, 1}, {-1, -1}, {1, -1}};
    for (int k = 0; k < 4; ++k) {
        const int corner = sign > 0 ? k : 3 - k;
        Vec3 local;
        local[axis] = sign * box.halfExtents[axis];
        local[u] = kSquare[corner][0] * box.halfExtents[u];
        local[v] = kSquare[corner][1] * box.halfExtents[v];
        const std::uint32_t id =
            (local.x() > 0 ? 1u : 0u) | (local.y() > 0 ? 2u : 0u) | (local.z() > 0 ? 4u : 0u);
        f.add(pose, local, id);
    }
    f.setFace(pose, sign * Vec3::Unit(axis), d, static_cast<std::uint32_t>(2 * axis + (sign > 0)));
}

/// A cylinder cap's polygon: the rim vertices, counter-clockwise from outside, and the rim's
/// deepest point along d inserted between its two neighbours when it lies more than
/// kRimDepthGain beyond their chord.
void capFeature(const Cylinder& cylinder, const Transform& pose, const Vec3& d, Feature& f) {
    const Real h = cylinder.halfLength, r = cylinder.radius;
    const bool top = d.z() > 0;
    const Real radial = std::hypot(d.x(), d.y());
    const Real step = 2 * std::numbers::pi / kCapVertexCount;
    Real phase = std::atan2(d.y(), d.x());
    if (phase < 0)
        phase += 2 * std::numbers::pi;
    const int below = std::min(kCapVertexCount - 1, static_cast<int>(phase / step));
    const Real nearest =
        std::max(std::cos(phase - below * step), std::cos((below + 1) * step - phase));
    const bool insert = r * radial * (1 - nearest) > kRimDepthGain;
    // Walking the top cap counter-clockwise the deepest point follows vertex `below`; walking the
    // bottom one (clockwise about +z) it follows the vertex after `below`.
    const int insertAfter = top ? below : (below + 1) % kCapVertexCount;
    for (int k = 0; k < kCapVertexCount; ++k) {
        const int index = top ? k : kCapVertexCount - 1 - k;
        const Real angle = step * index;
        f.add(pose, Vec3(r * std::cos(angle), r * std::sin(angle), top ? h : -h),
              static_cast<std::uint32_t>(top ? index : kCapVertexCount + index));
        if (insert && index == insertAfter)
            f.add(pose, Vec3(r * d.x() / radial, r * d.y() / radial, top ? h : -h), top ? 35 : 36);
    }
    f.setFace(pose, Vec3(0, 0, top ? 1 : -1), d, top ? 0 : 1);
    f.isCap = true;
    f.capCenter = pose.apply(Vec3(0, 0, top ? h : -h));
    f.capRadius = r;
}

/// Cap polygon, side line or rim point. Ids: top rim vertices 0..15, bottom 16..31, side line
/// ends 32 (bottom) and 33 (top), the rim point 34, a tilted cap's deepest rim point 35 (top) and
/// 36 (bottom); faces: top 0, bottom 1, side 2, rim 3.
void cylinderFeature(const Cylinder& cylinder, const Transform& pose, const Vec3& d, Feature& f) {
    const Real h = cylinder.halfLength, r = cylinder.radius;
    const Real radial = std::hypot(d.x(), d.y());
    if (std::abs(d.z()) >= kCapCos)
        return capFeature(cylinder, pose, d, f);
    const Vec3 rim(r * d.x() / radial, r * d.y() / radial, 0);  // radial > 0 here
    if (std::abs(d.z()) <= kSegmentSin) {
        f.add(pose, rim - Vec3(0, 0, h), 32);
        f.add(pose, rim + Vec3(0, 0, h), 33);
        f.id = 2;
        return;
    }
    f.add(pose, rim + Vec3(0, 0, d.z() > 0 ? h : -h), 34);
    f.id = 3;
}

/// The hull face whose normal is closest to d (lowest index on ties).
void hullFeature(const HullData& hull, const Transform& pose, const Vec3& d, Feature& f) {
    std::size_t best = 0;
    for (std::size_t i = 1; i < hull.faces.size(); ++i) {
        if (hull.faces[i].normal.dot(d) > hull.faces[best].normal.dot(d))
            best = i;
    }
    const HullFace& face = hull.faces[best];
    const std::uint32_t count = std::min<std::uint32_t>(face.count, kMaxClipVertices / 2);
    for (std::uint32_t k = 0; k < count; ++k) {
        const std::uint32_t vertex = hull.faceVertices[face.first + k];
        f.add(pose, hull.vertices[vertex], vertex);
    }
    if (count == face.count) {
        f.setFace(pose, face.normal, d, static_cast<std::uint32_t>(best));
    } else {
        f.count = 0;  // too many vertices to clip: the contact falls back to a single point
        f.id = static_cast<std::uint32_t>(best);
    }
}

/// The feature of `shape` at `pose` most aligned with `direction` (world, unit).
void featureAlong(const Shape& shape, const Transform& pose, const Vec3& direction, Feature& f) {
    const Vec3 d = pose.rotation.conjugate() * direction;
    switch (typeOf(shape)) {
        case ShapeType::Sphere:
            f.add(pose, std::get<Sphere>(shape).radius * d, 0);
            break;
        case ShapeType::Capsule:
            capsuleFeature(std::get<Capsule>(shape), pose, d, f);
            break;
        case ShapeType::Box:
            boxFeature(std::get<Box>(shape), pose, d, f);
            break;
        case ShapeType::Cylinder:
            cylinderFeature(std::get<Cylinder>(shape), pose, d, f);
            break;
        case ShapeType::ConvexHull:
            hullFeature(*std::get<ConvexHull>(shape).data, pose, d, f);
            break;
        default:
            break;  // half-spaces have their own routine
    }
}

void addSinglePoint(const ConvexContact& contact, const Feature& a, const Feature& b,
                    Manifold& out) {
    out.clear();
    out.normal = contact.normal;
    const std::uint32_t vertexA = a.count == 1 ? a.ids[0] : 0x3FFu;
    const std::uint32_t vertexB = b.count == 1 ? b.ids[0] : 0x3FFu;
    const std::uint32_t id = kSinglePointTag | (a.id & 0x1FFu) << 21 | (b.id & 0x1FFu) << 12 |
                             (vertexA & 0x3Fu) << 6 | (vertexB & 0x3Fu);
    out.add(0.5 * (contact.pointA + contact.pointB), contact.separation, id);
}

/// Two segments lying across the normal (a cylinder's side line, a capsule's core offset to its
/// surface) touch along a line when nearly parallel: two points, at the ends of the overlap of B's
/// segment projected on A's, each with its separation along the normal. The single witness point
/// there is ill-conditioned -- it runs the whole overlap for a turn of the segments' small angle
/// -- and a cylinder lying on a capsule in the soak's pile (axes 0.23 deg apart) was supported
/// at one end, then the other, every step, rocking at 0.4 rad/s for good. The ends' sideways
/// offset, up to the overlap's length times the angle, changes their separations along the
/// normal by its square over the radius of curvature only. Returns false when the segments are
/// not parallel within kSegmentSin or their projections do not overlap.
bool addParallelSegments(const ConvexContact& contact, const Feature& a, const Feature& b,
                         Real margin, Manifold& out) {
    const Vec3 directionA = a.vertices[1] - a.vertices[0];
    const Vec3 directionB = b.vertices[1] - b.vertices[0];
    const Real lengthA = directionA.norm(), lengthB = directionB.norm();
    if (!(lengthA > 0 && lengthB > 0) ||
        directionA.cross(directionB).norm() > kSegmentSin * lengthA * lengthB)
        return false;
    const Vec3 axis = directionA / lengthA;
    const Real startB = axis.dot(b.vertices[0] - a.vertices[0]);
    const Real endB = axis.dot(b.vertices[1] - a.vertices[0]);
    const Real low = std::max<Real>(0, std::min(startB, endB));
    const Real high = std::min(lengthA, std::max(startB, endB));
    if (!(high - low > 1e-9 * (1 + lengthA)))
        return false;
    out.clear();
    out.normal = contact.normal;
    const std::uint32_t pair = kSinglePointTag | (a.id & 0x1FFu) << 21 | (b.id & 0x1FFu) << 12;
    const std::array<Real, 2> ends{low, high};
    for (std::size_t i = 0; i < 2; ++i) {
        const Vec3 pointA = a.vertices[0] + ends[i] * axis;
        const Vec3 pointB = b.vertices[0] + ((ends[i] - startB) / (endB - startB)) * directionB;
        const Real separation = contact.normal.dot(pointB - pointA);
        if (separation <= margin)
            out.add(0.5 * (pointA + pointB), separation,
                    pair | 0x3Eu << 6 | static_cast<std::uint32_t>(i));
    }
    return out.pointCount > 0;
}

/// A clipped point's id never has 0x7FF in both edge labels (clipToManifold), so this names the
/// deepest point within a cap's disc.
constexpr std::uint32_t kDiscPointLabels = 0x7FFu << 11 | 0x7FFu;

using Point2 = Eigen::Matrix<Real, 2, 1>;

Real cross2(const Point2& a, const Point2& b) {
    return a.x() * b.y() - a.y() * b.x();
}

/// The lowest of the points offered, by height along a reference face's normal.
struct Lowest {
    Vec3 normal, origin;  ///< the reference plane: outward unit normal, a point on it
    Vec3 point = Vec3::Zero();
    Real height = std::numeric_limits<Real>::infinity();

    void consider(const Vec3& p) {
        if (normal.dot(p - origin) < height) {
            height = normal.dot(p - origin);
            point = p;
        }
    }
    bool found() const { return height < std::numeric_limits<Real>::infinity(); }
};

/// A cap's disc: centre, axis (its outward normal), radius and two axes in its plane.
struct Disc {
    Vec3 center, axis, e1, e2;
    Real radius;

    explicit Disc(const Feature& cap)
        : center(cap.capCenter),
          axis(cap.normal),
          e1(cap.normal.unitOrthogonal()),
          e2(cap.normal.cross(e1)),
          radius(cap.capRadius) {}
    /// A point's coordinates in the disc's plane, projected along the axis.
    Point2 at(const Vec3& p) const { return {e1.dot(p - center), e2.dot(p - center)}; }
    Vec3 rim(Real angle) const {
        return center + radius * (std::cos(angle) * e1 + std::sin(angle) * e2);
    }
};

/// The outward normal of a face's side k: the plane through its edge k, across the face.
Vec3 sideNormal(const Feature& face, int k) {
    const Vec3& from = face.vertices[static_cast<std::size_t>(k)];
    const Vec3& to = face.vertices[static_cast<std::size_t>((k + 1) % face.count)];
    return (to - from).cross(face.normal).normalized();
}

/// Cap as reference: the incident feature's lowest point over the true disc -- a vertex over it,
/// an edge's crossing of its rim, or the rim point down the incident face's slope when the face
/// covers it.
void lowestOverDisc(const Disc& disc, const Feature& incident, Lowest& lowest) {
    const int n = incident.count;
    const Real r2 = disc.radius * disc.radius;
    Real turn = 0;  // twice the projected polygon's signed area, for the inside test below
    for (int i = 0; i < (n == 2 ? 1 : n); ++i) {
        const Vec3& a = incident.vertices[static_cast<std::size_t>(i)];
        const Vec3& b = incident.vertices[static_cast<std::size_t>((i + 1) % n)];
        const Point2 qa = disc.at(a), d = disc.at(b) - qa;
        turn += cross2(qa, qa + d);
        for (const Vec3* end : {&a, &b})
            if (disc.at(*end).squaredNorm() <= r2)
                lowest.consider(*end);
        // |qa + t d| = r: t^2 d.d + 2 t qa.d + qa.qa - r^2 = 0; the roots within the edge.
        const Real dd = d.squaredNorm(), qd = qa.dot(d);
        const Real discriminant = qd * qd - dd * (qa.squaredNorm() - r2);
        if (dd > 0 && discriminant >= 0)
            for (const Real root : {-std::sqrt(discriminant), std::sqrt(discriminant)})
                if (const Real t = (-qd + root) / dd; t >= 0 && t <= 1)
                    lowest.consider(a + t * (b - a));
    }
    const Vec3& m = incident.normal;
    const Real mn = m.dot(disc.axis);
    if (n < 3 || !incident.isFace || std::abs(mn) <= kSegmentSin)
        return;
    // On the face's plane the height over the disc grows along `slope`.
    const Point2 slope(-m.dot(disc.e1) / mn, -m.dot(disc.e2) / mn);
    if (!(slope.squaredNorm() > 0))
        return;
    const Point2 x = -disc.radius * slope.normalized();
    for (int i = 0; i < n; ++i) {
        const Point2 qa = disc.at(incident.vertices[static_cast<std::size_t>(i)]);
        const Point2 qb = disc.at(incident.vertices[static_cast<std::size_t>((i + 1) % n)]);
        if (turn * cross2(qb - qa, x - qa) < 0)
            return;  // the face does not cover that rim point
    }
    const Vec3 onPlane = disc.center + x.x() * disc.e1 + x.y() * disc.e2;
    lowest.consider(onPlane + (m.dot(incident.vertices[0] - onPlane) / mn) * disc.axis);
}

/// Cap as incident: the disc's lowest point within the reference face's side planes -- its
/// lowest rim point, a rim crossing of a side plane, or a reference corner's foot on the disc.
void lowestOfDisc(const Feature& reference, const Disc& disc, Lowest& lowest) {
    const int n = reference.count;
    auto inside = [&](const Vec3& x) {
        for (int k = 0; k < n; ++k)
            if (sideNormal(reference, k).dot(x - reference.vertices[static_cast<std::size_t>(k)]) >
                kClipTolerance)
                return false;
        return true;
    };
    const Vec3& normal = reference.normal;
    const Point2 down(-normal.dot(disc.e1), -normal.dot(disc.e2));  // downhill, in the disc
    if (down.squaredNorm() > 0) {
        const Vec3 x = disc.rim(std::atan2(down.y(), down.x()));
        if (inside(x))
            lowest.consider(x);
    }
    const Real along = disc.axis.dot(normal);
    for (int k = 0; k < n; ++k) {
        const Vec3& v = reference.vertices[static_cast<std::size_t>(k)];
        if (std::abs(along) > kSegmentSin) {
            const Vec3 foot = v + (disc.axis.dot(disc.center - v) / along) * normal;
            if ((foot - disc.center).squaredNorm() <= disc.radius * disc.radius)
                lowest.consider(foot);
        }
        // The rim at angle t crosses side k where A cos t + B sin t = C.
        const Vec3 side = sideNormal(reference, k);
        const Real a = disc.radius * side.dot(disc.e1), b = disc.radius * side.dot(disc.e2);
        const Real c = side.dot(v - disc.center), size = std::hypot(a, b);
        if (!(size > 0) || std::abs(c) > size)
            continue;
        const Real phase = std::atan2(b, a), spread = std::acos(c / size);
        for (const Real angle : {phase - spread, phase + spread})
            if (const Vec3 x = disc.rim(angle); inside(x))
                lowest.consider(x);
    }
}

/// A cap is a polygon inscribed in its rim, so clipping misses contact between its sides and the
/// rim (a band up to r (1 - cos(pi / kCapVertexCount)) wide), whether the cap is the reference or
/// the incident feature. The lowest incident point over the reference, found on the true disc,
/// joins the manifold when it is more than kCapDepthTolerance deeper than the clipped points, and
/// the reduction keeps it (issue 20: the depth within 1e-6 m).
void addLowestOnDisc(const Feature& reference, const Feature& incident, bool referenceIsA,
                     Manifold& out) {
    Lowest lowest{reference.normal, reference.vertices[0]};
    if (reference.isCap)
        lowestOverDisc(Disc(reference), incident, lowest);
    else if (incident.isCap)
        lowestOfDisc(reference, Disc(incident), lowest);
    const Vec3 outward = referenceIsA ? out.normal : Vec3(-out.normal);
    const Real cosine = reference.normal.dot(outward);
    if (!lowest.found() || !(cosine > 0))
        return;
    const Real separation = lowest.height / cosine;
    std::array<ContactPoint, Manifold::kMaxPoints + 1> points;
    Real deepestKept = std::numeric_limits<Real>::infinity();
    for (int i = 0; i < out.pointCount; ++i) {
        points[static_cast<std::size_t>(i)] = out.points[static_cast<std::size_t>(i)];
        deepestKept = std::min(deepestKept, out.points[static_cast<std::size_t>(i)].separation);
    }
    if (!(separation < deepestKept - kCapDepthTolerance))
        return;
    const std::uint32_t owner = referenceIsA ? 0u : 1u << 31;
    points[static_cast<std::size_t>(out.pointCount)] = {
        lowest.point - (separation / 2) * outward, separation,
        owner | (reference.id % 511) << 22 | kDiscPointLabels};
    const Vec3 normal = out.normal;
    reduceContacts(
        std::span<const ContactPoint>(points.data(), static_cast<std::size_t>(out.pointCount) + 1),
        normal, out, false, kCapDepthTolerance);
}

}  // namespace

void collideConvex(const Shape& a, const Transform& poseA, const Shape& b, const Transform& poseB,
                   Real margin, Manifold& out) {
    out.clear();
    const ConvexContact contact = queryConvex(a, poseA, b, poseB);
    if (!(contact.separation <= margin))
        return;
    Feature featureA, featureB;
    featureAlong(a, poseA, contact.normal, featureA);
    featureAlong(b, poseB, -contact.normal, featureB);
    const bool capPair = featureA.isCap || featureB.isCap;
    const Real faceCos = capPair ? kCapCos : kFaceCos;
    const bool faceA = featureA.isFace && featureA.alignment >= faceCos;
    const bool faceB = featureB.isFace && featureB.alignment >= faceCos;
    const bool pointLike = featureA.count <= 1 || featureB.count <= 1;
    if (!featureA.isFace && !featureB.isFace && featureA.count == 2 && featureB.count == 2 &&
        addParallelSegments(contact, featureA, featureB, margin, out))
        return;
    if ((!faceA && !faceB) || pointLike || featureA.count + featureB.count > kMaxClipVertices) {
        return addSinglePoint(contact, featureA, featureB, out);
    }
    const bool referenceIsA =
        faceA && (!faceB || featureA.alignment + kReferenceTie >= featureB.alignment);
    const Feature& reference = referenceIsA ? featureA : featureB;
    const Feature& incident = referenceIsA ? featureB : featureA;
    std::array<ClipVertex, kMaxClipVertices> incidentVertices;
    for (int i = 0; i < incident.count; ++i) {
        const auto k = static_cast<std::size_t>(i);
        incidentVertices[k] = {incident.vertices[k], incident.ids[k]};
    }
    const ReferenceFace face{
        std::span<const Vec3>(reference.vertices.data(), static_cast<std::size_t>(reference.count)),
        reference.normal, reference.id};
    clipToManifold(face,
                   std::span<const ClipVertex>(incidentVertices.data(),
                                               static_cast<std::size_t>(incident.count)),
                   referenceIsA, margin, out, capPair ? &contact.normal : nullptr,
                   capPair ? kCapDepthTolerance : kDepthTolerance);
    // Clipping can lose a grazing contact to rounding at the side planes; keep the witness pair.
    if (out.pointCount == 0)
        return addSinglePoint(contact, featureA, featureB, out);
    if (reference.isCap || incident.isCap)
        addLowestOnDisc(reference, incident, referenceIsA, out);
}

}  // namespace tumble::detail
