#pragma once
/// The contact sweeps on compact, wide rows (SolverSettings::colouredContacts): the same rows as
/// ContactSolver's -- coupled or box friction per point, the manifold's normal block solved
/// exactly, the angular friction rows, the exactly solved groups -- laid out for four
/// manifolds at a time.
///
/// Colouring (chains). A manifold's colour is one after the last colour either of its moving
/// bodies has met, in constraint order (static and kinematic bodies never colour: the rows never
/// change their velocity). A colour's manifolds are independent, so four of them are updated
/// together, one per lane; within a sweep the colours run in order, and within a colour the
/// bundles. Every body then meets its manifolds in constraint order and updates on disjoint
/// bodies commute exactly, so the sweep is the scalar sweep's Gauss-Seidel to the bit: a tall
/// column keeps its bottom-to-top chain (one manifold per colour), a pyramid's rows fill the
/// lanes. Where the colours leave the lanes mostly empty (fewer manifolds than half the lanes:
/// a lone column) the rows are not built and the scalar sweep runs instead -- same bits, less
/// work. (Greedy colours, lowest free colour per manifold, filled the lanes of a column too but
/// alternated its levels: 1.9x the scalar sweep's penetration on stack-20, a base-40 pyramid's
/// landing spread 0.150 m against 0.045 m; bench/README.md, the colour-order study.)
///
/// Lanes. A lane is four doubles (GCC/Clang vector extension, 32 bytes): each operation is the
/// IEEE operation per lane, so the bits do not depend on the ISA the compiler picks (AVX2 or two
/// SSE2 halves) as long as nothing contracts a*b+c into an FMA (the project builds with
/// -ffp-contract=off). Padding lanes point at a dummy body with no mass and carry zero rows.
///
/// Per sweep and bundle: gather both bodies' velocities into lanes; the friction of every point
/// (the free 2x2 solve in the lanes, then the exact disc -- ContactSolver's solveDisc, the same
/// operations per lane -- in the lanes whose free answer leaves the disc); the angular friction
/// rows (lane by lane, rare); the normal block with the factor of the active set it cached (in the
/// lanes when last sweep's set still carries the load, otherwise the full active-set search of
/// solveNormalBlock for that lane). The velocities live in a compact per-body array during a sweep.

#include <array>
#include <cstdint>
#include <span>
#include <vector>

#include "tumble/core/solver_types.h"
#include "tumble/solver/solver_body.h"

namespace tumble {

struct ContactConstraint;  // contact_solver.h, which holds a ContactRows
struct NormalFactor;

/// Four doubles, one per lane, and a lane mask (all bits set where true).
using Lane = double __attribute__((vector_size(32), aligned(32)));
using LaneMask = std::int64_t __attribute__((vector_size(32), aligned(32)));

class ContactRows {
public:
    static constexpr int kWidth = 4;
    /// The rows are built when manifolds >= lanes / kMinimumFillDenominator and points >=
    /// point slots / kMinimumFillDenominator (a bundle has as many slots per lane as its
    /// largest manifold has points).
    static constexpr std::size_t kMinimumFillDenominator = 2;
    /// Whether `points` in `manifolds` are enough for the rows: two a manifold on average
    /// (build() says no below that, so prepare can decide before it copies the scalar rows).
    static bool enoughPoints(std::size_t points, std::size_t manifolds) {
        return points * kMinimumFillDenominator >= manifolds * 4;
    }
    /// A colour's manifolds are bundled by point count, 0 to 4.
    static constexpr std::uint32_t kGroupsPerColour = 5;

