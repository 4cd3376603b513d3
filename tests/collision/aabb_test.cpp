#include "tumble/collision/aabb.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

namespace tumble {
namespace {

TEST(Aabb, OverlapIncludesTouchingFaces) {
    const Aabb a{Vec3(0, 0, 0), Vec3(1, 1, 1)};
    EXPECT_TRUE(a.overlaps({Vec3(1, 0, 0), Vec3(2, 1, 1)}));
    EXPECT_FALSE(a.overlaps({Vec3(1.001, 0, 0), Vec3(2, 1, 1)}));
    EXPECT_FALSE(a.overlaps({Vec3(0, 0, -2), Vec3(1, 1, -0.5)}));
}

TEST(Aabb, RotatedBoxBoundIsTight) {
    // A unit cube turned 45 degrees about z spans sqrt(2)/2 * 2 along x and y.
    Transform pose;
    pose.position = Vec3(1, 2, 3);
    pose.rotation = Quat(Eigen::AngleAxis<Real>(std::numbers::pi / 4, Vec3::UnitZ()));
    const Aabb box = Aabb::ofOrientedBox(pose, Vec3(0.5, 0.5, 0.5));
    EXPECT_NEAR(box.upper.x() - box.lower.x(), std::sqrt(2.0), 1e-12);
    EXPECT_NEAR(box.upper.y() - box.lower.y(), std::sqrt(2.0), 1e-12);
    EXPECT_NEAR(box.upper.z() - box.lower.z(), 1.0, 1e-12);
    EXPECT_TRUE(box.center().isApprox(Vec3(1, 2, 3)));
}

TEST(Aabb, FattenedContainsOriginalAndMergeContainsBoth) {
    const Aabb a{Vec3(0, 0, 0), Vec3(1, 1, 1)};
    const Aabb b{Vec3(2, -1, 0), Vec3(3, 0, 4)};
    EXPECT_TRUE(a.fattened(0.1).contains(a));
    EXPECT_FALSE(a.contains(a.fattened(0.1)));
    const Aabb m = a.merged(b);
    EXPECT_TRUE(m.contains(a));
    EXPECT_TRUE(m.contains(b));
    EXPECT_DOUBLE_EQ(Aabb({Vec3::Zero(), Vec3(1, 2, 3)}).surfaceArea(), 2 * (2 + 6 + 3));
}

}  // namespace
}  // namespace tumble
