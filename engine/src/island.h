#pragma once
/// Islands and sleeping.
///
/// An island is a set of dynamic bodies joined by touching contacts (manifold.pointCount > 0),
/// springs and unbroken joints. Static and kinematic bodies join no island: a pile on the ground is
/// one island per group of touching bodies, not one for everything on the ground.
///
/// Falling asleep (the sleep stage, after the step's motion): each awake dynamic body's timer
/// grows by h while it is still (its centre's speed plus its angular speed times its extent below
/// WorldDef::linearSleepVelocity, and its angular speed below angularSleepVelocity) and resets
/// otherwise, or when it may not sleep, or when it touches
/// a moving kinematic body. Only when some timer has reached timeToSleep is a union-find run over
/// the awake bodies and touching active contacts; an island sleeps when its smallest timer has,
/// and -- when no touching contact holds any of its bodies -- in a step in which every body is in
/// balance: no point's velocity changed by more than 5e-5 g h, nor -- if a spring, joint, drag or
/// damping may act on it -- moves faster than that (a weight on a spring is slow near the ends
/// of a small bounce, or while a damper holds it, but not in balance there). A controller not
/// at its target keeps its joint's bodies awake, and so does a running joint motor.
/// Sleeping bodies lose their velocities, leave BodyStore::awake, and their contacts with
/// nothing awake on the other side are parked (ContactManager), so no per-step loop visits them.
///
/// Waking: the island of a sleeping body is not stored; it is found again by walking parked
/// touching contacts from the body, which is what joined it when it fell asleep. A whole island
/// wakes at once, with all its contacts active again. The bodies a spring or joint links to an
/// awake body are woken by the step (wakeSpringLinked, wakeJointLinked), not here.
///
/// Determinism: union-find roots are the smallest awake-list position of each set, islands fall
/// asleep in awake-list order and walks follow the body contact lists, all of which depend only
/// on the scene's history.

#include <cstdint>
#include <span>
#include <vector>

#include "body_store.h"
#include "contact_manager.h"
#include "event_log.h"
#include "joint_store.h"
#include "spring_store.h"
#include "step_context.h"
#include "tumble/world.h"

namespace tumble {

class Islands {
public:
    /// Wakes the island of a sleeping dynamic body, and resets the body's sleep timer whether it
    /// slept or not (a pushed body starts being still again). `midStep` is given when the stage
    /// that integrates forces has already run: the woken bodies catch up on it.
    void wake(BodyStore& bodies, ContactManager& contacts, std::uint32_t index,
              const StepContext* midStep = nullptr);
    /// The body was changed through the API: wake(index), and its next step does not count as
    /// still.
    void push(BodyStore& bodies, ContactManager& contacts, std::uint32_t index);
    /// push(index), then wake every sleeping body the body has a contact with: only those it
    /// touches, or all of them (for a static or kinematic body that was moved: a non-touching
    /// parked pair may touch now, and nothing would collide it).
    void wakeAround(BodyStore& bodies, ContactManager& contacts, std::uint32_t index,
                    bool touchingOnly);
    /// Puts the island of an awake dynamic body to sleep now, whatever its timers say.
    void sleepIslandOf(BodyStore& bodies, ContactManager& contacts, std::uint32_t index);

    /// Islands stage: wakes the islands the narrowphase found touched by awake bodies, so this
    /// step solves them (their bodies catch up on this step's forces).
    void wakeTouched(BodyStore& bodies, ContactManager& contacts, const StepContext& context);
    /// Sleep stage: timers, and the islands still for timeToSleep fall asleep. Springs join
    /// their two bodies' islands as touching contacts do, and so do unbroken joints.
    void updateSleep(BodyStore& bodies, ContactManager& contacts, const SpringStore& springs,
                     const DragStore& drag, const JointStore& joints, const StepContext& context,
                     const WorldDef& settings);

    /// Room for `bodyCount` bodies in every buffer below (each holds at most one entry per
    /// body), so that no step allocates in them until bodies are added.
    void reserve(std::size_t bodyCount);

    /// Where sleep and wake events go (the world's pending log); none when null.
    EventLog* events = nullptr;

private:
    /// markAwake / markNotAwake, with the event.
    void markAwake(BodyStore& bodies, std::uint32_t index);
    void markAsleep(BodyStore& bodies, std::uint32_t index);
    void putToSleep(BodyStore& bodies, ContactManager& contacts,
                    std::span<const std::uint32_t> indices);
    /// Union-find over awake-list positions: the set's root, halving the path on the way.
    std::uint32_t find(std::uint32_t position);
    void unite(std::uint32_t a, std::uint32_t b);

    std::vector<std::uint32_t> parent_;
    std::vector<Real> islandSleepTime_;  ///< smallest timer of each set, at its root
    /// Per awake-list position: has a touching contact; may something damp it (balance test)?
    enum Flag : std::uint8_t { kTouches = 1, kDamped = 2 };
    std::vector<std::uint8_t> flags_;
    /// Per set, at its root: does a contact hold it, else is it in balance this step?
    enum Balance : std::uint8_t { kInBalance, kOutOfBalance, kHeld };
    std::vector<std::uint8_t> islandBalance_;
    std::vector<std::uint32_t> stack_;
    std::vector<std::uint8_t> visited_;
    std::vector<std::uint32_t> sleepers_;
};

}  // namespace tumble
