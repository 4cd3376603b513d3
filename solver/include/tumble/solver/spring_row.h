#pragma once
/// Implicit spring-dampers as soft constraint rows (Catto's soft constraints), solved in
/// ConstraintSolver's sweeps next to the contacts (exactly, by spring_block.h, by default).
///
/// A spring of rest length L0, stiffness k and damping c between anchors at distance L pulls with
/// the tension k (L - L0) + c dL/dt; C = L - L0, J v = dL/dt, and lambda is the impulse along the
/// line on B (negative pulls the anchors together).
///
/// The bodies move by symplectic Euler, x1 = x0 + h v1, so the velocity v1 the solver returns is
/// the mean velocity over the step and v0 (the velocity at the step's start) that over the last
/// one: x_{-1} = x0 - h v0. In these variables Newmark's family reads as a three-level scheme,
///
///     v1 - v0 = h M^-1 (f_ext + w1 f(x1) + w0 f(x0) + w_1 f(x_{-1})),   w1 + w0 + w_1 = 1,
///
/// Symmetric weights (beta, 1 - 2 beta, beta) are second order and keep a linear mode's roots
/// on the unit circle (no numerical damping) while (omega h)^2 (1 - 4 beta) <= 4; beta = 1/12
/// (Fox-Goodwin) also makes the phase fourth order, beta = 1/4 (the trapezoidal rule) is stable
/// at every omega h. But in these variables an undamped scheme conserves a form that weighs the
/// positions by ~omega h / 2 at large omega h: a stiff spring released stretched at omega h =
/// 100 swung its mass 90x further than the stretch. Hence, by the element's (omega h)^2 =
/// h^2 k J M^-1 J' (prepareSpringRow): <= 1.5 beta = 1/12; up to 4 beta = 1/4 - 1/(4 (omega
/// h)^2), stable for a node's highest mode (~2x its element's); from 4 the damped weights
/// w1 = 1 / (1 + rho)^2, w0 = 2 rho w1, w_1 = rho^2 w1, which put both roots at omega h -> inf
/// on -rho, with rho = 4 / (omega h)^2 (rho = 0: implicit Euler, weights 1, 0, 0). The row's
/// spectralRadius scales rho (1 - SpringDef::numericalDamping; 0 for backward Euler) and, below
/// 1, selects the damped weights at every omega h. Damping takes the mean rate over the same
/// stencil, a = 1/2 (central: it dissipates exactly c (dL/dt)^2) with symmetric weights,
/// a = 1 / (1 + rho) on J v1 and 1 - a on J v0 with the damped ones. With C(x1) ~ C + h J v1
/// and C(x_{-1}) ~ C - h J v0 (linearised about x0):
///
///     lambda = -h (k (C + h (w1 J v1 - w_1 J v0)) + c (a J v1 + (1 - a) J v0))
///  => J v1 + bias + gamma lambda = 0,    r = h k w1 + c a,    gamma = 1 / (h r),
///     bias = (k C - (h k w_1 - c (1 - a)) J v0) / r,
///
/// a row whose effective mass is 1 / (J M^-1 J' + gamma); rho = 0 gives back implicit Euler's
/// gamma = 1 / (h (c + h k)) and bias = k C / (c + h k). Rigid in the limit k -> inf. The bias
/// is the spring's force, not a stabilisation bias: it is the same in the solver's biased and
/// relax sweeps, so a split-impulse step moves the bodies by exactly the spring's impulse.
/// Tension-only elements (threads) take the known levels with their own law, T = k max(C, 0)
/// (C_{-1} ~ C - h J v0): lambda = knownImpulse + the row's own impulse, knownImpulse =
/// -h k (w0 max(C, 0) + w_1 max(C_{-1}, 0)) applied once, bias = (k w1 C + c (1 - a) J v0) / r,
/// and the row is one-sided on the new level alone (its impulse <= 0: T1 >= 0). Linearising
/// the slack levels instead (a push k C < 0) delayed each catch and release: the net-10 sweep's
/// error was 2-4x larger. A thread slack over the last step (`catching`) takes the trapezoidal
/// weights (beta = 1/4) for that step where its scheme is undamped, implicit Euler where it is
/// damped: with beta = 1/12 catches a tumbling net's energy grew without bound at omega_e h =
/// 0.7 - 1.2 (explicit threads too, from 0.85), and with beta = 1/4 on every step too (x11 in
/// 60 s at 0.7); implicit Euler catches dissipated 98 % in 10 s from omega_e h = 0.7 and made
/// the net-10 sweep's error 6x the trapezoidal catches' at h = 1/240 (`net-energy`).
///
/// Undamped threads past Fox-Goodwin's range (1.5 <= (omega h)^2 <= 100, numericalDamping 0):
/// the discrete gradient (`discreteGradient`). Between 1.5 and 4 the trapezoidal catches above
/// lost a tumbling net's energy (`net-energy` at omega_e h = 1, (omega h)^2 = 2: min E/E0 0.04;
/// 0.9995 on the gradient). Why the three-level weights cannot serve them undamped: at
/// large omega h a taut step's known levels pull with ~(1 - w1) h k C while the new level, which
/// would push back, is cut off by the thread's max(C, 0), so a thread released from a stretch at
/// rest reaches ~0.75 omega h times its true speed (measured: beta = 1/4 on unresolved threads
/// blew the net-10 sweep up at 1/30 and `net-energy` from omega_e h = 5). Instead, in the level
/// velocity u_n (v_n is the step's mean), the energy-conserving midpoint scheme
///     x1 = x0 + h (u0 + u1) / 2,   u1 = u0 - h M^-1 G(x0, x1),
/// with G Gonzalez's discrete gradient of V = k max(L - L0, 0)^2 / 2, the force D m along
/// m = (d0 + d1) / (L0 + L1) (d the anchor span, L its length) with D = (V(L1) - V(L0)) / (L1 -
/// L0), keeps u' M u / 2 + V exactly: m . (d1 - d0) = L1 - L0. In the engine's variables
/// v1 = u0 - (h/2) M^-1 G(x0, x1) and u0 = v0 - (h/2) M^-1 G(x_-1, x0): each step's impulse is
/// last step's new half (`carried`, a vector along last step's m, applied once as the known
/// part) plus this step's, solved implicitly. A thread created, or woken after it slept in
/// equilibrium, starts consistently (u = v). D(c0, c1) is piecewise: both taut (k/2)(c0 + c1),
/// both slack 0, caught (k/2) c1^2 / (c1 - c0), released (k/2) c0^2 / (c0 - c1) (> 0: a thread
/// taut at the start always pulls). The row is Newton's linearisation of the new half at a
/// guessed end span (c1*, m*): with m* = s n, w = J v1 along n,
///     -2 lambda / (h s) = D(c0, c1*) + D' (c0 + h s w - c1*) + c s w,
///     r = s^2 (h D' + c),  gamma = 2 / (h r),  bias = s (D + D' (c0 - c1*)) / r.
/// The first guess solves the thread alone (threadStretchAlone: a scalar root); the block's
/// active-set rounds linearise a thread again where the solved span misses the model by more
/// than 0.03 % or turns m by more than 3e-4 rad, and a thread still unsettled for the last round
/// takes implicit Euler for the step. m's turn is in Newton's step too: two turn rows along t
/// perpendicular to m* (lineariseThreadTurn) hold -(h/2) D (d1 - d1*) . t / (L0 + L1), nothing
/// once the guess is right, and their impulse is part of the carried half. Left to the rounds
/// (a fixed point that contracts only while ~(omega_e h)^2 C / L is small) a tumbling net's
/// threads fell back to implicit Euler hundreds of times at omega_e h = 5. A thread slack at the
/// start takes load where its solved end is stretched (D > 0 there), not where its model pulls. In
/// 1D the converged scheme returns a bounce's and a release's speed exactly at every omega h (0.3
/// ... 100). Limits, measured: above (omega h)^2 ~ 100 the rounds do not settle a tumbling net
/// (`net-energy` at omega_e h = 10 grew without bound, with the Euler fallback 28x at 20), so the
/// stiffest keep the damped weights; on threads in Fox-Goodwin's range the midpoint's phase
/// error (twice leapfrog's) made the net-10 sweep's error at 1/240 ((omega h)^2 = 1.39) 0.0209 m
/// against the peers' 0.0195 (Fox-Goodwin's 0.0063), so they keep the weights above.
///
/// Undamped threads within Fox-Goodwin's range ((omega h)^2 < 1.5, c = 0) take the three-level
/// scheme's energy-conserving form on every step (`levelGradient`). Over the levels x_-1, x0, x1
/// (stretches) the symmetric scheme keeps the form M (x1 - x0)^2 / (2 h^2) + (k/2) Phi(x0, x1),
/// Phi(a, b) = beta (a+^2 + b+^2) + (1 - 2 beta) a+ b+ (a+ = max(a, 0)), exactly when the pull is
///     F = k G,   G = (Phi(x0, x1) - Phi(x_-1, x0)) / (x1 - x_-1)
/// (the work of F over x_-1 -> x1 is the form's change), which is Fox-Goodwin's beta x1 + (1 - 2
/// beta) x0 + beta x_-1 where the three are taut, 0 where they are slack and >= 0 always (Phi is
/// convex in each level: G, a divided difference, is nondecreasing in x1). In 3D it pulls along
/// Gonzalez's direction over the two levels, m = (d_-1 + d1) / (L_-1 + L1) = s n, for which
/// m . (d1 - d_-1) = L1 - L_-1 = h s (w0 + w) (w = J v1, w0 = J v0 along n): so the step's work
/// is exactly k (Phi(x0, x1) - Phi(x_-1, x0)). The row solves the step's whole pull, Newton's
/// linearisation at a guessed end stretch x1* (no known part, no carried half):
///     lambda = -h k s (G(x1*) + G' (x_-1 + h s (w0 + w) - x1*)),
///     r = h k s^2 G',  gamma = 1 / (h r),  bias = k s (G + G' (x_-1 + h s w0 - x1*)) / r.
/// m's turn is left to the block's rounds (a fixed point contracting like (omega h)^2 C / L, small
/// at a catch, where C ~ 0, and in this range; the discrete gradient's turn rows made the soft
/// 40 x 40 net 11x dearer). Why on every step, not only on catches and releases with Fox-Goodwin's
/// weights between: those record a taut step's end along its start line, short of the true
/// length, and each hand-over between the two measures pumped energy (`net-energy` max 1.05-1.08
/// at omega_e h 0.5-0.7; the form alone keeps its own energy within 0.11 %); the trapezoidal
/// catches before them lost a tumbling net's energy (0.30 of it left in 10 s at 0.5).
///
/// Deterministic: rows are solved in array order.

