#pragma once
/// The collision stages of a step: broadphase (bounds and pairs) and narrowphase (manifolds),
/// with the contact cache that carries impulses from one step to the next.
///
/// Storage. Every broadphase pair that may collide (shapes of two bodies, at least one dynamic)
/// owns a contact record in a pool of stable slots, threaded on both bodies' contact lists
/// (intrusive and doubly linked: an island is walked, and a body's contacts removed, in time
/// proportional to its contacts). A contact is *active* while at least one of its bodies is awake
/// (a dynamic body not asleep, or a kinematic body); only active contacts are collided and
/// solved. The contacts of a sleeping island are *parked*: kept with their manifolds and cached
/// impulses, visited by nothing per step, and activated again when the island wakes.
///
/// Several manifolds. A pair whose narrowphase gives several manifolds (a shape touching a mesh
/// along faces of different normals; ManifoldSet) holds the first in its own record and the others
/// in further records chained from it (Record::nextPart), each a contact of its own to the solver,
/// the islands and the application. They are made when first needed, live as long as the pair
/// and are collided only through it.
///
/// Determinism: the active list is kept sorted by pair (proxy ids), so the narrowphase and the
/// solver see contacts in an order that depends only on the scene's history; body contact lists
/// and pool slots are likewise history-ordered, never by address or hash.

#include <array>
#include <span>
#include <tuple>
#include <vector>

#include "body_store.h"
#include "event_log.h"
#include "shape_store.h"
#include "step_context.h"
#include "tumble/collision/grid_broadphase.h"
#include "tumble/contact.h"
#include "warning_log.h"

namespace tumble {

class ContactManager {
    friend struct CheckpointAccess;  ///< checkpoint.cpp saves and restores the private state
public:
    /// Registers a shape with the broadphase at its body's current pose.
    void addShape(ShapeStore& shapes, std::uint32_t slot, const BodyStore& bodies, Real h);
    /// Takes a shape out of the broadphase and destroys its contacts at once (the body must
    /// still be alive).
    void removeShape(ShapeStore& shapes, std::uint32_t slot, BodyStore& bodies);
    /// refreshBounds' answer when every body's boxes are finite.
    static constexpr std::uint32_t kNoBody = 0xFFFFFFFF;

    /// Re-reads one shape's bounds after a teleport (setTransform) or a new pose.
    void refreshShape(ShapeStore& shapes, std::uint32_t slot, const BodyStore& bodies, Real h);
    /// The box the broadphase holds for a shape whose tight box is `tight` on a body moving at
    /// `velocity`: swept over the next step of `h` and fattened by aabbMargin (m). Not finite
    /// when a huge but finite state overflows it; the broadphase refuses such a box.
    Aabb proxyBounds(const Aabb& tight, const Vec3& velocity, Real h) const;
    /// Whether every shape of body `index` gets a finite proxy box at the body's current state.
    bool boundsFinite(const ShapeStore& shapes, const BodyStore& bodies, std::uint32_t index,
                      Real h) const;

    /// After the bodies moved: refresh the tight bounds of the awake bodies' shapes and move the
    /// proxies whose box, swept over the next step, left their fat box. Bounds are therefore
    /// always those of the current poses (sleeping and static bodies do not move), and queries
    /// between steps see them. Returns the index of the first awake body whose proxy box would
    /// not be finite, and then moves no proxy (the caller restores the state and calls again);
    /// kNoBody when all are finite.
    std::uint32_t refreshBounds(ShapeStore& shapes, const BodyStore& bodies,
                                const StepContext& context);
    /// Broadphase stage: update the pair set from the fat boxes.
    void updatePairs() { broadphase_.update(); }
    /// Narrowphase stage: creates and destroys contacts as broadphase pairs appear and vanish,
    /// then computes a manifold for every active contact, with impulses of persisting points
    /// carried over (matched by feature id, else by proximity). A sleeping body that an awake
    /// dynamic body or a moving kinematic body touches is listed in wakeRequests().
    void updateContacts(const ShapeStore& shapes, BodyStore& bodies, const StepContext& context);

