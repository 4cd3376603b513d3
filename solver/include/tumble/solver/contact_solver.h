#pragma once
/// Contact constraints solved by projected Gauss-Seidel (PGS), the Stewart-Trinkle time-stepping
/// scheme of Bullet, PhysX and Havok, with the changes that make it right for engineering use:
///
/// - Non-penetration: one row per contact point, impulse lambda_n >= 0, complementary to the
///   normal velocity at the end of the step.
/// - Friction: Coulomb. Coupled by default: the two tangent rows of a point are solved together
///   with their 2x2 effective mass and the tangent impulse is projected onto the disc
///   |lambda_t| <= mu lambda_n, so friction is the same in every direction. The box model (each
///   tangent row clamped to [-mu lambda_n, mu lambda_n] on its own, as in the ESA study's Bullet)
///   is kept as an option; it overestimates friction by up to sqrt(2) off the tangent axes.
/// - Restitution: Newton's law v_n+ = -e v_n-, with v_n- the approach speed measured BEFORE the
///   solve, below a threshold speed contacts are inelastic. A point that approaches faster and
///   reaches the surface within the step demands v_n >= v_n+ in the same rows as every other
///   contact (normal_block.h, normalTarget), so contacts that carry the impact on -- a box
///   resting on the ground under a falling ball -- answer it together. A speculative point
///   (s > 0) that bounces would rebound from where it stands, s above the surface; the
///   split-impulse pass moves it by -(1 + e) s instead, which puts it where a bounce at the
///   moment of impact (t = s / |v-|) would have taken it, so bounce heights do not grow by s per
///   impact.
/// - Stabilisation: split impulse by default. The velocity sweeps aim to remove a fraction of
///   the penetration beyond the slop within the step (a bias, as in Baumgarte); the positions are
///   advanced with those biased velocities. Then `relaxIterations` sweeps without the bias,
///   warm-started from the biased impulses, take the push-out velocity back out of the real
///   velocity: the correction moves positions but leaves no energy behind. The difference
///   between the two (per body) is the pseudo-velocity. Because the biased solve is warm-started
///   like the rest, the correction reaches through a tall stack, which a separate cold-started
///   position solve (tried first) did not: its stacks leaned inside the slop and fell. Baumgarte
///   (the bias left in the real velocity, k_erp = 0.2) is kept to reproduce the study's energy
///   gain at impacts.
/// - Each manifold's normal rows are solved as one block (normal_block.h): exact, no order bias.
///   Small groups of manifolds between bodies of very different masses, or carrying an impact,
///   are solved as one block of all their normal rows (normal_islands.h), which PGS cannot
///   converge (a 1000:1 stack launched itself).
/// - Speculative contacts: a point with separation s > 0 only demands v_n >= -s / h: the bodies
///   may close the gap within the step but not pass it, so fast bodies do not tunnel.
/// - Spinning and rolling friction (optional, per manifold): a rigid point contact cannot resist
///   a relative spin about its normal, nor rolling, so a ball dropped into a pile spins and rolls
///   for ever and keeps the pile awake. A real contact is a patch: its torsional friction is
///   limited to spinningFriction x normal force, its rolling resistance to rollingFriction x
///   normal force (lengths, as Bullet's spinning and rolling friction and ODE's rho). One scalar
///   row about the normal, clamped; two rows about the tangents solved as a disc like the
///   linear friction. Only the angular velocities enter; rows exist only when the length > 0.
///
/// Works on flat arrays of SolverBody (velocities, inverse masses) and ContactConstraint (indices
/// into the body array); knows no shapes. Deterministic: constraints are solved in array order.

#include <array>
#include <cmath>
#include <cstdint>
#include <span>
#include <vector>

#include "tumble/core/solver_types.h"
#include "tumble/solver/contact_rows.h"
#include "tumble/solver/disc_block.h"
#include "tumble/solver/normal_islands.h"
#include "tumble/solver/solver_body.h"
#include "tumble/solver/sweep_rows.h"

