// The general convex path: GJK distance against closed forms and brute force, libccd's EPA
// penetration and the exact polytope depth against separating-axis references, and the manifolds
// collideConvex builds.

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <memory>
#include <numbers>
#include <random>
#include <vector>

#include "ccd_adapter.h"
#include "gjk.h"
#include "pair_routines.h"

namespace tumble::detail {
namespace {

// ---- references -------------------------------------------------------------------------------

/// Distance between segments [p1, q1] and [p2, q2] (Ericson, Real-Time Collision Detection 5.1.9).
Real segmentDistance(const Vec3& p1, const Vec3& q1, const Vec3& p2, const Vec3& q2) {
    const Vec3 d1 = q1 - p1, d2 = q2 - p2, r = p1 - p2;
    const Real a = d1.squaredNorm(), e = d2.squaredNorm(), f = d2.dot(r);
    Real s = 0, t = 0;
    if (a <= 1e-30 && e <= 1e-30)
        return r.norm();
    if (a <= 1e-30) {
        t = std::clamp(f / e, Real(0), Real(1));
    } else {
        const Real c = d1.dot(r);
        if (e <= 1e-30) {
            s = std::clamp(-c / a, Real(0), Real(1));
        } else {
            const Real b = d1.dot(d2), denom = a * e - b * b;
            s = denom > 0 ? std::clamp((b * f - c * e) / denom, Real(0), Real(1)) : 0;
            t = (b * s + f) / e;
            if (t < 0) {
                t = 0;
                s = std::clamp(-c / a, Real(0), Real(1));
            } else if (t > 1) {
                t = 1;
                s = std::clamp((b - c) / a, Real(0), Real(1));
            }
        }
    }
    return (p1 + s * d1 - (p2 + t * d2)).norm();
}

Real pointBoxDistance(const Vec3& p, const Box& box, const Transform& pose) {
    const Vec3 local = pose.applyInverse(p);
    const Vec3 clamped = local.cwiseMax(-box.halfExtents).cwiseMin(box.halfExtents);
    return (local - clamped).norm();
}

std::array<Vec3, 8> boxCorners(const Box& box, const Transform& pose) {
    std::array<Vec3, 8> corners;
    for (int i = 0; i < 8; ++i) {
        const Vec3 signs(i & 1 ? 1 : -1, i & 2 ? 1 : -1, i & 4 ? 1 : -1);
        corners[static_cast<std::size_t>(i)] = pose.apply(signs.cwiseProduct(box.halfExtents));
    }
    return corners;
}

/// The 12 edges as corner index pairs (corners differ in one sign bit).
std::vector<std::array<int, 2>> boxEdges() {
    std::vector<std::array<int, 2>> edges;
    for (int i = 0; i < 8; ++i) {
        for (int bit = 1; bit < 8; bit <<= 1) {
            if (!(i & bit))
                edges.push_back({i, i | bit});
        }
    }
    return edges;
}

/// How far box B must move along the unit `axis` to clear box A (m): the overlap of their
/// projections, max over A minus min over B; negative when the axis already separates them.
Real overlapAlong(const Box& a, const Transform& poseA, const Box& b, const Transform& poseB,
                  const Vec3& axis) {
    const Mat3 ra = poseA.rotation.toRotationMatrix(), rb = poseB.rotation.toRotationMatrix();
    const Real extentA = (ra.transpose() * axis).cwiseAbs().dot(a.halfExtents);
    const Real extentB = (rb.transpose() * axis).cwiseAbs().dot(b.halfExtents);
    return extentA + extentB - axis.dot(poseB.position - poseA.position);
}

/// Penetration depth of two overlapping boxes by the separating-axis test: the least overlap over
/// the 3 + 3 face axes and the 9 edge-edge axes. Negative when they are apart.
Real satDepth(const Box& a, const Transform& poseA, const Box& b, const Transform& poseB) {
    const Mat3 ra = poseA.rotation.toRotationMatrix(), rb = poseB.rotation.toRotationMatrix();
    std::vector<Vec3> axes;
    for (int i = 0; i < 3; ++i) {
        axes.push_back(ra.col(i));
        axes.push_back(rb.col(i));
        for (int j = 0; j < 3; ++j) {
            const Vec3 cross = ra.col(i).cross(rb.col(j));
            if (cross.norm() > 1e-9)
                axes.push_back(cross.normalized());
        }
    }
    Real depth = std::numeric_limits<Real>::infinity();
    for (const Vec3& axis : axes) {
        depth = std::min({depth, overlapAlong(a, poseA, b, poseB, axis),
                          overlapAlong(a, poseA, b, poseB, -axis)});
    }
    return depth;
}

/// Whether segment [p, q] meets the box (slab test in the box frame).
bool segmentMeetsBox(const Vec3& p, const Vec3& q, const Box& box, const Transform& pose) {
    const Vec3 from = pose.applyInverse(p), to = pose.applyInverse(q);
    Real enter = 0, leave = 1;
    for (int i = 0; i < 3; ++i) {
        const Real d = to[i] - from[i], h = box.halfExtents[i];
        if (std::abs(d) < 1e-300) {
            if (std::abs(from[i]) > h)
                return false;
            continue;
        }
        const Real t1 = (-h - from[i]) / d, t2 = (h - from[i]) / d;
        enter = std::max(enter, std::min(t1, t2));
        leave = std::min(leave, std::max(t1, t2));
    }
    return enter <= leave;
}

/// Distance from a segment to a box that it does not cross: the closest pair involves an end of
/// the segment (distance to a face plane is linear along the segment) or a box edge.
Real segmentBoxDistance(const Vec3& p, const Vec3& q, const Box& box, const Transform& pose) {
    Real best = std::min(pointBoxDistance(p, box, pose), pointBoxDistance(q, box, pose));
    const std::array<Vec3, 8> corners = boxCorners(box, pose);
    for (const auto& edge : boxEdges()) {
        best = std::min(best, segmentDistance(p, q, corners[edge[0]], corners[edge[1]]));
    }
    return best;
}

/// Distance between disjoint boxes by brute force over vertex-box and edge-edge pairs: the
/// closest points of two polytopes are always attained by one of those.
Real boxBoxDistance(const Box& a, const Transform& poseA, const Box& b, const Transform& poseB) {
    const std::array<Vec3, 8> ca = boxCorners(a, poseA), cb = boxCorners(b, poseB);
    Real best = std::numeric_limits<Real>::infinity();
    for (const Vec3& c : ca)
        best = std::min(best, pointBoxDistance(c, b, poseB));
    for (const Vec3& c : cb)
        best = std::min(best, pointBoxDistance(c, a, poseA));
    const auto edges = boxEdges();
    for (const auto& ea : edges) {
        for (const auto& eb : edges) {
            best = std::min(best, segmentDistance(ca[ea[0]], ca[ea[1]], cb[eb[0]], cb[eb[1]]));
        }
    }
    return best;
}

/// The core of a sphere or capsule as a segment (a sphere's is degenerate).
void coreSegment(const Shape& shape, const Transform& pose, Vec3& p, Vec3& q) {
    const Real h = shape.index() == 1 ? std::get<Capsule>(shape).halfLength : 0;
    p = pose.apply(Vec3(0, 0, -h));
    q = pose.apply(Vec3(0, 0, h));
}

/// Distance between the cores (segment, point or box) of two shapes, by closed form or brute
/// force; the separation of the shapes is this minus the radii whenever it is > 0.
Real referenceCoreDistance(const Shape& a, const Transform& poseA, const Shape& b,
                           const Transform& poseB) {
    const bool boxA = typeOf(a) == ShapeType::Box, boxB = typeOf(b) == ShapeType::Box;
    if (boxA && boxB) {
        const Box& boxOfA = std::get<Box>(a);
        const Box& boxOfB = std::get<Box>(b);
        if (satDepth(boxOfA, poseA, boxOfB, poseB) >= 0)
            return 0;  // overlapping
        return boxBoxDistance(boxOfA, poseA, boxOfB, poseB);
    }
    Vec3 p, q;
    if (boxA || boxB) {
        coreSegment(boxA ? b : a, boxA ? poseB : poseA, p, q);
        const Box& box = std::get<Box>(boxA ? a : b);
        const Transform& boxPose = boxA ? poseA : poseB;
        if (segmentMeetsBox(p, q, box, boxPose))
            return 0;
        return segmentBoxDistance(p, q, box, boxPose);
    }
    Vec3 r, s;
    coreSegment(a, poseA, p, q);
    coreSegment(b, poseB, r, s);
    return segmentDistance(p, q, r, s);
}

struct Random {
    std::mt19937_64 engine{20261121};
    Real uniform(Real lo, Real hi) { return std::uniform_real_distribution<Real>(lo, hi)(engine); }
    Quat rotation() {
        std::normal_distribution<Real> normal;
        Quat q(normal(engine), normal(engine), normal(engine), normal(engine));
        q.normalize();
        return q;
    }
    Vec3 unit() { return rotation() * Vec3::UnitX(); }
    Shape shape(int type) {
        if (type == 0)
            return Sphere{uniform(0.1, 1)};
        if (type == 1)
            return Capsule{uniform(0.1, 1), uniform(0.05, 1)};
        return Box{Vec3(uniform(0.1, 1), uniform(0.1, 1), uniform(0.1, 1))};
    }
};

/// A box as a hand-built hull: corners indexed by sign bits, faces counter-clockwise from outside.
ConvexHull boxHull(const Vec3& halfExtents) {
    auto data = std::make_shared<HullData>();
    for (int i = 0; i < 8; ++i) {
        data->vertices.push_back(
            Vec3(i & 1 ? 1 : -1, i & 2 ? 1 : -1, i & 4 ? 1 : -1).cwiseProduct(halfExtents));
    }
    // Per face: outward axis and sign, corners counter-clockwise about the outward normal.
    const std::array<std::array<std::uint32_t, 4>, 6> quads = {{{1, 3, 7, 5},    // +x
                                                                {0, 4, 6, 2},    // -x
                                                                {2, 6, 7, 3},    // +y
                                                                {0, 1, 5, 4},    // -y
                                                                {4, 5, 7, 6},    // +z
                                                                {0, 2, 3, 1}}};  // -z
    for (int f = 0; f < 6; ++f) {
        HullFace face;
        face.normal = (f % 2 == 0 ? 1.0 : -1.0) * Vec3::Unit(f / 2);
        face.offset = halfExtents[f / 2];
        face.first = static_cast<std::uint32_t>(data->faceVertices.size());
        face.count = 4;
        for (std::uint32_t v : quads[static_cast<std::size_t>(f)])
            data->faceVertices.push_back(v);
        data->faces.push_back(face);
    }
    for (const auto& edge : boxEdges()) {
        data->edges.push_back(
            {static_cast<std::uint32_t>(edge[0]), static_cast<std::uint32_t>(edge[1])});
    }
    return ConvexHull{data};
}

Transform pose(const Vec3& position, const Quat& rotation = Quat::Identity()) {
    return Transform{position, rotation};
}

// ---- GJK distance and EPA depth ---------------------------------------------------------------

TEST(GjkEpa, HandBuiltBoxHullIsConsistent) {
    const ConvexHull hull = boxHull(Vec3(1, 2, 3));
    for (const HullFace& face : hull.data->faces) {
        const Vec3& v0 = hull.data->vertices[hull.data->faceVertices[face.first]];
        const Vec3& v1 = hull.data->vertices[hull.data->faceVertices[face.first + 1]];
        const Vec3& v2 = hull.data->vertices[hull.data->faceVertices[face.first + 2]];
        EXPECT_GT((v1 - v0).cross(v2 - v1).dot(face.normal), 0);  // counter-clockwise
        EXPECT_NEAR(face.normal.dot(v0), face.offset, 1e-15);
    }
}

TEST(GjkEpa, RandomPairsMatchClosedFormsAndBruteForce) {
    Random random;
    std::array<std::array<int, 3>, 3> compared{};
    Real maxError = 0;
    int penetrating = 0;
    for (int n = 0; n < 10000; ++n) {
        const int typeA = n % 3, typeB = (n / 3) % 3;
        const Shape a = random.shape(typeA), b = random.shape(typeB);
        const Transform poseA =
            pose(Vec3(random.uniform(-1, 1), random.uniform(-1, 1), random.uniform(-1, 1)),
                 random.rotation());
        const Transform poseB =
            pose(poseA.position + random.uniform(0, 3.5) * random.unit(), random.rotation());
        const Real core = referenceCoreDistance(a, poseA, b, poseB);
        if (core <= 1e-6)
            continue;  // cores overlap: no closed form (boxes: EPA test below)
        const Real expected = core - roundingRadius(a) - roundingRadius(b);
        const ConvexContact contact = queryConvex(a, poseA, b, poseB);
        const Real error = std::abs(contact.separation - expected);
        maxError = std::max(maxError, error);
        EXPECT_LE(error, 1e-9) << "types " << typeA << ", " << typeB << " pair " << n;
        // The witness points realise the separation along the normal.
        EXPECT_NEAR((contact.pointB - contact.pointA).dot(contact.normal), contact.separation,
                    1e-9);
        ++compared[static_cast<std::size_t>(typeA)][static_cast<std::size_t>(typeB)];
        if (expected < 0)
            ++penetrating;
    }
    int total = 0;
    for (const auto& row : compared) {
        for (int count : row) {
            EXPECT_GT(count, 300);  // every type pair is exercised
            total += count;
        }
    }
    std::printf("[ GJK ] %d pairs compared (%d penetrating rounded shapes), max error %.3g m\n",
                total, penetrating, maxError);
}

/// A random pair of boxes overlapping by at most `maxGap` along the line of their centres (so the
/// penetration depth is at most that): B is placed by bisection on where it just touches A.
void shallowOverlap(Random& random, Real maxGap, Box& a, Transform& poseA, Box& b,
                    Transform& poseB) {
    a = Box{Vec3(random.uniform(0.1, 1), random.uniform(0.1, 1), random.uniform(0.1, 1))};
    b = Box{Vec3(random.uniform(0.1, 1), random.uniform(0.1, 1), random.uniform(0.1, 1))};
    poseA = pose(Vec3::Zero(), random.rotation());
    poseB = pose(Vec3::Zero(), random.rotation());
    const Vec3 direction = random.unit();
    Real inside = 0, outside = 4;  // the overlapping offsets along `direction` form [0, touch)
    for (int i = 0; i < 60; ++i) {
        poseB.position = 0.5 * (inside + outside) * direction;
        (satDepth(a, poseA, b, poseB) > 0 ? inside : outside) = 0.5 * (inside + outside);
    }
    poseB.position = (inside - random.uniform(1e-4, maxGap)) * direction;
}

TEST(GjkEpa, ShallowOverlapsOfRandomBoxesMatchSeparatingAxes) {
    Random random;
    Real maxErrorEpa = 0, maxErrorMpr = 0;
    int mprMisses = 0, count = 0;
    for (; count < 5000; ++count) {
        Box a, b;
        Transform poseA, poseB;
        shallowOverlap(random, 0.02, a, poseA, b, poseB);
        const Real depth = satDepth(a, poseA, b, poseB);
        const ConvexContact exact = queryConvex(a, poseA, b, poseB);  // separating axes
        EXPECT_NEAR(-exact.separation, depth, 1e-6) << "pair " << count;
        const ConvexContact epa = queryConvex(a, poseA, b, poseB, PenetrationMethod::Epa);
        const Real error = std::abs(-epa.separation - depth);
        maxErrorEpa = std::max(maxErrorEpa, error);
        EXPECT_LE(error, 1e-6) << "pair " << count;
        // Moving B by the depth along the returned normal just separates the boxes.
        EXPECT_NEAR(overlapAlong(a, poseA, b, poseB, epa.normal), -epa.separation, 1e-9);
        // MPR's portal direction need not be the minimum one: never shallower, sometimes deeper.
        const ConvexContact mpr = queryConvex(a, poseA, b, poseB, PenetrationMethod::Mpr);
        EXPECT_GE(-mpr.separation, depth - 1e-9);
        maxErrorMpr = std::max(maxErrorMpr, -mpr.separation - depth);
        if (-mpr.separation - depth > 1e-6)
            ++mprMisses;
    }
    std::printf(
        "[ EPA ] %d shallow box overlaps: max |EPA - SAT| %.3g m; MPR off by > 1e-6 in "
        "%d (max %.3g m)\n",
        count, maxErrorEpa, mprMisses, maxErrorMpr);
}

TEST(GjkEpa, AllOverlapsOfRandomBoxesMatchSeparatingAxes) {
    // Shallow and deep (centre near centre) overlaps. The default query takes the least overlap
    // over the 15 axes itself; libccd's EPA (asked explicitly) sometimes stops on a face of the
    // Minkowski difference that is not the nearest, which only the statistics below record: its
    // depth is measured along its direction, so it is never shallower than the minimum.
    Random random;
    int epaMisses = 0, count = 0;
    Real maxError = 0, maxEpaExcess = 0;
    while (count < 10000) {
        const Box a{Vec3(random.uniform(0.1, 1), random.uniform(0.1, 1), random.uniform(0.1, 1))};
        const Box b{Vec3(random.uniform(0.1, 1), random.uniform(0.1, 1), random.uniform(0.1, 1))};
        const Transform poseA = pose(Vec3::Zero(), random.rotation());
        const Transform poseB = pose(random.uniform(0, 2) * random.unit(), random.rotation());
        const Real depth = satDepth(a, poseA, b, poseB);
        if (depth <= 1e-6)
            continue;
        ++count;
        const ConvexContact contact = queryConvex(a, poseA, b, poseB);
        const Real error = std::abs(-contact.separation - depth);
        maxError = std::max(maxError, error);
        EXPECT_LE(error, 1e-6) << "pair " << count << " depth " << depth;
        // The normal realises the depth, and the witness points lie that far apart along it.
        EXPECT_NEAR(overlapAlong(a, poseA, b, poseB, contact.normal), -contact.separation, 1e-9);
        EXPECT_NEAR((contact.pointB - contact.pointA).dot(contact.normal), contact.separation,
                    1e-9);
        const ConvexContact epa = queryConvex(a, poseA, b, poseB, PenetrationMethod::Epa);
        EXPECT_GE(-epa.separation, depth - 1e-9);
        maxEpaExcess = std::max(maxEpaExcess, -epa.separation - depth);
        if (-epa.separation - depth > 1e-6)
            ++epaMisses;
    }
    std::printf(
        "[ SAT ] %d box overlaps: max |depth - SAT| %.3g m; libccd EPA deeper by > 1e-6 in %d "
        "(max %.3g m)\n",
        count, maxError, epaMisses, maxEpaExcess);
}

/// Penetration depth of two posed hulls by brute force: the least overlap over every face normal
/// of both and every cross product of an edge of A with an edge of B, in both directions, from
/// projections of all world vertices. Negative when they are apart.
Real bruteForceHullDepth(const HullData& a, const Transform& poseA, const HullData& b,
                         const Transform& poseB) {
    std::vector<Vec3> verticesA, verticesB;
    for (const Vec3& v : a.vertices)
        verticesA.push_back(poseA.apply(v));
    for (const Vec3& v : b.vertices)
        verticesB.push_back(poseB.apply(v));
    std::vector<Vec3> axes;
    for (const HullFace& face : a.faces)
        axes.push_back(poseA.rotation * face.normal);
    for (const HullFace& face : b.faces)
        axes.push_back(poseB.rotation * face.normal);
    for (const auto& edgeA : a.edges) {
        const Vec3 directionA = verticesA[edgeA[1]] - verticesA[edgeA[0]];
        for (const auto& edgeB : b.edges) {
            const Vec3 cross = directionA.cross(verticesB[edgeB[1]] - verticesB[edgeB[0]]);
            if (cross.norm() > 1e-9 * directionA.norm())
                axes.push_back(cross.normalized());
        }
    }
    Real depth = std::numeric_limits<Real>::infinity();
    for (const Vec3& axis : axes) {
        const Real infinity = std::numeric_limits<Real>::infinity();
        Real lowA = infinity, highA = -infinity, lowB = infinity, highB = -infinity;
        for (const Vec3& v : verticesA) {
            lowA = std::min(lowA, axis.dot(v));
            highA = std::max(highA, axis.dot(v));
        }
        for (const Vec3& v : verticesB) {
            lowB = std::min(lowB, axis.dot(v));
            highB = std::max(highB, axis.dot(v));
        }
        depth = std::min({depth, highA - lowB, highB - lowA});
    }
    return depth;
}

/// A hull of `count` random points in a box of random half extents, or of the box's 8 corners
/// when count is 8 and `corners` is set.
ConvexHull randomHull(Random& random, int count, bool corners) {
    const Vec3 half(random.uniform(0.1, 1), random.uniform(0.1, 1), random.uniform(0.1, 1));
    std::vector<Vec3> points;
    for (int i = 0; i < count; ++i) {
        const Vec3 signs(i & 1 ? 1 : -1, i & 2 ? 1 : -1, i & 4 ? 1 : -1);
        points.push_back(corners ? Vec3(signs.cwiseProduct(half))
                                 : Vec3(random.uniform(-1, 1) * half.x(),
                                        random.uniform(-1, 1) * half.y(),
                                        random.uniform(-1, 1) * half.z()));
    }
    return ConvexHull::fromPoints(points);
}

TEST(GjkEpa, AllOverlapsOfRandomHullsMatchBruteForceSeparatingAxes) {
    // Hulls of 4 to 40 random points and of box corners (Qhull-built), against each other and
    // against boxes given as Box (whose faces and edges the query takes from its axes).
    Random random;
    int count = 0, boxPairs = 0;
    Real maxError = 0;
    while (count < 4000) {
        const int kind = count % 4;  // 0, 1: clouds; 2: box corners; 3: cloud against a Box
        const int points = 4 + static_cast<int>(random.uniform(0, 37));
        const ConvexHull a = randomHull(random, kind == 2 ? 8 : points, kind == 2);
        const ConvexHull hullB = randomHull(random, kind == 0 ? points : 8, kind != 0);
        const Transform poseA = pose(Vec3::Zero(), random.rotation());
        const Transform poseB = pose(random.uniform(0, 1.5) * random.unit(), random.rotation());
        const Real depth = bruteForceHullDepth(*a.data, poseA, *hullB.data, poseB);
        if (depth <= 1e-6)
            continue;
        ++count;
        // kind 3: the same box as a Box shape (hullB holds its corners).
        const Vec3 half = hullB.data->vertices[0].cwiseAbs();
        const Shape b = kind == 3 ? Shape(Box{half}) : Shape(hullB);
        boxPairs += kind == 3;
        const ConvexContact contact = queryConvex(a, poseA, b, poseB);
        const Real error = std::abs(-contact.separation - depth);
        maxError = std::max(maxError, error);
        EXPECT_LE(error, 1e-6) << "pair " << count << " kind " << kind << " depth " << depth;
        // The normal realises the depth: B moved out along it by the depth just touches A.
        const Real along = bruteForceHullDepth(
            *a.data, poseA, *hullB.data,
            pose(poseB.position - contact.separation * contact.normal, poseB.rotation));
        EXPECT_NEAR(along, 0, 1e-9) << "pair " << count;
        EXPECT_NEAR((contact.pointB - contact.pointA).dot(contact.normal), contact.separation,
                    1e-9);
    }
    std::printf("[ SAT ] %d hull overlaps (%d hull-Box): max |depth - brute-force SAT| %.3g m\n",
                count, boxPairs, maxError);
}

TEST(GjkEpa, DeepRoundedAndLargeHullOverlapsMatchBruteForceSeparatingAxes) {
    // A sphere's or capsule's core (point, segment) inside a hull: the core depth over the hull's
    // faces and its edges crossed with the segment, plus the radius. And hulls of 80 points on a
    // sphere (over 192 edges), which take the query's brute-force edge path.
    Random random;
    int rounded = 0, large = 0;
    Real maxError = 0;
    while (rounded < 400) {
        const ConvexHull hull =
            randomHull(random, 4 + static_cast<int>(random.uniform(0, 30)), false);
        const Transform poseA = pose(Vec3::Zero(), random.rotation());
        const Transform poseB = pose(random.uniform(0, 0.5) * random.unit(), random.rotation());
        const bool capsule = rounded % 2 == 1;
        const Real radius = random.uniform(0.05, 0.3), halfLength = random.uniform(0.05, 0.6);
        HullData core;  // the core as a vertex list with its edge, no faces
        core.vertices = {Vec3(0, 0, capsule ? -halfLength : 0)};
        if (capsule) {
            core.vertices.push_back(Vec3(0, 0, halfLength));
            core.edges.push_back({0, 1});
        }
        const Real coreDepth = bruteForceHullDepth(*hull.data, poseA, core, poseB);
        if (coreDepth <= 1e-6)
            continue;
        ++rounded;
        const Shape b = capsule ? Shape(Capsule{radius, halfLength}) : Shape(Sphere{radius});
        const ConvexContact contact = queryConvex(hull, poseA, b, poseB);
        maxError = std::max(maxError, std::abs(-contact.separation - coreDepth - radius));
        EXPECT_NEAR(-contact.separation, coreDepth + radius, 1e-6) << "pair " << rounded;
    }
    while (large < 30) {
        const auto sphereHull = [&] {
            std::vector<Vec3> points;
            for (int i = 0; i < 80; ++i)
                points.push_back(0.5 * random.unit());
            return ConvexHull::fromPoints(points);
        };
        const ConvexHull a = sphereHull(), b = sphereHull();
        ASSERT_GT(a.data->edges.size(), 192u);
        const Transform poseA = pose(Vec3::Zero(), random.rotation());
        const Transform poseB = pose(random.uniform(0, 0.9) * random.unit(), random.rotation());
        const Real depth = bruteForceHullDepth(*a.data, poseA, *b.data, poseB);
        if (depth <= 1e-6)
            continue;
        ++large;
        const ConvexContact contact = queryConvex(a, poseA, b, poseB);
        maxError = std::max(maxError, std::abs(-contact.separation - depth));
        EXPECT_NEAR(-contact.separation, depth, 1e-6) << "large pair " << large;
    }
    std::printf(
        "[ SAT ] %d sphere/capsule cores in hulls, %d 80-point hull pairs: max error %.3g m\n",
        rounded, large, maxError);
}

TEST(GjkEpa, CentredStackAvoidsLibccdDegenerateSimplex) {
    // With libccd's default start direction, a box centred on another yields depth 0.
    const Box box{Vec3(1, 1, 1)};
    for (const Real x : {0.0, 0.1, 0.013}) {
        const ConvexContact contact =
            queryConvex(box, pose(Vec3::Zero()), box, pose(Vec3(x, 0, 1.9)));
        EXPECT_NEAR(contact.separation, -0.1, 1e-9);
        EXPECT_NEAR(contact.normal.z(), 1, 1e-9);
    }
}

TEST(GjkEpa, SphereCentredOnACylinderEndsWithTheShallowerAxis) {
    // From the sphere's centre every direction is nearly as deep, and libccd's EPA (no iteration
    // cap) refined the sphere's boundary without end: the fuzzer's timeout. The depth is the
    // sphere's radius plus the cylinder's nearer side: its radius, or its half length.
    const Quat tilt(Eigen::AngleAxis<Real>(0.7, Vec3(1, 2, 3).normalized()));
    struct Case {
        Sphere sphere;
        Cylinder cylinder;
        Vec3 at;
    };
    for (const Case& c : {Case{Sphere{0.5}, Cylinder{1e-3, 4e-4}, Vec3(0.015, 238.575, -996.094)},
                          Case{Sphere{0.5}, Cylinder{1e-3, 4e-4}, Vec3::Zero()},
                          Case{Sphere{0.5}, Cylinder{10, 20}, Vec3::Zero()},
                          Case{Sphere{2}, Cylinder{0.3, 0.1}, Vec3(1e5, 0, 0)}}) {
        const Real expected = c.sphere.radius + std::min(c.cylinder.radius, c.cylinder.halfLength);
        for (const Vec3& offset : {Vec3(Vec3::Zero()), Vec3(1.1e-5, -0.7e-5, 0.3e-5)}) {
            const ConvexContact contact =
                queryConvex(c.sphere, pose(c.at + offset), c.cylinder, pose(c.at, tilt));
            EXPECT_NEAR(-contact.separation, expected, 2e-5)
                << "sphere " << c.sphere.radius << " in cylinder " << c.cylinder.radius;
            EXPECT_NEAR(contact.normal.norm(), 1, 1e-12);
        }
    }
}

TEST(GjkEpa, SphereCentredOnACapsuleAxisEndsEpaAtItsSupportBudget) {
    // Two rounded cores give EPA the full, curved shapes (their cores' difference is flat). A
    // small sphere a nanometre off a capsule's axis, far from the origin, sees the round side
    // equally deep all round, and libccd's EPA takes over 10x the support budget to settle
    // (found by a search over such pairs); the budget ends it early. The pair has its closed form
    // in the narrowphase; the general query must still give the exact depth: the two radii.
    const Vec3 at(-291.02095811311659, -617.30220292626223, 501.64198914892165);
    const Vec3 off(1.1777785959609106e-09, 5.5195533177061857e-10, 2.94501641506534e-11);
    const Quat turn(-0.12196489161370491, 0.67654271430654556, -0.2370844137291494,
                    0.68644409947139506);
    const Sphere sphere{0.0010964156526219017};
    const Capsule capsule{0.23249739287426008, 1.8535814418889558};
    const ConvexContact contact =
        queryConvex(sphere, pose(at), capsule, pose(at + off, turn.normalized()));
    EXPECT_NEAR(-contact.separation, sphere.radius + capsule.radius, 1e-9);
}

// ---- manifolds --------------------------------------------------------------------------------

/// Expects `out` to hold exactly the `expected` positions (any order) at `separation`.
void expectPoints(const Manifold& out, const std::vector<Vec3>& expected, Real separation,
                  Real tolerance) {
    ASSERT_EQ(out.pointCount, static_cast<int>(expected.size()));
    for (const Vec3& e : expected) {
        bool found = false;
        for (int i = 0; i < out.pointCount; ++i) {
            if ((out.points[i].position - e).norm() <= tolerance) {
                found = true;
                EXPECT_NEAR(out.points[i].separation, separation, tolerance);
            }
        }
        EXPECT_TRUE(found) << "no contact at " << e.transpose();
    }
}

TEST(GjkEpa, HullRestingOnHullGivesFourPointsLikeBoxes) {
    const Quat turn(Eigen::AngleAxis<Real>(0.5, Vec3::UnitZ()));
    const Transform below = pose(Vec3(0.1, -0.2, 0));
    const Transform above = pose(Vec3(0.1, -0.2, 0.5 + 0.3 - 0.01), turn);
    std::vector<Vec3> corners;  // the upper box's bottom corners, midway into the overlap
    for (const Vec3& c : {Vec3(1, 1, 0), Vec3(-1, 1, 0), Vec3(-1, -1, 0), Vec3(1, -1, 0)}) {
        corners.push_back(above.apply(Vec3(0.3 * c.x(), 0.3 * c.y(), -0.3 + 0.005)));
    }
    Manifold hulls, boxes;
    collideConvex(boxHull(Vec3(1, 1, 0.5)), below, boxHull(Vec3::Constant(0.3)), above, 0.02,
                  hulls);
    collideConvex(Box{Vec3(1, 1, 0.5)}, below, Box{Vec3::Constant(0.3)}, above, 0.02, boxes);
    expectPoints(hulls, corners, -0.01, 1e-9);
    expectPoints(boxes, corners, -0.01, 1e-9);
    // The same with hulls that Qhull builds from the corners.
    std::vector<Vec3> lowerCorners, upperCorners;
    for (int i = 0; i < 8; ++i) {
        const Vec3 signs(i & 1 ? 1 : -1, i & 2 ? 1 : -1, i & 4 ? 1 : -1);
        lowerCorners.push_back(signs.cwiseProduct(Vec3(1, 1, 0.5)));
        upperCorners.push_back(0.3 * signs);
    }
    Manifold qhulls;
    collideConvex(ConvexHull::fromPoints(lowerCorners), below, ConvexHull::fromPoints(upperCorners),
                  above, 0.02, qhulls);
    expectPoints(qhulls, corners, -0.01, 1e-9);
    EXPECT_NEAR(hulls.normal.z(), 1, 1e-12);
}

TEST(GjkEpa, FeatureIdsPersistWhileTheContactDoes) {
    const ConvexHull lower = boxHull(Vec3(1, 1, 0.5)), upper = boxHull(Vec3::Constant(0.3));
    Manifold first, second;
    collideConvex(lower, pose(Vec3::Zero()), upper, pose(Vec3(0, 0, 0.79)), 0.02, first);
    collideConvex(
        lower, pose(Vec3::Zero()), upper,
        pose(Vec3(1e-3, -2e-3, 0.7905), Quat(Eigen::AngleAxis<Real>(1e-3, Vec3::UnitZ()))), 0.02,
        second);
    ASSERT_EQ(first.pointCount, 4);
    ASSERT_EQ(second.pointCount, 4);
    for (int i = 0; i < 4; ++i)
        EXPECT_EQ(first.points[i].featureId, second.points[i].featureId);
}

TEST(GjkEpa, SpeculativeMarginKeepsOnlyPointsWithinIt) {
    const ConvexHull lower = boxHull(Vec3(1, 1, 0.5)), upper = boxHull(Vec3::Constant(0.3));
    Manifold out;
    collideConvex(lower, pose(Vec3::Zero()), upper, pose(Vec3(0, 0, 0.805)), 0.01, out);
    ASSERT_EQ(out.pointCount, 4);
    for (int i = 0; i < 4; ++i)
        EXPECT_NEAR(out.points[i].separation, 0.005, 1e-9);
    collideConvex(lower, pose(Vec3::Zero()), upper, pose(Vec3(0, 0, 0.815)), 0.01, out);
    EXPECT_EQ(out.pointCount, 0);
    // Tilted by 2 degrees about x: only the low edge (2 points) lies within the margin.
    const Real tilt = 2 * std::numbers::pi / 180;
    const Transform tilted =
        pose(Vec3(0, 0, 0.5 + 0.3 * std::cos(tilt) + 0.3 * std::sin(tilt) - 0.001),
             Quat(Eigen::AngleAxis<Real>(tilt, Vec3::UnitX())));
    collideConvex(lower, pose(Vec3::Zero()), upper, tilted, 0.01, out);
    ASSERT_EQ(out.pointCount, 2);
    for (int i = 0; i < 2; ++i)
        EXPECT_NEAR(out.points[i].separation, -0.001, 1e-9);
}

TEST(GjkEpa, CylinderStandingOnBoxTouchesAlongTheRim) {
    const Cylinder cylinder{0.3, 0.4};
    const Transform standing =
        pose(Vec3(0.2, 0.1, 0.5 + 0.4 - 0.01), Quat(Eigen::AngleAxis<Real>(0.3, Vec3::UnitZ())));
    Manifold out;
    collideConvex(Box{Vec3(2, 2, 0.5)}, pose(Vec3::Zero()), cylinder, standing, 0.02, out);
    ASSERT_EQ(out.pointCount, 4);
    EXPECT_NEAR(out.normal.z(), 1, 1e-12);
    for (int i = 0; i < 4; ++i) {
        const Vec3 p = out.points[i].position;
        EXPECT_NEAR(std::hypot(p.x() - 0.2, p.y() - 0.1), 0.3, 1e-9);
        EXPECT_NEAR(p.z(), 0.5 - 0.005, 1e-9);
        EXPECT_NEAR(out.points[i].separation, -0.01, 1e-9);
    }
    // The four spread round the rim: their hull is an inscribed square (area 2 r^2). For four
    // points in convex position the area is half the largest |diagonal x diagonal| of the three
    // pairings.
    const auto& p = out.points;
    Real area = 0;
    for (const auto& [i, j, k, l] :
         {std::array{0, 2, 1, 3}, std::array{0, 1, 2, 3}, std::array{0, 3, 1, 2}}) {
        const Vec3 diagonal1 = p[j].position - p[i].position;
        const Vec3 diagonal2 = p[l].position - p[k].position;
        area = std::max(area, 0.5 * std::abs(diagonal1.cross(diagonal2).z()));
    }
    EXPECT_NEAR(area, 2 * 0.3 * 0.3, 1e-9);
}

TEST(GjkEpa, CylinderLyingOnBoxTouchesAlongALine) {
    const Cylinder cylinder{0.3, 0.4};
    const Quat alongX(Eigen::AngleAxis<Real>(std::numbers::pi / 2, Vec3::UnitY()));
    const Transform lying = pose(Vec3(0.2, 0.1, 0.5 + 0.3 - 0.01), alongX);
    Manifold out;
    collideConvex(Box{Vec3(2, 2, 0.5)}, pose(Vec3::Zero()), cylinder, lying, 0.02, out);
    expectPoints(out, {Vec3(0.2 - 0.4, 0.1, 0.495), Vec3(0.2 + 0.4, 0.1, 0.495)}, -0.01, 1e-9);
}

TEST(GjkEpa, CapsuleLyingOnBoxTouchesAlongALine) {
    const Quat alongY(Eigen::AngleAxis<Real>(std::numbers::pi / 2, Vec3::UnitX()));
    Manifold out;
    collideConvex(Capsule{0.2, 0.5}, pose(Vec3(0, 0.3, 0.5 + 0.2 - 0.02), alongY),
                  Box{Vec3(2, 2, 0.5)}, pose(Vec3::Zero()), 0.02, out);
    EXPECT_NEAR(out.normal.z(), -1, 1e-12);  // from the capsule (A) down to the box (B)
    expectPoints(out, {Vec3(0, -0.2, 0.49), Vec3(0, 0.8, 0.49)}, -0.02, 1e-9);
}

TEST(GjkEpa, SphereOnHullEdgeGivesOnePoint) {
    // The sphere's centre lies beyond the hull's +x/+z edge: the normal runs from the edge.
    const Vec3 centre(1 + 0.3, 0, 0.5 + 0.4);
    Manifold out;
    collideConvex(Sphere{0.55}, pose(centre), boxHull(Vec3(1, 1, 0.5)), pose(Vec3::Zero()), 0.02,
                  out);
    ASSERT_EQ(out.pointCount, 1);
    EXPECT_NEAR(out.points[0].separation, 0.5 - 0.55, 1e-9);
    EXPECT_NEAR((out.normal - Vec3(-0.6, 0, -0.8)).norm(), 0, 1e-9);
}

TEST(GjkEpa, CrossedEdgesGiveOnePointAtTheBruteForceDistance) {
    const Box box{Vec3(0.5, 0.5, 0.5)};
    const Quat edgeDown(Eigen::AngleAxis<Real>(std::numbers::pi / 4, Vec3::UnitX()));
    const Quat edgeUp =
        Quat(Eigen::AngleAxis<Real>(std::numbers::pi / 2, Vec3::UnitZ())) * edgeDown;
    const Transform lower = pose(Vec3::Zero(), edgeDown);
    const Transform upper = pose(Vec3(0.05, 0.02, std::sqrt(2.0) - 0.003), edgeUp);
    Manifold out;
    collideConvex(box, lower, box, upper, 0.02, out);
    ASSERT_EQ(out.pointCount, 1);
    EXPECT_NEAR(out.points[0].separation, -satDepth(box, lower, box, upper), 1e-6);
    EXPECT_NEAR(std::abs(out.normal.z()), 1, 1e-6);
}

}  // namespace
}  // namespace tumble::detail
