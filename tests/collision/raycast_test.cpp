// Ray casts and point queries checked against references written independently in world
// coordinates: a signed "inside" function per shape (bisected along rays, marched along random
// rays), the support function (a hit normal, or the direction from a closest point to the query,
// must carry a supporting plane through the point), the active-face normals, and dense samples of
// each surface. Every test uses random rotated and translated poses.

#include "tumble/collision/raycast.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <memory>
#include <numbers>
#include <random>
#include <string>
#include <vector>

#include "tumble/core/error.h"

namespace tumble {
namespace {

constexpr Real kPi = std::numbers::pi;
/// Agreement demanded of fractions, surface residuals and normals (closed forms vs references).
constexpr Real kTolerance = 1e-9;

template <typename... Fs>
struct Overloaded : Fs... {
    using Fs::operator()...;
};
// C++20 deduces this for aggregates; Clang 14 does not yet.
template <typename... Fs>
Overloaded(Fs...) -> Overloaded<Fs...>;

Vec3 randomDirection(std::mt19937& rng) {
    std::normal_distribution<Real> normal;
    return Vec3(normal(rng), normal(rng), normal(rng)).normalized();
}

Transform randomPose(std::mt19937& rng) {
    std::uniform_real_distribution<Real> uniform(-3, 3);
    Transform pose;
    pose.position = Vec3(uniform(rng), uniform(rng), uniform(rng));
    std::normal_distribution<Real> normal;
    pose.rotation = Quat(normal(rng), normal(rng), normal(rng), normal(rng)).normalized();
    return pose;
}

/// Hull data from vertices and face loops; each loop is turned counter-clockwise seen from
/// outside (its Newell normal pointing away from the vertex mean).
ConvexHull handHull(std::vector<Vec3> vertices, std::vector<std::vector<std::uint32_t>> loops) {
    auto data = std::make_shared<HullData>();
    Vec3 mean = Vec3::Zero();
    for (const Vec3& v : vertices)
        mean += v;
    mean /= static_cast<Real>(vertices.size());
    data->vertices = std::move(vertices);
    data->centroid = mean;
    for (std::vector<std::uint32_t>& loop : loops) {
        Vec3 newell = Vec3::Zero();
        for (std::size_t k = 0; k < loop.size(); ++k)
            newell += data->vertices[loop[k]].cross(data->vertices[loop[(k + 1) % loop.size()]]);
        if (newell.dot(data->vertices[loop[0]] - mean) < 0) {
            std::reverse(loop.begin(), loop.end());
            newell = -newell;
        }
        HullFace face;
        face.normal = newell.normalized();
        face.offset = face.normal.dot(data->vertices[loop[0]]);
        face.first = static_cast<std::uint32_t>(data->faceVertices.size());
        face.count = static_cast<std::uint32_t>(loop.size());
        data->faceVertices.insert(data->faceVertices.end(), loop.begin(), loop.end());
        data->faces.push_back(face);
    }
    return ConvexHull{data};
}

/// A box as a hull: vertex i has sign bits (x, y, z) = bits (0, 1, 2) of i.
ConvexHull boxHull(const Vec3& half) {
    std::vector<Vec3> vertices;
    for (int i = 0; i < 8; ++i)
        vertices.emplace_back((i & 1) ? half.x() : -half.x(), (i & 2) ? half.y() : -half.y(),
                              (i & 4) ? half.z() : -half.z());
    std::vector<std::vector<std::uint32_t>> loops;
    for (std::uint32_t axis = 0; axis < 3; ++axis) {
        const std::uint32_t bit = 1u << axis;
        const std::uint32_t a = 1u << ((axis + 1) % 3);
        const std::uint32_t b = 1u << ((axis + 2) % 3);
        for (std::uint32_t side : {0u, bit})
            loops.push_back({side, side | a, side | a | b, side | b});
    }
    return handHull(std::move(vertices), std::move(loops));
}

ConvexHull tetrahedronHull() {
    return handHull({Vec3(0.9, -0.2, -0.4), Vec3(-0.5, 0.7, -0.3), Vec3(-0.3, -0.6, -0.5),
                     Vec3(0.1, 0.05, 0.8)},
                    {{0, 1, 2}, {0, 1, 3}, {1, 2, 3}, {2, 0, 3}});
}

ConvexHull cloudHull() {
    std::mt19937 rng(7);
    std::vector<Vec3> points;
    for (int i = 0; i < 40; ++i)
        points.push_back(randomDirection(rng).cwiseProduct(Vec3(0.9, 0.6, 0.4)));
    return ConvexHull::fromPoints(points);
}

struct Case {
    std::string name;
    Shape shape;
};

/// Every bounded shape type, with hulls built by hand and by Qhull.
std::vector<Case> boundedCases() {
    return {{"sphere", Sphere{0.7}},
            {"capsule", Capsule{0.4, 0.9}},
            {"capsule of zero length", Capsule{0.5, 0}},
            {"box", Box{Vec3(0.3, 0.8, 0.5)}},
            {"flat cylinder", Cylinder{0.6, 0.15}},
            {"tall cylinder", Cylinder{0.3, 1.1}},
            {"hull box", boxHull(Vec3(0.3, 0.8, 0.5))},
            {"hull tetrahedron", tetrahedronHull()},
            {"hull of a cloud", cloudHull()}};
}

Vec3 axisOf(const Transform& pose, int i) {
    return pose.rotation * Vec3::Unit(i);
}

/// <= 0 exactly on the closed solid; the distance to the surface for spheres and capsules, a max
/// of plane or cylinder distances otherwise. Written in world terms, apart from the shape code.
Real inside(const Shape& shape, const Transform& pose, const Vec3& x) {
    const Vec3 c = pose.position;
    const Vec3 a = axisOf(pose, 2);
    return std::visit(
        Overloaded{[&](const auto&) { return Real(INFINITY); },  // surfaces: not solids
                   [&](const Sphere& s) { return (x - c).norm() - s.radius; },
                   [&](const Capsule& s) {
                       const Real along = std::clamp((x - c).dot(a), -s.halfLength, s.halfLength);
                       return (x - c - along * a).norm() - s.radius;
                   },
                   [&](const Box& s) {
                       Real worst = -std::numeric_limits<Real>::infinity();
                       for (int i = 0; i < 3; ++i)
                           worst = std::max(
                               worst, std::abs((x - c).dot(axisOf(pose, i))) - s.halfExtents[i]);
                       return worst;
                   },
                   [&](const Cylinder& s) {
                       const Real along = (x - c).dot(a);
                       return std::max(std::abs(along) - s.halfLength,
                                       (x - c - along * a).norm() - s.radius);
                   },
                   [&](const ConvexHull& s) {
                       Real worst = -std::numeric_limits<Real>::infinity();
                       for (const HullFace& f : s.data->faces) {
                           const Vec3 n = pose.rotation * f.normal;
                           worst = std::max(worst, n.dot(x) - f.offset - n.dot(c));
                       }
                       return worst;
                   },
                   [&](const HalfSpace& s) {
                       const Vec3 n = pose.rotation * s.normal;
                       return n.dot(x) - s.offset - n.dot(c);
                   }},
        shape);
}

/// max over the solid of u . x, for unit u (bounded shapes only).
Real supportValue(const Shape& shape, const Transform& pose, const Vec3& u) {
    const Vec3 c = pose.position;
    const Vec3 a = axisOf(pose, 2);
    return u.dot(c) +
           std::visit(
               Overloaded{
                   [&](const auto&) { return Real(INFINITY); },  // surfaces: not tested here
                   [&](const Sphere& s) { return s.radius; },
                   [&](const Capsule& s) { return s.halfLength * std::abs(u.dot(a)) + s.radius; },
                   [&](const Box& s) {
                       Real sum = 0;
                       for (int i = 0; i < 3; ++i)
                           sum += s.halfExtents[i] * std::abs(u.dot(axisOf(pose, i)));
                       return sum;
                   },
                   [&](const Cylinder& s) {
                       return s.halfLength * std::abs(u.dot(a)) +
                              s.radius * (u - u.dot(a) * a).norm();
                   },
                   [&](const ConvexHull& s) {
                       Real best = -std::numeric_limits<Real>::infinity();
                       for (const Vec3& v : s.data->vertices)
                           best = std::max(best, u.dot(pose.rotation * v));
                       return best;
                   },
                   [&](const HalfSpace&) { return std::numeric_limits<Real>::infinity(); }},
               shape);
}

/// The outward normals of the surface pieces through x (within `slack` of each piece): the
/// normal of a hit must be one of them.
std::vector<Vec3> activeNormals(const Shape& shape, const Transform& pose, const Vec3& x,
                                Real slack) {
    const Vec3 c = pose.position;
    const Vec3 a = axisOf(pose, 2);
    std::vector<Vec3> normals;
    std::visit(Overloaded{[&](const auto&) {},  // surfaces: not tested here
                          [&](const Sphere&) { normals.push_back((x - c).normalized()); },
                          [&](const Capsule& s) {
                              const Real along =
                                  std::clamp((x - c).dot(a), -s.halfLength, s.halfLength);
                              normals.push_back((x - c - along * a).normalized());
                          },
                          [&](const Box& s) {
                              for (int i = 0; i < 3; ++i) {
                                  const Real along = (x - c).dot(axisOf(pose, i));
                                  if (std::abs(std::abs(along) - s.halfExtents[i]) <= slack)
                                      normals.push_back(along > 0 ? axisOf(pose, i)
                                                                  : Vec3(-axisOf(pose, i)));
                              }
                          },
                          [&](const Cylinder& s) {
                              const Real along = (x - c).dot(a);
                              const Vec3 radial = x - c - along * a;
                              if (std::abs(std::abs(along) - s.halfLength) <= slack)
                                  normals.push_back(along > 0 ? a : Vec3(-a));
                              if (std::abs(radial.norm() - s.radius) <= slack)
                                  normals.push_back(radial.normalized());
                          },
                          [&](const ConvexHull& s) {
                              for (const HullFace& f : s.data->faces) {
                                  const Vec3 n = pose.rotation * f.normal;
                                  if (std::abs(n.dot(x - c) - f.offset) <= slack)
                                      normals.push_back(n);
                              }
                          },
                          [&](const HalfSpace& s) { normals.push_back(pose.rotation * s.normal); }},
               shape);
    return normals;
}

Real nearestNormalError(const std::vector<Vec3>& candidates, const Vec3& normal) {
    Real best = std::numeric_limits<Real>::infinity();
    for (const Vec3& n : candidates)
        best = std::min(best, (n - normal).norm());
    return best;
}

/// A random point of the solid (rejection in a ball about the pose), at least `depth` inside.
Vec3 randomInside(std::mt19937& rng, const Shape& shape, const Transform& pose, Real depth) {
    std::uniform_real_distribution<Real> uniform(-1.2, 1.2);
    for (;;) {
        const Vec3 x = pose.position + Vec3(uniform(rng), uniform(rng), uniform(rng));
        if (inside(shape, pose, x) < -depth)
            return x;
    }
}

/// A random point outside the solid, at least `clearance` away (by `inside`), within 4 m.
Vec3 randomOutside(std::mt19937& rng, const Shape& shape, const Transform& pose, Real clearance) {
    std::uniform_real_distribution<Real> uniform(-4, 4);
    for (;;) {
        const Vec3 x = pose.position + Vec3(uniform(rng), uniform(rng), uniform(rng));
        if (inside(shape, pose, x) > clearance)
            return x;
    }
}

/// The first t in [0, 1] at which the segment from `outsidePoint` to `insidePoint` enters the
/// solid: on a convex solid the inside part is an interval ending at 1, so bisection finds it.
Real bisectEntry(const Shape& shape, const Transform& pose, const Vec3& outsidePoint,
                 const Vec3& insidePoint) {
    Real low = 0;
    Real high = 1;
    for (int i = 0; i < 80; ++i) {
        const Real mid = (low + high) / 2;
        if (inside(shape, pose, outsidePoint + mid * (insidePoint - outsidePoint)) <= 0)
            high = mid;
        else
            low = mid;
    }
    return high;
}

TEST(Raycast, EntryMatchesBisectionAndNormalIsTheSurfaces) {
    std::mt19937 rng(11);
    std::uniform_real_distribution<Real> scale(0.25, 4);
    Real worstFraction = 0;
    Real worstNormal = 0;
    Real worstSupport = 0;
    for (const Case& c : boundedCases()) {
        SCOPED_TRACE(c.name);
        for (int trial = 0; trial < 2000; ++trial) {
            const Transform pose = randomPose(rng);
            const Vec3 from = randomOutside(rng, c.shape, pose, 1e-3);
            const Vec3 to = randomInside(rng, c.shape, pose, 1e-3);
            // A direction of arbitrary length: the fraction scales inversely.
            const Real stretch = scale(rng);
            const Ray ray{from, (to - from) * stretch, 1 / stretch};
            const std::optional<RayHit> hit = raycast(c.shape, pose, ray);
            ASSERT_TRUE(hit.has_value());
            const Real expected = bisectEntry(c.shape, pose, from, to) / stretch;
            worstFraction = std::max(worstFraction, std::abs(hit->fraction - expected));
            ASSERT_NEAR(hit->fraction, expected, kTolerance);
            ASSERT_TRUE(hit->point.isApprox(from + hit->fraction * ray.direction, 1e-14));
            ASSERT_NEAR(hit->normal.norm(), 1, 1e-12);
            ASSERT_LT(hit->normal.dot(ray.direction), 0);
            const Real normalError =
                nearestNormalError(activeNormals(c.shape, pose, hit->point, 1e-9), hit->normal);
            worstNormal = std::max(worstNormal, normalError);
            ASSERT_LE(normalError, kTolerance);
            // The plane through the hit with that normal supports the solid.
            const Real supportGap =
                std::abs(supportValue(c.shape, pose, hit->normal) - hit->normal.dot(hit->point));
            worstSupport = std::max(worstSupport, supportGap);
            ASSERT_LE(supportGap, kTolerance);
        }
    }
    std::printf(
        "[ measured ] entry fraction vs bisection %.3g, normal vs active faces %.3g, "
        "support-plane gap %.3g\n",
        worstFraction, worstNormal, worstSupport);
}

/// Random rays (origins inside and outside, any direction and length) against a march of
/// 2000 samples: a miss must have no sample inside; a hit at t > 0 must start outside, lie on
/// the surface, have no sample inside before it and match the marched entry refined by bisection.
TEST(Raycast, RandomRaysAgreeWithAMarch) {
    std::mt19937 rng(12);
    std::uniform_real_distribution<Real> length(0.2, 6);
    constexpr int kSteps = 2000;
    int hits = 0;
    int misses = 0;
    Real worstFraction = 0;
    for (const Case& c : boundedCases()) {
        SCOPED_TRACE(c.name);
        for (int trial = 0; trial < 400; ++trial) {
            const Transform pose = randomPose(rng);
            std::uniform_real_distribution<Real> offset(-2.5, 2.5);
            const Vec3 origin = pose.position + Vec3(offset(rng), offset(rng), offset(rng));
            // Aimed near the shape, so that hits and misses both come up often.
            const Vec3 target = pose.position + randomDirection(rng) * length(rng) / 5;
            const Ray ray{origin, (target - origin).normalized() * length(rng), length(rng) / 2};
            const std::optional<RayHit> hit = raycast(c.shape, pose, ray);
            int firstInside = -1;
            for (int k = 0; k <= kSteps && firstInside < 0; ++k) {
                const Real t = ray.maxFraction * k / kSteps;
                if (inside(c.shape, pose, origin + t * ray.direction) < 0)
                    firstInside = k;
            }
            if (!hit) {
                ++misses;
                ASSERT_EQ(firstInside, -1) << "missed a ray that enters the solid";
                continue;
            }
            ++hits;
            ASSERT_LE(hit->fraction, ray.maxFraction);
            if (hit->fraction == 0) {
                ASSERT_LE(inside(c.shape, pose, origin), 1e-12);
                continue;
            }
            ASSERT_GT(inside(c.shape, pose, origin), 0);
            ASSERT_NEAR(inside(c.shape, pose, hit->point), 0, kTolerance);
            if (firstInside < 0)
                continue;  // grazing within one march step: the surface check above suffices
            ASSERT_GT(firstInside, 0);
            const Vec3 before =
                origin + ray.maxFraction * (firstInside - 1) / kSteps * ray.direction;
            const Vec3 after = origin + ray.maxFraction * firstInside / kSteps * ray.direction;
            const Real expected = ray.maxFraction / kSteps *
                                  (firstInside - 1 + bisectEntry(c.shape, pose, before, after));
            worstFraction = std::max(worstFraction, std::abs(hit->fraction - expected));
            ASSERT_NEAR(hit->fraction, expected, kTolerance);
        }
    }
    EXPECT_GT(hits, 1000);
    EXPECT_GT(misses, 1000);
    std::printf("[ measured ] %d hits, %d misses; marched entry %.3g\n", hits, misses,
                worstFraction);
}

TEST(Raycast, RayFromInsideHitsAtZeroAgainstItsDirection) {
    std::mt19937 rng(13);
    for (const Case& c : boundedCases()) {
        SCOPED_TRACE(c.name);
        for (int trial = 0; trial < 300; ++trial) {
            const Transform pose = randomPose(rng);
            const Vec3 origin = randomInside(rng, c.shape, pose, 1e-6);
            const Vec3 direction = randomDirection(rng) * 3;
            const std::optional<RayHit> hit = raycast(c.shape, pose, {origin, direction, 0});
            ASSERT_TRUE(hit.has_value());
            EXPECT_EQ(hit->fraction, 0);
            EXPECT_EQ(hit->point, origin);
            EXPECT_TRUE(hit->normal.isApprox(-direction / 3, 1e-15));
            // A zero direction is a point query.
            const std::optional<RayHit> still = raycast(c.shape, pose, {origin, Vec3::Zero(), 1});
            ASSERT_TRUE(still.has_value());
            EXPECT_EQ(still->fraction, 0);
            EXPECT_EQ(still->normal, Vec3::Zero());
            const Vec3 away = randomOutside(rng, c.shape, pose, 1e-6);
            EXPECT_FALSE(raycast(c.shape, pose, {away, Vec3::Zero(), 1}).has_value());
        }
    }
}

TEST(Raycast, MaxFractionCutsTheRayAndBehindIsAMiss) {
    std::mt19937 rng(14);
    for (const Case& c : boundedCases()) {
        SCOPED_TRACE(c.name);
        for (int trial = 0; trial < 300; ++trial) {
            const Transform pose = randomPose(rng);
            const Vec3 from = randomOutside(rng, c.shape, pose, 1e-2);
            const Vec3 to = randomInside(rng, c.shape, pose, 1e-2);
            const std::optional<RayHit> hit = raycast(c.shape, pose, {from, to - from, 1});
            ASSERT_TRUE(hit.has_value());
            EXPECT_TRUE(raycast(c.shape, pose, {from, to - from, hit->fraction + 1e-9}));
            EXPECT_FALSE(raycast(c.shape, pose, {from, to - from, hit->fraction - 1e-9}));
            EXPECT_TRUE(
                raycast(c.shape, pose, {from, to - from, std::numeric_limits<Real>::infinity()}));
            EXPECT_FALSE(raycast(c.shape, pose, {from, from - to, 100}));  // pointing away
        }
    }
}

/// Rays parallel to local axes, where a slab or the round side sees no motion, and a ray starting
/// on a face heading in; expected values by hand in the local frame.
TEST(Raycast, RaysAlongLocalAxesMatchHandValues) {
    std::mt19937 rng(20);
    for (int trial = 0; trial < 200; ++trial) {
        const Transform pose = randomPose(rng);
        const auto cast = [&](const Shape& shape, const Vec3& from, const Vec3& along) {
            return raycast(shape, pose, {pose.apply(from), pose.rotation * along, 10});
        };
        const auto expectHit = [&](const std::optional<RayHit>& hit, Real fraction,
                                   const Vec3& localNormal) {
            ASSERT_TRUE(hit.has_value());
            EXPECT_NEAR(hit->fraction, fraction, 1e-12);
            EXPECT_TRUE(hit->normal.isApprox(pose.rotation * localNormal.normalized(), 1e-12));
        };
        const Cylinder cylinder{0.6, 0.4};
        expectHit(cast(cylinder, Vec3(0.2, -0.3, -2), Vec3(0, 0, 2)), 0.8, -Vec3::UnitZ());
        expectHit(cast(cylinder, Vec3(-2, 0.1, 0.1), Vec3(1, 0, 0)), 2 - std::sqrt(0.35),
                  Vec3(-std::sqrt(0.35), 0.1, 0));
        EXPECT_FALSE(cast(cylinder, Vec3(0.7, 0, -2), Vec3(0, 0, 1)));
        const Capsule capsule{0.4, 0.9};
        expectHit(cast(capsule, Vec3(0.1, 0.2, -3), Vec3(0, 0, 1)), 2.1 - std::sqrt(0.11),
                  Vec3(0.1, 0.2, -std::sqrt(0.11)));
        expectHit(cast(capsule, Vec3(-2, 0.1, 0.5), Vec3(0.5, 0, 0)), (2 - std::sqrt(0.15)) / 0.5,
                  Vec3(-std::sqrt(0.15), 0.1, 0));
        EXPECT_FALSE(cast(capsule, Vec3(0.5, 0, -3), Vec3(0, 0, 1)));
        const Box box{Vec3(0.3, 0.8, 0.5)};
        expectHit(cast(box, Vec3(-2, 0.1, 0.2), Vec3(1, 0, 0)), 1.7, -Vec3::UnitX());
        EXPECT_FALSE(cast(box, Vec3(-2, 0.81, 0), Vec3(1, 0, 0)));
        // On a face heading in: fraction 0; rounding may put the origin just inside, where the
        // normal -direction is the face normal too.
        const std::optional<RayHit> start = cast(box, Vec3(0.3, 0.1, 0.2), Vec3(-1, 0, 0));
        expectHit(start, 0, Vec3::UnitX());
        EXPECT_FALSE(std::signbit(start->fraction));
    }
}

TEST(Raycast, HandBuiltHullBoxAgreesWithTheBox) {
    std::mt19937 rng(15);
    const Vec3 half(0.3, 0.8, 0.5);
    const Shape box = Box{half};
    const Shape hull = boxHull(half);
    for (int trial = 0; trial < 2000; ++trial) {
        const Transform pose = randomPose(rng);
        const Ray ray{pose.position + 2.5 * randomDirection(rng), randomDirection(rng) * 5, 1};
        const std::optional<RayHit> a = raycast(box, pose, ray);
        const std::optional<RayHit> b = raycast(hull, pose, ray);
        ASSERT_EQ(a.has_value(), b.has_value());
        if (a) {
            EXPECT_NEAR(a->fraction, b->fraction, 1e-14);
            EXPECT_TRUE(a->normal.isApprox(b->normal, 1e-12));
        }
        const Vec3 p = pose.position + 1.5 * randomDirection(rng);
        EXPECT_TRUE(closestPoint(box, pose, p).isApprox(closestPoint(hull, pose, p), 1e-13));
    }
}

TEST(Raycast, HalfSpaceIsAPlane) {
    std::mt19937 rng(16);
    std::uniform_real_distribution<Real> uniform(-3, 3);
    for (int trial = 0; trial < 2000; ++trial) {
        const Transform pose = randomPose(rng);
        const HalfSpace ground{randomDirection(rng), uniform(rng)};
        const Vec3 n = pose.rotation * ground.normal;
        const Real offset = ground.offset + n.dot(pose.position);  // world plane n . x = offset
        const Ray ray{Vec3(uniform(rng), uniform(rng), uniform(rng)), randomDirection(rng) * 4, 1};
        const Real height = n.dot(ray.origin) - offset;
        const Real rate = n.dot(ray.direction);
        const std::optional<RayHit> hit = raycast(ground, pose, ray);
        if (height <= 0) {
            ASSERT_TRUE(hit.has_value());
            EXPECT_EQ(hit->fraction, 0);
        } else if (rate < 0 && -height / rate <= 1) {
            ASSERT_TRUE(hit.has_value());
            EXPECT_NEAR(hit->fraction, -height / rate, 1e-12);
            EXPECT_TRUE(hit->normal.isApprox(n, 1e-14));
        } else {
            EXPECT_FALSE(hit.has_value());
        }
        const Vec3 p = ray.origin;
        const Vec3 expected = height <= 0 ? p : Vec3(p - height * n);
        EXPECT_TRUE(closestPoint(ground, pose, p).isApprox(expected, 1e-13));
        EXPECT_EQ(containsPoint(ground, pose, p), height <= 0);
    }
}

/// Fills each face (as a fan of triangles) with a triangular grid of 160 steps a side.
void hullFaceSamples(const HullData& hull, std::vector<Vec3>& out) {
    constexpr int kSteps = 160;
    for (const HullFace& f : hull.faces) {
        const Vec3& a = hull.vertices[hull.faceVertices[f.first]];
        for (std::uint32_t k = 1; k + 1 < f.count; ++k) {
            const Vec3& b = hull.vertices[hull.faceVertices[f.first + k]];
            const Vec3& d = hull.vertices[hull.faceVertices[f.first + k + 1]];
            for (int i = 0; i <= kSteps; ++i)
                for (int j = 0; i + j <= kSteps; ++j)
                    out.push_back(a + (b - a) * (Real(i) / kSteps) + (d - a) * (Real(j) / kSteps));
        }
    }
}

/// Points spread over the surface so that every surface point has a sample within about 0.01 m.
std::vector<Vec3> surfaceSamples(const Shape& shape, const Transform& pose) {
    std::vector<Vec3> local;
    const auto ring = [&](Real radius, Real z, int count) {
        for (int i = 0; i < count; ++i) {
            const Real angle = 2 * kPi * i / count;
            local.emplace_back(radius * std::cos(angle), radius * std::sin(angle), z);
        }
    };
    const auto sphere = [&](Real radius, Real z, int sign) {  // hemisphere (sign != 0) or all
        for (int i = 0; i <= 200; ++i) {
            const Real polar = kPi * i / 200;
            const Real height = radius * std::cos(polar);
            if (sign * height >= 0)
                ring(radius * std::sin(polar), z + height,
                     1 + static_cast<int>(400 * std::sin(polar)));
        }
    };
    std::visit(
        Overloaded{
            [&](const auto&) {},  // surfaces: not tested here
            [&](const Sphere& s) { sphere(s.radius, 0, 0); },
            [&](const Capsule& s) {
                sphere(s.radius, s.halfLength, 1);
                sphere(s.radius, -s.halfLength, -1);
                for (int i = 0; i <= 200; ++i)
                    ring(s.radius, -s.halfLength + 2 * s.halfLength * i / 200, 300);
            },
            [&](const Cylinder& s) {
                for (int i = 0; i <= 220; ++i)
                    ring(s.radius, -s.halfLength + 2 * s.halfLength * i / 220, 400);
                for (int i = 0; i <= 60; ++i) {
                    const Real radius = s.radius * i / 60;
                    ring(radius, s.halfLength, 1 + static_cast<int>(400 * radius / s.radius));
                    ring(radius, -s.halfLength, 1 + static_cast<int>(400 * radius / s.radius));
                }
            },
            [&](const Box& s) { hullFaceSamples(*boxHull(s.halfExtents).data, local); },
            [&](const ConvexHull& s) { hullFaceSamples(*s.data, local); },
            [&](const HalfSpace&) {}},
        shape);
    std::vector<Vec3> world;
    world.reserve(local.size());
    for (const Vec3& x : local)
        world.push_back(pose.apply(x));
    return world;
}

TEST(ClosestPoint, IsTheProjectionAndBeatsEverySurfaceSample) {
    std::mt19937 rng(17);
    Real worstSurface = 0;
    Real worstSupport = 0;
    Real worstSampling = 0;
    for (const Case& c : boundedCases()) {
        SCOPED_TRACE(c.name);
        for (int poseTrial = 0; poseTrial < 2; ++poseTrial) {
            const Transform pose = randomPose(rng);
            const std::vector<Vec3> samples = surfaceSamples(c.shape, pose);
            for (int trial = 0; trial < 60; ++trial) {
                const Vec3 p = randomOutside(rng, c.shape, pose, 1e-4);
                const Vec3 q = closestPoint(c.shape, pose, p);
                // q is on the surface, and the plane through q normal to p - q supports the solid:
                // together they make q the projection of p.
                const Real surface = std::abs(inside(c.shape, pose, q));
                const Vec3 u = (p - q).normalized();
                const Real support = std::abs(supportValue(c.shape, pose, u) - u.dot(q));
                worstSurface = std::max(worstSurface, surface);
                worstSupport = std::max(worstSupport, support);
                ASSERT_LE(surface, kTolerance);
                ASSERT_LE(support, kTolerance);
                Real nearestSample = std::numeric_limits<Real>::infinity();
                for (const Vec3& s : samples)
                    nearestSample = std::min(nearestSample, (p - s).norm());
                const Real distance = (p - q).norm();
                ASSERT_LE(distance, nearestSample + 1e-12);
                worstSampling = std::max(worstSampling, nearestSample - distance);
                ASSERT_LE(nearestSample - distance, 0.01);  // the sampling resolution
            }
            for (int trial = 0; trial < 60; ++trial) {
                const Vec3 p = randomInside(rng, c.shape, pose, 0);
                EXPECT_EQ(closestPoint(c.shape, pose, p), p);
            }
        }
    }
    std::printf(
        "[ measured ] closest point: surface residual %.3g, support-plane gap %.3g, "
        "nearest sample farther by at most %.3g m\n",
        worstSurface, worstSupport, worstSampling);
}

TEST(ClosestPoint, MatchesClosedFormsOfRoundShapes) {
    std::mt19937 rng(18);
    for (int trial = 0; trial < 2000; ++trial) {
        const Transform pose = randomPose(rng);
        const Vec3 p = pose.position + 3 * randomDirection(rng);
        const Vec3 c = pose.position;
        const Vec3 a = axisOf(pose, 2);
        // Sphere: along the ray from the centre.
        EXPECT_TRUE(
            closestPoint(Sphere{0.7}, pose, p).isApprox(c + 0.7 * (p - c).normalized(), 1e-14));
        // Capsule: the nearest axis point pushed out by the radius.
        const Real along = std::clamp((p - c).dot(a), -0.9, 0.9);
        const Vec3 axisPoint = c + along * a;
        EXPECT_TRUE(closestPoint(Capsule{0.4, 0.9}, pose, p)
                        .isApprox(axisPoint + 0.4 * (p - axisPoint).normalized(), 1e-14));
    }
}

TEST(ContainsPoint, AgreesWithTheWorldFrameReference) {
    std::mt19937 rng(19);
    int insideCount = 0;
    int outsideCount = 0;
    for (const Case& c : boundedCases()) {
        SCOPED_TRACE(c.name);
        for (int trial = 0; trial < 5000; ++trial) {
            const Transform pose = randomPose(rng);
            std::uniform_real_distribution<Real> offset(-1, 1);
            const Vec3 p = pose.position + Vec3(offset(rng), offset(rng), offset(rng));
            const Real level = inside(c.shape, pose, p);
            if (std::abs(level) < 1e-12)
                continue;  // on the surface to rounding: either answer is right
            ASSERT_EQ(containsPoint(c.shape, pose, p), level < 0) << "level " << level;
            ++(level < 0 ? insideCount : outsideCount);
        }
    }
    EXPECT_GT(insideCount, 2000);
    EXPECT_GT(outsideCount, 2000);
}

TEST(Raycast, CheckRayRefusesBadRays) {
    const Real nan = std::numeric_limits<Real>::quiet_NaN();
    EXPECT_NO_THROW(checkRay({Vec3::Zero(), Vec3::Zero(), 0}, "ray"));
    EXPECT_NO_THROW(
        checkRay({Vec3::Zero(), Vec3::UnitX(), std::numeric_limits<Real>::infinity()}, "ray"));
    EXPECT_THROW(checkRay({Vec3(nan, 0, 0), Vec3::UnitX(), 1}, "ray"), InvalidArgument);
    EXPECT_THROW(
        checkRay({Vec3::Zero(), Vec3(0, std::numeric_limits<Real>::infinity(), 0), 1}, "ray"),
        InvalidArgument);
    EXPECT_THROW(checkRay({Vec3::Zero(), Vec3::UnitX(), -0.5}, "ray"), InvalidArgument);
    EXPECT_THROW(checkRay({Vec3::Zero(), Vec3::UnitX(), nan}, "ray"), InvalidArgument);
    try {
        checkRay({Vec3::Zero(), Vec3::UnitX(), -0.5}, "World::raycast ray");
    } catch (const InvalidArgument& error) {
        EXPECT_NE(std::string(error.what()).find("Ray.maxFraction = -0.5"), std::string::npos);
    }
}

}  // namespace
}  // namespace tumble
