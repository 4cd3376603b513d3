// ldltInverse (solver/src/ldlt4.h): bit for bit Eigen's LDLT inverse of a symmetric 4x4, and an
// inverse where the block is invertible.

#include "ldlt4.h"

#include <gtest/gtest.h>

#include <Eigen/Cholesky>
#include <bit>
#include <cstdint>
#include <random>

namespace tumble {
namespace {

Mat4 eigenInverse(const Mat4& m) {
    return m.ldlt().solve(Mat4::Identity());
}

// Every entry's bits, so that -0 against +0 or a different last bit fails.
::testing::AssertionResult sameBits(const Mat4& a, const Mat4& b) {
    for (int r = 0; r < 4; ++r)
        for (int c = 0; c < 4; ++c)
            if (std::bit_cast<std::uint64_t>(a(r, c)) != std::bit_cast<std::uint64_t>(b(r, c)))
                return ::testing::AssertionFailure()
                       << "entry (" << r << ", " << c << "): " << a(r, c) << " against " << b(r, c);
    return ::testing::AssertionSuccess();
}

Mat4 randomMatrix(std::mt19937_64& rng, Real scale) {
    std::uniform_real_distribution<Real> u(-1, 1);
    Mat4 m;
    for (int r = 0; r < 4; ++r)
        for (int c = 0; c < 4; ++c)
            m(r, c) = scale * u(rng);
    return m;
}

// The friction anchors' use: a face's normal block (rank 3 for four coplanar points, 1..4 points
// padded with the identity), regularised by 1e-9 of its largest diagonal entry.
Mat4 faceBlock(std::mt19937_64& rng, int points) {
    std::uniform_real_distribution<Real> u(-1, 1);
    std::uniform_real_distribution<Real> logMass(-3, 3);
    const Real inverseMass = std::pow(10.0, logMass(rng));
    const Vec3 normal = Vec3(u(rng), u(rng), u(rng)).normalized();
    Eigen::Matrix<Real, 3, 4> arms;  // corner arms in the face's plane
    const Vec3 side = normal.unitOrthogonal();
    const Vec3 other = normal.cross(side);
    for (int i = 0; i < 4; ++i)
        arms.col(i) = u(rng) * side + u(rng) * other + 0.5 * normal;
    const Eigen::Matrix<Real, 3, 3> inverseInertia =
        inverseMass * Eigen::Matrix<Real, 3, 3>::Identity();
    Mat4 k = Mat4::Identity();
    for (int i = 0; i < points; ++i)
        for (int j = 0; j < points; ++j) {
            const Vec3 ti = arms.col(i).cross(normal);
            const Vec3 tj = arms.col(j).cross(normal);
            k(i, j) = inverseMass + ti.dot(inverseInertia * tj);
        }
    const Real scale = k.diagonal().head(points).maxCoeff();
    k.diagonal().head(points).array() += 1e-9 * scale;
    return k;
}

TEST(Ldlt4, SameBitsAsEigenOnRandomSymmetricBlocks) {
    std::mt19937_64 rng(0x1d174);
    for (int trial = 0; trial < 20000; ++trial) {
        const Real scale = std::pow(10.0, trial % 13 - 6);
        const Mat4 b = randomMatrix(rng, scale);
        Mat4 m;
        switch (trial % 4) {
            case 0:  // positive definite
                m = b * b.transpose() + scale * scale * Mat4::Identity();
                break;
            case 1: {  // positive semi-definite of rank 1..3
                Mat4 low = b;
                low.rightCols(1 + trial / 4 % 3).setZero();
                m = low * low.transpose();
                break;
            }
            case 2:  // indefinite
                m = b + b.transpose();
                break;
            default:  // a zero row and column, anywhere
                m = b * b.transpose();
                m.row(trial / 4 % 4).setZero();
                m.col(trial / 4 % 4).setZero();
                break;
        }
        ASSERT_TRUE(sameBits(ldltInverse(m), eigenInverse(m))) << "trial " << trial << "\n" << m;
    }
}

TEST(Ldlt4, SameBitsAsEigenOnFaceBlocks) {
    std::mt19937_64 rng(0xface);
    for (int trial = 0; trial < 20000; ++trial) {
        const Mat4 k = faceBlock(rng, 1 + trial % 4);
        ASSERT_TRUE(sameBits(ldltInverse(k), eigenInverse(k))) << "trial " << trial << "\n" << k;
    }
}

// Small integers, zeros of both signs among them: exact products and sums, where only the order
// and the signs of zeros tell two routines apart.
TEST(Ldlt4, SameBitsAsEigenOnSparseIntegerBlocks) {
    std::mt19937_64 rng(3);
    const Real values[] = {-2, -1, -0.0, 0, 0, 0, 1, 2, 3};
    std::uniform_int_distribution<int> pick(0, 8);
    for (int trial = 0; trial < 50000; ++trial) {
        Mat4 m;
        for (int r = 0; r < 4; ++r)
            for (int c = 0; c <= r; ++c)
                m(r, c) = m(c, r) = values[pick(rng)];
        ASSERT_TRUE(sameBits(ldltInverse(m), eigenInverse(m))) << "trial " << trial << "\n" << m;
    }
}

TEST(Ldlt4, ZeroAndDiagonalBlocks) {
    EXPECT_TRUE(sameBits(ldltInverse(Mat4::Zero()), Mat4::Zero()));
    Mat4 d = Mat4::Zero();
    d.diagonal() << 4, 0, 0.5, 2;
    Mat4 expected = Mat4::Zero();
    expected.diagonal() << 0.25, 0, 2, 0.5;  // D's pseudo-inverse: a zero pivot gives a zero row
    EXPECT_TRUE(sameBits(ldltInverse(d), expected));
}

TEST(Ldlt4, ReadsOnlyTheLowerTriangle) {
    std::mt19937_64 rng(7);
    for (int trial = 0; trial < 1000; ++trial) {
        const Mat4 b = randomMatrix(rng, 1);
        const Mat4 m = b * b.transpose() + Mat4::Identity();
        Mat4 scribbled = m;
        scribbled.triangularView<Eigen::StrictlyUpper>() = randomMatrix(rng, 1e6);
        ASSERT_TRUE(sameBits(ldltInverse(scribbled), ldltInverse(m))) << "trial " << trial;
    }
}

// Where the block is well conditioned (B B' + I, entries of B in [-1, 1]: condition under 17),
// the product with the block is the identity to 1e-13, set before measuring (~30 roundings of
// O(1) terms).
TEST(Ldlt4, InvertsWellConditionedBlocks) {
    std::mt19937_64 rng(11);
    for (int trial = 0; trial < 10000; ++trial) {
        const Mat4 b = randomMatrix(rng, 1);
        const Mat4 m = b * b.transpose() + Mat4::Identity();
        const Real error = (m * ldltInverse(m) - Mat4::Identity()).cwiseAbs().maxCoeff();
        ASSERT_LE(error, 1e-13) << "trial " << trial;
    }
}

}  // namespace
}  // namespace tumble