    // --- active and parked contacts (for the islands and solve stages) -----------------------
    /// Slots of the active contacts in pair order. Contacts parked since the last narrowphase
    /// stay listed (isActive false) until the next one.
    std::span<const std::uint32_t> activeSlots() const { return active_; }
    /// The active contacts with points, in pair order: what the solve, the sleep stage's islands
    /// and the impacts walk (a settled pile's active list is four-fifths neighbours that do not
    /// touch). Built by the narrowphase and kept by flushActivations; like activeSlots(), a slot
    /// parked or destroyed since stays listed until the next narrowphase (check isActive).
    std::span<const std::uint32_t> touchingSlots() const { return touching_; }
    bool isActive(std::uint32_t slot) const { return state_[slot].active; }
    /// False once the contact is destroyed (its slot may be reused after the next narrowphase).
    bool isAlive(std::uint32_t slot) const { return state_[slot].alive; }
    /// One past the largest slot in use: per-contact side arrays are sized by it.
    std::uint32_t slotCount() const { return static_cast<std::uint32_t>(pool_.size()); }
    Contact& contact(std::uint32_t slot) { return pool_[slot].contact; }
    const Contact& contact(std::uint32_t slot) const { return pool_[slot].contact; }
    /// Marks a parked contact active; it is listed at flushActivations() or the next
    /// narrowphase, whichever comes first.
    void activate(std::uint32_t slot);
    /// Parks a contact (both its bodies are asleep or static).
    void deactivate(std::uint32_t slot) { state_[slot].active = false; }
    /// Lists the contacts activated since the last narrowphase, so this step solves them.
    void flushActivations();
    /// Calls visit(slot, contact, otherBodyIndex) for each contact of body `index`. visit may
    /// activate or deactivate contacts, but not create or destroy them.
    template <typename Visit>
    void forEachContact(const BodyStore& bodies, std::uint32_t index, Visit&& visit) const;

    /// A static or kinematic body's shape was teleported: the sleeping bodies it pairs with at
    /// the next broadphase update are woken (see wakeRequests()).
    void markPlaced(std::uint32_t proxy);
    /// Dense indices of sleeping bodies the last narrowphase found touched (or that a placed
    /// shape reached); valid until the bodies change.
    std::span<const std::uint32_t> wakeRequests() const { return wakeRequests_; }
    void clearWakeRequests() { wakeRequests_.clear(); }

    /// Every contact, active or parked, in pair order. Built when asked (it is not needed by the
    /// step), so sleeping contacts cost nothing unless the application reads them.
    std::span<const Contact> contacts() const;
    const GridBroadphase& broadphase() const { return broadphase_; }
    /// Keeps two shapes' proxies from pairing (jointed bodies), or lets them pair again; their
    /// contact goes or comes at the next broadphase update.
    void setPairExcluded(std::uint32_t proxyA, std::uint32_t proxyB, bool excluded) {
        broadphase_.setPairExcluded(proxyA, proxyB, excluded);
    }
    std::uint32_t shapeOfProxy(std::uint32_t proxy) const { return proxyToShape_[proxy]; }

    Real contactMargin = 0.02;  ///< speculative distance added to h |v_rel| (m)
    /// Where contact begin and end events go (the world's pending log); none when null. A
    /// contact begins when its manifold gets its first points and ends when it loses its last
    /// ones or is destroyed with points (its pair separated, a shape or body was destroyed).
    EventLog* events = nullptr;
    /// Where a contact that begins between dynamic bodies of very different masses is reported;
    /// none when null.
    WarningLog* warnings = nullptr;
    Real aabbMargin = 0.1;  ///< fat box growth (m)

private:
    static constexpr std::uint32_t kNone = 0xFFFFFFFF;

