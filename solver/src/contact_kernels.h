#pragma once
/// The per-manifold pieces of the contact sweep that ContactSolver and ContactRows share
/// (contact_solver.cpp holds their derivations).

#include <Eigen/Core>

#include "tumble/solver/contact_solver.h"

namespace tumble {

/// The coupled friction update of one point: the impulse in the disc |lambda| <= radius that
/// removes as much of the slip vt as the block k allows, from the impulse `old`.
Eigen::Matrix<Real, 2, 1> solveDisc(const DiscBlock& k, const Eigen::Matrix<Real, 2, 1>& old,
                                    const Eigen::Matrix<Real, 2, 1>& vt, Real radius);

/// Torsion and rolling resistance of one manifold, with its current normal impulses; returns the
/// change as a speed at the farthest point (m/s).
Real solveAngularFriction(SolverBody& a, SolverBody& b, ContactConstraint& c, Real omega);

/// The normal rows of one manifold: its block solved exactly (normal_block.h) with the cached
/// factor, or point by point when it has one point or the block is degenerate. Raises
/// largestChange to the velocity change when settings.tolerance > 0.
void solveManifoldNormals(SolverBody& a, SolverBody& b, ContactConstraint& c, NormalFactor& factor,
                          const SolverSettings& settings, Real inverseH, Real bias,
                          Real& largestChange);

}  // namespace tumble
