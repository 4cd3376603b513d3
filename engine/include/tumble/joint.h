#pragma once
/// Joints: ball-socket, hinge (revolute), slider (prismatic), fixed (weld) and distance (rod or
/// rope), with limits, motors and breaking. Solved as rows with the contacts (the rows and their
/// stabilisation: solver/include/tumble/solver/joint_row.h in the source tree).
///
/// A joint is defined in the world frame at the poses the bodies have when it is created: the
/// anchor is a world point, the axis a world direction, and the relative orientation of the
/// bodies at creation is the one a fixed joint or slider keeps and a hinge calls angle 0. The
/// world stores them in the bodies' frames, so later motion carries them along.

#include <cstdint>
#include <limits>

#include "tumble/body.h"
#include "tumble/core/math.h"
#include "tumble/core/solver_types.h"

namespace tumble {

/// A value handle to a joint, like BodyId: checked by generation and world, zero is null.
struct JointId {
    std::uint32_t index = 0;       ///< slot in the world's joint table
    std::uint32_t generation = 0;  ///< 0 means null; bumped each time the slot is reused
    std::uint32_t world = 0;       ///< tag of the World that made it (see BodyId::world)

    bool isNull() const { return generation == 0; }
    friend bool operator==(JointId, JointId) = default;
};

/// Everything needed to create a joint. Copied by World::createJoint, never retained.
struct JointDef {
    JointType type = JointType::Ball;
    BodyId bodyA;  ///< must be a valid body
    /// A valid body other than bodyA, or null: then A is joined to the world (a fixed frame).
    BodyId bodyB;
    /// Where the bodies are joined, world frame at creation (m), finite. For a distance joint,
    /// A's end of the rod or rope.
    Vec3 anchor = Vec3::Zero();
    /// Distance joints only: B's end, world frame at creation (m), finite.
    Vec3 anchorB = Vec3::Zero();
    /// Hinge: the rotation axis; slider: the direction of travel. World frame at creation,
    /// finite and non-zero (normalised by the world). Positive angles turn B about it
    /// counter-clockwise relative to A; positive translations move B along it.
    Vec3 axis = Vec3::UnitZ();
    /// Distance joints: the rod length or the rope's maximum (m), finite and >= 0; a negative
    /// value (the default) takes the anchors' distance at creation.
    Real length = -1;
    bool rope = false;  ///< distance joints: one-sided, the anchors may come closer than length

    /// Hinge (rad) and slider (m) limits on the angle or translation, 0 at creation. A hinge's
    /// limits must lie in [-pi, pi]; lower <= upper (equal locks the joint).
    bool enableLimit = false;
    Real lower = 0;
    Real upper = 0;

    /// Hinge and slider motor: drives d(angle)/dt (rad/s) or d(translation)/dt (m/s) toward
    /// motorSpeed with at most maxMotorForce (N m for a hinge, N for a slider, finite, >= 0).
    bool enableMotor = false;
    Real motorSpeed = 0;
    Real maxMotorForce = 0;

    /// The joint breaks (stops acting, reported by jointState and the step's events) at the end
    /// of a step whose reaction force on B exceeds breakForce (N) or whose reaction torque
    /// exceeds breakTorque (N m). Both > 0; infinity: unbreakable.
    Real breakForce = std::numeric_limits<Real>::infinity();
    Real breakTorque = std::numeric_limits<Real>::infinity();

    /// Whether the two bodies' shapes still collide with each other. Usually not: the parts of a
    /// mechanism overlap at their joints.
    bool collideConnected = false;
};

/// What a joint reports.
struct JointState {
    Vec3 force = Vec3::Zero();   ///< on B from the joint in the last step (N, world); A gets -force
    Vec3 torque = Vec3::Zero();  ///< on B in the last step, about the anchor (N m, world)
    /// Hinge angle (rad, in (-pi, pi]), slider translation (m) or distance (m) at the current
    /// poses; 0 for the others.
    Real position = 0;
    Real speed = 0;       ///< d(position)/dt at the current velocities (rad/s or m/s)
    bool broken = false;  ///< broke in some step (see JointDef::breakForce)
    /// The anchors carried by A and by B (or the world) at the current poses (m, world): they
    /// coincide while a ball, hinge or fixed joint holds; a distance joint's are the rod's ends.
    Vec3 anchorA = Vec3::Zero();
    Vec3 anchorB = Vec3::Zero();
    Vec3 axis = Vec3::UnitZ();  ///< hinge or slider axis carried by A, world, unit
};

}  // namespace tumble