    /// A contact's cold part: read when its shapes are near (the manifold, the cached
    /// impulses) or its bodies' lists change.
    struct Record {
        Contact contact;
        /// Edges (slot * 2 + side; side 0 = body A, 1 = body B) of the neighbours on body A's
        /// [0] and body B's [1] contact lists.
        std::array<std::uint32_t, 2> next{kNone, kNone};
        std::array<std::uint32_t, 2> previous{kNone, kNone};
        /// The pair's next manifold's record (see the file comment), or kNone.
        std::uint32_t nextPart = kNone;
    };
    /// A contact's hot part, in a compact array beside pool_: what the per-step walks over all
    /// active contacts read. In a settled pile most contacts are neighbours of neighbours whose
    /// boxes stay apart; the narrowphase decides them from this and the shapes' boxes alone,
    /// without touching their 400-byte records.
    struct SlotState {
        /// The pair, which orders active_: merging activations into it compares the keys of
        /// every listed contact (at 4,000 bodies a read from each of 52k records per step).
        ProxyPair key;
        std::uint32_t shapeA = 0;  ///< shape slots (contact.shapeA.index, contact.shapeB.index)
        std::uint32_t shapeB = 0;
        bool alive = false;
        bool active = false;
        bool listed = false;  ///< in active_ (dropped at the next narrowphase if not active)
        bool queued = false;  ///< in activated_, waiting to be listed
        /// The record (and the pair's further ones) holds an empty Manifold{} and zero
        /// impulses, exactly what collideActive writes for shapes whose boxes are apart: it may
        /// skip the record. Not saved in
        /// checkpoints (false after a load costs one full pass, never a different result).
        bool cleared = false;
        /// Which of its pair's manifolds the record holds: 0 for the pair's own record, which
        /// is collided, k > 0 for the further ones (see the file comment).
        std::uint8_t part = 0;
    };
    /// The order of active_ and touching_: by pair, a pair's records by part.
    bool precedes(std::uint32_t a, std::uint32_t b) const {
        return std::tie(state_[a].key, state_[a].part) < std::tie(state_[b].key, state_[b].part);
    }

    /// A free slot (reused or new) for a contact record.
    std::uint32_t allocateSlot();
    /// Creates the contact of a new broadphase pair, if its shapes may collide.
    void create(const ProxyPair& pair, const ShapeStore& shapes, BodyStore& bodies);
    /// Moves a shape's proxy when its tight box, swept over the next step of h, left its fat box.
    void moveProxy(ShapeRecord& shape, const BodyStore& bodies, Real h);
    /// Unlinks a contact from its bodies; its slot is reused once no list holds it.
    void destroy(std::uint32_t slot, BodyStore& bodies);
    /// The live contact of a pair, or kNone.
    std::uint32_t find(const ProxyPair& pair, const ShapeStore& shapes,
                       const BodyStore& bodies) const;
    void link(std::uint32_t slot, int side, BodyInfo& body);
    void unlink(std::uint32_t slot, int side, BodyInfo& body);
    /// Drops inactive contacts from active_ and frees the slots of destroyed ones.
    void compactActive();
    /// An active pair whose record the narrowphase rewrites this step.
    struct PairWork {
        std::uint32_t slot;
        std::uint32_t indexA;  ///< dense body indices
        std::uint32_t indexB;
        Real margin;  ///< speculative distance (m)
        bool near;    ///< the boxes are within the margin: collide (else the manifold is empty)
    };
    void collideActive(const ShapeStore& shapes, BodyStore& bodies, const StepContext& context);
    /// Collides a pair, rewrites its records and lists those with points in touching_.
    void collidePair(const PairWork& work, const ShapeStore& shapes, BodyStore& bodies);
    /// collidePair's rewrite for a pair with several manifolds, or records for them.
    void spreadParts(const PairWork& work, BodyStore& bodies);
    /// Adds a record for the pair's manifold `part` after the pair's record `last`.
    std::uint32_t addPart(std::uint32_t last, std::uint8_t part, BodyStore& bodies);
    /// Whether any of the records of the pair at `slot` has points.
    bool pairTouches(std::uint32_t slot) const;
    /// A shape's world pose in this narrowphase, computed at its first near pair and kept: in a
    /// pile a body has about six near pairs, each of which composed both poses from the bodies'
    /// states (3 % of pile-4000's instructions). The same function of the same state, so the
    /// same bits.
    const Transform& posedShape(std::uint32_t slot, const ShapeStore& shapes,
                                const BodyStore& bodies);
    /// A contact began (got its first points) or ended (lost its last): events and warnings.
    void reportTouch(const Contact& contact, bool began, const BodyStore& bodies,
                     std::uint32_t indexA, std::uint32_t indexB);
    /// Lists the sleeping body of a touching pair to be woken, if the other may wake it and
    /// its manifolds may push it this step (pushes).
    void wakeTouched(const BodyStore& bodies, std::uint32_t indexA, std::uint32_t indexB,
                     std::span<const Manifold> manifolds);
    bool pushes(const BodyStore& bodies, std::uint32_t indexA, std::uint32_t indexB,
                std::span<const Manifold> manifolds) const;