namespace tumble {

/// The two friction directions the solver uses for normal n (unit): orthonormal, right-handed
/// with n, and a deterministic function of n. Callers caching friction impulses between steps
/// convert through it. Inline: the constraint builder's kernel (lane_kernel.h) takes it in.
inline std::array<Vec3, 2> frictionBasis(const Vec3& n) {
    // The reference axis is the one least aligned with n, so the basis is a continuous function
    // of n except where that choice switches.
    const Vec3 axis = std::abs(n.x()) < 0.57735
                          ? Vec3::UnitX()
                          : (std::abs(n.y()) < 0.57735 ? Vec3::UnitY() : Vec3::UnitZ());
    const Vec3 first = n.cross(axis).normalized();
    return {first, n.cross(first)};
}

/// Refuses (InvalidArgument) settings outside the ranges documented on each field.
void checkSolverSettings(const SolverSettings& settings);

/// The Cholesky factor L of K_SS + eps 1 for one active set S. K (normal_block.h) is fixed for a
/// step and the active set rarely changes between sweeps, so each manifold keeps the last one it
/// factored: recomputing it at every call was a third of the block's time.
struct NormalFactor {
    static constexpr unsigned kNone = ~0u;
    unsigned set = kNone;       ///< S as a bit mask; kNone: nothing factored (reset per step)
    int size = 0;               ///< |S|
    std::array<int, 4> rows{};  ///< the rows of S, ascending
    Real l[4][4] = {};          ///< lower triangle of L, |S| x |S|
    /// 1 / L_ii: the substitutions multiply by it. Dividing by L_ii, eight dependent divisions
    /// per block solve, was the longest stretch of a lone column's sweep (one chain of
    /// manifolds); the product differs from the quotient by a rounding.
    Real inverseDiagonal[4] = {};
};

/// One contact point. The fields most passes read (the engine's build and read-back, the warm
/// start, the residual, the bounce bookkeeping) come first and fill the first two cache lines;
/// prepare's derived rows follow. A pile's manifolds hold 1.2 points of the four slots, and the
/// passes over the constraints stream only the lines they touch.
struct alignas(64) ContactConstraintPoint {
    Vec3 rA = Vec3::Zero();  ///< from A's centre of mass to the point (world, m)
    Vec3 rB = Vec3::Zero();  ///< from B's centre of mass to the point (world, m)
    Real separation = 0;     ///< along the normal at the start of the step (m); < 0 penetrating
    Real normalImpulse = 0;  ///< accumulated (N s): warm start in, result out
    std::array<Real, 2> tangentImpulse{};  ///< along tangent1, tangent2 (N s)
    /// Normal relative acceleration from the forces of this step (gravity...), (m/s^2); with it
    /// the solver finds when within the step, and how fast, a speculative point hits (see
    /// prepare). Zero when the caller does not know it.
    Real normalAcceleration = 0;
    /// Part of v_n that the other contacts' support gives within the step (m/s), set by prepare
    /// (bounce_support.h); the impact is found with it, the acceleration includes it.
    Real supportSpeed = 0;

