#pragma once
/// The world: owner of every body, and the fixed-step stepper.
///
/// Conventions, written once for the whole engine:
/// - SI units; right-handed frames; gravity along -Z by default.
/// - A body's pose is that of its origin; its centre of mass sits at MassProperties::localCenter.
/// - Velocities are world-frame: linear of the centre of mass, angular about it.
/// - The manifold normal (collision) points from body A to body B.
/// - Forces and torques applied between steps act during the next step and are then cleared.
/// - Changing a body through the API (pose, velocity, mass, a force, torque or impulse, adding or
///   removing a shape) wakes its island; moving or destroying a static or kinematic body, or
///   removing one of its shapes, wakes the islands it touches.
///
/// Threading: a World is not thread-safe; distinct worlds share only the atomic counter that
/// hands each its id tag when it is made, so they may be made and stepped on different threads.

#include <cstddef>
#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <span>
#include <vector>

#include "tumble/body.h"
#include "tumble/contact.h"
#include "tumble/control.h"
#include "tumble/core/math.h"
#include "tumble/events.h"
#include "tumble/joint.h"
#include "tumble/query.h"
#include "tumble/shape.h"
#include "tumble/spring.h"
#include "tumble/types.h"
#include "tumble/warnings.h"

namespace tumble {

/// Where the bodies' state lives in a world's storage, for readers that must not copy it (the
/// Python bindings' numpy views). Body k of World::bodies() has its values at
/// base + k * stride bytes from each pointer. Read only: writing bypasses the engine's checks
/// and waking. Valid until a body is created or destroyed or a checkpoint is restored.
struct DenseState {
    const Real* center = nullptr;           ///< centre of mass, world (m): x, y, z
    const Real* orientation = nullptr;      ///< body to world, as Quat::coeffs(): x, y, z, w
    const Real* linearVelocity = nullptr;   ///< of the centre of mass (m/s): x, y, z
    const Real* angularVelocity = nullptr;  ///< world frame (rad/s): x, y, z
    std::size_t count = 0;                  ///< bodies
    std::size_t stride = 0;                 ///< bytes from one body's values to the next's
};

class World {
public:
    explicit World(const WorldDef& def = {});
    ~World();
    World(World&&) noexcept;
    World& operator=(World&&) noexcept;
    World(const World&) = delete;
    World& operator=(const World&) = delete;

    // --- bodies -----------------------------------------------------------------------------
    /// Creates a body. Refuses (InvalidArgument) a non-finite pose or velocity, a non-unit
    /// orientation, negative damping, and for a dynamic body a mass or inertia that is not
    /// physical. Nothing is created when the definition is refused.
    BodyId createBody(const BodyDef& def);
    /// Destroys a body; its id and every copy of it become invalid.
    void destroyBody(BodyId id);
    /// Does the id name a live body of this world? (False for another world's id.)
    bool isValid(BodyId id) const;
    int bodyCount() const;
    /// Every body, in the order a step visits them (creation order until a body is destroyed:
    /// then the last body takes the destroyed one's place).
    std::vector<BodyId> bodies() const;
    /// The state of every body in the order of bodies(), in place (see DenseState).
    DenseState denseState() const;
    /// The body's shapes, in the order they were attached.
    std::vector<ShapeId> bodyShapes(BodyId id) const;
    /// The joints with the body at either end, in the order the solver sweeps them.
    std::vector<JointId> bodyJoints(BodyId id) const;
    /// The springs with the body at either end, in the order the solver sweeps them.
    std::vector<SpringId> bodySprings(BodyId id) const;

    BodyType bodyType(BodyId id) const;
    Vec3 position(BodyId id) const;  ///< body origin (m)
    Quat orientation(BodyId id) const;
    Transform transform(BodyId id) const;
    Vec3 centerOfMass(BodyId id) const;     ///< world frame (m)
    Vec3 linearVelocity(BodyId id) const;   ///< of the centre of mass (m/s)
    Vec3 angularVelocity(BodyId id) const;  ///< world frame (rad/s)
    /// Velocity of a point fixed to the body, given in world coordinates (m/s).
    Vec3 velocityAt(BodyId id, const Vec3& worldPoint) const;
    MassProperties massProperties(BodyId id) const;
    std::uint64_t userData(BodyId id) const;
    Real linearDamping(BodyId id) const;   ///< (1/s)
    Real angularDamping(BodyId id) const;  ///< (1/s)
    /// Pose interpolated between the previous and the current step: fraction 0 gives the previous
    /// pose, 1 the current one. For rendering between fixed steps (see advance()).
    Transform interpolatedTransform(BodyId id, Real fraction) const;

