#pragma once
/// The normal rows of a small group of contacts solved together, exactly, where Gauss-Seidel
/// cannot: bodies of very different masses pressed against each other.
///
/// Why: projected Gauss-Seidel passes load between two contacts that share a body at a rate set
/// by their coupling. For a body of mass m pressed between a contact to a body of mass M and
/// one to the ground, one sweep removes only a fraction m / (m + M) of the error: 1/1001 for a
/// 1000 kg box on a 1 kg box. Ten sweeps then do nothing; the light box did not hold the heavy
/// one, both sank 6 cm into the ground, and the split-impulse push-out, which the equally
/// unconverged relax sweeps could not take back out of the velocity, launched both boxes at
/// 1.6 m/s (10,000:1 sank 0.49 m instead). A ball bouncing on a 0.1 kg box resting on the ground
/// kept 6 % of its rebound height for the same reason.
///
/// What: contacts are grouped by the dynamic bodies they share (static and kinematic bodies do
/// not join groups). A group is solved directly when it has more than one manifold, at most
/// kMaxRows normal rows, and either masses that differ by kMassRatio or more within it or a
/// bouncing point (an impact must reach the supports whole within the step: through three 1 kg
/// boxes, ten relax sweeps left a 1 kg ball half its rebound height); everything else keeps the
/// per-manifold block of normal_block.h. In every sweep, after the group's friction
/// rows, its normal rows are one linear complementarity problem
///
///     find lambda >= 0 with  w = K (lambda - lambda0) + g >= 0  and  lambda_i w_i = 0,
///
/// K the group's Delassus matrix (K_ij: normal velocity change at row i per unit impulse at row
/// j, nonzero where the rows share a body), g the rows' v_n - target with the current impulses
/// lambda0. Solving a block of rows exactly with the others held is still a Gauss-Seidel step,
/// so springs, joints and friction around it are unaffected. A rigid face's four coplanar
/// points make K singular; K + eps 1 (eps 1e-10 of the largest diagonal) picks the minimum-norm
/// split, as normal_block.h does, and makes the problem one with a P-matrix, which principal
/// pivoting solves in finitely many steps (Murty; Judice & Pires' block pivoting first, which
/// flips every infeasible row at once and is usually done in one or two steps from last sweep's
/// set). Should the pivoting not finish within its budget the group falls back to the
/// per-manifold blocks for that sweep.
///
/// Cost: one Cholesky of the active rows per pivot, (n^3) / 3 for n <= kMaxRows, in groups that
/// need it only; groups of equal masses (piles, pyramids) never take this path.

#include <cstdint>
#include <span>
#include <vector>

#include "tumble/solver/solver_body.h"

namespace tumble {

struct ContactConstraint;

class NormalIslands {
public:
    static constexpr int kMaxRows = 32;    ///< normal rows of the largest group solved here
    static constexpr Real kMassRatio = 4;  ///< smallest max/min mass ratio solved here
    static constexpr std::uint32_t kNone = ~0u;

    /// Groups the constraints, picks those solved here, builds their K and marks their
    /// constraints (ContactConstraint::normalGroup); every other constraint gets kNone. Needs
    /// prepare()'s angular Jacobians. Allocates only when the arrays grow.
    void prepare(std::span<const SolverBody> bodies, std::span<ContactConstraint> constraints);
    bool empty() const { return groupCount_ == 0; }
    /// One exact solve of every group's normal rows at the current velocities, with the targets
    /// of ContactSolver's rows (bias, slop, 1/h as there) and SOR factor `relaxation`. Returns
    /// the largest change of a row's velocity (m/s).
    Real solve(std::span<SolverBody> bodies, std::span<ContactConstraint> constraints,
               Real relaxation, Real bias, Real slop, Real inverseH);

private:
    void selectGroups(std::span<const SolverBody> bodies, std::span<ContactConstraint> constraints);
    void buildMatrices(std::span<const SolverBody> bodies,
                       std::span<const ContactConstraint> constraints);
    bool solveGroup(int group, const std::vector<Real>& c, std::vector<Real>& lambda);

    int groupCount_ = 0;
    std::vector<std::uint32_t> parent_;       ///< union-find over bodies
    std::vector<std::uint32_t> rootGroup_;    ///< group of each root body, or kNone
    std::vector<std::uint32_t> groupBegin_;   ///< first row of each group in rows_ (size + 1)
    std::vector<std::uint32_t> matrixBegin_;  ///< first entry of each group's K in matrix_
    std::vector<std::uint32_t> counts_[2];    ///< prepare()'s per-group scratch
    struct Row {
        std::uint32_t constraint = 0;
        int point = 0;
    };
    std::vector<Row> rows_;
    std::vector<Real> matrix_;                ///< each group's K, n x n row-major
    std::vector<Real> groupMass_[2];          ///< smallest and largest mass of each candidate group
    std::vector<std::uint8_t> groupBounces_;  ///< a point of the candidate group bounces
    // Scratch of solve().
    std::vector<Real> gap_, impulse_, exact_, factor_, work_;
    std::vector<std::uint8_t> active_;
};

}  // namespace tumble
