#pragma once
/// The scalar contact sweep's own compact copy of the prepared constraints (the default path;
/// the coloured one has ContactRows). A ContactConstraint keeps four point slots of 576 bytes
/// whatever its point count, with the prepare and report fields between the swept ones: on
/// pile-4000 the sweeps streamed ~35 MB twenty times a step, past the 32 MB L3 (the time per
/// step grew 3.45x from 2k to 4k bodies). Here each manifold is a small header and its points
/// follow one another in a second array, holding only what a sweep reads or writes; the rest
/// (the box model's masses, the angular friction rows, the report fields) is read from the
/// constraint in the rare cases that need it. The arithmetic is ContactSolver's, on
/// the same values in the same order: the trajectories are bitwise those of the constraints.

#include <array>
#include <cstdint>
#include <span>
#include <vector>

#include "tumble/core/lane_kernel.h"
#include "tumble/core/solver_types.h"
#include "tumble/solver/disc_block.h"
#include "tumble/solver/solver_body.h"

namespace tumble {

struct ContactConstraint;  // contact_solver.h, which holds a SweepRows
struct NormalFactor;

/// A point's rows, in the order the sweep reads them (names as ContactConstraintPoint's, so the
/// normal kernels of normal_block.h take either).
struct SweepPoint {
    /// rA x t_k and rB x t_k (m) by axis, [axis][k]: the sweep forms v_t along t_1 and t_2 in
    /// the two lanes of one register, with the dot products' operations in their order.
    std::array<std::array<Real, 2>, 3> tangentAngularA{};
    std::array<std::array<Real, 2>, 3> tangentAngularB{};
    DiscBlock tangent;  ///< K on the tangent plane, with its inverse and eigen-decomposition
    std::array<Real, 2> tangentImpulse{};   ///< along t_1, t_2 (N s)
    Real normalImpulse = 0;                 ///< (N s)
    Real normalMass = 0;                    ///< (kg)
    std::array<Vec3, 2> tangentImpulseA{};  ///< IA^-1 (rA x t_k)
    std::array<Vec3, 2> tangentImpulseB{};  ///< IB^-1 (rB x t_k)
    Vec3 angularA = Vec3::Zero();           ///< rA x n (m)
    Vec3 angularB = Vec3::Zero();           ///< rB x n (m)
    Real separation = 0;                    ///< (m), for normalTarget
    /// normalTarget at the sweep's bias, slop and 1/h, set by the first sweep that uses them
    /// (SweepRows::sweep): it is the same for all the sweeps of a phase, and recomputed in each
    /// it was a tenth of a pile's normal rows.
    Real target = 0;                      ///< (m/s)
    Real reboundSpeed = 0;                ///< (m/s)
    Real bounceCorrection = 0;            ///< (m)
    Vec3 angularImpulseA = Vec3::Zero();  ///< IA^-1 (rA x n)
    Vec3 angularImpulseB = Vec3::Zero();  ///< IB^-1 (rB x n)
    bool bounces = false;
};

/// A manifold's header: its bodies, basis and where its points and block are.
struct SweepManifold {
    static constexpr std::uint32_t kNoBlock = ~0u;
    std::uint32_t bodyA = 0;
    std::uint32_t bodyB = 0;
    std::uint32_t constraint = 0;    ///< index of its ContactConstraint
    std::uint32_t firstPoint = 0;    ///< into the points array
    std::uint32_t block = kNoBlock;  ///< into the blocks array: several points, or measuring
    std::uint8_t pointCount = 0;
    bool angular = false;  ///< spinning or rolling rows
    bool grouped = false;  ///< normal rows solved by NormalIslands
    Vec3 normal = Vec3::UnitZ();
    /// The friction basis t_1, t_2 by axis, [axis][k]: the sweep forms both rows' slip in two
    /// lanes (SweepPoint::tangentAngularA), and tangents() gives them back as vectors.
    std::array<std::array<Real, 2>, 3> tangentAxes{};
    Real friction = 0;
    /// The friction rows' target: v_t along t_1, t_2 (m/s); 0 but in the soft step.
    std::array<Real, 2> tangentTarget{};

