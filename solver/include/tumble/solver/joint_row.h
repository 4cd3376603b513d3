#pragma once
/// Joints as constraint rows, solved in ConstraintSolver's PGS sweeps before the contacts,
/// with the same warm starting and stabilisation.
///
/// Every joint has one block of equality rows, solved exactly in each sweep (so a ball joint has
/// no order bias between its directions, and a weld on a long lever with a small inertia, whose
/// linear and angular rows are strongly coupled, holds: solved as two blocks one after the
/// other, such a weld did not converge and gained energy), plus an axial row:
///
/// - point rows (ball, hinge, fixed): the anchors coincide. J v = vB + wB x rB - vA - wA x rA,
///   K = (1/mA + 1/mB) 1 - [rA]x IA^-1 [rA]x - [rB]x IB^-1 [rB]x, C = pB - pA (3 rows).
/// - perpendicular rows (slider): B's anchor stays on A's axis: the same rows along the two
///   directions t1, t2 normal to the axis, with A's lever arm rA + d (d = pB - pA), C = t . d.
/// - angular rows: hinge: wB - wA has no component normal to the axis (2 rows, C = the
///   rotation taking A's axis to B's, normal part); fixed and slider: wB - wA = 0 (3 rows, C =
///   the rotation vector from the relative orientation at creation to the current one).
///   K = IA^-1 + IB^-1, projected on the rows.
/// - axial row (one Jacobian, up to three uses): hinge: axis . (wB - wA); slider: the linear
///   velocity along the axis; distance: along the line between the anchors. It carries the
///   motor (J v -> target speed, |impulse| <= maxMotorForce h), the lower and upper limits
///   (one-sided, like a contact: lambda >= 0 at the lower limit, <= 0 at the upper), or, when
///   lower == upper (a rod, a locked hinge), one equality row.
///
/// Stabilisation. Under split impulse (the default) the velocity sweeps carry no position error
/// at all: after them, solveJointPositions runs its own Gauss-Seidel sweeps on the
/// pseudo-velocities, aiming to remove beta C within the step (beta = splitImpulseFactor), and
/// the pseudo-velocities move the bodies this step only. Sharing the contacts' scheme (the bias
/// in the biased sweeps, taken out again by the relax sweeps) was tried first: on a chain the
/// relax sweeps do not converge, the rest of the bias stayed in the real velocity and in the
/// warm start, and a 20-link chain hanging at rest gained energy until it exploded (as it does
/// under Baumgarte with 10 iterations). Under Baumgarte the target -beta C / h stays in every
/// velocity sweep (beta = baumgarte), for the study's comparison. A limit not yet reached
/// (C > 0) is speculative, as a contact gap: J v >= -C / h in every sweep.
///
/// Curvature. Semi-implicit Euler moves an anchor on a spinning body along the chord, so even a
/// row satisfied exactly in velocity drifts by ~h^2 |w|^2 r / 2 per step. Removing that drift as
/// a position error afterwards loses kinetic energy at every step (a rod pendulum released at
/// 170 deg swung with half its period); so the drift, predicted from the current velocities in
/// every sweep, is part of each row's target in the real velocity: the constraint holds at the
/// end of the step, as in SHAKE, whose energy error stays bounded. The error left is O(h^3).
///
/// Deterministic: joints are solved in array order.

#include <array>
#include <cstdint>
#include <limits>
#include <span>
#include <vector>

#include "tumble/core/solver_types.h"
#include "tumble/solver/solver_body.h"
#include "tumble/solver/spring_row.h"

namespace tumble {

struct JointRow {
    JointType type = JointType::Ball;
    std::uint32_t bodyA = 0;  ///< index into the solver's body array
    std::uint32_t bodyB = 0;
    Vec3 rA = Vec3::Zero();          ///< from A's centre of mass to its anchor (world, m)
    Vec3 rB = Vec3::Zero();          ///< from B's centre of mass to its anchor (world, m)
    Vec3 separation = Vec3::Zero();  ///< anchor B - anchor A at the start of the step (world, m)
    /// Hinge, slider: the joint axis fixed in A (world, unit); distance: the direction used
    /// when the anchors coincide.
    Vec3 axis = Vec3::UnitZ();
    /// Rotation vector (rad, world): hinge: taking A's axis to B's (only the part normal to the
    /// axis is used); fixed, slider: from the orientation B should have relative to A to the one
    /// it has.
    Vec3 angularError = Vec3::Zero();
    /// The axial coordinate at the start of the step: hinge angle (rad), slider translation
    /// along the axis (m), distance between the anchors (m).
    Real position = 0;
    Real lower = -std::numeric_limits<Real>::infinity();  ///< limit on position; -inf: none
    Real upper = std::numeric_limits<Real>::infinity();   ///< limit on position; +inf: none
    bool motor = false;
    Real motorSpeed = 0;     ///< target d(position)/dt (rad/s or m/s)
    Real maxMotorForce = 0;  ///< torque (N m) or force (N) cap, >= 0

