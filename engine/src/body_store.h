#pragma once
/// Dense body storage behind value handles.
///
/// Bodies live in parallel contiguous arrays indexed by a dense `index`; ids are those of a
/// HandlePool (handle_pool.h). Destroying a body moves the last body into its dense index, so
/// dense order depends only on the sequence of create/destroy calls -- never on addresses or
/// hashing -- which keeps stepping deterministic.
///
/// Awake bodies (dynamic bodies not asleep, and every kinematic body) are also listed in `awake`,
/// which is what the per-body loops of a step walk: a sleeping or static body is never visited.
/// The list's order depends only on the sequence of create/destroy/wake/sleep events.

#include <cstdint>
#include <vector>

#include "handle_pool.h"
#include "tumble/body.h"

namespace tumble {

/// The state the integrator reads and writes each step.
struct BodyMotion {
    Vec3 center = Vec3::Zero();           ///< centre of mass, world (m)
    Quat orientation = Quat::Identity();  ///< body to world
    Vec3 linearVelocity = Vec3::Zero();   ///< (m/s)
    Vec3 angularVelocity = Vec3::Zero();  ///< world frame (rad/s)
};

/// Inverse mass data. Static and kinematic bodies have zero inverse mass and inertia.
struct BodyInertia {
    Real inverseMass = 0;                     ///< (1/kg)
    Vec3 localCenter = Vec3::Zero();          ///< centre of mass in the body frame (m)
    Mat3 inertiaLocal = Mat3::Zero();         ///< about the centre of mass, body axes (kg m^2)
    Mat3 inverseInertiaLocal = Mat3::Zero();  ///< its inverse
};

struct BodyForces {
    Vec3 force = Vec3::Zero();   ///< (N), world
    Vec3 torque = Vec3::Zero();  ///< (N m), world, about the centre of mass
};

struct BodyInfo {
    BodyType type = BodyType::Dynamic;
    Real linearDamping = 0;
    Real angularDamping = 0;
    Real gravityScale = 1;
    MassProperties mass;  ///< as given, for reporting
    std::uint64_t userData = 0;
    std::uint32_t firstShape = kNoShape;  ///< slot of the body's first shape
    std::uint32_t firstContact = kNone;   ///< head of its contact list (ContactManager edges)
    std::uint32_t awakeIndex = kNone;     ///< position in BodyStore::awake; kNone when not awake
    Real sleepTime = 0;                   ///< how long it has been still (s)
    bool allowSleep = true;
    /// Changed through the API since the last step: the next step does not count as still, so
    /// a body pushed every step never sleeps, however long the step.
    bool pushed = false;
    /// Created asleep (BodyDef::awake = false) and not woken since: adding shapes to it does not
    /// wake it, so a pile can be built asleep.
    bool builtAsleep = false;
    bool massFromShapes = false;  ///< mass properties come from the shapes
    bool fixedRotation = false;   ///< BodyDef::fixedRotation: zero inverse inertia
    /// Largest distance from the centre of mass to a point of the body's shapes (m), an upper
    /// bound from each shape's bounding sphere; 0 without shapes. Derived from the shapes and
    /// the mass (World::Impl::refreshExtent), so not saved in a checkpoint but recomputed.
    Real extent = 0;

    static constexpr std::uint32_t kNoShape = 0xFFFFFFFF;
    static constexpr std::uint32_t kNone = 0xFFFFFFFF;
};

class BodyStore : public DenseStore<BodyId> {
    friend struct CheckpointAccess;  ///< checkpoint.cpp saves and restores the private state
public:
    BodyStore() : DenseStore("BodyId", "body") {}
    BodyId add(const BodyDef& def);
    void remove(BodyId id);

    void setMass(std::uint32_t index, const MassProperties& mass);

    bool isAwake(std::uint32_t index) const { return info[index].awakeIndex != BodyInfo::kNone; }
    /// A dynamic body that is not awake.
    bool isSleeping(std::uint32_t index) const {
        return info[index].type == BodyType::Dynamic && !isAwake(index);
    }
    bool isAwakeDynamic(std::uint32_t index) const {
        return info[index].type == BodyType::Dynamic && isAwake(index);
    }
    /// A kinematic body with any velocity: what it touches cannot rest.
    bool isMovingKinematic(std::uint32_t index) const {
        return info[index].type == BodyType::Kinematic &&
               !(motion[index].linearVelocity.isZero(0) && motion[index].angularVelocity.isZero(0));
    }
    /// Appends the body to the awake list (it must not be on it).
    void markAwake(std::uint32_t index);
    /// Takes the body off the awake list (it must be on it); the last entry takes its place.
    void markNotAwake(std::uint32_t index);
    /// previousMotion = motion for the awake bodies (the others do not move).
    void savePreviousMotion();
    /// motion = previousMotion for the awake bodies.
    void restorePreviousMotion();

    // Parallel arrays, all of size count().
    std::vector<BodyMotion> motion;
    std::vector<BodyMotion>
        previousMotion;  ///< state before the last step: rollback + interpolation
    std::vector<BodyInertia> inertia;
    std::vector<BodyForces> forces;
    std::vector<BodyInfo> info;
    std::vector<std::uint32_t> awake;  ///< dense indices of the awake bodies
};

}  // namespace tumble
