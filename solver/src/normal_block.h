#pragma once
/// The normal rows of one contact manifold (up to four points between the same two bodies) solved
/// together, exactly, as a small linear complementarity problem:
///
///     find lambda >= 0 with  w = K lambda + c >= 0  and  lambda_i w_i = 0,
///
/// K the manifold's normal block (K_ij: normal velocity change at point i per unit impulse at
/// point j), c the normal velocities, less their targets, that remain with lambda = 0.
///
/// Why a block: solving the points one after another (plain Gauss-Seidel) hands each increment of
/// load to the first corner it reaches, so a box that is still taking up load is tipped a little
/// every sweep. In a tall stack that bias never settles within ten sweeps and the stack leans
/// until it falls (a 20-cube stack fell within 5 s). The exact block solve has no order.
///
/// Method: the active sets are enumerated, largest first (at rest all four points carry load).
/// For each set S the equalities K_SS lambda_S = -c_S are solved by Cholesky; the set is the
/// answer when lambda_S >= 0 and w >= 0 off S. Four coplanar points give a singular 4x4 block
/// (a rigid face has three contact degrees of freedom, not four): a small diagonal
/// regularisation then picks the minimum-norm split of the load, the symmetric one, and a set
/// whose equalities cannot be met (w_S != 0) is rejected.

#include <Eigen/Core>

#include "tumble/core/math.h"

namespace tumble {

using Mat4 = Eigen::Matrix<Real, 4, 4>;
using Vec4 = Eigen::Matrix<Real, 4, 1>;

/// Solves the LCP above for the first n (1..4) rows of k and c. `lambda` comes in as the last
/// answer (its positive entries are the first active set tried) and on success goes out as the
/// new one (entries past n zero); returns false when no active set checks out to rounding (a
/// degenerate block), leaving lambda unchanged.
bool solveNormalBlock(const Mat4& k, int n, const Vec4& c, Vec4& lambda);

}  // namespace tumble
