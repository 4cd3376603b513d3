#pragma once
/// The solver's view of a body: velocities and inverse mass, nothing else. Static and kinematic
/// bodies have zero inverse mass and inertia, so impulses leave them unchanged.

#include "tumble/core/math.h"

namespace tumble {

struct SolverBody {
    Vec3 linearVelocity = Vec3::Zero();   ///< of the centre of mass (m/s)
    Vec3 angularVelocity = Vec3::Zero();  ///< world frame (rad/s)
    Real inverseMass = 0;                 ///< (1/kg)
    Mat3 inverseInertia = Mat3::Zero();   ///< world frame (1/(kg m^2))

    /// Velocity of the point at offset r (m) from the centre of mass.
    Vec3 velocityAt(const Vec3& r) const { return linearVelocity + angularVelocity.cross(r); }
};

/// Applies an impulse p (N s) at offset r (m) from the centre of mass:
/// v += p / m,  w += I^-1 (r x p). Inline: the solver's innermost loop calls it.
inline void applyImpulse(SolverBody& body, const Vec3& impulse, const Vec3& r) {
    body.linearVelocity += body.inverseMass * impulse;
    body.angularVelocity += body.inverseInertia * r.cross(impulse);
}

/// The effective mass along unit direction n of the pair (A, B) at offsets rA, rB (kg): the
/// inverse of  1/mA + 1/mB + (rA x n)' IA^-1 (rA x n) + (rB x n)' IB^-1 (rB x n).
/// Zero when neither body can move along n.
Real effectiveMass(const SolverBody& a, const Vec3& rA, const SolverBody& b, const Vec3& rB,
                   const Vec3& n);

}  // namespace tumble
