// Shape checks, bounding boxes and support points, against closed forms.

#include <gtest/gtest.h>

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

Quat randomRotation(std::mt19937& rng) {
    std::normal_distribution<Real> normal;
    Quat q(normal(rng), normal(rng), normal(rng), normal(rng));
    q.normalize();
    return q;
}

Vec3 randomDirection(std::mt19937& rng) {
    std::normal_distribution<Real> normal;
    return Vec3(normal(rng), normal(rng), normal(rng)).normalized();
}

ConvexHull randomHull(std::mt19937& rng, int count) {
    std::uniform_real_distribution<Real> uniform(-1, 1);
    std::vector<Vec3> points;
    for (int i = 0; i < count; ++i)
        points.emplace_back(uniform(rng), 0.5 * uniform(rng), 2 * uniform(rng));
    return ConvexHull::fromPoints(points);
}

TEST(ShapeCheck, AcceptsValidShapes) {
    std::mt19937 rng(1);
    const std::vector<Shape> shapes = {Sphere{0.1},         Capsule{0.2, 0},
                                       Box{Vec3(1, 2, 3)},  Cylinder{0.3, 0.4},
                                       randomHull(rng, 20), HalfSpace{Vec3(0, 0.6, 0.8), -1}};
    for (const Shape& shape : shapes)
        EXPECT_NO_THROW(checkShape(shape, "test"));
}

TEST(ShapeCheck, RefusesBadDimensionsNamingFieldValueAndRule) {
    const std::string sphere = refusal([] { checkShape(Sphere{-0.5}, "ShapeDef.shape"); });
    EXPECT_TRUE(contains(sphere, "ShapeDef.shape: Sphere.radius = -0.5"));
    EXPECT_TRUE(contains(sphere, "must be finite and > 0"));

    const std::string capsule = refusal([] { checkShape(Capsule{0, 1}, "ShapeDef.shape"); });
    EXPECT_TRUE(contains(capsule, "Capsule.radius = 0"));
    EXPECT_TRUE(contains(capsule, "> 0"));
    EXPECT_TRUE(contains(refusal([] {
                             checkShape(Capsule{1, -0.1}, "w");
                         }),
                         "Capsule.halfLength = -0.1 m must be finite and >= 0"));

    EXPECT_TRUE(contains(refusal([] { checkShape(Box{Vec3(1, 0, 1)}, "w"); }),
                         "Box.halfExtents.y = 0 m must be finite and > 0"));
    EXPECT_TRUE(
        contains(refusal([] { checkShape(Box{Vec3(1, 1, -2)}, "w"); }), "Box.halfExtents.z = -2"));
    const Real nan = std::numeric_limits<Real>::quiet_NaN();
    EXPECT_TRUE(contains(refusal([&] { checkShape(Box{Vec3(nan, 1, 1)}, "w"); }),
                         "Box.halfExtents.x = nan"));
    EXPECT_TRUE(contains(refusal([] {
                             checkShape(Cylinder{1, 0}, "w");
                         }),
                         "Cylinder.halfLength = 0 m must be finite and > 0"));
    const Real inf = std::numeric_limits<Real>::infinity();
    EXPECT_TRUE(contains(refusal([&] {
                             checkShape(Cylinder{inf, 1}, "w");
                         }),
                         "Cylinder.radius = inf"));
}

TEST(ShapeCheck, RefusesNonUnitHalfSpaceNormalAndNullHull) {
    const std::string message = refusal([] {
        checkShape(HalfSpace{Vec3(0, 0, 2), 0}, "ShapeDef.shape");
    });
    EXPECT_TRUE(contains(message, "ShapeDef.shape: HalfSpace.normal = (0, 0, 2)"));
    EXPECT_TRUE(contains(message, "length 2"));
    EXPECT_TRUE(contains(message, "unit length"));
    // Within 1e-6 of unit length is accepted.
    EXPECT_NO_THROW(checkShape(HalfSpace{Vec3(0, 0, 1 + 5e-7), 0}, "w"));
    EXPECT_TRUE(contains(refusal([] {
                             checkShape(HalfSpace{Vec3(0, 0, 1 + 2e-6), 0}, "w");
                         }),
                         "HalfSpace.normal"));

    EXPECT_TRUE(contains(refusal([] { checkShape(ConvexHull{}, "ShapeDef.shape"); }),
                         "ShapeDef.shape: ConvexHull.data is null"));
    EXPECT_TRUE(contains(refusal([] { checkShape(ConvexHull{std::make_shared<HullData>()}, "w"); }),
                         "0 vertices"));
}

