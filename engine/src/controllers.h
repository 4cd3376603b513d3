#pragma once
/// The joint controllers of tumble/control.h: one record per controlled joint, in the order they
/// were set (which is the order they act in, so stepping stays deterministic). Few joints carry
/// controllers, so a joint's record is found by a linear search.

#include <vector>

#include "body_store.h"
#include "joint_store.h"
#include "tumble/control.h"
#include "tumble/joint.h"

namespace tumble {

struct ControllerRecord {
    JointId joint;
    ControllerDef def;
    ControllerState state;
    ControllerState previousState;  ///< before the last step, for a failed step's rollback
    bool started = false;           ///< has acted once (velocity mode's derivative needs two)
    bool previousStarted = false;
};

class Controllers {
    friend struct CheckpointAccess;  ///< checkpoint.cpp saves and restores the private state
public:
    /// The record of a joint's controller, or null.
    ControllerRecord* find(JointId joint);
    const ControllerRecord* find(JointId joint) const;
    /// Adds or replaces a joint's controller; the integral and the derivative start afresh.
    void set(JointId joint, const ControllerDef& def);
    /// Removes a joint's controller; returns whether it had one.
    bool remove(JointId joint);
    std::size_t count() const { return records_.size(); }

    /// Forces stage: each controller whose joint is unbroken and has an awake dynamic body
    /// computes its output from the current state and adds it as a torque (hinge) or force
    /// (slider) to the joint's awake dynamic bodies, equal and opposite. Controllers of
    /// destroyed joints are dropped. A controller not yet at its target (nor stalled short of
    /// it without an integral) marks its bodies pushed, so they do not fall asleep.
    void apply(const JointStore& joints, BodyStore& bodies, Real h);
    /// The start of a step: what restore() returns to (once per step, not per substep).
    void save();
    /// A failed step: the integrals and errors go back to what they were at save().
    void restore();

private:
    std::vector<ControllerRecord> records_;
};

}  // namespace tumble
