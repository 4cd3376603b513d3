#pragma once
/// Semi-implicit (symplectic) Euler, split in the two halves the constraint solve sits between:
///
///     u(n+1) = u(n) + h M^-1 f(n)          integrateVelocities  (then the constraint solve)
///     s(n+1) = s(n) + h S(s) u(n+1)        integratePositions   (with the NEW velocities)

#include <span>

#include "body_store.h"
#include "step_context.h"
#include "tumble/solver/contact_solver.h"

namespace tumble {

/// Gravity, applied forces and torques, the gyroscopic term and damping -> velocities of the
/// awake dynamic bodies. Kinematic bodies keep their velocities; sleeping and static bodies are
/// not visited. The applied forces and torques (BodyForces) act for `forceSteps` x h: 1 in the
/// default step; the soft step's first substep takes the step's whole impulse (n) and its other
/// substeps none (0), soft_step.cpp.
void integrateVelocities(BodyStore& bodies, const StepContext& context, Real forceSteps = 1);
/// The same for one dynamic body (one woken in the middle of a step catches up on its forces).
void integrateVelocity(BodyStore& bodies, std::uint32_t index, const StepContext& context,
                       Real forceSteps = 1);

/// An applied torque's angular acceleration in body axes, I_body^-1 R' torque (rad/s^2): the one
/// form integrateVelocity and the soft step's bounce prediction share (the same bits in both).
inline Vec3 torqueAcceleration(const BodyInertia& inertia, const Mat3& rotation,
                               const Vec3& torque) {
    return inertia.inverseInertiaLocal * (rotation.transpose() * torque);
}

/// Moves every awake body with its velocity. Orientation: q(n+1) = exp(h w / 2) q(n), the
/// exact rotation for a constant angular velocity over the step, then renormalised against
/// rounding.
/// `pseudo` (one per awake body in BodyStore::awake order, or empty) holds split-impulse
/// velocities that move the positions in this step only and are never stored.
void integratePositions(BodyStore& bodies, std::span<const PseudoVelocity> pseudo,
                        const StepContext& context);

/// Moves every awake dynamic body by h times the given velocities (one per awake body, in
/// BodyStore::awake order) and nothing else: a position correction that leaves the real
/// velocities alone.
void displaceBodies(BodyStore& bodies, std::span<const PseudoVelocity> velocities, Real h);

/// The torque-free Euler equations I dw/dt = -w x (I w) in body axes over one step, by the
/// implicit midpoint rule:  I (w1 - w0) + h wm x (I wm) = 0,  wm = (w0 + w1) / 2.
///
/// Why implicit midpoint: it preserves every quadratic invariant of the flow, and both |I w|^2
/// (angular momentum) and w'Iw (kinetic energy) are quadratic, so a spinning asymmetric body keeps
/// both to the solver tolerance -- the explicit term gains energy and blows up about the
/// intermediate axis, and plain implicit Euler (Bullet's choice) bleeds energy away.
/// Solved for wm by Newton's method on f(x) = 2 I (x - w0) + h x x (I x), whose Jacobian is
/// 2 I + h (skew(x) I - skew(I x)); it converges in 2-4 iterations for h |w| < 1.
/// `inverseInertia` is inertia.inverse() (the body's stored one: not recomputed every step).
Vec3 gyroscopicMidpoint(const Mat3& inertia, const Mat3& inverseInertia, const Vec3& w0, Real h);

}  // namespace tumble
