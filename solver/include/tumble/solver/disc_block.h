#pragma once
/// The 2x2 block of two coupled rows whose impulse is limited to a disc (contact_solver.h).

#include "tumble/core/math.h"

namespace tumble {

/// A symmetric positive definite 2x2 block K (velocity change per unit impulse of two coupled
/// rows) with what the solve of an impulse limited to a disc needs: friction at a point (linear)
/// and rolling resistance (angular).
struct DiscBlock {
    Eigen::Matrix<Real, 2, 2> block = Eigen::Matrix<Real, 2, 2>::Zero();    ///< K
    Eigen::Matrix<Real, 2, 2> inverse = Eigen::Matrix<Real, 2, 2>::Zero();  ///< K^-1
    /// K = axes diag(moments) axes': its eigen-decomposition, for the case on the rim
    Eigen::Matrix<Real, 2, 1> moments = Eigen::Matrix<Real, 2, 1>::Zero();
    Eigen::Matrix<Real, 2, 2> axes = Eigen::Matrix<Real, 2, 2>::Identity();
    /// Fills the members from K; false (and all zero) when K is singular.
    bool set(const Eigen::Matrix<Real, 2, 2>& k);
};

}  // namespace tumble
