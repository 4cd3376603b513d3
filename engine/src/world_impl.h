#pragma once
/// The world's private state, shared by the files that implement World (world.cpp for bodies and
/// the step, world_shapes.cpp for shapes and contacts, world_queries.cpp for queries).

#include <algorithm>
#include <cstdint>
#include <functional>

#include "body_store.h"
#include "contact_manager.h"
#include "controllers.h"
#include "event_log.h"
#include "impacts.h"
#include "island.h"
#include "joint_store.h"
#include "joints.h"
#include "shape_store.h"
#include "solve_stage.h"
#include "spring_store.h"
#include "springs.h"
#include "step_context.h"
#include "tumble/world.h"
#include "warning_log.h"

namespace tumble {

inline bool isFinite(const BodyMotion& m) {
    return m.center.allFinite() && m.orientation.coeffs().allFinite() &&
           m.linearVelocity.allFinite() && m.angularVelocity.allFinite();
}

struct World::Impl {
    WorldDef settings;
    BodyStore bodies;
    Real time = 0;
    std::uint64_t stepCount = 0;
    Real accumulator = 0;
    Profile profile;
    ShapeStore shapes;
    ContactManager contacts;
    Islands islands;
    SolveStage solve;
    SpringStore springs;
    JointStore joints;
    DragStore drag;
    ForceElements forceElements;
    SolverStats solverStats;
    Controllers controllers;
    std::function<void(World&, Real)> preStep;
    bool inPreStep = false;
    ImpactTracker impacts;
    EventLog pendingEvents;  ///< appended to by the stages and the API
    EventLog events;         ///< published when a step returns
    WarningLog warnings;

    /// Points the stages at this world's event and warning logs (after construction or load).
    void connectLogs() {
        contacts.events = &pendingEvents;
        islands.events = &pendingEvents;
        contacts.warnings = &warnings;
    }

    StepContext context() const {
        return {settings.timeStep, 1 / settings.timeStep, settings.gravity};
    }

    const BodyMotion& motion(BodyId id) const { return bodies.motion[bodies.indexOf(id)]; }

    Vec3 origin(std::uint32_t index) const {
        const BodyMotion& m = bodies.motion[index];
        return m.center - m.orientation * bodies.inertia[index].localCenter;
    }

    // Dynamic bodies only; forces on static and kinematic bodies are ignored by design. A
    // pushed body wakes.
    BodyForces* forcesOf(BodyId id) {
        const std::uint32_t index = bodies.indexOf(id);
        if (bodies.info[index].type != BodyType::Dynamic)
            return nullptr;
        islands.push(bodies, contacts, index);
        return &bodies.forces[index];
    }

    // The body was changed through the API: wake its island; a moved or reshaped static or
    // kinematic body also wakes what it has contacts with (see Islands::wakeAround).
    void wakeChanged(std::uint32_t index, bool moved = false) {
        const bool touchingOnly = !moved || bodies.info[index].type == BodyType::Dynamic;
        islands.wakeAround(bodies, contacts, index, touchingOnly);
    }

    // After a teleport: the body's shapes take their new bounds at once (queries see them).
    void refreshShapesOf(std::uint32_t bodyIndex) {
        for (std::uint32_t slot = bodies.info[bodyIndex].firstShape; slot != BodyInfo::kNoShape;
             slot = shapes.records[slot].nextInBody) {
            contacts.refreshShape(shapes, slot, bodies, settings.timeStep);
        }
    }

    // BodyInfo::extent after the body's shapes or centre of mass changed.
    void refreshExtent(std::uint32_t bodyIndex) {
        BodyInfo& info = bodies.info[bodyIndex];
        const Vec3& center = bodies.inertia[bodyIndex].localCenter;
        info.extent = 0;
        for (std::uint32_t slot = info.firstShape; slot != BodyInfo::kNoShape;
             slot = shapes.records[slot].nextInBody) {
            const ShapeDef& def = shapes.records[slot].def;
            info.extent = std::max(info.extent, (def.localPose.position - center).norm() +
                                                    boundingRadius(def.geometry));
        }
    }

    // Joints that broke in the step just taken stop filtering their bodies' collisions, and
    // are reported.
    void releaseBrokenJoints() {
        for (const std::uint32_t index : solve.brokenJoints()) {
            setJointedPairsExcluded(joints, shapes, bodies, contacts, index, false);
            const JointDef& def = joints.records[index].def;
            const JointStepState& state = joints.state[index];
            pendingEvents.jointBreak.push_back(
                {joints.idAt(index), def.bodyA, def.bodyB, state.force, state.torque});
        }
    }

    // Calls the application's pre-step callback, if any (world_control.cpp).
    void runPreStep(World& world);

    // The events of the step just taken, and of the API calls before it, become readable.
    void publishEvents() {
        events.swap(pendingEvents);
        pendingEvents.clear();
    }

    // A body is being destroyed: its joints go (their exclusions go with its shapes), and what
    // they held wakes.
    void removeJointsOf(BodyId body) {
        for (std::uint32_t i = joints.count(); i-- > 0;) {
            const JointDef& def = joints.records[i].def;
            if (!(def.bodyA == body || def.bodyB == body))
                continue;
            const BodyId other = def.bodyA == body ? def.bodyB : def.bodyA;
            if (!other.isNull())
                islands.push(bodies, contacts, bodies.indexOf(other));
            joints.remove(joints.idAt(i));
        }
    }

    // Checks the new state; on a non-finite body restores the state from before the step.
    // Sleeping and static bodies did not move: only the awake ones are visited.
    StepStatus finalize() {
        for (const std::uint32_t i : bodies.awake) {
            if (!isFinite(bodies.motion[i])) {
                bodies.restorePreviousMotion();
                return {StepStatus::Code::NonFiniteState, bodies.idAt(i), SpringId{}};
            }
        }
        for (const std::uint32_t i : bodies.awake)
            bodies.forces[i] = {};
        contacts.refreshBounds(shapes, bodies, context());
        time += settings.timeStep;
        stepCount += 1;
        return {};
    }
};

}  // namespace tumble