#include <cstdint>
#include <span>

#include "tumble/solver/solver_body.h"

namespace tumble {

struct SpringRow {
    std::uint32_t bodyA = 0;  ///< index into the solver's body array
    std::uint32_t bodyB = 0;
    Vec3 rA = Vec3::Zero();  ///< from A's centre of mass to its anchor (world, m)
    Vec3 rB = Vec3::Zero();  ///< from B's centre of mass to its anchor (world, m)
    /// Both anchors at their bodies' centres of mass (rA = rB = 0, not a world end): a net's.
    /// False asks nothing of the row.
    bool centred = false;
    Vec3 direction = Vec3::UnitX();  ///< unit, from anchor A to anchor B
    Real length = 0;                 ///< anchor distance at the start of the step (m)
    Real restLength = 1;             ///< (m), > 0
    Real stiffness = 0;              ///< k (N/m), >= 0
    Real damping = 0;                ///< c (N s/m), >= 0
    bool tensionOnly = false;        ///< pulls only: lambda <= 0
    Real impulse = 0;                ///< accumulated lambda (N s): warm start in, result out
    /// In [0, 1]: 1 the default weights, below 1 the damped ones scaled by it, 0 implicit
    /// Euler (see above).
    Real spectralRadius = 0;
    /// Anchor B's velocity minus anchor A's at the step's start, before any force of the step
    /// (m/s): J v0 of the scheme. Unused when spectralRadius = 0.
    Vec3 startVelocity = Vec3::Zero();
    /// A thread that was slack over the last step (see above).
    bool catching = false;
    /// The block solve adds the element's transverse (geometric) stiffness when it is taut
    /// (SpringBlockSolver::prepare).
    bool geometricStiffness = false;
    /// A thread on the energy-conserving scheme (see below): the row solves the new half of the
    /// discrete gradient, linearised at the stretch `linearisedAt`.
    bool discreteGradient = false;
    /// A resolved undamped thread: the row solves its whole pull, the three-level scheme's
    /// energy-conserving form linearised at `linearisedAt`.
    bool levelGradient = false;
    /// A `levelGradient` row's stretch at the level before the step, |d0 - h v0| - L0 (m).
    Real lastStretch = 0;
    /// Its half impulse of the last step on B's anchor (N s; -carried on A's), applied again in
    /// this one (prepareSpringRows).
    Vec3 carried = Vec3::Zero();
    Vec3 span = Vec3::Zero();  ///< anchor B - anchor A at the step's start (m)
    Real linearisedAt = 0;     ///< C1* (m): the end-of-step stretch the row is linearised at
    /// The block solve's turn rows' impulse on B's anchor (N s), the rest of the new half.
    Vec3 turn = Vec3::Zero();

