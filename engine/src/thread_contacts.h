#pragma once
/// Contacts of threads -- springs with SpringDef::contactRadius > 0 -- with the shapes of static
/// and kinematic bodies: the segment between a thread's two anchors as a capsule of that
/// radius, so a net caught on a rim between its nodes hangs on it instead of slipping through.
///
/// A node is a body and touches shapes through the ordinary contacts; a thread joins two bodies
/// and is no body, so its contacts are rows of their own (solver/segment_contact_row.h) that
/// split each impulse between the thread's nodes by the contact point's parameter t. Found
/// each step from the springs: the segment's box (grown by the radius and the speculative
/// margin) is tested against the static and kinematic shapes (box by box when they are few, else
/// through the broadphase) and the capsule collided with every one it meets, through the
/// ordinary narrowphase. Where a node has shapes of its own, the capsule starts a radius away
/// from it: what lies nearer is the node's own contacts', as is a capsule point whose surface
/// point on the shape lies inside the node's sphere (the end cap reaches past the trim).
///
/// Rows are warm started as the contacts are: each takes the impulses the previous step's
/// nearest row of the same spring and shape ended with (its point within a contact radius along
/// the thread, its normal within ~25 degrees; each old row lends once). Cold rows were why a
/// net draped over a box's edge never came to rest: ten sweeps from zero against the exactly
/// solved threads left the rows short every step, the relax sweeps kept changing the velocities
/// (pseudo-velocities of 2 cm/s on resting nodes) and the net flapped at a median 5 mm/s. The
/// cache is checkpoint state. The contacts are not reported, woken on or united into islands
/// (static and kinematic bodies join none).
///
/// Deterministic: springs in dense order, each one's shapes in slot order. A warm step
/// allocates nothing (the arrays only grow).

#include <cstdint>
#include <span>
#include <vector>

#include "body_store.h"
#include "contact_manager.h"
#include "shape_store.h"
#include "spring_store.h"
#include "step_context.h"
#include "tumble/collision/manifold.h"
#include "tumble/solver/segment_contact_row.h"

namespace tumble {

class ThreadContacts {
public:
    /// This step's rows of every contact thread with an awake dynamic body at either end, on
    /// the solve stage's solver bodies (solve_stage.h, solverBodyIndex).
    std::span<SegmentContactRow> build(const SpringStore& springs, const BodyStore& bodies,
                                       const ShapeStore& shapes, const ContactManager& contacts,
                                       const StepContext& context);
    /// Keeps the solved rows' impulses for the next step's warm start.
    void store();

    /// A solved row as the next step finds it: its spring and shape, where, and its impulses.
    struct Cached {
        std::uint32_t spring = 0;  ///< dense index
        std::uint32_t slot = 0;    ///< shape slot
        Real t = 0;
        Vec3 normal = Vec3::UnitZ();
        Real normalImpulse = 0;              ///< (N s)
        Vec3 tangentImpulse = Vec3::Zero();  ///< world (N s)
    };

    /// An active contact of a node with points, as the rows' depth rule reads it.
    struct NodeContact {
        std::uint32_t body = 0;    ///< the other body (dense index)
        Vec3 out = Vec3::UnitZ();  ///< its normal, from the other body to the node
    };

private:
    friend struct CheckpointAccess;  ///< checkpoint.cpp saves and restores the cache
    /// The static and kinematic shapes' slots into fixedShapes_, in slot order, up to one past
    /// the number candidates() tests one by one.
    void listFixedShapes(const BodyStore& bodies, const ShapeStore& shapes);
    /// Static and kinematic shapes whose tight box meets `box`, in slot order, into shapes_;
    /// half-spaces only when `planes`.
    void candidates(const Aabb& box, bool planes, const BodyStore& bodies, const ShapeStore& shapes,
                    const ContactManager& contacts);
    /// The rows of spring `index` (with an awake dynamic end) against the shapes it meets,
    /// appended to rows_.
    void collideThread(std::uint32_t index, const SpringStore& springs, const BodyStore& bodies,
                       const ShapeStore& shapes, const ContactManager& contacts, Real h);

    /// Lends `row` the impulses of the nearest cached row of its spring and shape.
    void warmStart(SegmentContactRow& row, std::uint32_t spring, std::uint32_t slot, Real length,
                   Real radius);

    std::vector<SegmentContactRow> rows_;
    std::vector<Cached> keys_;        ///< rows_' springs and shapes (the rest filled by store())
    std::vector<Cached> cache_;       ///< the previous step's solved rows, by spring then slot
    std::vector<std::uint8_t> lent_;  ///< scratch: cache_ entries already lent this step
    std::size_t cursor_ = 0;          ///< scratch: first cache_ entry of the spring being built
    /// Node `index`'s active contacts with points; every body's are gathered on the step's first
    /// asking, from the touching list (gatherNodeContacts).
    std::span<const NodeContact> nodeContacts(std::uint32_t index, const BodyStore& bodies,
                                              const ContactManager& contacts);
    void gatherNodeContacts(const BodyStore& bodies, const ContactManager& contacts);

    std::vector<std::uint32_t> shapes_;       ///< scratch: candidate shape slots of one thread
    std::vector<std::uint32_t> fixedShapes_;  ///< scratch: listFixedShapes'
    std::vector<NodeContact> nodeContacts_;   ///< scratch: every body's, by body
    std::vector<std::uint32_t> nodeFirst_;    ///< scratch: body i's are [first[i], first[i + 1])
    std::vector<std::uint32_t> nodeFill_;     ///< scratch: gatherNodeContacts' write positions
    bool gathered_ = false;                   ///< nodeContacts_ holds this step's
    ManifoldSet manifolds_;                   ///< scratch
};

/// The depth rule of a thread's row against body `s` (dense index): sets `row.separation` from
/// the capsule's `separation` (m) and `row.pushOut`, from how the thread's nodes touch s
/// (`contactsA`, `contactsB`: their active contacts; empty for a node without shapes). `axis` is
/// the thread's unit direction from A to B, `radius` its contact radius (m); reads row.t and
/// row.normal. Rows push out their full depth unless both nodes touch s and the thread either
/// rests on them on the row's side (a sag of up to one radius allowed, no push) or, not crossing
/// over an edge between them, lies along s's rim (no push). Where only one node touches s, a row
/// whose surface point on s (`fromA`, `fromB`: from each node) lies within 2 radii of it, over
/// another feature than the node's face, with the thread leaving across that feature into the
/// node's contact plane and its axis out of s, counts no depth (the capsule leaving the node over
/// the edge it rests on); details in thread_contacts.cpp.
void setRowDepth(SegmentContactRow& row, Real separation, Real radius, const Vec3& axis,
                 std::span<const ThreadContacts::NodeContact> contactsA,
                 std::span<const ThreadContacts::NodeContact> contactsB, std::uint32_t s,
                 const Vec3& fromA, const Vec3& fromB);

}  // namespace tumble
