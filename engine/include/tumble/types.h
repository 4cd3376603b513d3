#pragma once
/// The settings a World is made with and what its steps report: WorldDef, Profile, StepStatus,
/// AdvanceResult. With tumble/core/solver_types.h (the solver's settings and statistics, joint
/// types) these are the plain types of the API; tumble/world.h includes both.

#include <cstdint>

#include "tumble/body.h"
#include "tumble/core/math.h"
#include "tumble/core/solver_types.h"
#include "tumble/spring.h"

namespace tumble {

/// World settings. Checked by the World constructor and by the setters.
struct WorldDef {
    Vec3 gravity = Vec3(0, 0, -9.81);  ///< (m/s^2), finite
    Real timeStep = 1.0 / 60.0;        ///< fixed step h (s), finite and > 0
    int maxStepsPerAdvance = 8;        ///< advance() runs at most this many steps per call, >= 1
    /// Substeps per step, >= 1: step() advances timeStep as this many substeps of timeStep /
    /// substeps, each running forces, collision, solve and integration. The pre-step callback,
    /// sleeping and the publication of events happen once per step. More substeps resolve fast
    /// motion (a whipping chain) that one step of h cannot, at the cost of a full step each.
    /// The default step's count: with solver.softSubsteps > 0 the soft step substeps on its own
    /// and only 1 is accepted (the World refuses both > 1, naming the two fields), so a world
    /// integrates at h / substeps or h / softSubsteps, never their product.
    int substeps = 1;
    /// Speculative contact distance (m), >= 0: pairs closer than this plus the distance they can
    /// close in one step (h |v_rel|) get contact points, so fast bodies are stopped before they
    /// pass through each other.
    Real contactMargin = 0.02;
    /// Growth of the broadphase's fat boxes (m), >= 0: a shape moving less than this costs the
    /// broadphase nothing.
    Real aabbMargin = 0.1;
    /// The contact solver: iterations, friction model, stabilisation, restitution threshold.
    SolverSettings solver{};

    /// Sleeping: an island (dynamic bodies joined by touching contacts) whose every body has been
    /// still for timeToSleep falls asleep -- it is no longer integrated,
    /// solved or collided, and costs nothing per step -- until something touches or pushes it.
    /// When false, bodies never fall asleep by themselves (World::setAwake still works).
    bool enableSleep = true;
    /// A body counts as still when no point of it moves faster than this (m/s), finite and >= 0:
    /// the speed of its centre of mass plus its angular speed times its extent (the largest
    /// distance from the centre of mass to a point of its shapes). 0.05 m/s: one step of free
    /// fall at 60 Hz already gives g h = 0.16 m/s, so a falling or bouncing body is never still
    /// for long, while resting contact leaves far less than this. Measuring the turn by the speed
    /// it gives the body's points makes the test fair across sizes: a 15 cm sphere spinning
    /// slowly about its contact normal (no friction opposes that at a point contact) counts as
    /// still at 0.3 rad/s, a 10 m beam turning at 0.01 rad/s does not.
    Real linearSleepVelocity = 0.05;
    /// And no faster than this (rad/s), finite and >= 0, whatever its size: 0.5 rad/s takes
    /// 13 s per turn, so a small body that spins visibly stays awake. It binds only for bodies
    /// smaller than linearSleepVelocity / angularSleepVelocity (10 cm).
    Real angularSleepVelocity = 0.5;
    /// How long every body of an island must stay still before it falls asleep (s), finite and
    /// > 0. Long against the turning point of a bounce or a swing (a ball rising at 1 m/s is
    /// below 0.05 m/s for 10 ms), short enough that a settled pile stops costing time quickly.
    Real timeToSleep = 0.5;

    /// Approach speed from which a contact's stopping impulse is reported as an impact (m/s),
    /// > 0; infinity: no impact events, and no per-contact work for them. 0.5 m/s is three
    /// steps of free fall at 60 Hz and a drop of 13 mm: resting, sliding and rolling contacts
    /// (approaching at ~0 at the start of each step) and settling jitter stay below it.
    Real impactSpeedThreshold = 0.5;
};

/// Wall-clock time spent in each stage of the last step (s), in the order they run. The stages
/// from forces to bounds, and solveStages, run once per substep and are summed over them.
struct Profile {
    double forces = 0;       ///< external forces, explicit springs, drag, gravity, gyroscopic term,
                             ///< damping -> velocities
    double broadphase = 0;   ///< the pair set, from the fat boxes
    double narrowphase = 0;  ///< manifolds and the contact cache
    double islands = 0;      ///< waking the sleeping islands that awake bodies began to touch
    double solve = 0;        ///< constraint rows built, solved (solveStages), written back
    double integrate = 0;    ///< velocities -> positions and orientations
    double finalize = 0;  ///< finiteness check and rollback, broken joints, impacts; force clearing
    double bounds = 0;    ///< tight bounds at the new poses; proxies moved in the broadphase
    double sleep = 0;     ///< sleep timers, union-find of islands, islands falling asleep
    double total = 0;
    /// The solve's own stages (part of `solve`), summed over the substeps. Under the soft step
    /// (SolverSettings::softSubsteps) the solve integrates too: velocity holds its substeps'
    /// velocities, warm starts and biased sweeps, relax their sweeps without bias, positions
    /// their positions and the anchor pass; it measures no residual (0).
    SolverProfile solveStages;
};

/// What a step reports. A step never throws; when it fails, the world is left exactly as it was
/// before the step so the caller can inspect or save it.
struct StepStatus {
    enum class Code : std::uint8_t {
        Ok,
        NonFiniteState,  ///< a body's state became NaN or infinite; see `body`
        /// A body's state is finite but too large for what is derived from it: its bounding
        /// box, swept over the next step, overflows (a velocity or position near the largest
        /// double); see `body`.
        Overflow,
    };
    Code code = Code::Ok;
    BodyId body;  ///< the first offending body, when there is one
    /// The spring that drove it, where known: of the springs attached to `body`, the one with
    /// the largest tension in the failed step, the stiffest among those whose tension
    /// overflowed (an explicit spring past its stability limit, h > 2 / omega, is the usual
    /// culprit). Null when no spring is attached.
    SpringId spring;

    bool ok() const { return code == Code::Ok; }
};

/// What advance() did.
struct AdvanceResult {
    int steps = 0;         ///< whole steps taken
    Real fraction = 0;     ///< leftover time / h, in [0, 1): interpolate poses by it for rendering
    Real droppedTime = 0;  ///< time discarded because the step cap was reached (s)
    StepStatus status;     ///< status of the last step taken (Ok if none)
};

}  // namespace tumble
