#pragma once
/// The world's private state, shared by the files that implement World (world.cpp for bodies and
/// the step, world_shapes.cpp for shapes and contacts, world_queries.cpp for queries).

#include <algorithm>
#include <cstdint>
#include <functional>
#include <vector>

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

/// A body's mass properties as the compound of its shapes at their densities (world_shapes.cpp).
MassProperties compoundMass(const ShapeStore& shapes, std::uint32_t firstShape);

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
    /// With substeps: the motion at the start of the step of the bodies awake before the current
    /// substep, by position in bodies.awake (append-only within a step), and how many are kept.
    /// previousMotion holds the start of the substep meanwhile, as the solve and the impacts
    /// need; the step's start goes back into it when the step ends (rollback, interpolation).
    std::vector<BodyMotion> stepStart;
    std::size_t stepStartCount = 0;
    /// Put in every id this world hands out, and required of every id it is handed; unique per
    /// World object (World::World), kept by a checkpoint load, never saved, never read by a step.
    std::uint32_t worldTag = 0;

    void setWorldTag(std::uint32_t tag) {
        worldTag = tag;
        bodies.setWorld(tag);
        shapes.setWorld(tag);
        springs.setWorld(tag);
        joints.setWorld(tag);
    }

    /// Points the stages at this world's event and warning logs (after construction or load).
    void connectLogs() {
        contacts.events = &pendingEvents;
        islands.events = &pendingEvents;
        contacts.warnings = &warnings;
    }

    /// The whole step: sleep timers.
    StepContext context() const {
        return {settings.timeStep, 1 / settings.timeStep, settings.gravity};
    }
    /// One substep, h / substeps: every stage between the pre-step callback and sleeping.
    StepContext substepContext(int substeps) const {
        const Real h = settings.timeStep / substeps;
        return {h, 1 / h, settings.gravity};
    }

    const BodyMotion& motion(BodyId id) const { return bodies.motion[bodies.indexOf(id)]; }

    Vec3 origin(std::uint32_t index) const {
        const BodyMotion& m = bodies.motion[index];
        return m.center - m.orientation * bodies.inertia[index].localCenter;
    }

    // A body's angular velocity after an angular impulse (world frame, N m s).
    Vec3 angularVelocityAfter(std::uint32_t index, const Vec3& impulse) const {
        const BodyMotion& m = bodies.motion[index];
        const Mat3 rotation = m.orientation.toRotationMatrix();
        return m.angularVelocity + rotation * (bodies.inertia[index].inverseInertiaLocal *
                                               (rotation.transpose() * impulse));
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

    // A shape leaves the broadphase (its contacts end), and comes back with its current filter
    // and its body's current type, its joints' exclusions set again (world_bodies.cpp).
    void detachShape(std::uint32_t slot);
    void attachShape(std::uint32_t slot);

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

    // Storage a step fills with at most one entry per body -- the awake list, the islands' walks
    // and union-find, the sleep events -- holds the body count before the step needs it, so it
    // grows when bodies are added, never in a warm step where one first falls asleep or wakes.
    // In a step a body wakes at most once and falls asleep at most once, after (the sleep stage
    // runs last): two sleep events; the API's own events before the step come on top.
    void reserveForBodies() {
        const std::size_t n = bodies.count();
        bodies.awake.reserve(n);
        islands.reserve(n);
        pendingEvents.sleep.reserve(pendingEvents.sleep.size() + 2 * n);
        events.sleep.reserve(2 * n);  // pending after the swap
    }

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

    // Forces, collision, solve and integration over one substep (world.cpp), each stage's time
    // added to the profile.
    StepStatus substep(const StepContext& context);

    // Between two substeps: previousMotion becomes the start of the next substep, after the
    // step's start of the bodies woken in the last one (still at rest in previousMotion) is
    // kept in stepStart.
    void beginSubstep() {
        stepStart.reserve(bodies.count());  // the awake list may grow to it: see reserveForBodies
        stepStart.resize(bodies.awake.size());
        for (std::size_t k = stepStartCount; k < bodies.awake.size(); ++k)
            stepStart[k] = bodies.previousMotion[bodies.awake[k]];
        stepStartCount = bodies.awake.size();
        bodies.savePreviousMotion();
    }

    // Puts the awake bodies back where the step began (before its first substep); sleeping and
    // static bodies did not move. True when earlier substeps had moved them, so that the bounds
    // differ from those of the restored poses.
    bool rollBackStep() {
        bodies.restorePreviousMotion();  // the substep's start
        const bool moved = stepStartCount > 0;
        for (std::size_t k = 0; k < stepStartCount; ++k) {
            bodies.motion[bodies.awake[k]] = stepStart[k];
            bodies.previousMotion[bodies.awake[k]] = stepStart[k];
        }
        stepStartCount = 0;
        return moved;
    }

    // Checks the substep's new state; a non-finite body rolls the step back. `moved` tells the
    // bounds stage whether the poses now differ from those its last refresh saw: after a
    // rollback only when earlier substeps had moved them.
    StepStatus checkFinite(bool& moved) {
        for (const std::uint32_t i : bodies.awake) {
            if (!isFinite(bodies.motion[i])) {
                moved = rollBackStep();
                return {StepStatus::Code::NonFiniteState, bodies.idAt(i), SpringId{}};
            }
        }
        return {};
    }

    // The bounds stage: the awake shapes' boxes follow their bodies. A body whose box, swept over
    // the next step and fattened, overflows although its state is finite (a speed or position
    // near the largest double) fails the step like a non-finite one, so the broadphase never
    // sees an infinite box.
    StepStatus refreshBounds(const StepContext& context) {
        const std::uint32_t overflow = contacts.refreshBounds(shapes, bodies, context);
        if (overflow == ContactManager::kNoBody)
            return {};
        const BodyId body = bodies.idAt(overflow);
        rollBackStep();
        // Earlier substeps moved the boxes, and the failed refresh left some half-updated.
        contacts.refreshBounds(shapes, bodies, context);
        return {StepStatus::Code::Overflow, body, SpringId{}};
    }

    // After the last substep of a successful step: previousMotion goes back to the step's start
    // (interpolation spans the step), the applied forces are spent, the clock advances.
    void endStep() {
        for (std::size_t k = 0; k < stepStartCount; ++k)
            bodies.previousMotion[bodies.awake[k]] = stepStart[k];
        stepStartCount = 0;
        for (const std::uint32_t i : bodies.awake)
            bodies.forces[i] = {};
        time += settings.timeStep;
        stepCount += 1;
    }
};

}  // namespace tumble