    /// Angular momentum about the centre of mass, world frame (kg m^2/s).
    Vec3 angularMomentum(BodyId id) const;
    /// Translational plus rotational kinetic energy (J).
    Real kineticEnergy(BodyId id) const;
    /// Sum over all dynamic bodies (J).
    Real kineticEnergy() const;

    void setTransform(BodyId id, const Vec3& position, const Quat& orientation);
    /// Refused on a static body.
    void setLinearVelocity(BodyId id, const Vec3& velocity);
    /// Refused on a static body.
    void setAngularVelocity(BodyId id, const Vec3& velocity);
    void setMassProperties(BodyId id, const MassProperties& mass);
    /// Changes the body's type. Static: velocities become zero and the body leaves the awake
    /// list. Kinematic: keeps its velocity and is always awake. Dynamic: takes the compound mass
    /// of its shapes if any of them has ShapeDef::updateBodyMass, else the mass it was given
    /// (BodyDef::mass or setMassProperties), and wakes. Static and kinematic bodies have no
    /// mass (zero inverse mass and inertia) and lose their pending forces. The body's contacts
    /// end and are found again by the next step (static bodies do not collide with each other);
    /// what it touched wakes. Refuses (InvalidArgument), changing nothing: a half-space shape
    /// on a body that would not be static, a joint that would join no dynamic body, and for
    /// Dynamic a mass that is not physical.
    void setBodyType(BodyId id, BodyType type);
    /// (1/s), finite and >= 0 (BodyDef::linearDamping); acts from the next step.
    void setLinearDamping(BodyId id, Real damping);
    /// (1/s), finite and >= 0 (BodyDef::angularDamping); acts from the next step.
    void setAngularDamping(BodyId id, Real damping);
    /// Opaque to the engine, handed back by userData (BodyDef::userData).
    void setUserData(BodyId id, std::uint64_t userData);

    // --- sleeping (see WorldDef::enableSleep) -------------------------------------------------
    /// Is the body simulated? Kinematic bodies are always awake, static bodies never.
    bool isAwake(BodyId id) const;
    /// Wakes the body's island (true), or puts it to sleep now (false): the body and every
    /// dynamic body joined to it by touching contacts stop, whatever their timers and allowSleep
    /// say, and wake again by the usual rules. Waking a static body does nothing; a kinematic
    /// body cannot sleep (refused).
    void setAwake(BodyId id, bool awake);
    /// Awake dynamic and kinematic bodies: those a step integrates.
    int awakeBodyCount() const;

    // --- shapes and contacts -----------------------------------------------------------------
    /// Attaches a shape to a body. Refuses a bad geometry (see checkShape), a bad material
    /// (friction, spinningFriction or rollingFriction negative or not finite, restitution outside
    /// [0, 1], density <= 0), a non-finite or non-unit local
    /// pose, and a half-space on a non-static body. See ShapeDef::updateBodyMass.
    ShapeId createShape(BodyId body, const ShapeDef& def);
    /// Detaches and destroys a shape; a dynamic body whose mass came from its shapes keeps the
    /// mass it had.
    void destroyShape(ShapeId id);
    bool isValid(ShapeId id) const;
    BodyId shapeBody(ShapeId id) const;
    const ShapeDef& shapeDef(ShapeId id) const;
    /// Replaces the shape's material (ShapeDef::material), refused (InvalidArgument, naming the
    /// field) as createShape refuses it. Friction, restitution and the friction lengths act from
    /// the next step. A new density changes the body's mass only when that mass comes from its
    /// shapes (a dynamic body given its mass by shapes with ShapeDef::updateBodyMass): it
    /// becomes the compound of all its shapes. Wakes the body.
    void setShapeMaterial(ShapeId id, const Material& material);
    /// Replaces the shape's collision filter (ShapeDef::filter; every value is valid): its
    /// contacts end now, and the next step finds those the new filter allows. Wakes the body
    /// and what it touched.
    void setShapeFilter(ShapeId id, const CollisionFilter& filter);
    /// The shape's world pose.
    Transform shapeTransform(ShapeId id) const;
    /// Tight bounding box at the shape's current pose (m).
    Aabb shapeBounds(ShapeId id) const;
    /// The contacts found by the last step, in a deterministic order; valid until the next step
    /// or the next change to bodies or shapes. Contacts of sleeping islands are listed as they
    /// were when the island fell asleep.
    std::span<const Contact> contacts() const;

