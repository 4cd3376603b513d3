// ConvexHull::fromPoints: the only file that knows Qhull (the reentrant C library, libqhull_r).
//
// Qhull reports errors by longjmp to a point set inside qh_new_qhull and prints them to a FILE*;
// we hand it an in-memory stream, so nothing reaches stderr and its message can be quoted in the
// InvalidArgument. No other Qhull function that can fail is called after qh_new_qhull returns
// (its error handler would then exit the process).
//
// Qhull and the flatness test see the cloud moved to its bounding box's centre and scaled to unit
// size; the hull keeps the caller's exact coordinates (vertices are input points by index).
//
// Determinism: the output order depends only on the input, never on Qhull's internal lists or on
// addresses. Vertices are kept in the order of their input index; each face's loop starts at its
// smallest vertex index; faces are sorted by their loops; edges by their index pairs.

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <limits>
#include <memory>
#include <string>
#include <vector>

#include "tumble/collision/shape.h"
#include "tumble/core/error.h"

extern "C" {
#include <libqhull_r/qhull_ra.h>
}

namespace tumble {
namespace {

/// Relative tolerance below which the input counts as flat (collinear or coplanar): the thickness
/// of the cloud must exceed this fraction of its bounding box's half-size. Qhull needs a clearly
/// 3-d simplex to start; clouds thinner than this produce slivers whose mass properties are
/// meaningless anyway.
constexpr Real kFlatTolerance = 1e-9;

/// An in-memory FILE* collecting Qhull's diagnostics instead of stderr.
class MessageStream {
public:
    MessageStream() : file_(open_memstream(&buffer_, &size_)) {}
    ~MessageStream() {
        if (file_ != nullptr)
            std::fclose(file_);
        std::free(buffer_);
    }
    MessageStream(const MessageStream&) = delete;
    MessageStream& operator=(const MessageStream&) = delete;

    FILE* file() const { return file_; }
    /// The first line of what Qhull wrote (its error code and summary).
    std::string firstLine() {
        if (file_ == nullptr)
            return "";
        std::fflush(file_);
        const std::string text(buffer_ != nullptr ? buffer_ : "", size_);
        return text.substr(0, text.find('\n'));
    }

private:
    char* buffer_ = nullptr;
    std::size_t size_ = 0;
    FILE* file_ = nullptr;
};

/// Owns one Qhull instance and frees all its memory on every path out.
class QhullRun {
public:
    QhullRun(FILE* errors) : qh_(std::make_unique<qhT>()) { qh_zero(qh_.get(), errors); }
    ~QhullRun() {
        qh_freeqhull(qh_.get(), !qh_ALL);
        int currentLong = 0;
        int totalLong = 0;
        qh_memfreeshort(qh_.get(), &currentLong, &totalLong);
    }
    QhullRun(const QhullRun&) = delete;
    QhullRun& operator=(const QhullRun&) = delete;