    // Filled by prepare().
    Real normalMass = 0;    ///< effective mass along the normal (kg)
    Real reboundSpeed = 0;  ///< v_n at the end of the step after a bounce (m/s)
    /// (m): a speculative point that bounced at separation s > 0 rebounds from the surface, not
    /// from s; the biased sweeps pull it back by this (see prepare and normalTarget)
    Real bounceCorrection = 0;
    bool bounces = false;          ///< Newton's law holds this step: the row is v_n >= reboundSpeed
    Real approachSpeed = 0;        ///< v_n before the solve (m/s), negative when approaching
    Real impactTime = 0;           ///< of the impact within the step (s), 0 when already touching
    Real impactSpeed = 0;          ///< v_n at that time (m/s), negative when approaching
    Vec3 angularA = Vec3::Zero();  ///< rA x n: A's angular normal Jacobian (m)
    Vec3 angularB = Vec3::Zero();  ///< rB x n (m)
    Vec3 angularImpulseA = Vec3::Zero();  ///< IA^-1 (rA x n): A's spin per unit normal impulse
    Vec3 angularImpulseB = Vec3::Zero();  ///< IB^-1 (rB x n)
    DiscBlock tangent;  ///< K on the tangent plane: slip velocity per impulse (1/kg)
    std::array<Real, 2> tangentMass{};      ///< 1 / K_tt of each tangent row (kg), box model
    std::array<Vec3, 2> tangentAngularA{};  ///< rA x t_k for the two tangents (m)
    std::array<Vec3, 2> tangentAngularB{};  ///< rB x t_k (m)
    std::array<Vec3, 2> tangentImpulseA{};  ///< IA^-1 (rA x t_k)
    std::array<Vec3, 2> tangentImpulseB{};  ///< IB^-1 (rB x t_k)
};

/// A manifold: its own fields first (those prepare fills too), the four point slots last, so a
/// one-point manifold's hot lines lie together.
struct ContactConstraint {
    std::uint32_t bodyA = 0;  ///< index into the body array
    std::uint32_t bodyB = 0;
    Vec3 normal = Vec3::UnitZ();  ///< from A to B, unit
    Real friction = 0;            ///< Coulomb mu, >= 0 (no friction rows when 0)
    Real restitution = 0;         ///< Newton's e, in [0, 1]
    /// Torsional friction length (m), >= 0: the torque about the normal is limited to this times
    /// the manifold's normal force (a contact patch of radius a under uniform pressure and
    /// Coulomb mu has 2/3 mu a). No row when 0.
    Real spinningFriction = 0;
    /// Rolling resistance length (m), >= 0: the torque opposing rolling (relative spin about
    /// the tangents) is limited to this times the normal force. No rows when 0.
    Real rollingFriction = 0;
    /// Accumulated torsion and rolling-resistance impulse on B, -this on A (N m s), world frame:
    /// warm start in, result out.
    Vec3 angularImpulse = Vec3::Zero();
    int pointCount = 0;
    /// Split impulse: false leaves the depth beyond the slop out of the biased sweeps; it is
    /// pushed out afterwards on the pseudo-velocities alone (sprung_push_out.h). For the
    /// contacts of bodies that springs end on.
    bool pushOut = true;
    /// True when the builder already set `tangents` to frictionBasis(normal) (it projects the
    /// cached friction onto them): prepare() keeps them instead of taking the basis again.
    bool tangentsSet = false;

    // Filled by prepare().
    /// Group whose normal rows NormalIslands solves together, or NormalIslands::kNone: the
    /// manifold's own block (normal_block.h).
    std::uint32_t normalGroup = NormalIslands::kNone;
    std::array<Vec3, 2> tangents{Vec3::UnitX(), Vec3::UnitY()};
    Real spinMass = 0;           ///< 1 / n'(IA^-1 + IB^-1) n (kg m^2); 0: no spinning row
    bool rollingActive = false;  ///< rolling rows solved this step
    /// Farthest point from either centre of mass (m); 0 without spinning and rolling friction.
    Real angularReach = 0;
    /// K_ij: normal velocity change at point i per unit normal impulse at point j (1/kg).
    Eigen::Matrix<Real, 4, 4> normalBlock = Eigen::Matrix<Real, 4, 4>::Zero();
    DiscBlock rolling;  ///< K of the relative spin about the tangents (1/(kg m^2))

