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
#include <cstdint>
#include <span>
#include <vector>

#include "tumble/solver/joint_row.h"
#include "tumble/solver/normal_islands.h"
#include "tumble/solver/solver_body.h"
#include "tumble/solver/spring_block.h"
#include "tumble/solver/spring_row.h"

namespace tumble {

enum class FrictionModel : std::uint8_t {
    Coupled,  ///< disc projection: isotropic (default)
    Box,      ///< two independent tangent rows (the study's Bullet)
};

enum class Stabilisation : std::uint8_t {
    SplitImpulse,  ///< pseudo-velocities, never in the real velocity (default)
    Baumgarte,     ///< bias k_erp / h * depth in the velocity rows (Bullet's default)
};

/// How the implicit spring rows are solved (spring_block.h).
enum class SpringSolve : std::uint8_t {
    Direct,     ///< all rows at once by a sparse factorisation: implicit Euler at any stiffness
    Iterative,  ///< Gauss-Seidel next to the contacts: cheaper, wrong when unconverged
};

struct SolverSettings {
    int iterations = 10;  ///< PGS sweeps over the velocity rows, >= 1
    /// Split impulse: sweeps without the bias after the biased ones, removing the push-out
    /// velocity, >= 0. Too few leave some of it in the real velocity: a 100 kg box on a 1 kg box
    /// bounced on the ground with 4 or 6 and came to rest with 8 or more.
    int relaxIterations = 10;
    Real tolerance = 0;   ///< (m/s), >= 0: stop early when no impulse changes a velocity
                          ///< by more than this in a sweep; 0 runs the full budget
    Real relaxation = 1;  ///< successive over-relaxation factor, in (0, 2)
    FrictionModel friction = FrictionModel::Coupled;
    Stabilisation stabilisation = Stabilisation::SplitImpulse;
    Real baumgarte = 0.2;  ///< k_erp, dimensionless, in [0, 1]
    Real splitImpulseFactor =
        0.2;  ///< fraction of the depth beyond the slop removed per step by split impulse, (0, 1]
    Real slop = 0.005;  ///< penetration left alone (m), >= 0
    Real restitutionThreshold =
        1;                  ///< approach speed below which contacts are inelastic (m/s), >= 0
    bool warmStart = true;  ///< start from the cached impulses
    SpringSolve springSolve = SpringSolve::Direct;
    /// Post-stabilisation of implicit springs: after the positions move, remove the length a
    /// spring gained by turning within the step, which the linearised solve cannot see (see
    /// SolveStage::projectSprings). Off reproduces the plain linearised implicit step.
    bool projectSprings = true;
    /// Implicit geometric stiffness of joints' point rows for the motion a step cannot resolve
    /// (see applyJointGeometricStiffness); off reproduces the explicit lever arms.
    bool jointGeometricStiffness = true;
    /// Ball joints' point rows: one exact sparse block solve per sweep (buildJointBlockRows)
    /// or Gauss-Seidel with the other joint rows.
    SpringSolve jointSolve = SpringSolve::Direct;
};

/// The two friction directions the solver uses for normal n (unit): orthonormal, right-handed
/// with n, and a deterministic function of n. Callers caching friction impulses between steps
/// convert through it.
std::array<Vec3, 2> frictionBasis(const Vec3& n);

/// Refuses (InvalidArgument) settings outside the ranges documented on each field.
void checkSolverSettings(const SolverSettings& settings);

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

struct ContactConstraintPoint {
    Vec3 rA = Vec3::Zero();  ///< from A's centre of mass to the point (world, m)
    Vec3 rB = Vec3::Zero();  ///< from B's centre of mass to the point (world, m)
    Real separation = 0;     ///< along the normal at the start of the step (m); < 0 penetrating
    Real normalImpulse = 0;  ///< accumulated (N s): warm start in, result out
    std::array<Real, 2> tangentImpulse{};  ///< along tangent1, tangent2 (N s)

    // Filled by prepare().
    Real normalMass = 0;              ///< effective mass along the normal (kg)
    DiscBlock tangent;                ///< K on the tangent plane: slip velocity per impulse (1/kg)
    Mat3 tangentMass = Mat3::Zero();  ///< diagonal: 1 / K_tt of each tangent row (kg), box model
    Vec3 angularA = Vec3::Zero();     ///< rA x n: A's angular normal Jacobian (m)
    Vec3 angularB = Vec3::Zero();     ///< rB x n (m)
    Vec3 angularImpulseA = Vec3::Zero();    ///< IA^-1 (rA x n): A's spin per unit normal impulse
    Vec3 angularImpulseB = Vec3::Zero();    ///< IB^-1 (rB x n)
    std::array<Vec3, 2> tangentAngularA{};  ///< rA x t_k for the two tangents (m)
    std::array<Vec3, 2> tangentAngularB{};  ///< rB x t_k (m)
    std::array<Vec3, 2> tangentImpulseA{};  ///< IA^-1 (rA x t_k)
    std::array<Vec3, 2> tangentImpulseB{};  ///< IB^-1 (rB x t_k)
    /// Normal relative acceleration from the forces of this step (gravity...), (m/s^2); with it
    /// the solver finds when within the step, and how fast, a speculative point hits (see
    /// prepare). Zero when the caller does not know it.
    Real normalAcceleration = 0;
    Real approachSpeed = 0;  ///< v_n before the solve (m/s), negative when approaching
    /// Part of v_n that the other contacts' support gives within the step (m/s), set by prepare
    /// (bounce_support.h); the impact is found with it, the acceleration includes it.
    Real supportSpeed = 0;
    Real impactTime = 0;    ///< of the impact within the step (s), 0 when already touching
    Real impactSpeed = 0;   ///< v_n at that time (m/s), negative when approaching
    Real reboundSpeed = 0;  ///< v_n at the end of the step after a bounce (m/s)
    bool bounces = false;   ///< Newton's law holds this step: the row is v_n >= reboundSpeed
    /// (m): a speculative point that bounced at separation s > 0 rebounds from the surface, not
    /// from s; the biased sweeps pull it back by this (see prepare and normalTarget)
    Real bounceCorrection = 0;
};

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
    std::array<ContactConstraintPoint, 4> points;

