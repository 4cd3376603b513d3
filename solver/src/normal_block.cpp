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
                f.inverseDiagonal[i] = 1 / f.l[i][i];
            } else {
                f.l[i][j] = sum / f.l[j][j];
            }
        }
    }
    f.set = set;
    return true;
}

}  // namespace

bool solveNormalBlock(const Mat4& k, int n, const Vec4& c, Vec4& lambda, NormalFactor& factor) {
    const unsigned all = (1u << n) - 1;
    const Real eps = kRegularisation * k.diagonal().head(n).maxCoeff();
    const Real tolerance =
        std::max(kNormalTolerance * c.head(n).cwiseAbs().maxCoeff(), kNormalFloor);
    // The set that carried load last time is usually the answer (a resting face: all of it; a
    // face merely touching: none of it), so it is tried first.
    const unsigned guess = detail::loadedSet(lambda, n);
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
            detail::solveFactored(factor, c, x);
        }
        if (detail::checksOut(k, n, c, set, x, tolerance)) {
            lambda = x;
            return true;
        }
    }
    return false;
}

}  // namespace tumble