    std::array<ContactConstraintPoint, 4> points;
};

/// Extra velocity state for split impulse: moves positions this step only.
struct PseudoVelocity {
    Vec3 linear = Vec3::Zero();
    Vec3 angular = Vec3::Zero();
};

/// `bodies` with their velocities replaced by `pseudo`'s (the same order) into `out`: the
/// position passes solve on the pseudo-velocities as the sweeps do on the velocities.
void loadPseudoBodies(std::span<const SolverBody> bodies, std::span<const PseudoVelocity> pseudo,
                      std::vector<SolverBody>& out);
/// A position pass's velocities back into `pseudo`.
void storePseudoBodies(std::span<const SolverBody> bodies, std::span<PseudoVelocity> pseudo);

/// How far a body has moved since the step began (the soft step's separations follow it).
struct BodyDisplacement {
    Vec3 translation = Vec3::Zero();  ///< of the centre of mass (m)
    Vec3 turn = Vec3::Zero();         ///< the substeps' rotation vectors h w, summed (rad)
};

/// The soft step's contact coefficients for one substep (softContact()), by kind: 0 rigid
/// (speculative points), 1 between moving bodies, 2 against a static body.
struct SoftContact {
    std::array<Real, 3> massScale{1, 1, 1};  ///< the rigid answer's share the row keeps
    std::array<Real, 3> biasRate{0, 0, 0};   ///< push-out speed per metre of depth (1/s)
    Real maxPush = 0;                        ///< (m/s)
    Real slop = 0;  ///< the rows' slop (m): the depth softTargets writes adds it back
};

/// The soft step's coefficients for a substep of length h (docs/ARCHITECTURE.md).
SoftContact softContact(const SolverSettings& settings, Real h);

/// The contact rows' part of a solve (ConstraintSolver runs the stages and the other rows).
/// Everything a step carries over lives in the constraints; the members are this step's groups
/// of exactly solved rows and scratch.
class ContactSolver {
public:
    /// Effective masses, friction bases, approach speeds, impact times and bounces of every
    /// point, the groups solved exactly (NormalIslands), then the warm start: the cached impulses
    /// applied to `bodies` (all of them after every approach speed is measured).
    /// Returns the deepest penetration (m, >= 0), found on the way.
    Real prepare(std::span<SolverBody> bodies, std::span<ContactConstraint> constraints, Real h,
                 const SolverSettings& settings);
    /// One PGS sweep over the contacts with the given bias factor; returns the largest velocity
    /// change an impulse made (m/s). With settings.tolerance 0 nothing reads it, and only the
    /// angular rows and the exact groups are measured.
    /// `resident`: nothing has changed the bodies' velocities since the last sweep (the caller
    /// solves no other rows between them), which lets the wide rows keep their copy.
    Real solveVelocitySweep(std::span<SolverBody> bodies, std::span<ContactConstraint> constraints,
                            const SolverSettings& settings, Real inverseH, Real bias,
                            bool resident = false);
    /// Largest complementarity residual of the contacts at the current velocities (m/s).
    Real residual(std::span<const SolverBody> bodies,
                  std::span<const ContactConstraint> constraints, const SolverSettings& settings,
                  Real inverseH, Real bias) const;

    /// Split impulse's relax sweeps aim at the rebound alone: drops the bounces' position
    /// correction (normalTarget) before them.
    void dropBounceCorrections(std::span<ContactConstraint> constraints);
    /// After the last sweep: the impulses are back in the constraints (from the wide or the
    /// compact narrow rows).
    void finish(std::span<ContactConstraint> constraints) const;