    // Filled by prepare().
    std::array<Vec3, 2> tangents{Vec3::UnitX(), Vec3::UnitY()};
    /// K_ij: normal velocity change at point i per unit normal impulse at point j (1/kg).
    Eigen::Matrix<Real, 4, 4> normalBlock = Eigen::Matrix<Real, 4, 4>::Zero();
    Real spinMass = 0;           ///< 1 / n'(IA^-1 + IB^-1) n (kg m^2); 0: no spinning row
    DiscBlock rolling;           ///< K of the relative spin about the tangents (1/(kg m^2))
    bool rollingActive = false;  ///< rolling rows solved this step
    Real angularReach = 0;       ///< farthest point from either centre of mass (m)
    /// Group whose normal rows NormalIslands solves together, or NormalIslands::kNone: the
    /// manifold's own block (normal_block.h).
    std::uint32_t normalGroup = NormalIslands::kNone;
};

struct SolverStats {
    int iterations = 0;           ///< velocity sweeps actually run
    Real maxResidual = 0;         ///< largest complementarity residual after the solve (m/s)
    Real deepestPenetration = 0;  ///< largest -separation at the start of the step (m), >= 0
};

/// Extra velocity state for split impulse: moves positions this step only.
struct PseudoVelocity {
    Vec3 linear = Vec3::Zero();
    Vec3 angular = Vec3::Zero();
};

class ContactSolver {
public:
    /// Solves the contacts for one step of length h. `bodies` hold the velocities after forces;
    /// on return they hold the constrained velocities, `pseudo` the split-impulse velocities
    /// (zero under Baumgarte) to add when integrating positions only. Impulses are written back
    /// into `constraints` for warm starting the next step. Allocates only when the arrays grow.
    /// Implicit spring rows (spring_row.h), when given, are solved first in every biased and
    /// relax sweep alike (they are forces, not stabilisation); their impulses are written back.
    /// Joint rows (joint_row.h), when given, are solved after the springs and before the
    /// contacts in every sweep, with the same bias as the contacts; impulses written back.
    SolverStats solve(std::span<SolverBody> bodies, std::span<ContactConstraint> constraints,
                      std::vector<PseudoVelocity>& pseudo, Real h, const SolverSettings& settings,
                      std::span<SpringRow> springs = {}, std::span<JointRow> joints = {});

private:
    void prepare(std::span<SolverBody> bodies, std::span<ContactConstraint> constraints, Real h,
                 const SolverSettings& settings);
    /// Runs up to `sweeps` PGS sweeps with the given bias factor; returns the number run.
    int runSweeps(std::span<SolverBody> bodies, std::span<ContactConstraint> constraints,
                  std::span<SpringRow> springs, const SolverSettings& settings, Real inverseH,
                  Real bias, int sweeps);
    Real solveVelocitySweep(std::span<SolverBody> bodies, std::span<ContactConstraint> constraints,
                            const SolverSettings& settings, Real inverseH, Real bias);
    Real solveAngularFriction(SolverBody& a, SolverBody& b, ContactConstraint& c, Real omega) const;
    void solveNormals(SolverBody& a, SolverBody& b, ContactConstraint& c,
                      const SolverSettings& settings, Real inverseH, Real bias,
                      Real& largestChange) const;
    Real residual(std::span<const SolverBody> bodies,
                  std::span<const ContactConstraint> constraints, const SolverSettings& settings,
                  Real inverseH, Real bias) const;

    SpringBlockSolver springBlock_;
    NormalIslands islands_;       ///< normal rows of small, ill-conditioned groups, solved exactly
    bool directSprings_ = false;  ///< this step's springs go through springBlock_
    /// Split impulse's position pass for the joints (solveJointPositions) on `pseudo`.
    void correctJoints(std::span<const SolverBody> bodies, std::vector<PseudoVelocity>& pseudo,
                       Real inverseH, const SolverSettings& settings);

    std::span<JointRow> joints_;            ///< of the solve in progress
    Real jointBias_ = 0;                    ///< their bias in the velocity sweeps (Baumgarte only)
    std::vector<Mat3> geometricStiffness_;  ///< scratch of applyJointGeometricStiffness
    SpringBlockSolver jointBlock_;          ///< ball joints' point rows (jointSolve Direct)
    std::vector<SpringRow> jointBlockRows_;
    bool directJoints_ = false;              ///< this step's ball joints go through jointBlock_
    std::vector<SolverBody> pseudoBodies_;   ///< the joints' position pass works on these
    std::vector<SolverBody> supportBodies_;  ///< scratch of addSupportAcceleration
};

}  // namespace tumble
