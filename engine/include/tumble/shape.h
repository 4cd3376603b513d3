#pragma once
/// Shapes attached to bodies: ids, materials and the definition.

#include <cstdint>

#include "tumble/collision/shape.h"
#include "tumble/core/math.h"

namespace tumble {

/// A value handle to a shape; same rules as BodyId (zero is null, generation and world checked).
struct ShapeId {
    std::uint32_t index = 0;       ///< slot in the world's shape table
    std::uint32_t generation = 0;  ///< 0 means null; bumped each time the slot is reused
    std::uint32_t world = 0;       ///< tag of the World that made it (see BodyId::world)

    bool isNull() const { return generation == 0; }
    friend bool operator==(ShapeId, ShapeId) = default;
};

/// Surface and bulk properties of a shape.
struct Material {
    Real friction = 0.5;   ///< Coulomb coefficient, >= 0
    Real restitution = 0;  ///< Newton's coefficient, in [0, 1]
    Real density = 1000;   ///< (kg/m^3), > 0; used when the shape sets its body's mass
    /// Torsional friction length (m), finite and >= 0: a contact resists spin about its normal
    /// with a torque up to this times its normal force. A rigid point contact has none; a patch
    /// of radius a with Coulomb mu has about 2/3 mu a. A pair uses the larger of the two. Meant
    /// for round bodies: a manifold of several points (a face) already resists spin and tipping
    /// through its points, and these add to that.
    Real spinningFriction = 0;
    /// Rolling resistance length (m), finite and >= 0: a contact resists rolling with a torque up
    /// to this times its normal force (a ball of radius r rests on slopes up to atan(this / r)).
    /// A pair uses the larger of the two.
    Real rollingFriction = 0;
};

/// Which shapes may touch: a and b collide when (a.category & b.mask) and (b.category & a.mask)
/// are both non-zero.
struct CollisionFilter {
    std::uint32_t category = 1;
    std::uint32_t mask = 0xFFFFFFFF;
};

/// Everything needed to attach a shape to a body. Copied by World::createShape.
struct ShapeDef {
    Shape geometry = Sphere{};  ///< in the shape's frame
    Transform localPose{};      ///< the shape's frame in the body frame
    Material material{};
    CollisionFilter filter{};
    /// When true (default) and the body is dynamic, the body's mass properties become those of
    /// all its shapes at their densities (compound by the parallel-axis theorem), replacing any
    /// mass set by hand.
    bool updateBodyMass = true;
};

}  // namespace tumble