    /// A sweep-and-prune per grid cell. One sweep-and-prune over a whole pile keeps its
    /// endpoints sorted on the vertical axis too, where a pile five layers deep packs all its
    /// bodies: a moving box bubbles past O(n) endpoints there (1,160 per move at 10k bodies,
    /// 512 at 4k), and the broadphase grew as n^2.8. Cells bound that walk by their contents;
    /// the pair sets are the same.
    GridBroadphase broadphase_;
    std::vector<std::uint32_t> proxyToShape_;
    std::vector<Record> pool_;
    std::vector<SlotState> state_;          ///< beside pool_, one per slot
    std::vector<std::uint32_t> freeSlots_;  ///< reused last-in first-out
    std::vector<std::uint32_t> dead_;       ///< destroyed, not yet free
    std::vector<std::uint32_t> active_;     ///< sorted by key
    std::vector<std::uint32_t> activated_;  ///< to merge into active_
    std::vector<std::uint32_t> touching_;   ///< sorted by key; see touchingSlots()
    std::vector<std::uint32_t> scratch_;
    std::vector<std::uint32_t> touchingScratch_;
    std::vector<PairWork> work_;  ///< collideActive's second pass
    ManifoldSet manifolds_;       ///< collidePair's (kept: 700 bytes, not cleared per pair)
    Real stepLength_ = 0;         ///< this narrowphase's h (s), for pushes
    std::vector<std::uint32_t> addedParts_;  ///< records addPart made, to list in active_
    struct CachedPose {
        Transform pose;
        std::uint64_t narrowphase = 0;  ///< the narrowphase it was computed in (0: none)
    };
    std::vector<CachedPose> poses_;  ///< by shape slot; see posedShape
    std::uint64_t narrowphaseCount_ = 0;
    std::vector<std::uint32_t> wakeRequests_;
    std::vector<std::uint32_t> placedProxies_;  ///< sorted; see markPlaced
    mutable std::vector<Contact> view_;
    mutable std::vector<std::uint32_t> viewOrder_;
    mutable bool viewStale_ = true;
};

template <typename Visit>
void ContactManager::forEachContact(const BodyStore& bodies, std::uint32_t index,
                                    Visit&& visit) const {
    std::uint32_t edge = bodies.info[index].firstContact;
    while (edge != kNone) {
        const std::uint32_t slot = edge >> 1;
        const int side = static_cast<int>(edge & 1);
        const Record& record = pool_[slot];
        edge = record.next[side];
        const BodyId other = side == 0 ? record.contact.bodyB : record.contact.bodyA;
        visit(slot, record.contact, bodies.indexOf(other));
    }
}

/// The world pose of a shape on a body (body origin pose composed with the shape's local pose).
Transform shapePose(const ShapeRecord& shape, const BodyStore& bodies);

}  // namespace tumble
