// GJK against cylinders, whose curved rim makes the simplex crowd into slivers near convergence:
// separations of spheres and capsules from cylinders against an independent reference, and the
// soak's capsule-cylinder pair that GJK once called overlapping 0.11 m apart.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <random>

#include "ccd_adapter.h"
#include "gjk.h"
#include "tumble/collision/narrowphase.h"

namespace tumble::detail {
namespace {

// Distance from point p (world) to the solid cylinder (m), 0 inside: closed form in its frame.
Real pointCylinderDistance(const Vec3& p, const Cylinder& cylinder, const Transform& pose) {
    const Vec3 local = pose.rotation.conjugate() * (p - pose.position);
    const Real radial = std::max<Real>(0, std::hypot(local.x(), local.y()) - cylinder.radius);
    const Real axial = std::max<Real>(0, std::abs(local.z()) - cylinder.halfLength);
    return std::hypot(radial, axial);
}

// Distance from the segment [p, q] to the cylinder: convex along the segment (a convex set's
// distance function is convex), so a golden-section search finds its minimum.
Real segmentCylinderDistance(const Vec3& p, const Vec3& q, const Cylinder& cylinder,
                             const Transform& pose) {
    const auto at = [&](Real t) { return pointCylinderDistance(p + t * (q - p), cylinder, pose); };
    const Real ratio = (std::sqrt(5.0) - 1) / 2;
    Real a = 0, b = 1;
    for (int i = 0; i < 200 && b - a > 1e-15; ++i) {
        const Real c = b - ratio * (b - a), d = a + ratio * (b - a);
        (at(c) < at(d) ? b : a) = at(c) < at(d) ? d : c;
    }
    return std::min({at(0), at(1), at(0.5 * (a + b))});
}

// Reference separation of a sphere or a capsule (local z axis) from a cylinder (m).
Real referenceSeparation(const Shape& rounded, const Transform& pose, const Cylinder& cylinder,
                         const Transform& cylinderPose) {
    if (const auto* sphere = std::get_if<Sphere>(&rounded))
        return pointCylinderDistance(pose.position, cylinder, cylinderPose) - sphere->radius;
    const auto& capsule = std::get<Capsule>(rounded);
    const Vec3 axis = pose.rotation * Vec3(0, 0, capsule.halfLength);
    return segmentCylinderDistance(pose.position - axis, pose.position + axis, cylinder,
                                   cylinderPose) -
           capsule.radius;
}

TEST(GjkCylinder, SoakCapsuleNearACylinderIsNotOverlapping) {
    // Bodies of the 500-body soak at t = 6.03 s: GJK's sliver simplex called the capsule's
    // segment and the cylinder overlapping, and the contact came out 0.1 m deep (the capsule's
    // radius) with the shapes 0.11 m apart; the solver then pushed on it every step.
    const Transform capsulePose{
        Vec3(-0.72672054082948001, -1.6689918481228279, 0.09667557592297793),
        Quat(0.69376140545580145, 0.59003816099776429, 0.40032919408080458, 0.10142296205978685)};
    const Transform cylinderPose{
        Vec3(-0.50476468539228392, -1.6191469701540169, 0.39786583116953617),
        Quat(-0.50392349122516344, 0.58437200796202426, -0.15338937185577203,
             -0.61728613454666748)};
    const Capsule capsule{0.1, 0.1};
    const Cylinder cylinder{0.14, 0.1};
    const Real expected = referenceSeparation(capsule, capsulePose, cylinder, cylinderPose);
    ASSERT_NEAR(expected, 0.110263, 1e-6);
    const CoreDistance core = coreDistance(capsule, capsulePose, cylinder, cylinderPose);
    EXPECT_FALSE(core.overlapping);
    EXPECT_NEAR(core.distance - capsule.radius, expected, 1e-9);
    Manifold manifold;
    collide(capsule, capsulePose, cylinder, cylinderPose, 0.05, manifold);
    EXPECT_EQ(manifold.pointCount, 0);  // beyond the margin
    collide(capsule, capsulePose, cylinder, cylinderPose, 0.2, manifold);
    ASSERT_EQ(manifold.pointCount, 1);
    EXPECT_NEAR(manifold.points[0].separation, expected, 1e-9);
}

TEST(GjkCylinder, SeparatedSpheresAndCapsulesMatchTheReference) {
    std::mt19937_64 engine{20261122};
    const auto uniform = [&](Real lo, Real hi) {
        return std::uniform_real_distribution<Real>(lo, hi)(engine);
    };
    const auto rotation = [&] {
        std::normal_distribution<Real> normal;
        return Quat(normal(engine), normal(engine), normal(engine), normal(engine)).normalized();
    };
    int compared = 0;
    Real worst = 0;
    for (int n = 0; n < 20000; ++n) {
        const Cylinder cylinder{uniform(0.05, 1), uniform(0.05, 1)};
        const Shape other = n % 2 == 0 ? Shape(Sphere{uniform(0.05, 1)})
                                       : Shape(Capsule{uniform(0.05, 1), uniform(0.05, 1)});
        const Transform cylinderPose{Vec3(uniform(-1, 1), uniform(-1, 1), uniform(-1, 1)),
                                     rotation()};
        const Transform pose{cylinderPose.position + uniform(0, 3) * (rotation() * Vec3::UnitX()),
                             rotation()};
        const Real expected = referenceSeparation(other, pose, cylinder, cylinderPose);
        if (expected + roundingRadius(other) <= 1e-6)
            continue;  // the core reaches the cylinder: a penetration, not a distance
        const ConvexContact contact = queryConvex(other, pose, cylinder, cylinderPose);
        const Real error = std::abs(contact.separation - expected);
        worst = std::max(worst, error);
        EXPECT_LE(error, 1e-7) << "pair " << n << ": " << contact.separation << " against "
                               << expected;
        ++compared;
    }
    EXPECT_GT(compared, 10000);
    std::printf("[ GJK ] %d sphere/capsule-cylinder pairs, max error %.3g m\n", compared, worst);
}

}  // namespace
}  // namespace tumble::detail
