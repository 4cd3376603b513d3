#pragma once
/// Spring-damper elements and aerodynamic drag: the force elements of lumped-mass strings and
/// nets.
///
/// A spring joins an anchor on body A to an anchor on body B, or to a fixed world point. Its
/// tension (N, positive when it pulls the anchors together) is k (L - L0) + c dL/dt. Two
/// formulations, chosen per element:
/// - Explicit: the force is computed from the state at the start of the step and applied with the
///   other forces before the velocity update, exactly as in the ESA study. Stable only while
///   h < 2 / omega for a mass on one spring, omega = sqrt(k / m); a uniform string of masses
///   m and elements k needs h < 1 / omega_e (its highest mode is 2 omega_e).
/// - Implicit (default): a soft constraint row in the solver, a three-level Newmark scheme on
///   the spring (see tumble/solver/spring_row.h): second order and without numerical damping
///   while the step resolves the element (omega h <= 2), so only c dissipates; a stiffer element
///   is damped (spectral radius 4 / (omega h)^2) rather than left to swing -- except an undamped
///   thread (tension-only, numericalDamping 0) with 4 <= (omega h)^2 <= 100, which takes an
///   energy-conserving discrete gradient, so its catches bounce instead of sticking. Stable at
///   any stiffness. `numericalDamping` adds damping at every omega h on request.
/// - BackwardEuler: the same row with implicit Euler (first order): stable at any stiffness, but
///   it damps every mode it resolves poorly (a soft net lost 12-68 % of its energy in 2 s).

#include <cstdint>

#include "tumble/body.h"
#include "tumble/core/math.h"

namespace tumble {

/// A value handle to a spring, like BodyId: checked by generation and world, zero is null.
struct SpringId {
    std::uint32_t index = 0;       ///< slot in the world's spring table
    std::uint32_t generation = 0;  ///< 0 means null; bumped each time the slot is reused
    std::uint32_t world = 0;       ///< tag of the World that made it (see BodyId::world)

    bool isNull() const { return generation == 0; }
    friend bool operator==(SpringId, SpringId) = default;
};

enum class SpringFormulation : std::uint8_t {
    Explicit,       ///< force before the velocity update (the study's scheme; h < 1 / omega_e)
    Implicit,       ///< soft constraint row, Newmark: second order, energy-true (default)
    BackwardEuler,  ///< soft constraint row, implicit Euler: first order, dissipative
};

/// Everything needed to create a spring. Copied by World::createSpring, never retained.
struct SpringDef {
    BodyId bodyA;  ///< must be a valid body
    /// A valid body other than bodyA, or null: then the spring is anchored at the world point
    /// localAnchorB.
    BodyId bodyB;
    Vec3 localAnchorA = Vec3::Zero();  ///< in A's body frame, from its origin (m)
    Vec3 localAnchorB = Vec3::Zero();  ///< in B's body frame, or a world point when bodyB is null
    Real restLength = 1;               ///< L0 (m), finite and > 0
    Real stiffness = 0;                ///< k (N/m), finite and >= 0; see axialStiffness
    Real damping = 0;                  ///< c (N s/m), finite and >= 0
    bool tensionOnly = false;          ///< a thread: pulls when stretched, pushes never
    SpringFormulation formulation = SpringFormulation::Implicit;
    /// Implicit only, in [0, 1]: 0 (default) no numerical damping where the step resolves the
    /// element; d > 0 takes damped weights everywhere, spectral radius (1 - d) at omega h <= 2
    /// (first order: measured 5e-4 of the energy per step at omega h = 0.1, d = 0.1); 1 is
    /// implicit Euler. Physical damping is `damping` alone.
    Real numericalDamping = 0;
    /// (m), finite and >= 0: when > 0 the segment between the anchors touches the shapes of
    /// static and kinematic bodies as a capsule of this radius -- a thread of a net caught on a
    /// rim between its nodes (engine/src/thread_contacts.h). 0 (default): it passes through.
    Real contactRadius = 0;
    /// Coulomb mu of the segment, finite and >= 0; mixed with the shape's friction as two
    /// shapes' (geometric mean). Used only when contactRadius > 0.
    Real contactFriction = 0.5;
};

/// k = E A / L0 (N/m) of a uniform elastic bar or thread. Refuses (InvalidArgument) E, A or L0
/// that are not finite and > 0.
Real axialStiffness(Real youngsModulus, Real area, Real restLength);

/// What a spring reports.
struct SpringState {
    Real length = 0;     ///< anchor distance at the current poses (m)
    Real tension = 0;    ///< of the last step (N); positive pulls the anchors together
    bool slack = false;  ///< a tension-only element that carried nothing in the last step
    /// A discrete-gradient thread's half impulse of the last step on anchor B (N s; its negative
    /// on A), which the next step applies again; zero for other elements. The scheme's velocity
    /// at the step's end is the step's velocity plus this impulse's (spring_row.h).
    Vec3 carried = Vec3::Zero();
};

/// Aerodynamic drag on a body's centre of mass, applied with the other forces (explicitly):
/// with u = projection v, the force is -(linear + quadratic |u|) u. The projection restricts drag
/// to chosen directions, e.g. diag(1, 1, 0) for horizontal drag only, as in the ESA study.
/// Explicit, so stable while h (linear + 2 quadratic |u|) / m < 2.
struct Drag {
    Real linear = 0;                     ///< b1 (N s/m), finite and >= 0
    Real quadratic = 0;                  ///< b2 (N s^2/m^2), finite and >= 0
    Mat3 projection = Mat3::Identity();  ///< finite; identity: isotropic
};

}  // namespace tumble