    std::array<Vec3, 2> tangents() const {
        return {Vec3(tangentAxes[0][0], tangentAxes[1][0], tangentAxes[2][0]),
                Vec3(tangentAxes[0][1], tangentAxes[1][1], tangentAxes[2][1])};
    }
};

class SweepRows {
public:
    /// Empties the rows, keeping their storage.
    void clear();
    /// Appends prepared constraint `index` (after the warm start and the groups' selection).
    void add(const ContactConstraint& c, std::uint32_t index, const SolverSettings& settings);
    /// One sweep, as ContactSolver::solveVelocitySweep (which calls it) without the exactly
    /// solved groups; returns the largest velocity change (m/s) when measuring. `softScales`:
    /// the soft step's mass scales by SoftContact's kinds (its biased sweep), or null.
    /// `patches`: the soft step's sweeps, whose coupled friction starts from a sliding
    /// manifold's patch (slide_patch.h).
    Real sweep(std::span<SolverBody> bodies, std::span<ContactConstraint> constraints,
               std::span<NormalFactor> factors, const SolverSettings& settings, Real inverseH,
               Real bias, const Real* softScales = nullptr, bool patches = false);
    /// Soft step: the points' separations, one per point in the rows' order, and the friction
    /// targets, one per constraint.
    void softTargets(std::span<const Real> separations,
                     std::span<const std::array<Real, 2>> tangentTargets);
    /// Soft step: no bounce in the rows (restitution is applied once, after the substeps).
    void dropBounces();
    /// Soft step: the accumulated impulses applied to the bodies again (a substep's warm start).
    void warmStart(std::span<SolverBody> bodies, std::span<const ContactConstraint> constraints);
    /// The normal impulses of the grouped manifolds, after the groups' solve.
    void readGroupImpulses(std::span<const ContactConstraint> constraints);
    /// Split impulse's relax sweeps aim at the rebound alone (see ConstraintSolver::relax).
    void dropBounceCorrections();
    /// The impulses back into the constraints after the last sweep.
    void store(std::span<ContactConstraint> constraints) const;

private:
    /// The points added since clear().
    std::span<SweepPoint> points() { return {points_.data(), pointCount_}; }
    /// sweep() with `patches`, and whether it is the default step's plain sweep (no soft scales,
    /// not measuring, coupled friction), fixed at compile time (sweep_rows.cpp says why).
    template <bool Patches, bool Plain>
    TUMBLE_FLATTEN Real sweepWith(std::span<SolverBody> bodies,
                                  std::span<ContactConstraint> constraints,
                                  std::span<NormalFactor> factors, const SolverSettings& given,
                                  Real inverseH, Real bias, const Real* softScalesGiven);

    /// sweepWith<false, true>, the default step's sweep, as a lane kernel (lane_kernel.h): its
    /// AVX2 copy's three-operand instructions save the baseline's register copies.
    Real sweepPlain(std::span<SolverBody> bodies, std::span<ContactConstraint> constraints,
                    std::span<NormalFactor> factors, const SolverSettings& settings, Real inverseH,
                    Real bias);

    std::vector<SweepManifold> manifolds_;
    /// The first pointCount_ are this step's; the rest is storage kept for the next steps.
    std::vector<SweepPoint> points_;
    std::size_t pointCount_ = 0;
    std::vector<Eigen::Matrix<Real, 4, 4>> blocks_;  ///< normal blocks (normal_block.h)
    std::vector<std::uint32_t> grouped_;             ///< manifolds with grouped normal rows
    /// What the points' targets were computed with (bit patterns); stale after anything that
    /// changes a point's target inputs (add, softTargets, dropBounces, dropBounceCorrections).
    bool targetsStale_ = true;
    std::array<std::uint64_t, 3> targetInputs_{};  ///< bias, slop, 1/h
    /// Soft step, per manifold: its patch slid in the substep's biased sweep (slide_patch.h).
    std::vector<std::uint8_t> slidBiased_;
};

}  // namespace tumble