/// support() against closed forms of the support function h(d) = max over the shape of x . d.
TEST(Support, MatchesClosedFormSupportFunctions) {
    std::mt19937 rng(2);
    const Real r = 0.7;
    const Real h = 1.3;
    const Vec3 e(0.4, 0.9, 1.6);
    for (int trial = 0; trial < 1000; ++trial) {
        const Vec3 d = randomDirection(rng) * 3.0;  // support must not depend on |d|
        const Real radial = std::hypot(d.x(), d.y());
        EXPECT_NEAR(support(Sphere{r}, d).dot(d), r * d.norm(), 1e-12);
        EXPECT_NEAR(support(Sphere{r}, d).norm(), r, 1e-12);
        EXPECT_NEAR(support(Capsule{r, h}, d).dot(d), h * std::abs(d.z()) + r * d.norm(), 1e-12);
        EXPECT_NEAR(support(Box{e}, d).dot(d), e.dot(d.cwiseAbs()), 1e-12);
        const Vec3 rim = support(Cylinder{r, h}, d);
        EXPECT_NEAR(rim.dot(d), h * std::abs(d.z()) + r * radial, 1e-12);
        EXPECT_NEAR(std::hypot(rim.x(), rim.y()), r, 1e-12) << "on the rim";
        EXPECT_NEAR(std::abs(rim.z()), h, 1e-12);
    }
    // Directions along the axis: the cap centre (every cap point is farthest).
    EXPECT_TRUE(support(Cylinder{r, h}, Vec3(0, 0, -2)).isApprox(Vec3(0, 0, -h)));
}

TEST(Support, HullIsTheBruteForceMaximumOverItsVertices) {
    std::mt19937 rng(3);
    const ConvexHull hull = randomHull(rng, 60);
    for (int trial = 0; trial < 1000; ++trial) {
        const Vec3 d = randomDirection(rng);
        Real best = -std::numeric_limits<Real>::infinity();
        for (const Vec3& v : hull.data->vertices)
            best = std::max(best, v.dot(d));
        EXPECT_EQ(support(hull, d).dot(d), best);
    }
}

// The bounding radius is the farthest any point of the shape lies from its origin: no support
// point in any direction lies beyond it, and (these shapes being closed) some direction reaches
// it to within the sampling's resolution.
TEST(BoundingRadius, IsTheFarthestSupportPoint) {
    std::mt19937 rng(5);
    const std::vector<Shape> shapes = {Sphere{0.15}, Capsule{0.1, 0.3}, Box{Vec3(0.15, 0.12, 0.1)},
                                       Cylinder{0.14, 0.1}, randomHull(rng, 40)};
    const std::vector<Real> exact = {0.15, 0.4, std::sqrt(0.15 * 0.15 + 0.12 * 0.12 + 0.01),
                                     std::hypot(0.14, 0.1), -1};
    for (std::size_t i = 0; i < shapes.size(); ++i) {
        const Real radius = boundingRadius(shapes[i]);
        if (exact[i] > 0) {
            EXPECT_NEAR(radius, exact[i], 1e-15) << "shape " << i;
        }
        Real farthest = 0;
        for (int trial = 0; trial < 20000; ++trial)
            farthest = std::max(farthest, support(shapes[i], randomDirection(rng)).norm());
        EXPECT_LE(farthest, radius * (1 + 1e-12)) << "shape " << i;
        // A sphere, a capsule's end caps, a hull's vertices are hit exactly; a box's corner and
        // a cylinder's rim by directions within their normal cones, which sampling finds.
        EXPECT_GE(farthest, radius * (1 - 1e-3)) << "shape " << i;
    }
    EXPECT_EQ(boundingRadius(HalfSpace{}), std::numeric_limits<Real>::infinity());
}