    /// Colours the prepared constraints and builds the rows from them (their Jacobians, masses,
    /// targets and warm-start impulses); false, with no rows built, when the colours would fill
    /// fewer than half the lanes, the points fewer than half the bundles' point slots, or the
    /// manifolds under two points on average (a pile: the scalar sweep is faster there). Allocates
    /// only when the arrays grow.
    bool build(std::span<const SolverBody> bodies, std::span<const ContactConstraint> constraints,
               const SolverSettings& settings, Real inverseH);
    /// One sweep over the rows, as ContactSolver::solveVelocitySweep (which calls it) without
    /// the exactly solved groups; returns the largest velocity change (m/s) when measuring.
    /// `soft`: the soft step's biased sweep, each touching point's answer scaled by the mass
    /// scale softTargets gave it (SweepRows::sweep's softScales, the same bits).
    /// `resident`: the bodies' velocities are as the last sweep stored them (nothing has changed
    /// them since), so the copy of them into the rows' own array is skipped.
    /// `patches`: the soft step's sweeps (SweepRows::sweep's, the same bits).
    Real sweep(std::span<SolverBody> bodies, std::span<ContactConstraint> constraints,
               std::span<NormalFactor> factors, const SolverSettings& settings, Real bias,
               Real inverseH, bool soft = false, bool resident = false, bool patches = false);
    /// Soft step: each point's separation (`separations`, constraint j's points from
    /// `firstPoint[j]`) as its target at the substep's inverseH, no bounce; `scales`:
    /// SoftContact::massScale.
    /// `tangentTargets`: each constraint's friction target (v_t along t_1, t_2, m/s).
    void softTargets(std::span<const Real> separations, std::span<const std::uint32_t> firstPoint,
                     std::span<const std::array<Real, 2>> tangentTargets,
                     const std::array<Real, 3>& scales, Real slop, Real inverseH);
    /// The normal impulses of the manifolds in exactly solved groups, after the groups' solve.
    void readGroupImpulses(std::span<const ContactConstraint> constraints);
    /// Split impulse's relax sweeps aim at the rebound alone (see ConstraintSolver::relax).
    void dropBounceCorrections();
    /// Writes the impulses back into the constraints (warm start of the next step, reports).
    void store(std::span<ContactConstraint> constraints) const;
    /// Number of colours of the last build.
    int colourCount() const { return colourCount_; }

private:
    struct Point {
        Lane angularA[3], angularB[3];  // rA x n, rB x n
        Lane impulseA[3], impulseB[3];  // I^-1 (r x n)
        Lane tangentAngularA[2][3], tangentAngularB[2][3];
        Lane tangentImpulseA[2][3], tangentImpulseB[2][3];
        Lane tangentBlock[4], tangentInverse[4];  // K and K^-1 on the tangent plane, by rows
        Lane tangentMoments[2], tangentAxes[4];   // K's eigen-decomposition (DiscBlock), by rows
        Lane tangentMass[2];                      // box model
        Lane normalMass;
        Lane normalImpulse, tangentImpulse[2];
        // normalTarget = (targetBase + bias/h * depth) - bounceCorrection/h
        Lane targetBase, depth, correction;
    };
    // A bundle's normal block and the factor it cached: only bundles of several points (and
    // every bundle when measuring the change) have one, so a pile's bundles stream no 1 KB of
    // zeros.
    struct Block {
        Lane block[16];           // the normal block K, by rows
        Lane factor[16];          // L of the cached active set by rows, identity on the other rows
        Lane inverseDiagonal[4];  // 1 / L_ii (NormalFactor::inverseDiagonal), 1 off the set
    };
    struct Bundle {
        static constexpr std::uint32_t kNoBlock = ~0u;
        std::uint32_t firstPoint = 0;    // its maxPoints slots in points_
        std::uint32_t block = kNoBlock;  // into blocks_
        std::array<std::uint32_t, 4> bodyA{}, bodyB{}, constraint{};
        std::array<std::uint8_t, 4> points{};  // per lane; 0 for padding
        std::uint8_t maxPoints = 0;
        std::uint8_t laneCount = 0;
        bool angular = false;           // a lane has spinning or rolling rows
        bool grouped = false;           // a lane's normal rows belong to an exactly solved group
        std::array<bool, 4> normals{};  // per lane: this sweep solves its normal rows
        std::array<unsigned, 4> factorSet{};  // the active set `factor` holds, per lane
        Lane normal[3], tangents[2][3];
        Lane inverseMassA, inverseMassB, friction;
        Lane tangentTarget[2]{};  // the friction rows' v_t target; 0 but in the soft step
        LaneMask hasPoint[4];     // lanes whose manifold has point i
        LaneMask solved{};        // lanes with points whose normal rows the sweep solves
        unsigned slidBiased = 0;  // soft step: lanes whose patch slid in the biased sweep
    };
    struct Velocity {
        Real v[6];  // linear, then angular (world)
    };

