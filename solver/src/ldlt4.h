#pragma once
/// The inverse of a symmetric 4x4 by LDLT with diagonal pivoting, the same bits as Eigen 3.4's
/// `m.ldlt().solve(Mat4::Identity())` (ldlt_inplace<Lower>, then _solve_impl on the identity),
/// operation for operation and in the same order. Eigen's general routines (dynamic blocks, gemv,
/// a blocked triangular solve with packing) cost ~10x the arithmetic on a 4x4; the friction
/// anchors' pass inverts one block per manifold a step. Only the lower triangle is read. A zero
/// pivot gives a zero row of D's pseudo-inverse, as Eigen's. tests/solver/ldlt4_test.cpp checks
/// the bits against the installed Eigen: if an Eigen release changes its LDLT, that test says so.

#include "normal_block.h"

namespace tumble {

Mat4 ldltInverse(Mat4 m);

}  // namespace tumble