TEST(Support, RefusesHalfSpace) {
    EXPECT_TRUE(contains(refusal([] { support(HalfSpace{}, Vec3::UnitZ()); }), "unbounded"));
}

/// boundsOf at random poses holds 1,000 random support points and touches the shape on all six
/// sides: the support point along each world axis lies on the box face.
TEST(Bounds, ContainAllSupportPointsAndAreTight) {
    std::mt19937 rng(4);
    const std::vector<Shape> shapes = {Sphere{0.7},        Capsule{0.3, 1.1},  Box{Vec3(0.4, 1, 2)},
                                       Cylinder{0.6, 0.9}, Cylinder{2.0, 0.1}, randomHull(rng, 40)};
    std::uniform_real_distribution<Real> uniform(-10, 10);
    const Real tolerance = 1e-12 * 16;  // rounding of coordinates up to ~16 m
    for (const Shape& shape : shapes) {
        for (int poseTrial = 0; poseTrial < 5; ++poseTrial) {
            const Transform pose{Vec3(uniform(rng), uniform(rng), uniform(rng)),
                                 randomRotation(rng)};
            const Aabb box = boundsOf(shape, pose);
            const Quat inverse = pose.rotation.conjugate();
            for (int trial = 0; trial < 1000; ++trial) {
                const Vec3 p = pose.apply(support(shape, inverse * randomDirection(rng)));
                ASSERT_TRUE((p.array() >= box.lower.array() - tolerance).all() &&
                            (p.array() <= box.upper.array() + tolerance).all())
                    << "shape " << shape.index() << " point " << p.transpose();
            }
            for (int i = 0; i < 3; ++i) {
                const Vec3 axis = Vec3::Unit(i);
                EXPECT_NEAR(pose.apply(support(shape, inverse * axis))[i], box.upper[i], tolerance)
                    << "shape " << shape.index() << " axis " << i;
                EXPECT_NEAR(pose.apply(support(shape, inverse * -axis))[i], box.lower[i], tolerance)
                    << "shape " << shape.index() << " axis " << i;
            }
        }
    }
}

TEST(Bounds, CylinderAlongAWorldAxisIsItsBox) {
    // Axis turned onto world x: extent (h, r, r).
    const Transform pose{Vec3(1, 2, 3),
                         Quat(Eigen::AngleAxis<Real>(std::numbers::pi / 2, Vec3::UnitY()))};
    const Aabb box = boundsOf(Cylinder{0.5, 2}, pose);
    EXPECT_TRUE(box.lower.isApprox(Vec3(-1, 1.5, 2.5), 1e-15));
    EXPECT_TRUE(box.upper.isApprox(Vec3(3, 2.5, 3.5), 1e-15));
}

TEST(Bounds, HalfSpaceIsUnboundedExceptAlongAnAxisAlignedNormal) {
    // An unrotated ground plane z <= 0.5 at height 2: the solid ends at z = 2.5.
    const Aabb ground = boundsOf(HalfSpace{Vec3::UnitZ(), 0.5}, Transform{Vec3(7, 8, 2)});
    EXPECT_EQ(ground.upper.z(), 2.5);
    EXPECT_EQ(ground.lower.z(), -kHalfSpaceBound);
    for (int i = 0; i < 2; ++i) {
        EXPECT_EQ(ground.lower[i], -kHalfSpaceBound);
        EXPECT_EQ(ground.upper[i], kHalfSpaceBound);
    }
    // A ceiling x >= -1 (normal -x, offset 1): bounded below in x.
    const Aabb wall = boundsOf(HalfSpace{-Vec3::UnitX(), 1}, Transform{});
    EXPECT_EQ(wall.lower.x(), -1);
    EXPECT_EQ(wall.upper.x(), kHalfSpaceBound);
    // A tilted normal bounds nothing.
    const Aabb tilted = boundsOf(HalfSpace{Vec3(0, 0.6, 0.8), 0}, Transform{});
    EXPECT_EQ(tilted.lower, Vec3::Constant(-kHalfSpaceBound));
    EXPECT_EQ(tilted.upper, Vec3::Constant(kHalfSpaceBound));
    EXPECT_TRUE(tilted.center().allFinite());
}

}  // namespace
}  // namespace tumble
