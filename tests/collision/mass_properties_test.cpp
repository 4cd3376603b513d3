// Mass properties against textbook closed forms, and polyhedral integration against them.

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <limits>
#include <numbers>
#include <random>
#include <string>
#include <vector>

#include "refusal.h"
#include "tumble/collision/shape.h"
#include "tumble/core/error.h"

namespace tumble {
namespace {

using test::contains;
using test::refusal;

constexpr Real kPi = std::numbers::pi;

/// Relative agreement of mass, centre (relative to `length`) and inertia (relative to its norm).
::testing::AssertionResult sameMass(const MassProperties& actual, const MassProperties& expected,
                                    Real length, Real tolerance) {
    const Real massError = std::abs(actual.mass - expected.mass) / expected.mass;
    const Real centerError = (actual.localCenter - expected.localCenter).norm() / length;
    const Real inertiaError = (actual.inertia - expected.inertia).norm() / expected.inertia.norm();
    if (massError <= tolerance && centerError <= tolerance && inertiaError <= tolerance)
        return ::testing::AssertionSuccess();
    return ::testing::AssertionFailure()
           << "relative errors: mass " << massError << ", centre " << centerError << ", inertia "
           << inertiaError << "\nactual inertia\n"
           << actual.inertia << "\nexpected\n"
           << expected.inertia;
}

MassProperties expected(Real mass, const Vec3& center, const Mat3& inertia) {
    MassProperties out;
    out.mass = mass;
    out.localCenter = center;
    out.inertia = inertia;
    return out;
}

std::vector<Vec3> boxCorners(const Vec3& halfExtents, const Transform& pose) {
    std::vector<Vec3> corners;
    for (int i = 0; i < 8; ++i) {
        const Vec3 sign((i & 1) ? 1 : -1, (i & 2) ? 1 : -1, (i & 4) ? 1 : -1);
        corners.push_back(pose.apply(sign.cwiseProduct(halfExtents)));
    }
    return corners;
}

TEST(MassOf, SphereBoxCylinderMatchTextbookFormulas) {
    const Real density = 1250;
    const Real r = 0.3;
    const Real ms = density * 4.0 / 3.0 * kPi * r * r * r;
    EXPECT_TRUE(sameMass(massOf(Sphere{r}, density),
                         expected(ms, Vec3::Zero(), Mat3::Identity() * (2.0 / 5.0 * ms * r * r)), r,
                         1e-12));

    // Box of full sides a, b, c: I_x = m (b^2 + c^2) / 12.
    const Real a = 0.4, b = 1.2, c = 2.2;
    const Real mb = density * a * b * c;
    const Vec3 boxMoments(b * b + c * c, c * c + a * a, a * a + b * b);
    EXPECT_TRUE(sameMass(massOf(Box{Vec3(a, b, c) / 2}, density),
                         expected(mb, Vec3::Zero(), Mat3(boxMoments.asDiagonal()) * (mb / 12)), c,
                         1e-12));

    // Cylinder of radius r, length L about z: I_z = m r^2 / 2, I_x = m (3 r^2 + L^2) / 12.
    const Real length = 1.7;
    const Real mc = density * kPi * r * r * length;
    const Vec3 cylinderMoments(mc * (3 * r * r + length * length) / 12,
                               mc * (3 * r * r + length * length) / 12, mc * r * r / 2);
    EXPECT_TRUE(sameMass(massOf(Cylinder{r, length / 2}, density),
                         expected(mc, Vec3::Zero(), cylinderMoments.asDiagonal()), length, 1e-12));
}

TEST(MassOf, CapsuleMatchesCylinderPlusTwoHemispheres) {
    // The standard capsule formula with cylinder height H and radius r, masses m_c (cylinder) and
    // m_h (each hemisphere):  I_z = m_c r^2 / 2 + 2 m_h (2 r^2 / 5),
    // I_x = m_c (H^2 / 12 + r^2 / 4) + 2 m_h (2 r^2 / 5 + H^2 / 4 + 3 H r / 8).
    const Real density = 900;
    const Real r = 0.25;
    const Real height = 1.4;
    const Real mc = density * kPi * r * r * height;
    const Real mh = density * 2.0 / 3.0 * kPi * r * r * r;
    const Real axial = mc * r * r / 2 + 2 * mh * (2 * r * r / 5);
    const Real transverse = mc * (height * height / 12 + r * r / 4) +
                            2 * mh * (2 * r * r / 5 + height * height / 4 + 3 * height * r / 8);
    EXPECT_TRUE(sameMass(
        massOf(Capsule{r, height / 2}, density),
        expected(mc + 2 * mh, Vec3::Zero(), Vec3(transverse, transverse, axial).asDiagonal()),
        height, 1e-12));
    // No segment: a sphere.
    EXPECT_TRUE(sameMass(massOf(Capsule{r, 0}, density), massOf(Sphere{r}, density), r, 1e-12));
}

TEST(MassOf, HullOfBoxCornersEqualsTheBox) {
    const Vec3 halfExtents(0.3, 0.8, 1.9);
    const Transform pose{Vec3(4, -2, 7), Quat(0.9, 0.1, -0.3, 0.2).normalized()};
    const ConvexHull hull = ConvexHull::fromPoints(boxCorners(halfExtents, pose));
    const MassProperties box = transformed(massOf(Box{halfExtents}, 700), pose);
    EXPECT_TRUE(sameMass(massOf(hull, 700), box, 2 * halfExtents.maxCoeff(), 1e-12));
    EXPECT_TRUE(hull.data->centroid.isApprox(pose.position, 1e-14));
}

TEST(MassOf, HullOfRightTetrahedronMatchesClosedForm) {
    // Tetrahedron (0, a e_x, b e_y, c e_z): volume abc/6; about the origin, the integral of x^2
    // is V a^2 / 10 and of x y is V a b / 20; the centroid is (a, b, c) / 4.
    const Real a = 1.5, b = 0.7, c = 2.3;
    const std::array<Vec3, 4> points = {Vec3::Zero(), Vec3(a, 0, 0), Vec3(0, b, 0), Vec3(0, 0, c)};
    const MassProperties hull = massOf(ConvexHull::fromPoints(points), 1);
    const Real volume = a * b * c / 6;
    const Vec3 sides(a, b, c);
    Mat3 second = volume / 20 * sides * sides.transpose();
    second.diagonal() = volume / 10 * sides.cwiseProduct(sides);
    const Vec3 center = sides / 4;
    const Mat3 central = second - volume * center * center.transpose();
    const Mat3 inertia = central.trace() * Mat3::Identity() - central;
    EXPECT_TRUE(sameMass(hull, expected(volume, center, inertia), c, 1e-12));
    EXPECT_NE(inertia(0, 1), 0) << "the case exercises products of inertia";
}

/// A hull of points on a sphere lies between the ball of its smallest face distance and the
/// sphere: its mass and every diagonal moment are bounded by those two balls' (each moment is an
/// integral of a non-negative function over the solid, so grows with the solid).
TEST(MassOf, HullOfSampledSphereApproachesTheSphere) {
    const Real r = 0.8;
    const int count = 2000;
    std::vector<Vec3> points;
    const Real golden = kPi * (3 - std::sqrt(5.0));
    for (int i = 0; i < count; ++i) {  // Fibonacci sphere: near-uniform directions
        const Real z = 1 - (2 * i + 1) / Real(count);
        const Real rho = std::sqrt(1 - z * z);
        points.push_back(r * Vec3(rho * std::cos(golden * i), rho * std::sin(golden * i), z));
    }
    const ConvexHull hull = ConvexHull::fromPoints(points);
    Real inner = r;
    for (const HullFace& face : hull.data->faces)
        inner = std::min(inner, face.offset);
    EXPECT_GT(inner, r * (1 - 2e-3)) << "2,000 points sample the sphere to 0.2%";

    const MassProperties mass = massOf(hull, 1);
    const MassProperties outer = massOf(Sphere{r}, 1);
    const MassProperties innerBall = massOf(Sphere{inner}, 1);
    EXPECT_LT(mass.mass, outer.mass);
    EXPECT_GT(mass.mass, innerBall.mass);
    for (int i = 0; i < 3; ++i) {
        EXPECT_LT(mass.inertia(i, i), outer.inertia(i, i));
        EXPECT_GT(mass.inertia(i, i), innerBall.inertia(i, i));
    }
    EXPECT_LT(mass.localCenter.norm(), r * 1e-3);
    std::printf("[ measured ] sampled sphere (%d points): mass error %.2e relative\n", count,
                1 - mass.mass / outer.mass);
}

TEST(Combine, TwoOffsetBoxesMakeTheUnionBox) {
    // Boxes spanning x in [-1, 0.2] and [0.2, 1.5] with the same y, z section make the box
    // spanning [-1, 1.5], centred at x = 0.25.
    const Real density = 300;
    const Vec3 section(0, 0.35, 0.6);
    const MassProperties left =
        transformed(massOf(Box{Vec3(0.6, 0, 0) + section}, density), Transform{Vec3(-0.4, 0, 0)});
    const MassProperties right =
        transformed(massOf(Box{Vec3(0.65, 0, 0) + section}, density), Transform{Vec3(0.85, 0, 0)});
    const std::array<MassProperties, 2> parts = {left, right};
    const MassProperties whole =
        transformed(massOf(Box{Vec3(1.25, 0, 0) + section}, density), Transform{Vec3(0.25, 0, 0)});
    EXPECT_TRUE(sameMass(combine(parts), whole, 2.5, 1e-12));
}

TEST(Combine, RefusesZeroTotalMassAndNonFiniteParts) {
    EXPECT_TRUE(
        contains(refusal([] { combine({}); }), "total mass = 0 kg over 0 parts must be > 0"));
    MassProperties bad;
    bad.mass = std::numeric_limits<Real>::quiet_NaN();
    const std::array<MassProperties, 2> parts = {MassProperties{}, bad};
    EXPECT_TRUE(contains(refusal([&] { combine(parts); }), "parts[1]"));
}

TEST(Transformed, RotatedBoxMatchesTheHullOfItsRotatedCorners) {
    const Vec3 halfExtents(0.5, 0.2, 1.1);
    const Transform pose{Vec3(-3, 1, 0.5),
                         Quat(Eigen::AngleAxis<Real>(0.7, Vec3(1, 2, 3).normalized()))};
    const MassProperties moved = transformed(massOf(Box{halfExtents}, 1000), pose);
    const MassProperties hull = massOf(ConvexHull::fromPoints(boxCorners(halfExtents, pose)), 1000);
    EXPECT_TRUE(sameMass(moved, hull, 2.2, 1e-12));
    EXPECT_EQ(moved.inertia, moved.inertia.transpose());
    EXPECT_NE(moved.inertia(0, 1), 0) << "rotation mixes the axes";
}

TEST(MassOf, RefusesBadDensityHalfSpaceAndBadShapes) {
    EXPECT_TRUE(contains(refusal([] { massOf(Sphere{1}, 0); }),
                         "density = 0 kg/m^3 must be finite and > 0"));
    EXPECT_TRUE(contains(refusal([] { massOf(Box{}, -5); }), "density = -5"));
    EXPECT_TRUE(contains(refusal([] { massOf(Box{}, std::numeric_limits<Real>::infinity()); }),
                         "density = inf"));
    EXPECT_TRUE(contains(refusal([] { massOf(HalfSpace{}, 1000); }), "no finite mass"));
    EXPECT_TRUE(contains(refusal([] {
                             massOf(Capsule{0, 1}, 1000);
                         }),
                         "massOf: Capsule.radius = 0"));
}

}  // namespace
}  // namespace tumble