    void colour(std::span<const SolverBody> bodies, std::span<const ContactConstraint> constraints);
    void fill(Bundle& bundle, int lane, const ContactConstraint& c, std::uint32_t index, Real slop,
              Real inverseH);
    Real solveFriction(Bundle& bundle, const SolverSettings& settings, Lane (&v)[2][6]);
    /// gather, then solveFriction.
    Real gatherFriction(Bundle& bundle, const SolverSettings& settings, Lane (&v)[2][6]);
    /// Both kernels' body: the gather when kGather, then the friction's copy for the settings.
    template <bool kGather>
    Real frictionWith(Bundle& bundle, const SolverSettings& settings, Lane (&v)[2][6]);
    template <int kPoints, bool kPlain>
    Real solveFrictionLanes(Bundle& bundle, const SolverSettings& settings, Lane (&v)[2][6]);
    /// The sliding patch (slide_patch.h) of each lane of several points in `only` (bit per
    /// lane), lane by lane; `soft` leaves the lanes of exactly solved groups, as the biased
    /// sweep's friction does. Returns the lanes that slid (bit per lane), which the relax sweep
    /// solves again after its normal rows.
    unsigned slidePatches(Bundle& bundle, std::span<const SolverBody> solverBodies,
                          const SolverSettings& settings, bool soft, unsigned only,
                          Lane (&v)[2][6]);
    /// The lanes (bit per lane) whose patch surely sticks (patchSticks in slide_patch.h), which
    /// slidePatches leaves.
    unsigned stickingPatches(const Bundle& bundle, const Lane (&v)[2][6]) const;
    template <class Solve>
    bool onPatch(Bundle& bundle, int lane, std::span<const SolverBody> solverBodies,
                 Lane (&v)[2][6], Solve&& solve);
    /// solveFriction with the lanes in `held` (bit per lane) left as they were (soft step).
    Real solveFrictionHolding(Bundle& bundle, const SolverSettings& settings, Lane (&v)[2][6],
                              unsigned held);
    /// The soft relax sweep's rows after its normal rows: the lanes of one point's friction
    /// again, the angular rows, the faces whose patch slid solved again.
    Real relaxAfterNormals(Bundle& bundle, std::span<const SolverBody> bodies,
                           std::span<ContactConstraint> constraints, const SolverSettings& settings,
                           unsigned slid, Lane (&v)[2][6]);
    Real solveNormals(Bundle& bundle, std::span<ContactConstraint> constraints,
                      std::span<NormalFactor> factors, const SolverSettings& settings, Real bias,
                      Real inverseH, bool soft, Lane (&v)[2][6]);
    template <int kPoints>
    Real solveNormalsLanes(Bundle& bundle, std::span<ContactConstraint> constraints,
                           std::span<NormalFactor> factors, const SolverSettings& settings,
                           Real bias, Real inverseH, bool soft, Lane (&v)[2][6]);
    /// The torsion and rolling rows of the bundle's lanes that have them, on velocities_.
    Real solveAngular(Bundle& bundle, std::span<const SolverBody> bodies,
                      std::span<ContactConstraint> constraints, Real omega);
    Real solveAngularAlone(Bundle& bundle, int lane, std::span<const SolverBody> bodies,
                           ContactConstraint& c, Real omega);
    Real solveNormalsAlone(Bundle& bundle, int lane, ContactConstraint& c, NormalFactor& factor,
                           const SolverSettings& settings, Real bias, Real inverseH, bool soft);
    void gather(const Bundle& bundle, Lane (&v)[2][6]) const;
    void gatherLanes(const Bundle& bundle, Lane (&v)[2][6]) const;
    void scatter(const Bundle& bundle, const Lane (&v)[2][6]);
    void scatterLanes(const Bundle& bundle, const Lane (&v)[2][6]);

    std::vector<Bundle> bundles_;
    // The bundles' point slots, one after another: a bundle of one-point manifolds takes one
    // (a pile's), not four.
    std::vector<Point> points_;
    std::vector<Block> blocks_;
    std::vector<Velocity> velocities_;     // per body, then the dummy of the padding lanes
    std::vector<std::uint32_t> bodyNext_;  // per body: the lowest colour its next manifold may take
    std::vector<std::uint32_t> constraintColour_;
    std::vector<std::uint32_t> groupBegin_;  // per colour and point count, then the end
    std::vector<std::uint32_t> groupNext_;
    std::vector<std::uint32_t> order_;  // constraints by group, constraint order within one
    int colourCount_ = 0;
    // Soft step, per point slot as points_: the separation softTargets wrote (for a lane solved
    // alone) and the mass scale of the biased sweep (1 for a speculative point and padding).
    struct SoftSlot {
        Lane separation, scale;
    };
    std::vector<SoftSlot> soft_;
    std::array<Real, 3> softScales_{1, 1, 1};  // SoftContact::massScale
    bool softTargets_ = false;                 // since the build: the targets are softTargets'
};

}  // namespace tumble