    // Accumulated impulses, on B (A gets the opposite): warm start in, result out.
    Vec3 linearImpulse = Vec3::Zero();   ///< point or perpendicular block (N s, world)
    Vec3 angularImpulse = Vec3::Zero();  ///< angular block (N m s, world)
    Real motorImpulse = 0;               ///< axial motor row (N s or N m s)
    Real lowerImpulse = 0;               ///< lower limit row, >= 0; or the equality row
    Real upperImpulse = 0;               ///< upper limit row, <= 0
    /// linearImpulse one step further back (N s, world): how fast the tension changes
    /// (applyJointGeometricStiffness). Read only.
    Vec3 previousLinearImpulse = Vec3::Zero();

    // Filled by prepareJointRows().
    bool active = false;  ///< false when neither body can move
    int linearRows = 0;   ///< equality rows on the anchors' relative velocity, along directions
    int angularRows = 0;  ///< then equality rows on the relative spin, along directions
    std::array<Vec3, 6> directions{Vec3::Zero(), Vec3::Zero(), Vec3::Zero(),
                                   Vec3::Zero(), Vec3::Zero(), Vec3::Zero()};  ///< unit, world:
    ///< the linear rows' directions, then the angular rows'
    /// Inverse of the equality rows' block K = J M^-1 J' (the first linearRows + angularRows
    /// rows and columns; zero elsewhere).
    Eigen::Matrix<Real, 6, 6> blockInverse = Eigen::Matrix<Real, 6, 6>::Zero();
    Eigen::Matrix<Real, 6, 1> error = Eigen::Matrix<Real, 6, 1>::Zero();  ///< C per row (m, rad)
    Vec3 pointDrift = Vec3::Zero();     ///< predicted second-order drift of anchor B - anchor A (m)
    Vec3 leverA = Vec3::Zero();         ///< A's lever arm: rA, or rA + d for the slider (m)
    Vec3 axialLinear = Vec3::Zero();    ///< linear part of the axial Jacobian (unit or zero)
    Vec3 axialAngularA = Vec3::Zero();  ///< A's angular part (m, or 1 for the hinge)
    Vec3 axialAngularB = Vec3::Zero();
    Real axialMass = 0;    ///< 1 / (J M^-1 J') of the axial row
    Real axialDrift = 0;   ///< predicted second-order drift of position (m)
    Real pseudoLower = 0;  ///< position pass: lower limit (or equality) impulse, this step only
    Real pseudoUpper = 0;  ///< position pass: upper limit impulse, this step only
    /// The point rows go through the direct block (buildJointBlockRows), not the PGS sweeps.
    bool blockSolved = false;
};

/// Jacobians, effective masses and drift predictions for a step of length h; applies the
/// warm-start impulses (or zeroes them when !warmStart). Motor impulses are capped by the
/// force cap of this step.
void prepareJointRows(std::span<SolverBody> bodies, std::span<JointRow> rows, Real h,
                      bool warmStart);

/// One Gauss-Seidel pass over the joints: per joint the motor, the limits, the angular block,
/// then the point block (what matters most last). `bias` is beta (0 in the relax sweeps);
/// returns the largest change of a row's velocity caused by an update (m/s or rad/s).
Real solveJointRows(std::span<SolverBody> bodies, std::span<JointRow> rows, Real relaxation,
                    Real bias, Real inverseH);

/// Split impulse's position pass for joints: `sweeps` Gauss-Seidel sweeps on the
/// pseudo-velocities (held in `pseudoBodies`, with the real bodies' masses) that remove `bias`
/// (beta) of every position error within the step. Run after the velocity solve, cold-started:
/// the correction moves positions and never enters the real velocity or the warm start.
void solveJointPositions(std::span<SolverBody> pseudoBodies, std::span<JointRow> rows, Real bias,
                         Real inverseH, int sweeps);

/// Implicit geometric stiffness of the point rows (ball, hinge, fixed, slider), applied to the
/// bodies before the solve; `stiffness` is scratch, two entries per body (resized, so no
/// allocation once warm). The rows hold last step's impulses Lambda (the warm start, read
/// before prepareJointRows zeroes or projects them) and the step's before (previousLinearImpulse).
///
/// Why. A row's impulse acts at a lever arm r fixed at the step's start, but the body turns
/// within the step; the torque r x Lambda then changes by (h w x r) x Lambda = h S w with
/// S = r Lambda' - (Lambda . r) 1. Taking it at the start is explicit: a link under tension T
/// has a rotational mode of omega^2 = T L / I (12 T / (m L) for a rod) that semi-implicit Euler
/// only keeps while omega h < 2, however well the rows converge. The 20-link chain with a
/// 100x load (omega h ~ 6 at h = 1/60) flew apart with 10 or 300 sweeps alike, and with the
/// load on only 2 links; it held at h = 1/240.
///
/// What. The body gets the effective inertia A = I - beta h S (S summed over the body's rows
/// with the lagged Lambda; only its symmetric negative part K -- tension, restoring -- so
/// A >= I stays positive definite). beta per body from its own a^2 = (omega h)^2 (the largest
/// eigenvalue of h I^-1 K): 0 while a^2 <= 1 -- a body whose motion the step resolves is left
/// exactly as it was -- and 1/2 - 1/(2 a^2) beyond, which holds the effective a^2 / (1 + beta
/// a^2) in [1, 2), half symplectic Euler's single-mode limit (neighbouring links couple, and
/// Lambda lags a step). The body keeps its w0, A (w1 - w0) = sum r x Lambda, when the tension
/// is steady: on one mode symplectic Euler on A, determinant 1, nothing damped. It starts from
/// w0 - phi beta A^-1 K w0 instead, phi = min(1, kTensionDamping |S - S_prev| / |S|) (S_prev
/// from previousLinearImpulse): phi = 1 is backward Euler's start A^-1 I w0, amplification
/// 1 / (1 + beta a^2) per step. Why both: always phi = 1 damped every motion the tension
/// carries, the swing included (a 30-bead chain kept 54 % of its swing after 20 s at
/// h = 1/60); always phi = 0 let 2 rods under a 100x load pump energy out of the tension's
/// step-to-step change (lagged Lambda, an A that moves under w) and fly apart after ~15 s.
/// Distance rows are left out: their geometric stiffness couples the two bodies' translations.
void applyJointGeometricStiffness(std::span<SolverBody> bodies, std::span<const JointRow> rows,
                                  Real h, std::vector<Mat3>& stiffness);

/// The direct block of the joints (SolverSettings::jointSolve Direct): every active ball
/// joint's three point rows as rigid rows (zero softness) of a SpringBlockSolver, solved
/// exactly together in each sweep. PGS carries a load through a chain at ~N^2 sweeps, and a
/// 100:1 load under 20 links stretched the joints by ~10 mm with 10 + 10 sweeps (0.1 mm with
/// 200 + 200). Hinge, weld and slider blocks, limits and motors stay in PGS. Fills `block`
/// (three rows per such joint, in joint order, warm-started from linearImpulse, which
/// prepareJointRows has already applied) and marks the joints blockSolved. Call after
/// prepareJointRows.
void buildJointBlockRows(std::span<const SolverBody> bodies, std::span<JointRow> rows,
                         std::vector<SpringRow>& block);

/// Before each block solve: the rows' targets from the curvature drift at the current
/// velocities (and -beta C / h under Baumgarte, `bias` = beta).
void updateJointBlockTargets(std::span<const SolverBody> bodies, std::span<JointRow> rows,
                             std::span<SpringRow> block, Real bias, Real inverseH);

/// After the solve: the block's impulses back into the joints' linearImpulse.
void storeJointBlockImpulses(std::span<JointRow> rows, std::span<const SpringRow> block);

/// What a joint's impulses of the last solve mean as a reaction on B over a step of length h:
/// force (N, world) and torque about the anchor (N m, world).
Vec3 jointReactionForce(const JointRow& row, Real h);
Vec3 jointReactionTorque(const JointRow& row, Real h);

}  // namespace tumble
