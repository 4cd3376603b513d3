#include "tumble/world.h"

#include <atomic>
#include <chrono>
#include <cmath>

#include "checks.h"
#include "integrator.h"
#include "joints.h"
#include "tumble/core/error.h"
#include "tumble/core/timed.h"
#include "world_impl.h"

namespace tumble {
namespace {

using Clock = std::chrono::steady_clock;

// advance() treats an accumulator within this fraction of h as a whole step, so frames of exactly
// h do not skip a step to rounding.
constexpr Real kAccumulatorSlack = 1e-9;

// A tag per World object, so one world refuses another's ids. Counted from 1 (0 is the tag of
// null ids) and not reused until the count wraps after 2^32 - 1 worlds. Atomic: worlds may be
// made on several threads. The tag is only ever compared, so it cannot change a result.
std::uint32_t nextWorldTag() {
    static std::atomic<std::uint32_t> count{0};
    std::uint32_t tag = 0;
    while (tag == 0)
        tag = count.fetch_add(1, std::memory_order_relaxed) + 1;
    return tag;
}

// An impulse is finite (checked), but the velocity it gives may overflow: refused, as it would
// be the state a failed step rolls back to. (An overflowing sum of forces is left to the step,
// which reports it as a non-finite state and keeps the bodies where they were.)
void finiteSum(const Vec3& sum, const char* what) {
    if (!sum.allFinite())
        fail(what, " = (", sum.x(), ", ", sum.y(), ", ", sum.z(), ") overflows: must be finite");
}

}  // namespace

World::World(const WorldDef& def) : impl_(std::make_unique<Impl>()) {
    checks::worldDef(def);
    impl_->settings = def;
    impl_->setWorldTag(nextWorldTag());
    impl_->contacts.contactMargin = def.contactMargin;
    impl_->contacts.aabbMargin = def.aabbMargin;
    impl_->connectLogs();
}

World::~World() = default;
World::World(World&&) noexcept = default;
World& World::operator=(World&&) noexcept = default;

BodyId World::createBody(const BodyDef& def) {
    checks::bodyDef(def);
    return impl_->bodies.add(def);
}

void World::destroyBody(BodyId id) {
    const std::uint32_t index = impl_->bodies.indexOf(id);
    impl_->wakeChanged(index);  // what rested on it, or what it rested on, must fall
    std::uint32_t slot = impl_->bodies.info[index].firstShape;
    while (slot != BodyInfo::kNoShape) {
        const std::uint32_t next = impl_->shapes.records[slot].nextInBody;
        impl_->contacts.removeShape(impl_->shapes, slot, impl_->bodies);
        impl_->shapes.remove(impl_->shapes.idAt(slot));
        slot = next;
    }
    impl_->springs.removeAttachedTo(id);
    impl_->removeJointsOf(id);
    impl_->drag.remove(id);
    impl_->bodies.remove(id);
}
bool World::isValid(BodyId id) const {
    return impl_->bodies.isValid(id);
}
int World::bodyCount() const {
    return static_cast<int>(impl_->bodies.count());
}

BodyType World::bodyType(BodyId id) const {
    return impl_->bodies.info[impl_->bodies.indexOf(id)].type;
}
Vec3 World::position(BodyId id) const {
    return impl_->origin(impl_->bodies.indexOf(id));
}
Quat World::orientation(BodyId id) const {
    return impl_->motion(id).orientation;
}
Transform World::transform(BodyId id) const {
    return {position(id), orientation(id)};
}
Vec3 World::centerOfMass(BodyId id) const {
    return impl_->motion(id).center;
}
Vec3 World::linearVelocity(BodyId id) const {
    return impl_->motion(id).linearVelocity;
}
Vec3 World::angularVelocity(BodyId id) const {
    return impl_->motion(id).angularVelocity;
}

Vec3 World::velocityAt(BodyId id, const Vec3& worldPoint) const {
    const BodyMotion& m = impl_->motion(id);
    return m.linearVelocity + m.angularVelocity.cross(worldPoint - m.center);
}

MassProperties World::massProperties(BodyId id) const {
    return impl_->bodies.info[impl_->bodies.indexOf(id)].mass;
}
std::uint64_t World::userData(BodyId id) const {
    return impl_->bodies.info[impl_->bodies.indexOf(id)].userData;
}

Transform World::interpolatedTransform(BodyId id, Real fraction) const {
    const std::uint32_t index = impl_->bodies.indexOf(id);
    const BodyMotion& previous = impl_->bodies.previousMotion[index];
    const BodyMotion& current = impl_->bodies.motion[index];
    const Vec3& localCenter = impl_->bodies.inertia[index].localCenter;
    Transform t;
    t.rotation = previous.orientation.slerp(fraction, current.orientation);
    const Vec3 center = (1 - fraction) * previous.center + fraction * current.center;
    t.position = center - t.rotation * localCenter;
    return t;
}

Vec3 World::angularMomentum(BodyId id) const {
    const std::uint32_t index = impl_->bodies.indexOf(id);
    const BodyMotion& m = impl_->bodies.motion[index];
    const Mat3 rotation = m.orientation.toRotationMatrix();
    return rotation *
           (impl_->bodies.inertia[index].inertiaLocal * (rotation.transpose() * m.angularVelocity));
}

Real World::kineticEnergy(BodyId id) const {
    const std::uint32_t index = impl_->bodies.indexOf(id);
    const BodyInertia& inertia = impl_->bodies.inertia[index];
    if (inertia.inverseMass == 0)
        return 0;
    const BodyMotion& m = impl_->bodies.motion[index];
    const Vec3 bodyOmega = m.orientation.conjugate() * m.angularVelocity;
    return 0.5 * m.linearVelocity.squaredNorm() / inertia.inverseMass +
           0.5 * bodyOmega.dot(inertia.inertiaLocal * bodyOmega);
}

Real World::kineticEnergy() const {
    Real sum = 0;
    for (std::uint32_t i = 0; i < impl_->bodies.count(); ++i) {
        sum += kineticEnergy(impl_->bodies.idAt(i));
    }
    return sum;
}

void World::setTransform(BodyId id, const Vec3& position, const Quat& orientation) {
    const std::uint32_t index = impl_->bodies.indexOf(id);
    checks::finiteVector(position, "setTransform position");
    checks::unitQuaternion(orientation, "setTransform orientation");
    BodyMotion& m = impl_->bodies.motion[index];
    const BodyMotion before = m;
    m.orientation = orientation.normalized();
    m.center = position + m.orientation * impl_->bodies.inertia[index].localCenter;
    if (!m.center.allFinite() || !impl_->contacts.boundsFinite(impl_->shapes, impl_->bodies, index,
                                                               impl_->settings.timeStep)) {
        m = before;
        fail("setTransform position = (", position.x(), ", ", position.y(), ", ", position.z(),
             ") m: the body's centre of mass or the bounding box of a shape, swept over a step at "
             "its velocity, must be finite there");
    }
    // A teleport: nothing to interpolate across.
    impl_->bodies.previousMotion[index] = m;
    impl_->refreshShapesOf(index);
    impl_->wakeChanged(index, true);
    if (impl_->bodies.info[index].type != BodyType::Dynamic) {
        for (std::uint32_t slot = impl_->bodies.info[index].firstShape; slot != BodyInfo::kNoShape;
             slot = impl_->shapes.records[slot].nextInBody)
            impl_->contacts.markPlaced(impl_->shapes.records[slot].proxy);
    }
}

void World::setLinearVelocity(BodyId id, const Vec3& velocity) {
    const std::uint32_t index = impl_->bodies.indexOf(id);
    checks::finiteVector(velocity, "setLinearVelocity velocity");
    if (impl_->bodies.info[index].type == BodyType::Static)
        fail("setLinearVelocity: the body is static");
    impl_->islands.push(impl_->bodies, impl_->contacts, index);
    impl_->bodies.motion[index].linearVelocity = velocity;
}

void World::setAngularVelocity(BodyId id, const Vec3& velocity) {
    const std::uint32_t index = impl_->bodies.indexOf(id);
    checks::finiteVector(velocity, "setAngularVelocity velocity");
    if (impl_->bodies.info[index].type == BodyType::Static)
        fail("setAngularVelocity: the body is static");
    if (impl_->bodies.info[index].fixedRotation && !velocity.isZero(0)) {
        fail(
            "setAngularVelocity: the body is translation-only (BodyDef::fixedRotation) and "
            "cannot rotate; only a zero angular velocity is accepted");
    }
    impl_->islands.push(impl_->bodies, impl_->contacts, index);
    impl_->bodies.motion[index].angularVelocity = velocity;
}

void World::setMassProperties(BodyId id, const MassProperties& mass) {
    const std::uint32_t index = impl_->bodies.indexOf(id);
    if (impl_->bodies.info[index].type == BodyType::Dynamic) {
        checks::massProperties(mass, "setMassProperties mass");
    }
    impl_->bodies.setMass(index, mass);
    impl_->bodies.info[index].massFromShapes = false;
    impl_->refreshExtent(index);
    impl_->islands.push(impl_->bodies, impl_->contacts, index);
}

bool World::isAwake(BodyId id) const {
    return impl_->bodies.isAwake(impl_->bodies.indexOf(id));
}

void World::setAwake(BodyId id, bool awake) {
    Impl& w = *impl_;
    const std::uint32_t index = w.bodies.indexOf(id);
    const BodyType type = w.bodies.info[index].type;
    if (awake) {
        if (type == BodyType::Dynamic)
            w.islands.wake(w.bodies, w.contacts, index);
        return;
    }
    if (type == BodyType::Kinematic)
        fail("setAwake(false): the body is kinematic, and kinematic bodies never sleep");
    if (type == BodyType::Dynamic)
        w.islands.sleepIslandOf(w.bodies, w.contacts, index);
}

int World::awakeBodyCount() const {
    return static_cast<int>(impl_->bodies.awake.size());
}

void World::applyForce(BodyId id, const Vec3& force, const Vec3& worldPoint) {
    checks::finiteVector(force, "applyForce force");
    checks::finiteVector(worldPoint, "applyForce point");
    if (BodyForces* f = impl_->forcesOf(id)) {
        f->force += force;
        f->torque += (worldPoint - centerOfMass(id)).cross(force);
    }
}

void World::applyForceToCenter(BodyId id, const Vec3& force) {
    checks::finiteVector(force, "applyForceToCenter force");
    if (BodyForces* f = impl_->forcesOf(id))
        f->force += force;
}

void World::applyTorque(BodyId id, const Vec3& torque) {
    checks::finiteVector(torque, "applyTorque torque");
    if (BodyForces* f = impl_->forcesOf(id))
        f->torque += torque;
}

void World::applyLinearImpulse(BodyId id, const Vec3& impulse, const Vec3& worldPoint) {
    checks::finiteVector(impulse, "applyLinearImpulse impulse");
    checks::finiteVector(worldPoint, "applyLinearImpulse point");
    const std::uint32_t index = impl_->bodies.indexOf(id);
    if (impl_->bodies.info[index].type != BodyType::Dynamic)
        return;
    BodyMotion& m = impl_->bodies.motion[index];
    const Vec3 velocity = m.linearVelocity + impl_->bodies.inertia[index].inverseMass * impulse;
    const Vec3 angularImpulse = (worldPoint - m.center).cross(impulse);
    finiteSum(velocity, "applyLinearImpulse: the body's linear velocity");
    finiteSum(angularImpulse, "applyLinearImpulse: (point - centre of mass) x impulse");
    finiteSum(impl_->angularVelocityAfter(index, angularImpulse),
              "applyLinearImpulse: the body's angular velocity");
    impl_->islands.push(impl_->bodies, impl_->contacts, index);
    m.linearVelocity = velocity;
    applyAngularImpulse(id, angularImpulse);
}

void World::applyAngularImpulse(BodyId id, const Vec3& impulse) {
    checks::finiteVector(impulse, "applyAngularImpulse impulse");
    const std::uint32_t index = impl_->bodies.indexOf(id);
    if (impl_->bodies.info[index].type != BodyType::Dynamic)
        return;
    const Vec3 velocity = impl_->angularVelocityAfter(index, impulse);
    finiteSum(velocity, "applyAngularImpulse: the body's angular velocity");
    impl_->islands.push(impl_->bodies, impl_->contacts, index);
    impl_->bodies.motion[index].angularVelocity = velocity;
}

// One step of h = N substeps of h / N. Once per step: the pre-step callback, waking what springs
// and joints link, the rollback state, sleeping and the events. Per substep: the full pipeline
// (collision included, so contacts see the bodies where the substep starts).
StepStatus World::step() {
    Impl& w = *impl_;
    w.runPreStep(*this);  // application time, not the engine's: before the clock starts
    const Clock::time_point start = Clock::now();
    w.profile = {};
    w.reserveForBodies();
    if (w.springs.count() > 0)
        wakeSpringLinked(w.springs, w.bodies, w.contacts, w.islands);
    if (w.joints.count() > 0)
        wakeJointLinked(w.joints, w.bodies, w.contacts, w.islands);
    w.solve.noteKinematicChanges(w.bodies, w.settings.solver.softSubsteps > 0);
    w.bodies.savePreviousMotion();  // awake bodies: the others do not move
    w.springs.saveState();
    w.joints.saveState();
    w.controllers.save();

    // A step in which unresolved threads work runs as more substeps (springs.h).
    const int substeps =
        w.settings.substeps *
        (w.springs.implicitCount > 0
             ? threadSubsteps(w.springs, w.bodies, w.settings.timeStep / w.settings.substeps)
             : 1);
    const StepContext context = w.substepContext(substeps);
    StepStatus status;
    for (int substep = 0; substep < substeps && status.ok(); ++substep) {
        if (substep > 0)
            w.beginSubstep();
        status = w.substep(context);
    }
    w.profile.finalize += timed([&] {
        if (status.ok()) {
            w.endStep();
        } else {
            status.spring = w.springs.strongestOn(status.body);
            w.springs.restoreState();
            w.joints.restoreState();
            w.controllers.restore();
        }
    });
    w.profile.sleep = timed([&] {
        if (status.ok())
            w.islands.updateSleep(w.bodies, w.contacts, w.springs, w.drag, w.joints, w.context(),
                                  w.settings);
    });
    w.publishEvents();

    w.profile.total = std::chrono::duration<double>(Clock::now() - start).count();
    return status;
}

StepStatus World::Impl::substep(const StepContext& context) {
    // The soft step integrates velocities and positions in its own substeps, with the forces of
    // the step's start; springs and joints keep the sweeps (SolverSettings::softSubsteps).
    const bool soft =
        settings.solver.softSubsteps > 0 && springs.count() == 0 && joints.count() == 0;
    profile.forces += timed([&] {
        controllers.apply(joints, bodies, context.h);
        forceElements.apply(springs, drag, bodies);
        if (!soft) {
            integrateVelocities(bodies, context);
            forceElements.restore(bodies);
        }
    });
    profile.broadphase += timed([&] { contacts.updatePairs(); });
    profile.narrowphase += timed([&] { contacts.updateContacts(shapes, bodies, context); });
    profile.islands += timed([&] {
        // A body woken now gets its forces in the soft step's substeps, not here.
        const StepContext noCatchUp{0, context.inverseH, context.gravity};
        islands.wakeTouched(bodies, contacts, soft ? noCatchUp : context);
        // A body woken by a touch wakes what it is jointed to before the solve.
        if (joints.count() > 0)
            wakeJointLinked(joints, bodies, contacts, islands, &context);
    });
    profile.solve += timed([&] {
        if (soft) {
            solverStats = solve.runSoft(bodies, shapes, contacts, context, settings.solver);
            forceElements.restore(bodies);
            return;
        }
        solverStats =
            solve.run(bodies, shapes, contacts, springs, joints, context, settings.solver);
    });
    profile.solveStages += solve.solverProfile();
    profile.integrate += timed([&] {
        if (soft)
            return;  // the soft step moved the bodies
        integratePositions(bodies, solve.pseudoVelocities(), context);
        solve.projectSprings(bodies, springs, context, settings.solver);
    });
    StepStatus status;
    bool moved = true;  // the poses differ from those the bounds were last refreshed at
    profile.finalize += timed([&] { status = checkFinite(moved); });
    profile.bounds += timed([&] {
        if (!moved)
            return;
        const StepStatus bounds = refreshBounds(context);
        if (status.ok())
            status = bounds;
    });
    profile.finalize += timed([&] {
        if (status.ok()) {
            releaseBrokenJoints();
            impacts.update(contacts, bodies, settings.impactSpeedThreshold, pendingEvents.impact);
        }
    });
    return status;
}

AdvanceResult World::advance(Real frameTime) {
    if (!(std::isfinite(frameTime) && frameTime >= 0)) {
        fail("advance frameTime = ", frameTime, " (s) must be finite and >= 0");
    }
    Impl& w = *impl_;
    const Real h = w.settings.timeStep;
    AdvanceResult result;
    w.accumulator += frameTime;
    while (w.accumulator >= h * (1 - kAccumulatorSlack)) {
        if (result.steps == w.settings.maxStepsPerAdvance) {
            // Drop whole steps beyond the cap but keep the fraction, so rendering stays smooth.
            const Real whole = std::floor(w.accumulator / h + kAccumulatorSlack);
            result.droppedTime = whole * h;
            w.accumulator = std::max<Real>(0, w.accumulator - result.droppedTime);
            break;
        }
        result.status = step();
        if (!result.status.ok())
            break;
        w.accumulator = std::max<Real>(0, w.accumulator - h);
        result.steps += 1;
    }
    result.fraction = std::min<Real>(w.accumulator / h, 1);
    return result;
}

const WorldDef& World::settings() const {
    return impl_->settings;
}

void World::setGravity(const Vec3& gravity) {
    checks::finiteVector(gravity, "setGravity gravity");
    Impl& w = *impl_;
    if (gravity == w.settings.gravity)
        return;
    w.settings.gravity = gravity;
    // A resting pile rests under the gravity it settled in: every sleeper must feel the change.
    for (std::uint32_t i = 0; i < w.bodies.count(); ++i)
        w.islands.wake(w.bodies, w.contacts, i);
}

void World::setTimeStep(Real timeStep) {
    checks::timeStep(timeStep, "setTimeStep timeStep");
    impl_->settings.timeStep = timeStep;
    impl_->accumulator = 0;
}

void World::setMaxStepsPerAdvance(int steps) {
    if (steps < 1)
        fail("setMaxStepsPerAdvance steps = ", steps, " must be >= 1");
    impl_->settings.maxStepsPerAdvance = steps;
}

Real World::time() const {
    return impl_->time;
}
std::uint64_t World::stepCount() const {
    return impl_->stepCount;
}
const Profile& World::profile() const {
    return impl_->profile;
}

const SolverStats& World::solverStats() const {
    return impl_->solverStats;
}

void World::setSolverSettings(const SolverSettings& settings) {
    checkSolverSettings(settings);
    checks::substepCounts(impl_->settings.substeps, settings.softSubsteps, "setSolverSettings");
    impl_->settings.solver = settings;
}

}  // namespace tumble
