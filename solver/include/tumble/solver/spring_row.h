#pragma once
/// Implicit spring-dampers as soft constraint rows (Catto's soft constraints), solved in
/// ConstraintSolver's PGS sweeps next to the contacts.
///
/// A spring of rest length L0, stiffness k and damping c between anchors at distance L pulls with
/// the tension k (L - L0) + c dL/dt. Implicit Euler on it, with C = L - L0 and J v = dL/dt, asks
/// for the impulse lambda (along the line, on B; negative pulls the anchors together)
///
///     lambda = -h (k C(x1) + c J v1),   C(x1) ~ C + h J v1
///  => J v1 + (beta / h) C + gamma lambda = 0,  gamma = 1 / (h (c + h k)),  beta = h k / (c + h k),
///
/// a row whose effective mass is 1 / (J M^-1 J' + gamma). It is stable at any stiffness (implicit
/// Euler damps the modes it cannot resolve instead of amplifying them) and rigid in the limit
/// k -> inf. The (beta / h) C term is the spring's force, not a stabilisation bias: it is the same
/// in the solver's biased and relax sweeps, so a split-impulse step moves the bodies by exactly
/// the spring's impulse. Tension-only elements (threads) are one-sided rows, lambda <= 0.
///
/// Deterministic: rows are solved in array order.

#include <cstdint>
#include <span>

#include "tumble/solver/solver_body.h"

namespace tumble {

struct SpringRow {
    std::uint32_t bodyA = 0;  ///< index into the solver's body array
    std::uint32_t bodyB = 0;
    Vec3 rA = Vec3::Zero();          ///< from A's centre of mass to its anchor (world, m)
    Vec3 rB = Vec3::Zero();          ///< from B's centre of mass to its anchor (world, m)
    Vec3 direction = Vec3::UnitX();  ///< unit, from anchor A to anchor B
    Real length = 0;                 ///< anchor distance at the start of the step (m)
    Real restLength = 1;             ///< (m), > 0
    Real stiffness = 0;              ///< k (N/m), >= 0
    Real damping = 0;                ///< c (N s/m), >= 0
    bool tensionOnly = false;        ///< pulls only: lambda <= 0
    Real impulse = 0;                ///< accumulated lambda (N s): warm start in, result out

    // Filled by prepareSpringRows().
    Vec3 angularA = Vec3::Zero();         ///< rA x n (m)
    Vec3 angularB = Vec3::Zero();         ///< rB x n (m)
    Vec3 angularImpulseA = Vec3::Zero();  ///< IA^-1 (rA x n)
    Vec3 angularImpulseB = Vec3::Zero();  ///< IB^-1 (rB x n)
    Real mass = 0;                        ///< 1 / (J M^-1 J' + gamma) (kg); 0: inactive row
    Real softness = 0;                    ///< gamma (1/kg)
    Real bias = 0;                        ///< (beta / h) C (m/s)
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

/// Jacobians, softness and effective masses for a step of length h; applies the warm-start
/// impulses (or zeroes them when !warmStart). A row with k = c = 0, or whose anchors coincide
/// (no direction), is inactive.
void prepareSpringRows(std::span<SolverBody> bodies, std::span<SpringRow> rows, Real h,
                       bool warmStart);

/// One Gauss-Seidel pass over the rows with over-relaxation `relaxation`; returns the largest
/// change of a row's velocity J v caused by an update (m/s), for the solver's tolerance.
Real solveSpringRows(std::span<SolverBody> bodies, std::span<SpringRow> rows, Real relaxation);

}  // namespace tumble