    // Filled by prepareSpringRows().
    Vec3 angularA = Vec3::Zero();         ///< rA x n (m)
    Vec3 angularB = Vec3::Zero();         ///< rB x n (m)
    Vec3 angularImpulseA = Vec3::Zero();  ///< IA^-1 (rA x n)
    Vec3 angularImpulseB = Vec3::Zero();  ///< IB^-1 (rB x n)
    Real mass = 0;                        ///< 1 / (J M^-1 J' + gamma) (kg); 0: inactive row
    Real softness = 0;                    ///< gamma (1/kg)
    Real bias = 0;                        ///< (beta / h) C (m/s)
    /// A thread's impulse from the scheme's known levels, -h (w0 T0 + w_1 T_-1) (N s), applied
    /// once by prepareSpringRows(); `impulse` is the rest, the part the row solves for.
    Real knownImpulse = 0;
    /// A `levelGradient` thread slack at both levels before the step, left unlinearised by
    /// prepareSpringRows(deferSlackThreads): its direction, Jacobians, mass, softness, bias and
    /// `linearisedAt` are not yet the step's (finishSpringRow()); its impulse is 0.
    bool deferred = false;
};

/// The row's impulse lambda on its bodies: lambda n on B at its anchor, -lambda n on A.
inline void applySpringImpulse(SolverBody& a, SolverBody& b, const SpringRow& row, Real lambda) {
    a.linearVelocity -= (a.inverseMass * lambda) * row.direction;
    a.angularVelocity -= lambda * row.angularImpulseA;
    b.linearVelocity += (b.inverseMass * lambda) * row.direction;
    b.angularVelocity += lambda * row.angularImpulseB;
}

/// J v: the rate at which the anchors separate (m/s). Needs prepareSpringRows()'s Jacobians.
inline Real springRowSpeed(const SolverBody& a, const SolverBody& b, const SpringRow& row) {
    return row.direction.dot(b.linearVelocity - a.linearVelocity) +
           row.angularB.dot(b.angularVelocity) - row.angularA.dot(a.angularVelocity);
}

/// One row's Jacobians, softness, bias and effective mass for a step of length h (its impulse
/// untouched). A row with k = c = 0, or whose anchors coincide (no direction), gets mass 0:
/// inactive.
void prepareSpringRow(const SolverBody& a, const SolverBody& b, SpringRow& row, Real h);

/// A discrete-gradient thread row's anchor span at the step's end from the bodies' velocities
/// (m), and whether its linear model is off there by more than the tolerance.
bool threadRowStale(const SolverBody& a, const SolverBody& b, const SpringRow& row, Real h,
                    Vec3& endSpan);

/// A discrete-gradient thread row's stretch at the step's end from the bodies' velocities (m),
/// and that end's anchor span.
inline Real threadRowEndStretch(const SolverBody& a, const SolverBody& b, const SpringRow& row,
                                Real h, Vec3& endSpan) {
    // Inline: every active-set round asks it of each slack thread (~50,000 calls in 1.2 s of
    // the net-10 sweep's scene at 1/240).
    // Anchor B's velocity minus anchor A's with the bodies' current velocities (m/s).
    const Vec3 anchorSpeed = b.linearVelocity + b.angularVelocity.cross(row.rB) - a.linearVelocity -
                             a.angularVelocity.cross(row.rA);
    endSpan = row.span + h * anchorSpeed;
    return endSpan.norm() - row.restLength;
}

/// Whether threadRowEndStretch() exceeds `least` (m), the same answer. A `centred` row's anchor
/// speed leaves out the rotation terms: w x 0 is +-0, which changes at most the sign of a zero
/// component of the end span, whose length squares it (a non-finite angular velocity aside, a
/// step that fails anyway). The cross products were a third of settling a net's active set.
inline bool threadRowEndStretchExceeds(const SolverBody& a, const SolverBody& b,
                                       const SpringRow& row, Real h, Real least) {
    Vec3 endSpan;
    if (!row.centred)
        return threadRowEndStretch(a, b, row, h, endSpan) > least;
    endSpan = row.span + h * Vec3(b.linearVelocity - a.linearVelocity);
    return endSpan.norm() - row.restLength > least;
}

/// A discrete-gradient thread row whose linearisation did not settle, made an implicit Euler row
/// on its start-of-step line for the rest of the step (its carried half stays applied).
void implicitEulerThreadRow(const SolverBody& a, const SolverBody& b, SpringRow& row, Real h);

/// Whether a thread row pulls whatever its end stretch: a discrete-gradient thread taut at the
/// start, or a `levelGradient` one taut at the level before it.
inline bool threadRowPulls(const SpringRow& row) {
    return (row.discreteGradient && row.length >= row.restLength) ||
           (row.levelGradient && row.lastStretch > 0);
}

/// A discrete-gradient thread row linearised at the end-of-step span `endSpan`: its direction,
/// Jacobians, softness, bias and effective mass (its impulse untouched).
void lineariseThreadRow(const SolverBody& a, const SolverBody& b, SpringRow& row, Real h,
                        const Vec3& endSpan);

/// A discrete-gradient thread's turn row along `turn.direction` (set, perpendicular to the
/// thread's): Newton's linearisation of its pull's direction m = (d0 + d1) / (L0 + L1) at the
/// thread's guessed end span, so it holds no impulse once the guess is right (spring_row.cpp).
void lineariseThreadTurn(const SolverBody& a, const SolverBody& b, const SpringRow& thread,
                         SpringRow& turn, Real h);

/// Equal substeps of a step that an undamped thread with (omega h)^2 = `squared` at the step's h
/// may be split into and still take the discrete gradient in each, floor(omega h / 2); 0 when it
/// does not take the gradient at h.
int discreteGradientSubsteps(Real squared);

/// The (omega h)^2 from which an undamped thread takes the discrete gradient: below it,
/// discreteGradientSubsteps is 0.
Real discreteGradientBandStart();

/// Whether a prepared row's element is one the step does not resolve ((omega h)^2 >= 4): its
/// scheme damps it, and its turning within the step wants post-stabilisation.
bool springRowUnresolved(const SpringRow& row, Real h);

/// prepareSpringRow() on every row, then applies the warm-start impulses (or zeroes them when
/// !warmStart). deferSlackThreads: a `levelGradient` thread slack at both levels before the step
/// and holding no warm start is left `deferred` (most of a net in flight): the block solve starts
/// it inactive, and it is linearised again if caught, so its preparation is rarely read. Whoever
/// reads it calls finishSpringRow() first, with the same bodies and h: the row is then, bit for
/// bit, the one prepared at once.
void prepareSpringRows(std::span<SolverBody> bodies, std::span<SpringRow> rows, Real h,
                       bool warmStart, bool deferSlackThreads = false);

/// A `deferred` row's preparation, no longer deferred: the bodies' inverse masses and inertias
/// and h as prepareSpringRows() had them (their velocities are not read).
void finishSpringRow(const SolverBody& a, const SolverBody& b, SpringRow& row, Real h);

/// finishSpringRow() on every deferred row.
void finishSpringRows(std::span<const SolverBody> bodies, std::span<SpringRow> rows, Real h);

/// One Gauss-Seidel pass over the rows with over-relaxation `relaxation`; returns the largest
/// change of a row's velocity J v caused by an update (m/s), for the solver's tolerance.
Real solveSpringRows(std::span<SolverBody> bodies, std::span<SpringRow> rows, Real relaxation);

}  // namespace tumble
