// Cylinder caps nearly parallel to a face: the manifold must be a supporting polygon (several
// points) with the true depth, not one rim point the upper body rocks on.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <vector>

#include "exact_support.h"
#include "tumble/collision/narrowphase.h"

namespace tumble {
namespace {

constexpr Real kPi = std::numbers::pi;
constexpr Real kDegree = kPi / 180;
constexpr Real kMargin = 0.02;
/// The soak's stacked cylinder.
const Cylinder kCylinder{0.14, 0.1};

Transform pose(Real px, Real py, Real pz, Real qw, Real qx, Real qy, Real qz) {
    return {Vec3(px, py, pz), Quat(qw, qx, qy, qz).normalized()};
}
Quat about(const Vec3& axis, Real angle) {
    return Quat(Eigen::AngleAxis<Real>(angle, axis.normalized()));
}
using test::cylinderSupport;
/// Separation of two cylinders along n (A to B): negative overlap of their projections.
Real separationAlong(const Cylinder& a, const Transform& poseA, const Cylinder& b,
                     const Transform& poseB, const Vec3& n) {
    return n.dot(cylinderSupport(b, poseB, -n)) - n.dot(cylinderSupport(a, poseA, n));
}
Real deepest(const Manifold& m) {
    Real s = m.points[0].separation;
    for (int i = 1; i < m.pointCount; ++i)
        s = std::min(s, m.points[static_cast<std::size_t>(i)].separation);
    return s;
}
/// Widest distance between two manifold points, in the contact plane.
Real spread(const Manifold& m) {
    Real widest = 0;
    for (int i = 0; i < m.pointCount; ++i)
        for (int j = 0; j < i; ++j) {
            const Vec3 d = m.points[static_cast<std::size_t>(i)].position -
                           m.points[static_cast<std::size_t>(j)].position;
            widest = std::max(widest, (d - d.dot(m.normal) * m.normal).norm());
        }
    return widest;
}
/// Caps are 16-gons inscribed in the rim, which cut up to w = r (1 - cos(pi/16)) off the disc.
/// Where the incident rim's deepest point falls between two vertices, the manifold's deepest
/// point is shallower by up to w sin(tilt); where the reference polygon's side cuts off the
/// incident cap's deepest part, by up to w tan(tilt) more (tilt: the angle between the caps).
Real polygonError(const Cylinder& c, Real tilt) {
    return c.radius * (1 - std::cos(kPi / 16)) * (std::sin(tilt) + std::tan(tilt)) + 1e-6;
}

void expectCapManifold(const Transform& poseA, const Transform& poseB, bool stableIds = true) {
    Manifold m;
    collide(kCylinder, poseA, kCylinder, poseB, kMargin, m);
    ASSERT_GE(m.pointCount, 3);
    const Real exact = separationAlong(kCylinder, poseA, kCylinder, poseB, m.normal);
    const Vec3 zA = poseA.rotation * Vec3::UnitZ(), zB = poseB.rotation * Vec3::UnitZ();
    const Real tilt = std::acos(std::min<Real>(1, std::abs(zA.dot(zB))));
    // No point deeper than the overlap along the normal, the deepest one at it.
    for (int i = 0; i < m.pointCount; ++i)
        EXPECT_GE(m.points[static_cast<std::size_t>(i)].separation, exact - 1e-6);
    EXPECT_NEAR(deepest(m), exact, polygonError(kCylinder, tilt));
    // A supporting polygon, not a cluster at one rim point.
    EXPECT_GT(spread(m), kCylinder.radius);
    if (!stableIds)
        return;
    // The same points (ids) one step later, after a tiny motion.
    Transform movedB = poseB;
    movedB.position += Vec3(1e-7, -1e-7, 1e-7);
    Manifold again;
    collide(kCylinder, poseA, kCylinder, movedB, kMargin, again);
    ASSERT_EQ(again.pointCount, m.pointCount);
    for (int i = 0; i < m.pointCount; ++i)
        EXPECT_EQ(again.points[static_cast<std::size_t>(i)].featureId,
                  m.points[static_cast<std::size_t>(i)].featureId);
}

// Three pairs from the 5,000-body soak (bench/soak.cpp), where cylinders stacked cap on cap
// overlapped by 0.11-0.13 m with a one-point manifold; caps 2.0, 5.8 and 6.8 degrees apart.
TEST(CylinderCapManifold, SoakPairsGetASupportingPolygonAtTheTrueDepth) {
    expectCapManifold(
        pose(-0.33310285160025471, 2.471605348975189, 0.099365513586335982, 0.75288921134484421,
             -0.0024346161092589961, 0.00012211331926959091, -0.65814276048079146),
        pose(-0.36321999015333906, 2.4391591606809784, 0.18949435105384466, 0.35290044684949723,
             0.015273495923621344, 0.00029221768638531403, -0.93553616153760744));
    expectCapManifold(
        pose(-0.39807245226446247, -0.65179360764982663, 1.2935599629963097, 0.89032440890412567,
             -0.092840467146555999, 0.12174713034439032, 0.42881316540240988),
        pose(-0.36951429156293314, -0.6407042199659182, 1.3947737999978624, -0.019871015475449966,
             0.043112224755538012, 0.17637416683916365, 0.98317782323056568));
    expectCapManifold(
        pose(-0.36951429156293314, -0.6407042199659182, 1.3947737999978624, -0.019871015475449966,
             0.043112224755538012, 0.17637416683916365, 0.98317782323056568),
        pose(-0.40916955947763334, -0.66734959960088391, 1.50224477146424, 0.98906080574082367,
             -0.12853089745352878, 0.06910431537110058, -0.021520328626547559));
}

// Two upright cylinders whose caps are 2 degrees apart, the upper one's lowest rim point 1 mm
// deep: the lower one upright, tilted 0.5 degrees and tilted 1 degree (the upper one 1 degree
// the other way). That last pair is symmetric, and its depth is the same along either cap's
// normal and along z: the query normal jumps among the three under 1e-7 m of motion, so its ids
// are not checked (the reference face, and so the ids, follow the normal).
TEST(CylinderCapManifold, CapsTwoDegreesApartGetSeveralPoints) {
    const Real h = kCylinder.halfLength, r = kCylinder.radius;
    for (const Real lowerTilt : {0.0, -0.5, -1.0}) {
        SCOPED_TRACE(lowerTilt);
        const Real upperTilt = lowerTilt + 2;
        const Transform lower{Vec3::Zero(), about(Vec3::UnitX(), lowerTilt * kDegree)};
        const Real top =
            h * std::cos(lowerTilt * kDegree) + r * std::sin(std::abs(lowerTilt) * kDegree);
        const Real height =
            top + h * std::cos(upperTilt * kDegree) + r * std::sin(upperTilt * kDegree) - 1e-3;
        const Transform upper{Vec3(0, 0, height), about(Vec3::UnitX(), upperTilt * kDegree)};
        expectCapManifold(lower, upper, lowerTilt != -1.0);
    }
}

// A rim contact stays right: a cylinder 30 degrees from upright with its rim in a box face keeps
// the single witness point at the true depth; at 10 degrees the cap is clipped and its deepest
// point stays within the polygon's error of the true depth.
TEST(CylinderCapManifold, RimOnABoxFaceKeepsTheTrueDepth) {
    const Box box{Vec3(1, 1, 0.5)};
    const Transform boxPose{Vec3(0, 0, -0.5), Quat::Identity()};
    const Real h = kCylinder.halfLength, r = kCylinder.radius;
    for (const Real tilt : {30 * kDegree, 10 * kDegree}) {
        SCOPED_TRACE(tilt);
        const Real lowest = h * std::cos(tilt) + r * std::sin(tilt);
        const Transform cylinderPose{Vec3(0, 0, lowest - 2e-3), about(Vec3::UnitY(), tilt)};
        Manifold m;
        collide(box, boxPose, kCylinder, cylinderPose, kMargin, m);
        ASSERT_GE(m.pointCount, 1);
        EXPECT_GT(m.normal.z(), 1 - 1e-9);
        EXPECT_NEAR(deepest(m), -2e-3, polygonError(kCylinder, tilt));
        for (int i = 0; i < m.pointCount; ++i)
            EXPECT_GE(m.points[static_cast<std::size_t>(i)].separation, -2e-3 - 1e-6);
        if (tilt < 15 * kDegree) {
            EXPECT_GE(m.pointCount, 3);
        }
    }
}

}  // namespace
}  // namespace tumble
