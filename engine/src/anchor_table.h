#pragma once
/// Friction anchors (SolverSettings::frictionAnchors): velocity-level friction holds a sticking
/// point's velocity, not its place, so a box on a turning platform crept outward. Each
/// manifold's points get anchors on both bodies, seated together where the points are, and the
/// solver's anchor pass (friction_anchors.h) pulls them back together. The anchors live in a
/// side table by contact slot, which a world without anchors never fills: contact records and
/// the narrowphase are the same with the setting off.

#include <cstdint>
#include <vector>

#include "body_store.h"
#include "tumble/contact.h"
#include "tumble/solver/contact_solver.h"
#include "tumble/solver/friction_anchors.h"

namespace tumble {

class AnchorTable {
    friend struct CheckpointAccess;  ///< checkpoint.cpp saves and restores the anchors

public:
    /// Starts a solve: anchors that the last solve did not use are stale (their contact was
    /// parked, emptied or destroyed, and its slot may hold another pair now).
    void beginSolve() { ++solve_; }
    /// The drift each point of `c` (contact `slot`, its manifold `contact.manifold`) is expected
    /// to have at the end of the step: B's anchor - A's on the tangent plane, plus the bend of
    /// the points' paths over the step (m, world), into drifts[0 .. c.pointCount). Seats the
    /// manifold's anchors afresh (drift: the bend only) when a point has none, when a point
    /// rolled away from its anchors, or moved `lengths.reach` from them, and with `reseatStale`
    /// (the default step's pass, whose drift this is) when the pass did not halve last step's
    /// drift (a stale seat: anchor_table.cpp). Inline, as SolveStage::anchorDrift: their calls
    /// were 7 % of the drifts' instructions on pyramid-20.
    void drifts(std::uint32_t slot, const Contact& contact, const BodyMotion& a,
                const BodyMotion& b, Real h, const ContactConstraint& c,
                const AnchorLengths& lengths, bool reseatStale, Vec3* drifts) {
        if (entries_.size() <= slot)
            entries_.resize(slot + 1);
        driftsOf(entries_[slot], solve_, contact, a, b, h, c, lengths, reseatStale, drifts);
    }
    /// After the solve: a manifold whose friction reached its Coulomb limit slips as a whole
    /// (`slips`: slips() of its constraint), and its anchors are seated afresh next step.
    void release(std::uint32_t slot, bool slips);
    /// Whether the manifold's friction impulses reach the share of mu sum(lambda_n) at which it
    /// slips as a whole.
    static bool slips(const ContactConstraint& c);

private:
    struct Entry {
        std::array<Vec3, 4> onA{};               ///< from A's centre of mass, A's frame (m)
        std::array<Vec3, 4> onB{};               ///< from B's centre of mass, B's frame (m)
        std::array<std::uint32_t, 4> feature{};  ///< the manifold point each anchor belongs to
        int count = 0;                           ///< anchors seated; 0: none
        std::uint64_t solve = 0;                 ///< the solve that last used them
        /// The largest point drift handed to the pass in that solve (m); 0 without reseatStale
        Real drift = 0;
        /// Seated afresh as stale, and not yet back within the deadband since (anchor_table.cpp)
        bool reseated = false;
    };
    /// drifts() on the slot's entry, `solve` the current solve (anchor_table.cpp)
    static void driftsOf(Entry& entry, std::uint64_t solve, const Contact& contact,
                         const BodyMotion& a, const BodyMotion& b, Real h,
                         const ContactConstraint& c, const AnchorLengths& lengths, bool reseatStale,
                         Vec3* drifts);
    std::vector<Entry> entries_;  ///< by contact slot
    std::uint64_t solve_ = 0;
};

}  // namespace tumble
