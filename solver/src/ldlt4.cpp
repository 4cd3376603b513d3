// The 4x4 LDLT inverse of ldlt4.h, step for step as Eigen 3.4 takes it.

#include "ldlt4.h"

#include <array>
#include <cmath>
#include <limits>
#include <utility>

#include "tumble/core/lane_kernel.h"

namespace tumble {

// Compiled for AVX2 and the baseline (lane_kernel.h, the same bits): the friction anchor pass
// calls it for every manifold it holds, 2.1 % of pyramid-20's instructions. Its loops are
// unrolled (GCC unroll: the same operations in the same order, without the loop counters and
// branches that were 60 % of its instructions).
TUMBLE_LANE_KERNEL Mat4 ldltInverse(Mat4 m) {
    std::array<int, 4> swaps{0, 1, 2, 3};
#pragma GCC unroll 4
    for (int k = 0; k < 4; ++k) {
        // Diagonal pivoting: the first largest |m(j, j)|, j >= k.
        int p = k;
        Real biggest = std::abs(m(k, k));
        for (int j = k + 1; j < 4; ++j) {
            if (std::abs(m(j, j)) > biggest) {
                biggest = std::abs(m(j, j));
                p = j;
            }
        }
        swaps[k] = p;
        if (p != k) {
            for (int c = 0; c < k; ++c)
                std::swap(m(k, c), m(p, c));
            for (int r = p + 1; r < 4; ++r)
                std::swap(m(r, k), m(r, p));
            std::swap(m(k, k), m(p, p));
            for (int i = k + 1; i < p; ++i) {
                const Real held = m(i, k);
                m(i, k) = m(p, i);
                m(p, i) = held;
            }
        }
        if (k > 0) {
            std::array<Real, 3> temp;
            for (int j = 0; j < k; ++j)
                temp[j] = m(j, j) * m(k, j);
            Real dot = m(k, 0) * temp[0];
            for (int j = 1; j < k; ++j)
                dot += m(k, j) * temp[j];
            m(k, k) -= dot;
            // Eigen's gemv sums each row from zero; with one row left it takes a dot product.
            for (int r = k + 1; r < 4; ++r) {
                Real sum = r == 3 && k == 2 ? m(r, 0) * temp[0] : 0;
                for (int j = r == 3 && k == 2 ? 1 : 0; j < k; ++j)
                    sum += m(r, j) * temp[j];
                m(r, k) += Real(-1) * sum;
            }
        }
        const Real pivot = m(k, k);
        if (!(std::abs(pivot) > 0)) {
            if (k == 0) {  // a zero diagonal: Eigen keeps no transpositions
                swaps = {0, 1, 2, 3};
                break;
            }
            continue;
        }
        for (int r = k + 1; r < 4; ++r)
            m(r, k) /= pivot;
    }
    Mat4 x = Mat4::Identity();
    for (int k = 0; k < 4; ++k)
        if (swaps[k] != k)
            x.row(k).swap(x.row(swaps[k]));
#pragma GCC unroll 4
    for (int i = 0; i < 4; ++i)  // L, unit lower, by columns
#pragma GCC unroll 4
        for (int j = 0; j < 4; ++j)
#pragma GCC unroll 4
            for (int r = i + 1; r < 4; ++r)
                x(r, j) -= x(i, j) * m(r, i);
    for (int i = 0; i < 4; ++i) {  // D, pseudo-inverse
        if (std::abs(m(i, i)) > std::numeric_limits<Real>::min())
            x.row(i) /= m(i, i);
        else
            x.row(i).setZero();
    }
#pragma GCC unroll 4
    for (int i = 3; i >= 0; --i) {  // L', unit upper, by rows from a zero sum
#pragma GCC unroll 4
        for (int j = 0; j < 4; ++j) {
            Real sum = 0;
#pragma GCC unroll 4
            for (int r = i + 1; r < 4; ++r)
                sum += m(r, i) * x(r, j);
            x(i, j) = x(i, j) - sum;
        }
    }
    for (int k = 3; k >= 0; --k)
        if (swaps[k] != k)
            x.row(k).swap(x.row(swaps[k]));
    return x;
}

}  // namespace tumble