    // --- queries (through the broadphase; see query.h) ----------------------------------------
    // The broadphase is brought up to date by step(), so queries see its boxes as of the last
    // step: a shape created since then is not found until the next step, and one moved through
    // the API may be missed at its new place until then.
    /// The first shape hit by the segment origin + t translation, t in [0, 1].
    std::optional<RayCastHit> castRayClosest(const Vec3& origin, const Vec3& translation,
                                             const QueryFilter& filter = {}) const;
    /// Every shape the segment hits, nearest first.
    std::vector<RayCastHit> castRayAll(const Vec3& origin, const Vec3& translation,
                                       const QueryFilter& filter = {}) const;
    /// The shapes whose bounding boxes overlap `box`, in id order.
    std::vector<ShapeId> overlapAabb(const Aabb& box, const QueryFilter& filter = {}) const;
    /// The shapes that touch or penetrate `shape` placed at `pose`, in id order.
    std::vector<ShapeId> overlapShape(const Shape& shape, const Transform& pose,
                                      const QueryFilter& filter = {}) const;
    /// The point of a shape closest to `point` (the point itself when inside) (m).
    Vec3 closestPoint(ShapeId id, const Vec3& point) const;

    // --- forces (dynamic bodies; ignored on static and kinematic ones) -----------------------
    /// A force (N) at a point in world coordinates (m), for the next step.
    void applyForce(BodyId id, const Vec3& force, const Vec3& worldPoint);
    void applyForceToCenter(BodyId id, const Vec3& force);
    /// A torque (N m), world frame, for the next step.
    void applyTorque(BodyId id, const Vec3& torque);
    /// An impulse (N s) at a point in world coordinates, changing the velocity at once.
    void applyLinearImpulse(BodyId id, const Vec3& impulse, const Vec3& worldPoint);
    /// An angular impulse (N m s), world frame, changing the angular velocity at once.
    void applyAngularImpulse(BodyId id, const Vec3& impulse);

    // --- springs and drag (spring.h) ----------------------------------------------------------
    /// Creates a spring-damper. Refuses (InvalidArgument) a missing, stale or null bodyA, a
    /// stale bodyB, both ends on one body, rest length <= 0, stiffness or damping < 0, and
    /// non-finite values. Wakes the bodies it joins.
    SpringId createSpring(const SpringDef& def);
    /// Destroys a spring; its id becomes invalid. Destroying a body destroys its springs.
    void destroySpring(SpringId id);
    bool isValid(SpringId id) const;
    int springCount() const;
    /// Room for this many springs without reallocating (for generators of large nets).
    void reserveSprings(int count);
    const SpringDef& springDef(SpringId id) const;
    /// Current length, and the tension and slackness of the last step.
    SpringState springState(SpringId id) const;
    /// Elastic energy of all springs at the current poses (J).
    Real springPotentialEnergy() const;
    /// Sets a body's drag (all-zero coefficients remove it). Refuses negative or non-finite
    /// coefficients and a non-finite projection; ignored by static and kinematic bodies.
    void setDrag(BodyId id, const Drag& drag);
    Drag drag(BodyId id) const;

    // --- joints (joint.h) ----------------------------------------------------------------------
    /// Creates a joint at the bodies' current poses. Refuses (InvalidArgument) a missing, stale
    /// or null bodyA, a stale bodyB, both ends on one body, no dynamic body, non-finite anchors
    /// or axis, a zero hinge or slider axis, a zero distance, limits with lower > upper (or a
    /// hinge's outside [-pi, pi]), a negative or non-finite motor force, and break thresholds
    /// that are not > 0. Wakes the bodies it joins; unless collideConnected, their shapes stop
    /// colliding with each other.
    JointId createJoint(const JointDef& def);
    /// Destroys a joint; its id becomes invalid. Destroying a body destroys its joints.
    void destroyJoint(JointId id);
    bool isValid(JointId id) const;
    int jointCount() const;
    const JointDef& jointDef(JointId id) const;
    /// Reaction of the last step, position and speed at the current state, broken or not.
    JointState jointState(JointId id) const;
    /// Sets a hinge's or slider's motor (JointDef::enableMotor, motorSpeed, maxMotorForce) and
    /// wakes its bodies. Refuses a non-finite speed, a negative or non-finite force, and
    /// enabling a motor on a joint type that has none.
    void setJointMotor(JointId id, bool enable, Real speed, Real maxForce);

