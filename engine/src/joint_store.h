#pragma once
/// Dense storage of joints behind value handles, like SpringStore: parallel arrays indexed by the
/// dense index of a HandlePool, swap-with-last removal, so the order the solver sweeps them in
/// depends only on the sequence of create and destroy calls.

#include <cstdint>
#include <vector>

#include "handle_pool.h"
#include "tumble/joint.h"

namespace tumble {

/// A joint's definition in the bodies' frames, fixed at creation.
struct JointRecord {
    JointDef def;                          ///< as given (world frame at creation)
    Vec3 localAnchorA = Vec3::Zero();      ///< A's body frame, from its origin (m)
    Vec3 localAnchorB = Vec3::Zero();      ///< B's body frame, or a world point for a null B (m)
    Vec3 localAxisA = Vec3::UnitZ();       ///< A's frame, unit
    Vec3 localAxisB = Vec3::UnitZ();       ///< B's frame (or the world's), unit
    Vec3 localReferenceA = Vec3::UnitX();  ///< normal to the axis, A's frame: hinge angle 0
    Vec3 localReferenceB = Vec3::UnitX();  ///< the same direction in B's frame at creation
    Quat relativeOrientation = Quat::Identity();  ///< qA^-1 qB at creation
    Real length = 0;                              ///< distance joints (m)
};

/// The per-step result of a joint: its impulses as forces (so a change of h does not scale the
/// warm start) and whether it broke.
struct JointStepState {
    Vec3 linearForce = Vec3::Zero();          ///< point or perpendicular rows (N, world)
    Vec3 previousLinearForce = Vec3::Zero();  ///< linearForce one step earlier (N, world)
    Vec3 angularTorque = Vec3::Zero();        ///< angular rows (N m, world)
    Real motorForce = 0;                      ///< (N or N m)
    Real lowerForce = 0;
    Real upperForce = 0;
    Vec3 force = Vec3::Zero();   ///< reaction on B (N, world)
    Vec3 torque = Vec3::Zero();  ///< reaction torque on B (N m, world)
    bool broken = false;
};

class JointStore : public DenseStore<JointId> {
    friend struct CheckpointAccess;  ///< checkpoint.cpp saves and restores the private state
public:
    JointStore() : DenseStore("JointId", "joint") {}
    JointId add(const JointRecord& record);
    void remove(JointId id);

    /// state -> previousState at the start of a step, and back if the step fails.
    void saveState() { previousState = state; }
    void restoreState() { state = previousState; }

    std::vector<JointRecord> records;
    std::vector<JointStepState> state;
    std::vector<JointStepState> previousState;
};

}  // namespace tumble
