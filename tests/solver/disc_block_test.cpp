// The tangent block's eigen-decomposition, which the exact disc friction's rim solve relies on.

#include "tumble/solver/disc_block.h"

#include <gtest/gtest.h>

#include <random>

namespace tumble {
namespace {

using Mat2 = Eigen::Matrix<Real, 2, 2>;

// K = axes diag(moments) axes' with orthonormal axes and ascending moments, to rounding, for
// every orientation of the axes (both signs of the diagonal difference), the isotropic block of
// a sphere and blocks with no off-diagonal term.
TEST(DiscBlock, DecomposesEverySymmetricPositiveBlock) {
    std::mt19937_64 rng(7);
    std::uniform_real_distribution<Real> unit(0, 1);
    std::vector<Mat2> blocks = {Mat2::Identity() * 0.7, Mat2{{2, 0}, {0, 0.5}},
                                Mat2{{0.5, 0}, {0, 2}}, Mat2{{1, 1e-17}, {1e-17, 1}}};
    for (int i = 0; i < 1000; ++i) {
        const Real angle = 6.283185307179586 * unit(rng);
        const Real small = 1e-3 + unit(rng), large = small * (1 + 1e3 * unit(rng) * unit(rng));
        Mat2 r;
        r << std::cos(angle), -std::sin(angle), std::sin(angle), std::cos(angle);
        blocks.push_back(r * Eigen::Vector2d(small, large).asDiagonal() * r.transpose());
    }
    for (const Mat2& k : blocks) {
        DiscBlock d;
        ASSERT_TRUE(d.set(k));
        const Real scale = k.norm();
        EXPECT_LE(d.moments(0), d.moments(1));
        EXPECT_LE((d.axes.transpose() * d.axes - Mat2::Identity()).norm(), 1e-14);
        EXPECT_LE((d.axes * d.moments.asDiagonal() * d.axes.transpose() - k).norm(), 1e-14 * scale)
            << k;
        EXPECT_LE((d.inverse * k - Mat2::Identity()).norm(), 1e-9);
    }
}

TEST(DiscBlock, SingularBlockGivesNoRows) {
    DiscBlock d;
    EXPECT_FALSE(d.set(Mat2{{1, 1}, {1, 1}}));
    EXPECT_FALSE(d.set(Mat2::Zero()));
    EXPECT_EQ(d.moments, Eigen::Vector2d::Zero());
}

}  // namespace
}  // namespace tumble