    // --- control (control.h) ------------------------------------------------------------------
    /// Drives a hinge or slider joint with a PD/PID controller (replacing any it had; the
    /// integral starts at 0) and wakes its bodies. Refuses (InvalidArgument) another joint type,
    /// a negative or non-finite gain (kp, ki, kd), a non-finite target or targetVelocity, and a
    /// maxForce that is not > 0.
    void setJointController(JointId id, const ControllerDef& def);
    /// Changes a controller's set-point (and the set-point's rate, or the velocity mode's
    /// target) keeping its integral; wakes the joint's bodies. Refuses non-finite values and a
    /// joint without a controller. For scripted control from the pre-step callback.
    void setJointControllerTarget(JointId id, Real target, Real targetVelocity = 0);
    /// Removes a joint's controller (nothing if it has none). Destroying the joint removes it.
    void clearJointController(JointId id);
    /// The controller's definition as last set, or nullopt.
    std::optional<ControllerDef> jointController(JointId id) const;
    /// Error, integral and output of the last step (zeros before the first). Refuses a joint
    /// without a controller.
    ControllerState jointControllerState(JointId id) const;
    /// Called at the start of every step(), before anything moves, with the world and the
    /// simulated time at the start of that step (s): the place for an application to change
    /// targets, apply forces or edit the scene each step. An empty function removes it. The
    /// callback must not call step() or advance(), nor replace the callback (refused); what it
    /// throws leaves step() before any stage ran.
    void setPreStepCallback(std::function<void(World&, Real time)> callback);

    // --- events (events.h) ---------------------------------------------------------------------
    /// What happened since the previous step() returned; valid until the next step() returns.
    std::span<const ContactEvent> contactBeginEvents() const;
    std::span<const ContactEvent> contactEndEvents() const;
    /// See ImpactEvent and WorldDef::impactSpeedThreshold.
    std::span<const ImpactEvent> impactEvents() const;
    std::span<const JointBreakEvent> jointBreakEvents() const;
    std::span<const SleepEvent> sleepEvents() const;

    // --- stepping ----------------------------------------------------------------------------
    /// One fixed step of length settings().timeStep. Never throws (but see setPreStepCallback).
    StepStatus step();
    /// Real-time driver: adds frameTime to an accumulator and runs whole steps while it holds at
    /// least one step, at most settings().maxStepsPerAdvance of them (the excess time is dropped,
    /// so a slow frame cannot trigger a spiral of death). frameTime (s) must be finite and >= 0.
    AdvanceResult advance(Real frameTime);

    const WorldDef& settings() const;
    void setGravity(const Vec3& gravity);
    void setTimeStep(Real timeStep);
    void setMaxStepsPerAdvance(int steps);

    Real time() const;                ///< simulated time (s)
    std::uint64_t stepCount() const;  ///< steps taken so far
    const Profile& profile() const;   ///< stage timings of the last step
    /// Iterations used, largest complementarity residual and deepest penetration of the last step
    /// (of its last substep).
    const SolverStats& solverStats() const;
    /// Legal input the engine is known to handle poorly, found so far (tumble/warnings.h): raised
    /// when a shape, spring or joint is made and when a contact begins, once per cause, kept
    /// until cleared. At most 64 are kept; droppedWarnings() counts the rest.
    std::span<const Warning> warnings() const;
    std::size_t droppedWarnings() const;
    void clearWarnings();
    /// Refuses settings outside their documented ranges (checkSolverSettings).
    void setSolverSettings(const SolverSettings& settings);

private:
    struct Impl;
    friend struct CheckpointAccess;  ///< checkpoint.cpp saves and restores the private state
    template <typename OnHit>
    static void castRay(const Impl& w, const Vec3& origin, const Vec3& translation,
                        const QueryFilter& filter, OnHit&& onHit);
    std::unique_ptr<Impl> impl_;
};

}  // namespace tumble
