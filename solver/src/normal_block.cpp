#include "normal_block.h"

#include <algorithm>
#include <array>
#include <cmath>

namespace tumble {
namespace {

// Regularisation of the diagonal relative to its largest entry: large enough to make the singular
// 4x4 block of a rigid face factorisable, and to keep rounding out of the minimum-norm choice
// (the null-space part of a right-hand side is amplified by 1 / eps), small enough not to move a
// well-posed answer by more than eps relative: a resting box keeps ~1e-11 m/s.
constexpr Real kRegularisation = 1e-10;

// The active sets of four rows as bit masks, largest first, so the resting case (all four) and
// then the three-point cases are found first.
constexpr std::array<unsigned, 16> kSetsBySize = {0b1111, 0b0111, 0b1011, 0b1101, 0b1110, 0b0011,
                                                  0b0101, 0b0110, 0b1001, 0b1010, 0b1100, 0b0001,
                                                  0b0010, 0b0100, 0b1000, 0b0000};

// Factors K_SS + eps 1 = L L' for the rows in `set`; false if not positive.
bool factorActive(const Mat4& k, unsigned set, Real eps, NormalFactor& f) {
    f.set = NormalFactor::kNone;
    f.size = 0;
    for (int i = 0; i < 4; ++i) {
        if (set & (1u << i))
            f.rows[f.size++] = i;
    }
    const int m = f.size;
    for (int i = 0; i < m; ++i) {
        for (int j = 0; j <= i; ++j) {
            Real sum = k(f.rows[i], f.rows[j]) + (i == j ? eps : 0);
            for (int p = 0; p < j; ++p)
                sum -= f.l[i][p] * f.l[j][p];
            if (i == j) {
                if (!(sum > 0))
                    return false;
                f.l[i][i] = std::sqrt(sum);
            } else {
                f.l[i][j] = sum / f.l[j][j];
            }
        }
    }
    f.set = set;
    return true;
}

// Solves L L' x_S = -c_S by forward and back substitution; x is zero off the set. Unrolled for
// each size M: y and z stay in registers and the rows are read once. The operations and their
// order are the generic loop's (the trajectories are bitwise the same); the loop kept its eight
// dependent divisions waiting on stack round trips, on the sweep's critical path (a stack's
// column is one chain of manifolds).
template <int M>
[[gnu::always_inline]] inline void solveFactoredSize(const NormalFactor& f, const Vec4& c,
                                                     Vec4& x) {
    int rows[M];
    for (int i = 0; i < M; ++i)
        rows[i] = f.rows[i];
    Real y[M];
    for (int i = 0; i < M; ++i) {
        Real sum = -c(rows[i]);
        for (int p = 0; p < i; ++p)
            sum -= f.l[i][p] * y[p];
        y[i] = sum / f.l[i][i];
    }
    Real z[M];
    for (int i = M - 1; i >= 0; --i) {
        Real sum = y[i];
        for (int p = i + 1; p < M; ++p)
            sum -= f.l[p][i] * z[p];
        z[i] = sum / f.l[i][i];
    }
    x.setZero();
    for (int i = 0; i < M; ++i)
        x(rows[i]) = z[i];
}

void solveFactored(const NormalFactor& f, const Vec4& c, Vec4& x) {
    switch (f.size) {
        case 4:
            solveFactoredSize<4>(f, c, x);
            return;
        case 3:
            solveFactoredSize<3>(f, c, x);
            return;
        case 2:
            solveFactoredSize<2>(f, c, x);
            return;
        default:
            solveFactoredSize<1>(f, c, x);
            return;
    }
}

}  // namespace

bool solveNormalBlock(const Mat4& k, int n, const Vec4& c, Vec4& lambda, NormalFactor& factor) {
    const unsigned all = (1u << n) - 1;
    const Real eps = kRegularisation * k.diagonal().head(n).maxCoeff();
    const Real tolerance =
        std::max(kNormalTolerance * c.head(n).cwiseAbs().maxCoeff(), kNormalFloor);
    // The set that carried load last time is usually the answer (a resting face: all of it; a
    // face merely touching: none of it), so it is tried first.
    unsigned guess = 0;
    for (int i = 0; i < n; ++i) {
        if (lambda(i) > 0)
            guess |= 1u << i;
    }
    Vec4 x;
    for (int attempt = -1; attempt < static_cast<int>(kSetsBySize.size()); ++attempt) {
        const unsigned set = attempt < 0 ? guess : kSetsBySize[attempt];
        if ((set & ~all) != 0 || (attempt >= 0 && set == guess))
            continue;
        if (set == 0) {
            x.setZero();
        } else {
            // K is fixed within the step: the factor of last sweep's set is still good.
            if (factor.set != set && !factorActive(k, set, eps, factor))
                continue;
            solveFactored(factor, c, x);
        }
        const Vec4 w = k * x + c;
        bool ok = true;
        for (int i = 0; i < n && ok; ++i) {
            const bool active = (set & (1u << i)) != 0;
            ok = active ? (x(i) >= 0 && std::abs(w(i)) <= tolerance) : w(i) >= -tolerance;
        }
        if (ok) {
            lambda = x;
            return true;
        }
    }
    return false;
}

}  // namespace tumble
