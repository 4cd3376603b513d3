// Nearly parallel segment features -- a cylinder's side line, a capsule's core -- touch along a
// line: the manifold has two points, at the ends of the overlap, with the true depth. One witness
// point there runs the whole overlap for a small turn of the axes, and a cylinder lying on a
// capsule in the soak's pile rocked on one end, then the other, every step, for good.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <random>
#include <variant>

#include "exact_support.h"
#include "tumble/collision/narrowphase.h"
#include "tumble/world.h"

namespace tumble {
namespace {

constexpr Real kDegree = std::numbers::pi / 180;
constexpr Real kMargin = 0.02;

/// The exact support point of a cylinder or a capsule (axis z in its frame).
Vec3 support(const Shape& shape, const Transform& t, const Vec3& direction) {
    const Vec3 d = t.rotation.conjugate() * direction;
    if (const auto* capsule = std::get_if<Capsule>(&shape)) {
        const Vec3 end(0, 0, d.z() >= 0 ? capsule->halfLength : -capsule->halfLength);
        return t.apply(end + capsule->radius * d.normalized());
    }
    return test::cylinderSupport(std::get<Cylinder>(shape), t, direction);
}

Real radiusOf(const Shape& shape) {
    if (const auto* capsule = std::get_if<Capsule>(&shape))
        return capsule->radius;
    return std::get<Cylinder>(shape).radius;
}

// Random poses of a pair lying side by side, axes up to 0.5 degrees apart, B pressed into A by
// up to 5 mm and slid along A's axis by up to half a length: two points, as far apart as the
// overlap, never deeper than the overlap of the pair's extents along the manifold's normal (the
// deepest any point can be; the local gaps at the ends are shallower when B, tilted, reaches
// past A's end), and at that depth exactly when the axes are parallel. Tolerances: 1e-9 m of
// rounding on the depths; the points' spread within the overlap by what turning B moves its ends
// sideways, 2 (half length + radius) sin(angle).
TEST(ParallelSegments, SideBySidePairsGetTwoPointsAtTheTrueDepth) {
    const Shape shapes[] = {Cylinder{0.14, 0.1}, Capsule{0.1, 0.1}};
    std::mt19937 random(20261128);
    std::uniform_real_distribution<Real> unit(-1, 1);
    int checked = 0;
    for (const Shape& a : shapes) {
        for (const Shape& b : shapes) {
            for (int trial = 0; trial < 200; ++trial) {
                // A lies along x; B beside it along -z (below), its axis turned by a small angle.
                const Real angle = trial < 20 ? 0 : 0.5 * kDegree * std::abs(unit(random));
                const Vec3 turnAxis = Vec3(0, unit(random), unit(random)).normalized();
                const Real depth = 0.005 * std::abs(unit(random));
                const Real slide = 0.1 * unit(random);
                const Quat alongX = Quat::FromTwoVectors(Vec3::UnitZ(), Vec3::UnitX());
                const Transform local{Vec3::Zero(), alongX};
                const Real gap = radiusOf(a) + radiusOf(b) - depth;
                const Transform localB{Vec3(slide, 0, -gap),
                                       Quat(Eigen::AngleAxis<Real>(angle, turnAxis)) * alongX};
                // The whole pair turned and moved anywhere.
                const Quat frame =
                    Quat(unit(random), unit(random), unit(random), unit(random)).normalized();
                const Vec3 place(unit(random), unit(random), unit(random));
                const Transform poseA{frame * local.position + place, frame * local.rotation};
                const Transform poseB{frame * localB.position + place, frame * localB.rotation};
                Manifold m;
                collide(a, poseA, b, poseB, kMargin, m);
                ASSERT_EQ(m.pointCount, 2) << "trial " << trial << ", angle " << angle;
                const Vec3 n = m.normal;
                const Real exact = n.dot(support(b, poseB, -n)) - n.dot(support(a, poseA, n));
                const Real deepest = std::min(m.points[0].separation, m.points[1].separation);
                const Real overlap = 0.2 - std::abs(slide);  // both are 0.2 m long
                EXPECT_GE(deepest, exact - 1e-9) << "trial " << trial;
                if (angle == 0) {
                    EXPECT_NEAR(m.points[0].separation, -depth, 1e-9) << "trial " << trial;
                    EXPECT_NEAR(m.points[1].separation, -depth, 1e-9) << "trial " << trial;
                }
                const Vec3 apart = m.points[1].position - m.points[0].position;
                EXPECT_NEAR((apart - apart.dot(n) * n).norm(), overlap,
                            2 * (0.1 + radiusOf(b)) * std::sin(angle) + 1e-9)
                    << "trial " << trial;
                ++checked;
            }
        }
    }
    EXPECT_EQ(checked, 800);
}

// A cylinder lying in the groove of two capsules laid side by side comes to rest, at every small
// angle between its axis and theirs and at every density. With one point per capsule it was held
// on a line across its axis and see-sawed about it.
TEST(ParallelSegments, ACylinderInAGrooveOfCapsulesComesToRest) {
    for (const Real angle : {0.0, 0.1, 0.23, 0.5, 1.0}) {
        for (const Real density : {100.0, 700.0, 5000.0}) {
            WorldDef def{.timeStep = 1.0 / 60};
            def.enableSleep = false;
            World world(def);
            const Quat alongX = Quat::FromTwoVectors(Vec3::UnitZ(), Vec3::UnitX());
            const Material material{.friction = 0.5, .density = density};
            for (const Real y : {-0.12, 0.12}) {
                const BodyId log = world.createBody(BodyDef{
                    .type = BodyType::Static, .position = Vec3(0, y, 0.1), .orientation = alongX});
                world.createShape(log,
                                  ShapeDef{.geometry = Capsule{0.1, 0.1}, .material = material});
            }
            const Quat turned = Quat(Eigen::AngleAxis<Real>(angle * kDegree, Vec3::UnitZ())) *
                                Quat(Eigen::AngleAxis<Real>(0.3 * angle * kDegree, Vec3::UnitY())) *
                                alongX;
            // Resting on both: centre height where its side meets both capsules' surfaces.
            const Real z = 0.1 + std::sqrt(0.24 * 0.24 - 0.12 * 0.12) + 0.002;
            const BodyId cylinder =
                world.createBody(BodyDef{.position = Vec3(0.02, 0, z), .orientation = turned});
            world.createShape(cylinder,
                              ShapeDef{.geometry = Cylinder{0.14, 0.1}, .material = material});
            Real latest = 0;
            for (int step = 0; step < 240; ++step) {
                ASSERT_TRUE(world.step().ok());
                if (step >= 120) {
                    latest = std::max({latest, world.angularVelocity(cylinder).norm(),
                                       world.linearVelocity(cylinder).norm()});
                }
            }
            // Written before measuring: at rest within the solver's residual, 1e-3 (m/s, rad/s).
            EXPECT_LT(latest, 1e-3) << "angle " << angle << " deg, density " << density;
        }
    }
}

}  // namespace
}  // namespace tumble
