// The closed-form narrowphase pairs, the dispatch table and face clipping, against closed forms
// and brute-force references.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <random>
#include <vector>

#include "clipping.h"
#include "pair_routines.h"
#include "tumble/collision/narrowphase.h"

namespace tumble {
namespace {

constexpr Real kMargin = 0.02;
constexpr Real kPi = std::numbers::pi;

Transform at(const Vec3& position, const Quat& rotation = Quat::Identity()) {
    return {position, rotation};
}
Quat about(const Vec3& axis, Real angle) {
    return Quat(Eigen::AngleAxis<Real>(angle, axis.normalized()));
}
Manifold collided(const Shape& a, const Transform& poseA, const Shape& b, const Transform& poseB,
                  Real margin = kMargin) {
    Manifold m;
    collide(a, poseA, b, poseB, margin, m);
    return m;
}
std::vector<std::uint32_t> sortedIds(const Manifold& m) {
    std::vector<std::uint32_t> ids;
    for (int i = 0; i < m.pointCount; ++i)
        ids.push_back(m.points[static_cast<std::size_t>(i)].featureId);
    std::sort(ids.begin(), ids.end());
    return ids;
}
/// Index of the manifold point nearest `x`.
int nearestPoint(const Manifold& m, const Vec3& x) {
    int best = 0;
    for (int i = 1; i < m.pointCount; ++i)
        if ((m.points[static_cast<std::size_t>(i)].position - x).norm() <
            (m.points[static_cast<std::size_t>(best)].position - x).norm())
            best = i;
    return best;
}

/// Area of the convex hull of 2D points, by Andrew's monotone chain: the brute-force reference.
using P2 = Eigen::Matrix<Real, 2, 1>;
Real hullArea(std::vector<P2> p) {
    std::sort(p.begin(), p.end(), [](const P2& a, const P2& b) {
        return a.x() < b.x() || (a.x() == b.x() && a.y() < b.y());
    });
    auto turn = [](const P2& o, const P2& a, const P2& b) {
        return (a - o).x() * (b - o).y() - (a - o).y() * (b - o).x();
    };
    std::vector<P2> hull(2 * p.size());
    std::size_t k = 0;
    for (std::size_t i = 0; i < p.size(); ++i) {
        while (k >= 2 && turn(hull[k - 2], hull[k - 1], p[i]) <= 0)
            --k;
        hull[k++] = p[i];
    }
    for (std::size_t i = p.size() - 1, t = k + 1; i-- > 0;) {
        while (k >= t && turn(hull[k - 2], hull[k - 1], p[i]) <= 0)
            --k;
        hull[k++] = p[i];
    }
    Real area = 0;
    for (std::size_t i = 0; i + 1 < k; ++i)
        area += hull[i].x() * hull[i + 1].y() - hull[i + 1].x() * hull[i].y();
    return std::abs(area) / 2;
}
/// The largest hull area of any 4 of `points` (brute force over all subsets).
Real bestFourArea(const std::vector<P2>& points) {
    Real best = 0;
    const std::size_t n = points.size();
    for (std::size_t i = 0; i < n; ++i)
        for (std::size_t j = i + 1; j < n; ++j)
            for (std::size_t k = j + 1; k < n; ++k)
                for (std::size_t l = k + 1; l < n; ++l)
                    best = std::max(best, hullArea({points[i], points[j], points[k], points[l]}));
    return best;
}
Real manifoldAreaXY(const Manifold& m) {
    std::vector<P2> p;
    for (int i = 0; i < m.pointCount; ++i)
        p.push_back(m.points[static_cast<std::size_t>(i)].position.head<2>());
    return hullArea(p);
}

// --- Resting boxes: exact corners and separations --------------------------------------------

TEST(NarrowphaseBox, RestingOnBoxGivesFourCornersWithExactSeparation) {
    const Shape box = Box{};
    for (Real gap : {0.0, -1e-3, 0.5 * kMargin}) {
        const Manifold m = collided(box, at(Vec3::Zero()), box, at(Vec3(0, 0, 1 + gap)));
        ASSERT_EQ(m.pointCount, 4) << "gap " << gap;
        EXPECT_NEAR((m.normal - Vec3::UnitZ()).norm(), 0, 1e-12);
        for (Real x : {-0.5, 0.5})
            for (Real y : {-0.5, 0.5}) {
                const Vec3 corner(x, y, 0.5 + gap / 2);
                const ContactPoint& p = m.points[static_cast<std::size_t>(nearestPoint(m, corner))];
                EXPECT_NEAR((p.position - corner).norm(), 0, 1e-9) << "gap " << gap;
                EXPECT_NEAR(p.separation, gap, 1e-9);
            }
    }
    EXPECT_EQ(collided(box, at(Vec3::Zero()), box, at(Vec3(0, 0, 1 + 2 * kMargin))).pointCount, 0);
}

TEST(NarrowphaseBox, SmallBoxOverhangingIsClippedToTheOverlap) {
    // A 0.6 box shifted by (0.2, 0.1) on the unit box: the overlap is [-0.1, 0.5] x [-0.2, 0.4].
    const Manifold m =
        collided(Box{}, at(Vec3::Zero()), Box{Vec3::Constant(0.3)}, at(Vec3(0.2, 0.1, 0.8 - 1e-3)));
    ASSERT_EQ(m.pointCount, 4);
    for (Real x : {-0.1, 0.5})
        for (Real y : {-0.2, 0.4}) {
            const Vec3 corner(x, y, 0.5 - 0.5e-3);
            const ContactPoint& p = m.points[static_cast<std::size_t>(nearestPoint(m, corner))];
            EXPECT_NEAR((p.position - corner).norm(), 0, 1e-9);
            EXPECT_NEAR(p.separation, -1e-3, 1e-9);
        }
}

TEST(NarrowphaseHalfSpace, BoxRestingOnGroundGivesFourCornersWithExactSeparation) {
    const Shape ground = HalfSpace{};
    for (Real gap : {0.0, -1e-3, 0.5 * kMargin}) {
        const Manifold m = collided(Box{}, at(Vec3(3, -2, 0.5 + gap), about(Vec3::UnitZ(), 0.3)),
                                    ground, at(Vec3::Zero()));
        ASSERT_EQ(m.pointCount, 4);
        EXPECT_NEAR((m.normal + Vec3::UnitZ()).norm(), 0, 1e-15);  // from the box into the ground
        for (int i = 0; i < 4; ++i) {
            const ContactPoint& p = m.points[static_cast<std::size_t>(i)];
            EXPECT_NEAR(p.separation, gap, 1e-9);
            EXPECT_NEAR(p.position.z(), gap / 2, 1e-9);
            EXPECT_NEAR((p.position.head<2>() - Vec3(3, -2, 0).head<2>()).norm(), std::sqrt(0.5),
                        1e-9);
        }
    }
    EXPECT_EQ(
        collided(Box{}, at(Vec3(0, 0, 0.5 + 2 * kMargin)), ground, at(Vec3::Zero())).pointCount, 0);
}

TEST(NarrowphaseHalfSpace, TiltedAndOffsetHalfSpace) {
    // The half-space {n . x <= 1} in a frame rotated and moved: a sphere's separation is its
    // height above that plane minus its radius.
    const HalfSpace local{Vec3(0, 0, 1), 1};
    const Transform pose = at(Vec3(1, 2, 3), about(Vec3(1, 1, 0), 0.7));
    const Vec3 n = pose.rotation * local.normal;
    const Vec3 center = pose.apply(Vec3(0.3, -0.2, 1.25));
    const Manifold m = collided(Sphere{0.3}, at(center), local, pose);
    ASSERT_EQ(m.pointCount, 1);
    EXPECT_NEAR(m.points[0].separation, -0.05, 1e-12);
    EXPECT_NEAR((m.normal + n).norm(), 0, 1e-12);
    EXPECT_NEAR((m.points[0].position - (center - 0.275 * n)).norm(), 0, 1e-12);
}

// --- 30 degree twist: the clipped octagon reduced to 4 points --------------------------------

TEST(NarrowphaseBox, TwistedBoxKeepsLargestSupportArea) {
    const Quat twist = about(Vec3::UnitZ(), kPi / 6);
    const Manifold m = collided(Box{}, at(Vec3::Zero()), Box{}, at(Vec3(0, 0, 1), twist));
    ASSERT_EQ(m.pointCount, 4);
    // The octagon by brute force: corners of each square inside the other, and edge crossings.
    std::vector<P2> a, b, octagon;
    for (int k = 0; k < 4; ++k) {
        const P2 corner(k == 0 || k == 3 ? 0.5 : -0.5, k < 2 ? 0.5 : -0.5);
        a.push_back(corner);
        b.push_back((twist * Vec3(corner.x(), corner.y(), 0)).head<2>());
    }
    // Inside the unit square, or inside the twisted one (rotated back first).
    auto inside = [](const P2& p, bool twisted) {
        const Vec3 local = twisted ? Vec3(about(Vec3::UnitZ(), -kPi / 6) * Vec3(p.x(), p.y(), 0))
                                   : Vec3(p.x(), p.y(), 0);
        return std::abs(local.x()) <= 0.5 + 1e-12 && std::abs(local.y()) <= 0.5 + 1e-12;
    };
    for (const P2& p : a)
        if (inside(p, true))
            octagon.push_back(p);
    for (const P2& p : b)
        if (inside(p, false))
            octagon.push_back(p);
    for (int i = 0; i < 4; ++i)
        for (int j = 0; j < 4; ++j) {
            const P2 p = a[static_cast<std::size_t>(i)],
                     r = a[static_cast<std::size_t>((i + 1) % 4)] - p;
            const P2 q = b[static_cast<std::size_t>(j)],
                     s = b[static_cast<std::size_t>((j + 1) % 4)] - q;
            const Real d = r.x() * s.y() - r.y() * s.x();
            const P2 w = q - p;
            const Real t = (w.x() * s.y() - w.y() * s.x()) / d,
                       u = (w.x() * r.y() - w.y() * r.x()) / d;
            if (t >= 0 && t <= 1 && u >= 0 && u <= 1)
                octagon.push_back(p + t * r);
        }
    ASSERT_EQ(octagon.size(), 8u);
    for (int i = 0; i < 4; ++i) {
        const ContactPoint& p = m.points[static_cast<std::size_t>(i)];
        EXPECT_NEAR(p.separation, 0, 1e-12);
        EXPECT_NEAR(p.position.z(), 0.5, 1e-12);
        Real nearest = 1;
        for (const P2& v : octagon)
            nearest = std::min(nearest, (v - p.position.head<2>()).norm());
        EXPECT_LT(nearest, 1e-12);  // every kept point is a vertex of the octagon
    }
    EXPECT_NEAR(manifoldAreaXY(m), bestFourArea(octagon), 1e-9);
}

TEST(NarrowphaseClipping, ExactReductionMatchesBruteForceOnRandomSets) {
    // Up to kExactReduceLimit candidates every 4-subset is tried: the area can fall short of the
    // best only by the tie fraction. Beyond, the greedy choice: its worst ratio is measured.
    std::mt19937 rng(7);
    std::uniform_real_distribution<Real> uniform(-1, 1);
    Real worstExact = 1, worstGreedy = 1;
    for (int trial = 0; trial < 400; ++trial) {
        const int n = 5 + trial % 12;  // 5..16
        std::vector<ContactPoint> candidates;
        std::vector<P2> planar;
        for (int i = 0; i < n; ++i) {
            // On a random ellipse (convex position) or inside it: both kinds of sets occur.
            const Real angle = kPi * uniform(rng),
                       scale = trial % 2 ? 1.0 : 0.5 + 0.5 * std::abs(uniform(rng));
            const Vec3 x(scale * 2 * std::cos(angle), scale * std::sin(angle), 0);
            candidates.push_back({x, 0, static_cast<std::uint32_t>(i)});
            planar.push_back(x.head<2>());
        }
        Manifold m;
        detail::reduceContacts(candidates, -Vec3::UnitZ(), m);
        ASSERT_EQ(m.pointCount, 4);
        const Real ratio = manifoldAreaXY(m) / bestFourArea(planar);
        (n <= detail::kExactReduceLimit ? worstExact : worstGreedy) =
            std::min(ratio, n <= detail::kExactReduceLimit ? worstExact : worstGreedy);
    }
    EXPECT_GE(worstExact, 1 / (1 + detail::kAreaTieFraction) - 1e-12);
    RecordProperty("worstGreedyAreaRatio", std::to_string(worstGreedy));
    std::printf("greedy reduction (9..16 points): worst area ratio %.4f\n", worstGreedy);
    EXPECT_GE(worstGreedy, 0.9);  // measured 0.905 over these sets; guards against regressions
}

TEST(NarrowphaseClipping, DeepestPointIsAlwaysKept) {
    std::vector<ContactPoint> candidates;
    for (int i = 0; i < 12; ++i) {
        const Real angle = 2 * kPi * i / 12;
        candidates.push_back(
            {Vec3(std::cos(angle), std::sin(angle), 0), 0, static_cast<std::uint32_t>(i)});
    }
    candidates.push_back({Vec3(0.1, 0, 0), -0.01, 99});  // interior but deepest
    for (std::size_t size : {std::size_t{8}, candidates.size()}) {
        std::vector<ContactPoint> set(candidates.end() - static_cast<long>(size), candidates.end());
        Manifold m;
        detail::reduceContacts(set, -Vec3::UnitZ(), m);
        const std::vector<std::uint32_t> ids = sortedIds(m);
        EXPECT_EQ(std::count(ids.begin(), ids.end(), 99u), 1) << size;
    }
}

// --- Edge against edge ------------------------------------------------------------------------

TEST(NarrowphaseBox, CrossingEdgesGiveOnePointMidwayBetweenThem) {
    // A turned 45 deg about y has its top edge along y at height sqrt(1/2); B turned 45 deg about
    // x, then 20 deg about z, has its bottom edge along (cos 20, sin 20, 0).
    const Quat rotationA = about(Vec3::UnitY(), kPi / 4);
    const Quat rotationB = about(Vec3::UnitZ(), kPi / 9) * about(Vec3::UnitX(), kPi / 4);
    const Real h = std::sqrt(0.5);
    for (Real gap : {0.01, 0.0, -0.01}) {
        const Vec3 centerB(0.05, -0.1, 2 * h + gap);
        const Manifold m =
            collided(Box{}, at(Vec3::Zero(), rotationA), Box{}, at(centerB, rotationB));
        ASSERT_EQ(m.pointCount, 1) << gap;
        const Vec3 edgeA = rotationA * Vec3::UnitY(), edgeB = rotationB * Vec3::UnitX();
        EXPECT_NEAR(
            (m.normal - edgeA.cross(edgeB).normalized() * (edgeA.cross(edgeB).z() > 0 ? 1 : -1))
                .norm(),
            0, 1e-12);
        EXPECT_NEAR(m.points[0].separation, gap, 1e-12);
        // Midway: gap/2 from the line of each edge, and within both edges.
        const Vec3 onA(0, 0, h), onB = centerB - Vec3(0, 0, h);
        const Vec3 p = m.points[0].position;
        EXPECT_NEAR((p - onA).cross(edgeA).norm(), std::abs(gap) / 2, 1e-12);
        EXPECT_NEAR((p - onB).cross(edgeB).norm(), std::abs(gap) / 2, 1e-12);
        EXPECT_LE(std::abs((p - onA).dot(edgeA)), 0.5);
        EXPECT_LE(std::abs((p - onB).dot(edgeB)), 0.5);
        EXPECT_NEAR(p.z(), h + gap / 2, 1e-12);
    }
}

// --- Round shapes against the closed form ------------------------------------------------------

struct Closest {
    Vec3 a, b;
};
Vec3 closestOnSegment(const Vec3& p, const Vec3& s0, const Vec3& s1) {
    const Vec3 d = s1 - s0;
    const Real t =
        d.squaredNorm() > 0 ? std::clamp((p - s0).dot(d) / d.squaredNorm(), 0.0, 1.0) : 0.0;
    return s0 + t * d;
}
/// Segment-segment closest points the slow way: the interior stationary point if it lies in
/// the unit square, else the best of the four endpoint-to-segment candidates.
Closest closestSegments(const Vec3& a0, const Vec3& a1, const Vec3& b0, const Vec3& b1) {
    std::vector<Closest> options{{a0, closestOnSegment(a0, b0, b1)},
                                 {a1, closestOnSegment(a1, b0, b1)},
                                 {closestOnSegment(b0, a0, a1), b0},
                                 {closestOnSegment(b1, a0, a1), b1}};
    const Vec3 da = a1 - a0, db = b1 - b0, r = a0 - b0;
    Eigen::Matrix<Real, 2, 2> m;
    m << da.dot(da), -da.dot(db), -da.dot(db), db.dot(db);
    const Eigen::Matrix<Real, 2, 1> st =
        m.fullPivLu().solve(Eigen::Matrix<Real, 2, 1>(-da.dot(r), db.dot(r)));
    if (std::abs(m.determinant()) > 1e-12 && st.minCoeff() >= 0 && st.maxCoeff() <= 1)
        options.push_back({a0 + st[0] * da, b0 + st[1] * db});
    return *std::min_element(
        options.begin(), options.end(),
        [](const Closest& x, const Closest& y) { return (x.b - x.a).norm() < (y.b - y.a).norm(); });
}

TEST(NarrowphaseRound, RandomPairsMatchClosedForm) {
    std::mt19937 rng(11);
    std::uniform_real_distribution<Real> uniform(-1, 1), positive(0.05, 0.6);
    Real worstSeparation = 0, worstNormal = 0, worstPoint = 0;
    int compared = 0;
    for (int trial = 0; trial < 30000; ++trial) {
        const int kind = trial % 3;  // sphere-sphere, sphere-capsule, capsule-capsule
        const Real radiusA = positive(rng), radiusB = positive(rng);
        const Real halfA = kind == 2 ? positive(rng) : 0, halfB = kind >= 1 ? positive(rng) : 0;
        const Transform poseA =
            at(Vec3(uniform(rng), uniform(rng), uniform(rng)), Quat::UnitRandom());
        const Transform poseB =
            at(Vec3(uniform(rng), uniform(rng), uniform(rng)), Quat::UnitRandom());
        const Shape a = kind == 2 ? Shape(Capsule{radiusA, halfA}) : Shape(Sphere{radiusA});
        const Shape b = kind >= 1 ? Shape(Capsule{radiusB, halfB}) : Shape(Sphere{radiusB});
        const Vec3 axisA = poseA.rotation * Vec3::UnitZ(), axisB = poseB.rotation * Vec3::UnitZ();
        if (kind == 2 && axisA.cross(axisB).norm() < 0.025)
            continue;  // the two-point case (kParallelSine 0.02), below
        const Closest c =
            closestSegments(poseA.position - halfA * axisA, poseA.position + halfA * axisA,
                            poseB.position - halfB * axisB, poseB.position + halfB * axisB);
        const Real distance = (c.b - c.a).norm();
        const Vec3 normal = (c.b - c.a) / distance;
        const Real separation = distance - radiusA - radiusB;
        const Vec3 point = (c.a + radiusA * normal + c.b - radiusB * normal) / 2;
        const Manifold m = collided(a, poseA, b, poseB, 10.0);
        ASSERT_EQ(m.pointCount, 1);
        worstSeparation = std::max(worstSeparation, std::abs(m.points[0].separation - separation));
        worstNormal = std::max(worstNormal, (m.normal - normal).norm());
        worstPoint = std::max(worstPoint, (m.points[0].position - point).norm());
        ++compared;
        // A beyond-margin configuration gives nothing.
        if (separation > 0.01) {
            EXPECT_EQ(collided(a, poseA, b, poseB, separation - 1e-9).pointCount, 0);
        }
    }
    std::printf("%d round pairs: max error separation %.2e, normal %.2e, point %.2e\n", compared,
                worstSeparation, worstNormal, worstPoint);
    EXPECT_GT(compared, 29000);
    EXPECT_LT(worstSeparation, 1e-9);
    EXPECT_LT(worstNormal, 1e-9);
    EXPECT_LT(worstPoint, 1e-9);
}

TEST(NarrowphaseRound, ParallelCapsulesTouchAtBothEndsOfTheOverlap) {
    // Capsule B (half length 1) lies on capsule A (half length 0.5), shifted 0.8 along x: the
    // overlap of the axes is x in [-0.2, 0.5].
    const Quat alongX = about(Vec3::UnitY(), kPi / 2);
    for (Real gap : {0.0, -2e-3, 0.01}) {
        const Manifold m = collided(Capsule{0.2, 0.5}, at(Vec3::Zero(), alongX), Capsule{0.3, 1.0},
                                    at(Vec3(0.8, 0, 0.5 + gap), alongX));
        ASSERT_EQ(m.pointCount, 2);
        EXPECT_NEAR((m.normal - Vec3::UnitZ()).norm(), 0, 1e-12);
        for (Real x : {-0.2, 0.5}) {
            const ContactPoint& p =
                m.points[static_cast<std::size_t>(nearestPoint(m, Vec3(x, 0, 0.2)))];
            EXPECT_NEAR((p.position - Vec3(x, 0, 0.2 + gap / 2)).norm(), 0, 1e-12);
            EXPECT_NEAR(p.separation, gap, 1e-12);
        }
    }
}

TEST(NarrowphaseRound, SphereBoxOutsideAndInside) {
    const Shape box = Box{Vec3(0.5, 1, 1.5)};
    const Transform pose = at(Vec3(1, 0, 0), about(Vec3(0, 1, 1), 0.4));
    struct Case {
        Vec3 local, surface, outward;
    };
    const Real r = 0.25;
    const Case cases[] = {
        {Vec3(0.6, 0.2, 0.3), Vec3(0.5, 0.2, 0.3), Vec3::UnitX()},                // face
        {Vec3(0.6, 1.1, 0.3), Vec3(0.5, 1, 0.3), Vec3(1, 1, 0).normalized()},     // edge
        {Vec3(0.6, 1.1, -1.6), Vec3(0.5, 1, -1.5), Vec3(1, 1, -1).normalized()},  // corner
        {Vec3(0.1, 0.2, -1.3), Vec3(0.1, 0.2, -1.5), -Vec3::UnitZ()},             // inside
    };
    for (const Case& c : cases) {
        const Real depth =
            (c.local - c.surface).norm() * ((c.local - c.surface).dot(c.outward) > 0 ? 1 : -1);
        const Vec3 normal = -(pose.rotation * c.outward);
        const Manifold m = collided(Sphere{r}, at(pose.apply(c.local)), box, pose);
        ASSERT_EQ(m.pointCount, 1);
        EXPECT_NEAR(m.points[0].separation, depth - r, 1e-12);
        EXPECT_NEAR((m.normal - normal).norm(), 0, 1e-12);
        const Vec3 expected = (pose.apply(c.surface) + pose.apply(c.local) + r * normal) / 2;
        EXPECT_NEAR((m.points[0].position - expected).norm(), 0, 1e-12);
    }
}

// --- Other convex shapes on a half-space -------------------------------------------------------

// Two upright cylinders end to end, as a falling one first overlapped a resting one in a
// simulation (poses recorded from it): libccd's EPA returned the downward axis with a 1.2 m depth
// (the overlap measured the long way through). The contact must be the shallow one, normal up
// from A to B, and no deeper than the overlap of the end faces.
TEST(NarrowphaseConvex, CylindersEndToEndGiveTheShallowAxis) {
    const Cylinder cylinder{0.2, 0.3};
    const Transform poseA{
        Vec3(3.0425533561328604e-05, -5.4099856965131686e-07, 0.29999692841674352),
        Quat(0.99999999964244313, 6.5505932426274488e-07, 2.6717808593443831e-05,
             -9.183290702219679e-07)};
    const Transform poseB{Vec3(0.050063006373822633, -8.5949171430165278e-07, 0.8999942557537437),
                          Quat(0.99999999964265096, 6.5510122240661041e-07, 2.6717807769644303e-05,
                               6.5418943194509957e-07)};
    const Manifold m = collided(cylinder, poseA, cylinder, poseB);
    ASSERT_GT(m.pointCount, 0);
    EXPECT_GT(m.normal.z(), 0.999);
    for (int i = 0; i < m.pointCount; ++i)
        EXPECT_GT(m.points[i].separation, -1e-3);
}

TEST(NarrowphaseHalfSpace, CapsuleCylinderAndHull) {
    const Shape ground = HalfSpace{};
    // Capsule lying: both ends; standing: the lower end only.
    const Quat alongX = about(Vec3::UnitY(), kPi / 2);
    EXPECT_EQ(collided(Capsule{0.2, 0.5}, at(Vec3(0, 0, 0.2), alongX), ground, at(Vec3::Zero()))
                  .pointCount,
              2);
    const Manifold standing =
        collided(Capsule{0.2, 0.5}, at(Vec3(0, 0, 0.69)), ground, at(Vec3::Zero()));
    ASSERT_EQ(standing.pointCount, 1);
    EXPECT_NEAR(standing.points[0].separation, -0.01, 1e-12);
    // Cylinder standing flat: 4 rim points at separation -1e-3.
    const Manifold flat =
        collided(Cylinder{0.4, 0.3}, at(Vec3(1, 1, 0.299)), ground, at(Vec3::Zero()));
    ASSERT_EQ(flat.pointCount, 4);
    for (int i = 0; i < 4; ++i) {
        EXPECT_NEAR(flat.points[static_cast<std::size_t>(i)].separation, -1e-3, 1e-12);
        EXPECT_NEAR((flat.points[static_cast<std::size_t>(i)].position - Vec3(1, 1, -5e-4)).norm(),
                    0.4, 1e-12);
    }
    // Tilted by 0.3 rad about x, resting on its lowest rim point.
    const Quat tilt = about(Vec3::UnitX(), 0.3);
    const Real lowest = 0.3 * std::cos(0.3) + 0.4 * std::sin(0.3);
    const Manifold leaning =
        collided(Cylinder{0.4, 0.3}, at(Vec3(0, 0, lowest - 1e-3), tilt), ground, at(Vec3::Zero()));
    ASSERT_EQ(leaning.pointCount, 1);
    EXPECT_NEAR(leaning.points[0].separation, -1e-3, 1e-12);
    EXPECT_NEAR(leaning.points[0].position.x(), 0, 1e-12);
    // Lying on its side: the lowest point of each rim.
    const Manifold lying =
        collided(Cylinder{0.4, 0.3}, at(Vec3(0, 0, 0.4), alongX), ground, at(Vec3::Zero()));
    ASSERT_EQ(lying.pointCount, 2);
    EXPECT_NEAR(std::abs(lying.points[0].position.x() - lying.points[1].position.x()), 0.6, 1e-12);
    // A 12-sided prism lying on a face: its 12 lower vertices reduced to 4 of largest area.
    std::vector<Vec3> vertices;
    for (int i = 0; i < 12; ++i)
        for (Real z : {-0.2, 0.2})
            vertices.emplace_back(std::cos(2 * kPi * i / 12), std::sin(2 * kPi * i / 12), z);
    const Shape prism = ConvexHull::fromPoints(vertices);
    const Manifold onFace = collided(prism, at(Vec3(0, 0, 0.2)), ground, at(Vec3::Zero()));
    ASSERT_EQ(onFace.pointCount, 4);
    std::vector<P2> lower;
    for (int i = 0; i < 12; ++i)
        lower.emplace_back(std::cos(2 * kPi * i / 12), std::sin(2 * kPi * i / 12));
    EXPECT_NEAR(manifoldAreaXY(onFace) / bestFourArea(lower), 1, 1e-9);  // greedy finds the square
    // Tilted prism: its deepest vertex is kept.
    const Manifold tipped =
        collided(prism, at(Vec3(0, 0, 0.2), about(Vec3(1, 2, 0), 0.01)), ground, at(Vec3::Zero()));
    Real deepest = 1;
    for (const Vec3& v : vertices)
        deepest = std::min(deepest, (about(Vec3(1, 2, 0), 0.01) * v).z() + 0.2);
    Real kept = 1;
    for (int i = 0; i < tipped.pointCount; ++i)
        kept = std::min(kept, tipped.points[static_cast<std::size_t>(i)].separation);
    EXPECT_NEAR(kept, deepest, 1e-12);
    // Half-space against half-space: nothing.
    EXPECT_EQ(collided(ground, at(Vec3::Zero()), ground, at(Vec3(0, 0, -1))).pointCount, 0);
}

// --- Feature ids under jitter
// ---------------------------------------------------------------------

TEST(NarrowphaseFeatureIds, RestingBoxKeepsIdsUnderJitter) {
    const Shape box = Box{};
    const Shape ground = HalfSpace{};
    const Quat twist = about(Vec3::UnitZ(), kPi / 6);
    const std::vector<std::uint32_t> onGround =
        sortedIds(collided(box, at(Vec3(0, 0, 0.5)), ground, at(Vec3::Zero())));
    const std::vector<std::uint32_t> onBox =
        sortedIds(collided(box, at(Vec3::Zero()), box, at(Vec3(0, 0, 1))));
    const std::vector<std::uint32_t> twisted =
        sortedIds(collided(box, at(Vec3::Zero()), box, at(Vec3(0, 0, 1), twist)));
    ASSERT_EQ(onGround.size(), 4u);
    ASSERT_EQ(onBox.size(), 4u);
    ASSERT_EQ(twisted.size(), 4u);
    std::mt19937 rng(3);
    std::uniform_real_distribution<Real> jitter(-1e-6, 1e-6);
    for (int i = 0; i < 100; ++i) {
        const Vec3 shift(jitter(rng), jitter(rng), jitter(rng));
        const Quat turn = Quat(
            Eigen::AngleAxis<Real>(1e-6, Vec3(jitter(rng), jitter(rng), jitter(rng)).normalized()));
        EXPECT_EQ(
            sortedIds(collided(box, at(Vec3(0, 0, 0.5) + shift, turn), ground, at(Vec3::Zero()))),
            onGround);
        EXPECT_EQ(sortedIds(collided(box, at(Vec3::Zero()), box, at(Vec3(0, 0, 1) + shift, turn))),
                  onBox);
        EXPECT_EQ(sortedIds(collided(box, at(Vec3::Zero()), box,
                                     at(Vec3(0, 0, 1) + shift, turn * twist))),
                  twisted);
    }
}

// A body settling in a pile rocks by ~1e-5 rad: its flush face's points then differ in depth by
// ~1e-5 m. A face of more than 4 points (a twisted box's octagon, a hexagonal hull face) must keep
// the same 4, or the contact ids flip step to step and the pile never sleeps (soak.pile-sleeps).
TEST(NarrowphaseFeatureIds, FlushFacesOfManyPointsKeepIdsWhileRocking) {
    const Shape box = Box{};
    const Shape ground = HalfSpace{};
    std::vector<Vec3> prism;
    for (int k = 0; k < 6; ++k)
        for (const Real z : {-0.25, 0.25})
            prism.emplace_back(0.5 * std::cos(kPi * k / 3), 0.5 * std::sin(kPi * k / 3), z);
    const Shape hull = ConvexHull::fromPoints(prism);
    const Quat twist = about(Vec3::UnitZ(), 0.35);
    struct Pair {
        const Shape& a;
        Transform poseA;
        const Shape& b;
        Transform poseB;
    };
    const std::array<Pair, 3> pairs{{{box, at(Vec3::Zero()), box, at(Vec3(0, 0, 1), twist)},
                                     {hull, at(Vec3(0, 0, 0.25)), ground, at(Vec3::Zero())},
                                     {box, at(Vec3::Zero()), hull, at(Vec3(0, 0, 0.75))}}};
    std::mt19937 rng(5);
    std::uniform_real_distribution<Real> uniform(-1, 1);
    for (const Pair& pair : pairs) {
        const std::vector<std::uint32_t> resting =
            sortedIds(collided(pair.a, pair.poseA, pair.b, pair.poseB));
        ASSERT_EQ(resting.size(), 4u);
        int flips = 0;
        for (int i = 0; i < 200; ++i) {
            const Quat rock(Eigen::AngleAxis<Real>(
                1e-5, Vec3(uniform(rng), uniform(rng), uniform(rng)).normalized()));
            const Transform rocked{pair.poseA.position, rock * pair.poseA.rotation};
            flips += sortedIds(collided(pair.a, rocked, pair.b, pair.poseB)) != resting;
        }
        EXPECT_EQ(flips, 0) << "pair " << (&pair - pairs.data());
    }
}

// --- Dispatch: swapped order
// ----------------------------------------------------------------------

TEST(NarrowphaseDispatch, SwappedOrderFlipsTheNormalAndKeepsThePoints) {
    const Quat tilt = about(Vec3(1, 2, 3), 0.4);
    struct Pair {
        Shape a;
        Transform poseA;
        Shape b;
        Transform poseB;
    };
    const Pair pairs[] = {
        {Sphere{0.5}, at(Vec3(0.1, 0.2, 0.3)), Capsule{0.3, 0.4}, at(Vec3(0.4, 0.5, 0.6), tilt)},
        {Sphere{0.5}, at(Vec3(0.1, 0.2, 0.9)), Box{}, at(Vec3(0, 0, 0), tilt)},
        {Box{}, at(Vec3(0, 0, 0.55), tilt), HalfSpace{}, at(Vec3::Zero())},
        {Capsule{0.2, 0.5}, at(Vec3(0, 0, 0.2), tilt), HalfSpace{}, at(Vec3::Zero())},
        {Cylinder{0.4, 0.3}, at(Vec3(0, 0, 0.35), tilt), HalfSpace{}, at(Vec3::Zero())},
        {Box{}, at(Vec3::Zero()), Box{Vec3(0.3, 0.4, 0.5)}, at(Vec3(0.1, 0.2, 0.99))},
    };
    for (const Pair& p : pairs) {
        const Manifold forward = collided(p.a, p.poseA, p.b, p.poseB);
        const Manifold backward = collided(p.b, p.poseB, p.a, p.poseA);
        ASSERT_GT(forward.pointCount, 0);
        ASSERT_EQ(forward.pointCount, backward.pointCount);
        EXPECT_NEAR((forward.normal + backward.normal).norm(), 0, 1e-12);
        for (int i = 0; i < forward.pointCount; ++i) {
            const ContactPoint& f = forward.points[static_cast<std::size_t>(i)];
            const ContactPoint& g =
                backward.points[static_cast<std::size_t>(nearestPoint(backward, f.position))];
            EXPECT_NEAR((f.position - g.position).norm(), 0, 1e-12);
            EXPECT_NEAR(f.separation, g.separation, 1e-12);
            // Same-type pairs may pick the reference face on the other box: same points, other ids.
            if (typeOf(p.a) != typeOf(p.b)) {
                EXPECT_EQ(f.featureId, g.featureId);
            }
        }
    }
}

}  // namespace
}  // namespace tumble
