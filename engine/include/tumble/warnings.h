#pragma once
/// Warnings: legal input the engine is known to handle poorly. The world still steps, but the
/// result may be wrong in the way describe() says; each kind has a test in
/// tests/engine/extremes_test.cpp that shows what goes wrong. A warning is raised once per cause
/// (its kind and the bodies, spring or shape involved) and kept until World::clearWarnings().

#include <cstdint>
#include <string>

#include "tumble/body.h"
#include "tumble/joint.h"
#include "tumble/spring.h"

namespace tumble {

/// Dynamic bodies whose masses differ by more than this meet in a contact or joint: the
/// projected Gauss-Seidel solver passes impulses between them too slowly (measured with 10
/// iterations: a box 100x heavier rests on a light one; at 1e3 the light one sank 0.88 m).
/// Contact groups of at most 32 normal rows are now solved exactly (normal_islands.h), so a
/// heavy box rests on a light one at any ratio; in a larger group the limit remains.
inline constexpr double kMassRatioWarning = 100;

struct Warning {
    enum class Kind : std::uint8_t {
        /// A contact began, or a joint was made, between dynamic bodies whose mass ratio is
        /// above kMassRatioWarning. `value` is the ratio (>= 1); bodyA is the heavier.
        MassRatio,
        /// A shape on a dynamic body is smaller than twice the contact slop in some direction:
        /// its contacts leave up to the slop of penetration, half its size or more. `value` is
        /// the shape's smallest size (m), `limit` twice the slop. Scale the settings (slop,
        /// margins, step) with the bodies; see docs/validation.md.
        SmallerThanSlop,
        /// An explicit spring whose omega h is 2 or more, omega^2 = k (1/m_A + 1/m_B): its
        /// semi-implicit Euler step amplifies every oscillation and the state overflows within
        /// tens of steps. `value` is omega h, `limit` 2. Use SpringFormulation::Implicit.
        ExplicitSpringUnstable,
    };
    Kind kind = Kind::MassRatio;
    BodyId bodyA;
    BodyId bodyB;     ///< null when the cause has one body (or one end on the world)
    SpringId spring;  ///< ExplicitSpringUnstable only
    JointId joint;    ///< MassRatio raised by a joint only
    double value = 0;
    double limit = 0;
};

/// One line saying what was found, on which bodies, and what to do about it.
std::string describe(const Warning& warning);

}  // namespace tumble
