#pragma once
/// Joint controllers: PD and PID laws that drive a hinge's angle or a slider's translation (or
/// their rates) toward a target, as a torque (hinge, N m) or force (slider, N) the world applies
/// to the joint's two bodies, equal and opposite, at the start of each step.
///
/// Why an applied torque and not the joint's motor. The motor is a velocity servo solved as a
/// constraint: with a PD law as its target speed the loop becomes first order (the joint's
/// speed follows the command within a step, whatever the inertia), so the gains would not mean
/// what they mean on a real actuator and the closed loop would not be the one
/// I q'' + kd q' + kp (q - q*) = 0 that control design (and the pd-arm validation case)
/// predicts. An applied torque gives exactly that loop, with the cap acting as the actuator's
/// saturation. The price: the law is evaluated from the state at the start of the step
/// (explicit), so it is stable only while h sqrt(kp / I) and h kd / I stay below about 1,
/// with I the inertia (or mass) the joint drives -- for a stiffer servo, use the motor
/// (World::setJointMotor), which is solved implicitly.
///
/// The law, with q the joint's angle (rad, in (-pi, pi], the error wrapped into the same range)
/// or translation (m) and u the output:
/// - Position mode: e = target - q, u = kp e + ki (integral of e dt) + kd (targetVelocity - q').
/// - Velocity mode: e = targetVelocity - q', u = kp e + ki (integral of e dt) + kd de/dt, the
///   derivative by the difference of the errors of consecutive steps (0 at the first).
/// u is clamped to [-maxForce, maxForce]. Anti-windup: the integral does not grow while the
/// output is saturated in the direction of the error.

#include <cstdint>
#include <limits>

#include "tumble/core/math.h"

namespace tumble {

/// What a controller drives the joint toward.
enum class ControlMode : std::uint8_t {
    Position,  ///< the angle (rad) or translation (m): ControllerDef::target
    Velocity,  ///< the angular (rad/s) or linear (m/s) rate: ControllerDef::targetVelocity
};

/// A PD or PID controller on a hinge or slider joint. Copied by World::setJointController.
/// Units below are for a hinge; for a slider read N for N m and m for rad.
struct ControllerDef {
    ControlMode mode = ControlMode::Position;
    /// Position mode: the set-point, angle (rad) or translation (m), finite. Unused in velocity
    /// mode.
    Real target = 0;
    /// Velocity mode: the rate to hold (rad/s or m/s). Position mode: the rate at which the
    /// set-point itself moves, a feed-forward for kd (0 for a fixed set-point). Finite.
    Real targetVelocity = 0;
    /// Proportional gain, finite and >= 0: N m/rad (position mode) or N m s/rad (velocity mode).
    Real kp = 0;
    /// Integral gain, finite and >= 0: N m/(rad s) (position) or N m/rad (velocity). 0: a PD.
    Real ki = 0;
    /// Derivative gain, finite and >= 0: N m s/rad (position) or N m s^2/rad (velocity).
    Real kd = 0;
    /// Cap on the output torque (N m) or force (N), > 0; infinity: no cap.
    Real maxForce = std::numeric_limits<Real>::infinity();
};

/// What a controller did in the last step.
struct ControllerState {
    Real error = 0;     ///< e of the last step (rad, m, or rad/s, m/s in velocity mode)
    Real integral = 0;  ///< the integral of e (rad s or m s, rad or m in velocity mode)
    Real output = 0;    ///< the torque (N m) or force (N) applied, after the cap
};

}  // namespace tumble