    // The soft step (soft_contacts.cpp; SolveStage::runSoft runs the substeps). prepare() ran
    // with the scalar rows and the cached impulses divided among the substeps.
    /// Keeps each point's separation at the step's start and its bounce (applied once, at the
    /// end), and zeroes the sums of the substeps' impulses. `jumps`: by solver body, the
    /// velocity changes the application gave kinematic bodies since the last step (linear,
    /// angular), or empty; `start`: the bodies as the step began (before prepare's warm start).
    void beginSoft(std::span<ContactConstraint> constraints,
                   std::span<const PseudoVelocity> jumps = {},
                   std::span<const SolverBody> start = {});
    /// The separations where the bodies now stand (`moved`, by solver body), as the rows'
    /// targets under `soft`: the speculative gap, or the capped push-out encoded as a depth
    /// that the biased sweep (bias = h) turns into it. `last`: the step's last relax sweep, where
    /// a point that may bounce early in the next step is not slowed (soft_contacts.cpp).
    /// The friction rows' targets turn with the pair's shared spin about the normal (`bodies`:
    /// the current velocities) and leave `remaining` of beginSoft's jumps to later substeps;
    /// `biased`: for the biased sweep, before the substep's positions (soft_contacts.cpp).
    void softTargets(std::span<ContactConstraint> constraints, std::span<const SolverBody> bodies,
                     std::span<const BodyDisplacement> moved, const SoftContact& soft,
                     Real inverseH, Real remaining, bool biased, bool last);
    /// A substep's warm start: the accumulated impulses applied again.
    void softWarmStart(std::span<SolverBody> bodies,
                       std::span<const ContactConstraint> constraints);
    /// One sweep of a substep: soft and biased (`soft` given) or rigid without bias (null).
    void softSweep(std::span<SolverBody> bodies, std::span<ContactConstraint> constraints,
                   const SolverSettings& settings, Real inverseH, const SoftContact* soft);
    /// After a substep: its impulses into the constraints and added to the sums.
    void endSoftSubstep(std::span<ContactConstraint> constraints);
    /// Whether some point may bounce this step (beginSoft: restitution > 0).
    bool softBounces() const { return !softBounces_.empty(); }
    /// Which points bounce, and their impacts on the parabola of the substeps' flight, from the
    /// bodies' velocity changes over the first substep of hs (`change`, by solver body: the
    /// normal acceleration); h the step, `threshold` SolverSettings::restitutionThreshold.
    void softImpacts(std::span<const SolverBody> change,
                     std::span<const ContactConstraint> constraints, Real h, Real hs,
                     Real threshold);
    /// After the last substep: restitution once (with the exactly solved groups of the bouncing
    /// points, at the last relax sweep's targets: `slop` and `inverseH` the substep's), then the
    /// step's sums into the constraints. A point that bounced is lifted where its rebound would
    /// be at the step's end: `lift` (by solver body, zeroed here) gets the displacements, which
    /// the caller applies.
    void endSoft(std::span<SolverBody> bodies, std::span<ContactConstraint> constraints,
                 std::span<const BodyDisplacement> moved, std::span<PseudoVelocity> lift, Real slop,
                 Real inverseH);

private:
    /// endSoft's bouncing points in exactly solved groups: their groups' rigid solve with the
    /// bounces, and their lift (soft_contacts.cpp).
    void softGroupBounces(std::span<SolverBody> bodies, std::span<ContactConstraint> constraints,
                          std::span<const BodyDisplacement> moved, std::span<PseudoVelocity> lift,
                          Real slop, Real inverseH);
    /// One constraint's impulses summed over the substeps (N s).
    struct SoftSum {
        std::array<Real, 4> normal{};
        std::array<std::array<Real, 2>, 4> tangent{};
        Vec3 angular = Vec3::Zero();
    };
    /// A point as the soft step's separations need it, in the scalar rows' order.
    struct SoftPoint {
        static constexpr std::uint32_t kNotGrouped = ~0u;
        Vec3 angularA;  ///< rA x n (m): theta_A . this is the turn's share of the separation
        Vec3 angularB;  ///< rB x n (m)
        Vec3 normal;
        Real start;  ///< separation at the step's start (m)
        std::uint32_t bodyA;
        std::uint32_t bodyB;
        std::uint32_t grouped;  ///< 4 x constraint + point when NormalIslands solves it
        std::uint8_t kind;      ///< SoftContact's: 1 moving pair, 2 against a static body
    };
    /// A manifold with friction as the soft step's friction targets need it.
    struct SoftFriction {
        Vec3 normal;
        std::array<Vec3, 2> tangents;
        std::array<Real, 2> jump;  ///< v_t's change by the kinematic bodies' jumps (m/s)
        std::uint32_t bodyA;
        std::uint32_t bodyB;
        std::uint32_t constraint;
    };
    struct SoftBounce {
        std::uint32_t constraint = 0;
        int point = 0;
        Real target = 0;  ///< v_n after the bounce (m/s)
        Real lift = 0;    ///< the separation the rebound reaches by the step's end (m)
    };

    NormalIslands islands_;                   ///< normal rows of small, ill-conditioned groups,
                                              ///< solved exactly
    std::vector<SolverBody> supportBodies_;   ///< scratch of addSupportAcceleration
    std::vector<NormalFactor> factors_;       ///< each manifold's block factor, this step
    ContactRows rows_;                        ///< the wide rows (settings.colouredContacts)
    SweepRows narrow_;                        ///< the scalar sweep's compact rows, otherwise
    bool wide_ = false;                       ///< this step sweeps rows_
    bool bounceCorrections_ = false;          ///< some point has one this step
    std::vector<SoftPoint> softPoints_;       ///< soft step
    std::vector<Real> softSeparations_;       ///< soft step: the rows' current ones (m)
    bool softSeparationsStale_ = false;       ///< soft step: not yet computed this step
    std::vector<SoftFriction> softFriction_;  ///< soft step: the manifolds with friction
    /// soft step: each constraint's friction target, v_t along t_1, t_2 (m/s)
    std::vector<std::array<Real, 2>> softTangentTargets_;
    std::vector<std::uint32_t> softFirst_;  ///< soft step: each constraint's first SoftPoint
    std::vector<SoftSum> softSums_;         ///< soft step: per constraint
    std::vector<SoftBounce> softBounces_;   ///< soft step: the points that bounce
    std::vector<std::uint32_t> softLate_;   ///< soft step: restitution > 0, arriving later
    std::vector<SolverBody> softLifts_;     ///< soft step: softGroupBounces' displacements (m)
};

}  // namespace tumble
