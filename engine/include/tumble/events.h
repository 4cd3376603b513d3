#pragma once
/// What happened in a step, as arrays read after World::step() (never callbacks fired inside it).
///
/// Each array holds the events since the previous step() returned: those of the step itself and
/// those caused by API calls made between the two steps (destroying a touching shape ends its
/// contact; setAwake and pushes wake bodies). They stay valid, unchanged, until the next step()
/// returns, so a pre-step callback still reads the previous step's events. Ids are those of the
/// moment the event happened: a contact that ended because its shape or body was destroyed names
/// ids that are no longer valid (check World::isValid).
///
/// Order within each array is deterministic (the order the step met the events in).

#include <cstdint>

#include "tumble/body.h"
#include "tumble/core/math.h"
#include "tumble/joint.h"
#include "tumble/shape.h"

namespace tumble {

/// Two shapes began or stopped touching: their contact's manifold got its first points, or
/// lost its last ones (or the contact was destroyed while it had points). Manifold points
/// appear within the speculative margin (WorldDef::contactMargin plus h |v_rel|), so a contact
/// may begin a step before the shapes meet.
struct ContactEvent {
    ShapeId shapeA;
    ShapeId shapeB;
    BodyId bodyA;
    BodyId bodyB;
};

/// Two shapes met at a speed of at least WorldDef::impactSpeedThreshold.
///
/// Definition. A contact's impact starts in a step whose solve gave the contact a positive
/// normal impulse while its approach speed -- the largest over its points of -n . (vB - vA),
/// from the velocities the bodies had at the start of that step -- was at least the threshold.
/// A speculative contact stops the bodies over two steps (the first brings them together, the
/// second takes what speed is left), so the impact spans that step and the next one: it is
/// reported once, at the end of the next step (or when the contact ends first), with the sum
/// of the two steps' normal impulses. That sum includes what the contact carried of the other
/// forces in those two steps: a body of mass m landing on the ground at speed v without
/// bouncing gives normalImpulse = m (v + 2 g h).
struct ImpactEvent {
    ShapeId shapeA;
    ShapeId shapeB;
    BodyId bodyA;
    BodyId bodyB;
    Vec3 point = Vec3::Zero();    ///< impulse-weighted mean of the points, first step (m, world)
    Vec3 normal = Vec3::UnitZ();  ///< manifold normal, from A to B (unit, world)
    Real approachSpeed = 0;       ///< (m/s), >= the threshold
    Real normalImpulse = 0;       ///< total over the impact (N s), > 0
};

/// A breakable joint broke in the step (see JointDef::breakForce); it stops acting and stays
/// readable until destroyed.
struct JointBreakEvent {
    JointId joint;
    BodyId bodyA;
    BodyId bodyB;                ///< null when joined to the world
    Vec3 force = Vec3::Zero();   ///< the reaction on B that broke it (N, world)
    Vec3 torque = Vec3::Zero();  ///< the reaction torque on B (N m, world)
};

/// A dynamic body fell asleep (with its island) or woke up.
struct SleepEvent {
    BodyId body;
    bool asleep = false;  ///< true: fell asleep; false: woke
};

}  // namespace tumble
