#pragma once
/// Bodies: their ids, kinds, mass properties and definition.

#include <cstdint>

#include "tumble/core/mass.h"
#include "tumble/core/math.h"

namespace tumble {

/// A value handle to a body. The world owns the body; the id stays valid until the body is
/// destroyed, and a destroyed body's id is refused (its generation no longer matches) rather than
/// aliasing a newer body. An id is refused by every world but the one that made it (the `world`
/// tag). The zero id is null.
struct BodyId {
    std::uint32_t index = 0;       ///< slot in the world's table
    std::uint32_t generation = 0;  ///< 0 means null; bumped each time the slot is reused
    /// Tag of the World that made the id (0 in a null id): only checked, never part of a result.
    std::uint32_t world = 0;

    bool isNull() const { return generation == 0; }
    friend bool operator==(BodyId, BodyId) = default;
};

enum class BodyType : std::uint8_t {
    Static,     ///< never moves; infinite mass
    Kinematic,  ///< moves with the velocity the application sets; infinite mass, ignores forces
    Dynamic,    ///< moved by forces, gravity, contacts, springs and joints
};

/// Everything needed to create a body. Copied by World::createBody, never retained.
struct BodyDef {
    BodyType type = BodyType::Dynamic;
    Vec3 position = Vec3::Zero();         ///< body origin, world frame (m)
    Quat orientation = Quat::Identity();  ///< body to world; must be unit length (to 1e-6)
    Vec3 linearVelocity = Vec3::Zero();   ///< of the centre of mass, world frame (m/s)
    Vec3 angularVelocity = Vec3::Zero();  ///< world frame (rad/s)
    MassProperties mass{};                ///< used by dynamic bodies only
    /// (1/s), >= 0; implicit, (1 + h c) v1 = v0 + h (every force, contacts', springs' and
    /// joints' included) / m: terminal speed F / (m c), and no effect on where a body rests.
    Real linearDamping = 0;
    Real angularDamping = 0;     ///< (1/s), >= 0; implicit in the same way
    Real gravityScale = 1;       ///< multiplies the world's gravity for this body
    std::uint64_t userData = 0;  ///< opaque to the engine, handed back by World::userData
    /// May the body fall asleep? A body that may not keeps its whole island awake (dynamic
    /// bodies only; see WorldDef::enableSleep).
    bool allowSleep = true;
    /// Created awake (true) or asleep (false). A body created asleep is at rest until something
    /// touches or pushes it, so it must be dynamic, have zero velocities and allowSleep = true.
    bool awake = true;
    /// Translation only: the body never rotates (its inverse inertia is zero, so no torque,
    /// contact or joint turns it). A lumped node of a string or net is a point mass -- a thread
    /// slides over a surface, it does not roll on it. Torques and angular impulses on it do
    /// nothing. Dynamic bodies only, with a zero angularVelocity.
    bool fixedRotation = false;
};

}  // namespace tumble