    qhT* get() const { return qh_.get(); }

private:
    std::unique_ptr<qhT> qh_;
};

void checkPoints(std::span<const Vec3> points) {
    if (points.size() < 4)
        fail("ConvexHull::fromPoints: points.size() = ", points.size(),
             " must be >= 4 (a solid needs 4 non-coplanar points)");
    if (points.size() > static_cast<std::size_t>(std::numeric_limits<int>::max()))
        fail("ConvexHull::fromPoints: points.size() = ", points.size(), " exceeds Qhull's int");
    for (std::size_t i = 0; i < points.size(); ++i)
        if (!isFinite(points[i]))
            fail("ConvexHull::fromPoints: points[", i, "] = (", points[i].x(), ", ", points[i].y(),
                 ", ", points[i].z(), ") must be finite");
}

std::size_t farthestFrom(std::span<const Vec3> points, const auto& distance) {
    std::size_t best = 0;
    Real bestDistance = -1;
    for (std::size_t i = 0; i < points.size(); ++i) {
        const Real d = distance(points[i]);
        if (d > bestDistance) {
            bestDistance = d;
            best = i;
        }
    }
    return best;
}

/// The cloud moved to its bounding box's centre and scaled to half-size 1. Qhull and the flatness
/// test run on it, so their tolerances are relative and neither products of tiny coordinates
/// underflow nor a small hull far from the origin loses its digits.
struct UnitCloud {
    std::vector<Vec3> points;
    Real scale = 1;  ///< (m) per unit
};

UnitCloud normalise(std::span<const Vec3> points) {
    Vec3 lower = points[0];
    Vec3 upper = points[0];
    for (const Vec3& p : points) {
        lower = lower.cwiseMin(p);
        upper = upper.cwiseMax(p);
    }
    const Vec3 center = lower / 2 + upper / 2;
    UnitCloud cloud;
    cloud.scale = (upper / 2 - lower / 2).maxCoeff();
    if (cloud.scale == 0)
        fail("ConvexHull::fromPoints: all ", points.size(),
             " points coincide; a hull needs a solid");
    for (const Vec3& p : points)
        cloud.points.push_back((p - center) / cloud.scale);
    if (!std::all_of(cloud.points.begin(), cloud.points.end(),
                     [](const Vec3& p) { return isFinite(p); }))
        fail("ConvexHull::fromPoints: the points span more than ", cloud.scale,
             " m; coordinates must stay below 1e300 m");
    return cloud;
}

/// Refuses clouds that are collinear or coplanar, with a message saying which. Grows a simplex
/// greedily: the point farthest from a start, the farthest from that line, the farthest from
/// that plane; each must stand clear by kFlatTolerance of the (unit) half-size.
void checkSolid(const UnitCloud& cloud) {
    const std::span<const Vec3> points = cloud.points;
    const Vec3& p0 = points[0];
    const Vec3 p1 = points[farthestFrom(points, [&](const Vec3& p) { return (p - p0).norm(); })];
    const Vec3 axis = (p1 - p0).normalized();  // |p1 - p0| >= 1: the box has half-size 1
    const auto lineDistance = [&](const Vec3& p) { return (p - p0).cross(axis).norm(); };
    const Vec3 p2 = points[farthestFrom(points, lineDistance)];
    if (lineDistance(p2) <= kFlatTolerance)
        fail("ConvexHull::fromPoints: the ", points.size(),
             " points are collinear (farthest from their line by ", lineDistance(p2) * cloud.scale,
             " m); a hull needs 4 non-coplanar points");
    const Vec3 normal = (p1 - p0).cross(p2 - p0).normalized();
    const auto planeDistance = [&](const Vec3& p) { return std::abs(normal.dot(p - p0)); };
    const Vec3 p3 = points[farthestFrom(points, planeDistance)];
    if (planeDistance(p3) <= kFlatTolerance)
        fail("ConvexHull::fromPoints: the ", points.size(),
             " points are coplanar (farthest from their plane by ", planeDistance(p3) * cloud.scale,
             " m); a hull needs 4 non-coplanar points");
}

/// One merged facet as Qhull gives it: its outward normal and its vertices' input indices.
struct RawFace {
    Vec3 normal;
    std::vector<std::uint32_t> loop;
};

/// Runs Qhull with its default merging (C-0 in 3-d): coplanar facets are merged, so a box yields
/// six quadrilaterals. Returns each facet's outward normal and its vertices (unordered).
std::vector<RawFace> runQhull(std::span<const Vec3> points) {
    std::vector<coordT> coordinates;
    coordinates.reserve(3 * points.size());
    for (const Vec3& p : points)
        coordinates.insert(coordinates.end(), {p.x(), p.y(), p.z()});

    MessageStream messages;
    QhullRun run(messages.file());
    qhT* qh = run.get();
    char command[] = "qhull";
    const int exitCode = qh_new_qhull(qh, 3, static_cast<int>(points.size()), coordinates.data(),
                                      False, command, nullptr, messages.file());
    if (exitCode != 0)
        fail("ConvexHull::fromPoints: Qhull refused the ", points.size(), " points (exit code ",
             exitCode, "): ", messages.firstLine());

    std::vector<RawFace> faces;
    facetT* facet = nullptr;
    FORALLfacets {
        RawFace face;
        face.normal = Vec3(facet->normal[0], facet->normal[1], facet->normal[2]);
        vertexT* vertex = nullptr;
        vertexT** vertexp = nullptr;  // the cursor FOREACHvertex_ expects by name
        FOREACHvertex_(facet->vertices) {
            face.loop.push_back(static_cast<std::uint32_t>(qh_pointid(qh, vertex->point)));
        }
        faces.push_back(std::move(face));
    }
    return faces;
}

/// Orders a face's vertices counter-clockwise about its outward normal (by angle about their
/// mean, in the face plane), starting at the smallest index.
void orderLoop(std::vector<std::uint32_t>& loop, const Vec3& normal, std::span<const Vec3> points) {
    Vec3 center = Vec3::Zero();
    for (std::uint32_t i : loop)
        center += points[i];
    center /= static_cast<Real>(loop.size());
    // (u, v, normal) right-handed, so increasing atan2(v, u) turns counter-clockwise about normal.
    const Vec3 u = normal.unitOrthogonal();
    const Vec3 v = normal.cross(u);
    std::vector<std::pair<Real, std::uint32_t>> byAngle;
    for (std::uint32_t i : loop) {
        const Vec3 d = points[i] - center;
        byAngle.emplace_back(std::atan2(d.dot(v), d.dot(u)), i);
    }
    std::sort(byAngle.begin(), byAngle.end());
    for (std::size_t k = 0; k < loop.size(); ++k)
        loop[k] = byAngle[k].second;
    std::rotate(loop.begin(), std::min_element(loop.begin(), loop.end()), loop.end());
}

/// Fills `hull` from Qhull's facets: renumbers vertices to their input order, orders loops, sets
/// each face's plane (Newell normal of the loop in the unit cloud; offset = largest n.x over its
/// vertices, so no vertex lies outside its own face) and lists unique edges.
void buildHull(std::vector<RawFace>& faces, std::span<const Vec3> points, const UnitCloud& cloud,
               HullData& hull) {
    std::vector<std::uint32_t> used;
    for (RawFace& face : faces) {
        orderLoop(face.loop, face.normal, cloud.points);
        used.insert(used.end(), face.loop.begin(), face.loop.end());
    }
    std::sort(used.begin(), used.end());
    used.erase(std::unique(used.begin(), used.end()), used.end());
    const auto newIndex = [&](std::uint32_t input) {
        return static_cast<std::uint32_t>(std::lower_bound(used.begin(), used.end(), input) -
                                          used.begin());
    };
    for (std::uint32_t input : used)
        hull.vertices.push_back(points[input]);
    // Renumbering keeps the order of indices, so sorting by the renumbered loops is the same.
    std::sort(faces.begin(), faces.end(),
              [](const RawFace& a, const RawFace& b) { return a.loop < b.loop; });

    for (const RawFace& face : faces) {
        HullFace out;
        out.first = static_cast<std::uint32_t>(hull.faceVertices.size());
        out.count = static_cast<std::uint32_t>(face.loop.size());
        // Newell's normal: twice the area vector of the loop (unit cloud, so no underflow).
        Vec3 newell = Vec3::Zero();
        for (std::size_t k = 0; k < face.loop.size(); ++k) {
            const std::uint32_t input = face.loop[k];
            const std::uint32_t next = face.loop[(k + 1) % face.loop.size()];
            const std::uint32_t a = newIndex(input);
            const std::uint32_t b = newIndex(next);
            hull.faceVertices.push_back(a);
            newell += cloud.points[input].cross(cloud.points[next]);
            hull.edges.push_back({std::min(a, b), std::max(a, b)});
        }
        out.normal = newell.normalized();
        out.offset = -std::numeric_limits<Real>::infinity();
        for (std::uint32_t k = out.first; k < out.first + out.count; ++k)
            out.offset = std::max(out.offset, out.normal.dot(hull.vertices[hull.faceVertices[k]]));
        hull.faces.push_back(out);
    }
    std::sort(hull.edges.begin(), hull.edges.end());
    hull.edges.erase(std::unique(hull.edges.begin(), hull.edges.end()), hull.edges.end());
}

}  // namespace

ConvexHull ConvexHull::fromPoints(std::span<const Vec3> points) {
    checkPoints(points);
    const UnitCloud cloud = normalise(points);
    checkSolid(cloud);
    std::vector<RawFace> faces = runQhull(cloud.points);
    auto hull = std::make_shared<HullData>();
    buildHull(faces, points, cloud, *hull);
    // The centroid comes from the same polyhedral integration as the mass properties.
    const MassProperties mass = massOf(ConvexHull{hull}, 1);
    if (!(mass.mass > 0) || !std::isfinite(mass.mass) || !isFinite(mass.localCenter))
        fail("ConvexHull::fromPoints: the hull's volume = ", mass.mass, " m^3 of ", points.size(),
             " points spanning ", 2 * cloud.scale, " m is not representable; use metres");
    hull->centroid = mass.localCenter;
    return ConvexHull{std::move(hull)};
}

}  // namespace tumble
