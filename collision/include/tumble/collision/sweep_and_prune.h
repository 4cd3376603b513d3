#pragma once
/// Broadphase: which pairs of proxies have overlapping fat bounding boxes.
///
/// SweepAndPrune keeps the proxies' interval endpoints sorted along all three axes across updates
/// (each moved endpoint is bubbled into place, so a scene that barely moves costs little) and
/// maintains the overlapping pair set incrementally, reporting pairs added and removed by each
/// update. BruteForcePairs is the O(n^2) reference it is tested against.
///
/// Pair maintenance (details in sweep_and_prune.cpp): two boxes overlap iff, on every axis,
/// lower(a) <= upper(b) and lower(b) <= upper(a). With endpoints kept sorted by (value, lower
/// before upper), each of those inequalities is "this lower endpoint precedes that upper endpoint".
/// A pair can only change overlap status if one such order changes, i.e. if a lower and an upper
/// endpoint of the two proxies swap during an update. The update records every such swap as a
/// candidate pair and then decides each candidate against the final boxes, so the cost is
/// proportional to the number of swaps plus the number of changes, not to n^2.
///
/// The sweep axis: one of the three sorted axes, the one with the largest variance of box centres,
/// serves queries and ray casts (walk its endpoints, test the boxes) and the sweep that pairs new
/// proxies. It is re-chosen at update() only when another axis's variance exceeds the current one
/// by kAxisSwitchFactor (hysteresis, so a scene near a tie does not flip every step). All three
/// axes are always sorted, so a switch needs no re-sort, only a re-scan of box extents along the
/// new axis (O(n)).

#include <array>
#include <cstdint>
#include <vector>

#include "tumble/collision/aabb.h"

namespace tumble {

/// Filtering: proxies a and b may pair when (a.category & b.mask) and (b.category & a.mask)
/// are both non-zero, and not both are static.
struct ProxyFilter {
    std::uint32_t category = 1;
    std::uint32_t mask = 0xFFFFFFFF;
    bool isStatic = false;
};

/// A pair of proxy ids with first < second.
struct ProxyPair {
    std::uint32_t first = 0;
    std::uint32_t second = 0;
    friend bool operator==(ProxyPair, ProxyPair) = default;
    friend auto operator<=>(ProxyPair, ProxyPair) = default;
};

/// The fat-box policy the engine follows: a body's broadphase box is its tight box grown by
/// `margin` (m) and is replaced (and SweepAndPrune::move called) only when the tight box leaves
/// it. Returns true and sets `fat` to tight.fattened(margin) when that happens.
inline bool refitFatBox(Aabb& fat, const Aabb& tight, Real margin) {
    if (fat.contains(tight)) {
        return false;
    }
    fat = tight.fattened(margin);
    return true;
}

/// Ray fraction at which the segment origin + t direction, t in [0, maxFraction], enters `box`
/// (0 if the origin is inside); negative if it misses. Touching counts as a hit.
Real rayEntryFraction(const Vec3& origin, const Vec3& direction, Real maxFraction, const Aabb& box);

class SweepAndPrune {
    friend struct CheckpointAccess;  ///< checkpoint.cpp saves and restores the private state
public:
    /// A variance ratio above which the sweep axis is re-chosen (hysteresis), > 1.
    static constexpr Real kAxisSwitchFactor = 1.5;
    /// Proxies longer along the sweep axis than this many times the mean are "large": queries
    /// test them one by one instead of widening the walk of every query by their length.
    static constexpr Real kLargeExtentFactor = 8;

    /// Adds a proxy with its fat box; returns its id (dense, reused after removal: the smallest
    /// free id). The proxy joins the pair set at the next update(). Throws InvalidArgument for a
    /// non-finite box or one with lower > upper.
    std::uint32_t add(const Aabb& box, const ProxyFilter& filter);
    /// Removes a proxy. Its pairs appear in removedPairs() after the next update(), and its id
    /// is reused only after that update. Throws InvalidArgument for an id not in use.
    void remove(std::uint32_t proxy);
    /// Moves a proxy's box. Takes effect at the next update(). Throws like add().
    void move(std::uint32_t proxy, const Aabb& box);
    /// Changes a proxy's filter; its pairs are re-evaluated at the next update().
    void setFilter(std::uint32_t proxy, const ProxyFilter& filter);
    /// Excludes (or re-admits) the pair {a, b}, e.g. two bodies joined by a joint. Takes effect
    /// at the next update(). Exclusions of a proxy are forgotten when it is removed.
    void setPairExcluded(std::uint32_t a, std::uint32_t b, bool excluded);
    /// Re-sorts the endpoints and updates the pair set; addedPairs()/removedPairs() then hold
    /// what changed, in a deterministic order. Allocates nothing once buffers have grown.
    void update();

    const std::vector<ProxyPair>& pairs() const { return pairs_; }  ///< overlapping, sorted
    /// Pairs that appeared at the last update(), sorted.
    const std::vector<ProxyPair>& addedPairs() const { return added_; }
    /// Pairs that disappeared at the last update() (moved apart, filtered, excluded or a proxy
    /// removed), sorted.
    const std::vector<ProxyPair>& removedPairs() const { return removed_; }
    /// The sweep axis in use (0 = x, 1 = y, 2 = z).
    int axis() const { return axis_; }
    /// The box of a proxy as of the last update() (m).
    const Aabb& box(std::uint32_t proxy) const { return proxies_[proxy].box; }
    /// Number of proxies in the broadphase as of the last update().
    std::uint32_t proxyCount() const { return liveCount_; }

    /// Calls visit(proxy) once for each proxy whose box overlaps `box` (touching counts), as of
    /// the last update(). Walks the sweep axis from box.lower - (longest ordinary extent).
    template <typename Visit>
    void query(const Aabb& box, Visit&& visit) const;

    /// Casts the segment origin + t direction, t in [0, maxFraction], through the proxies' boxes
    /// as of the last update(). visit(proxy, maxFraction) is called for each box the segment
    /// (clipped to the current maxFraction) hits and returns the new maxFraction: return the
    /// argument to keep all hits, a shape's hit fraction to clip (closest hit), 0 to stop. Boxes
    /// are visited roughly front to back along the sweep axis, which lets clipping end the walk.
    template <typename Visit>
    void raycast(const Vec3& origin, const Vec3& direction, Real maxFraction, Visit&& visit) const;

    /// Checks every invariant (sortedness, back-pointers, pair set) in O(n^2); for tests
    /// and debug builds.
    bool isConsistent() const;

private:
    static constexpr std::uint32_t kNone = 0xFFFFFFFF;
    enum class State : std::uint8_t { Free, Pending, Live, Removing };

    /// One end of a proxy's interval on one axis. `tag` = proxy id * 2 + (1 if upper end).
    struct Endpoint {
        Real value = 0;
        std::uint32_t tag = 0;
        std::uint32_t proxy() const { return tag >> 1; }
        bool isUpper() const { return (tag & 1u) != 0; }
    };

    struct Proxy {
        Aabb box;  ///< as indexed in the endpoint lists
        ProxyFilter filter;
        /// Index of the lower [0] and upper [1] endpoint in endpoints_[axis].
        std::array<std::array<std::uint32_t, 2>, 3> endpoint{};
        std::uint32_t moveSlot = kNone;    ///< index in moves_ while a move is pending
        std::uint32_t activeSlot = kNone;  ///< scratch for the pairing sweep
        State state = State::Free;
        bool isIndexed = false;  ///< its endpoints are in the lists
        bool isNew = false;      ///< to be paired by the sweep at this update
        bool isLarge = false;    ///< tested one by one by queries (see kLargeExtentFactor)
    };

    struct Move {
        std::uint32_t proxy;
        Aabb box;
    };

    // Update stages, in order (sweep_and_prune.cpp).
    void dropRemovedEndpoints();
    void insertPendingEndpoints();
    void applyMoves();
    void moveEndpoint(int axis, std::uint32_t index, Real value);
    void sweepNewProxies();
    void resolveCandidates();
    void collectRemovedProxyPairs();
    void mergePairs();
    void chooseAxis();
    void rescanExtents();
    void reindex();
    void releaseIds();

    void checkId(std::uint32_t proxy, const char* what) const;
    bool mayPair(std::uint32_t a, std::uint32_t b) const;
    void addCentre(const Aabb& box, Real sign);
    void classifyExtent(std::uint32_t proxy);
    /// Start of the query walk: the first lower endpoint that may belong to an ordinary proxy
    /// reaching `value` along the sweep axis.
    std::size_t walkStart(Real value) const;
    /// End of a walk: the first endpoint with a value above `value`.
    std::size_t walkEnd(Real value) const;
    /// reach_ widened by a few ulps of |value| + reach_, so rounding in value -/+ reach never
    /// cuts a box off a walk.
    Real reachWithSlack(Real value) const;
    static void checkRay(const Vec3& origin, const Vec3& direction, Real maxFraction);

    std::vector<Proxy> proxies_;
    std::array<std::vector<Endpoint>, 3> endpoints_;
    std::vector<Move> moves_;
    std::vector<std::uint32_t> pending_;   ///< added since the last update
    std::vector<std::uint32_t> removing_;  ///< removed since the last update
    std::vector<std::uint32_t> freeIds_;   ///< min-heap of ids free for reuse
    std::vector<std::uint32_t> large_;     ///< large proxies, sorted
    std::vector<ProxyPair> excluded_;      ///< sorted
    std::vector<ProxyPair> candidates_;    ///< pairs whose status may have changed
    std::vector<ProxyPair> pairs_;
    std::vector<ProxyPair> added_;
    std::vector<ProxyPair> removed_;
    std::vector<ProxyPair> removedByProxy_;  ///< scratch: pairs of removed proxies
    std::vector<ProxyPair> removedByTest_;   ///< scratch: pairs that stopped overlapping
    std::vector<ProxyPair> scratchPairs_;
    std::vector<Endpoint> scratchEndpoints_;
    std::vector<std::uint32_t> activeOld_;  ///< scratch for the pairing sweep
    std::vector<std::uint32_t> activeNew_;
    std::uint32_t liveCount_ = 0;
    int axis_ = 0;
    bool structureChanged_ = false;  ///< proxies inserted or dropped during this update
    bool sweepNeeded_ = false;       ///< some proxy is new or has a new filter
    /// Sums over live proxies of centre - centreReference_ and its square, per axis: the
    /// variances that choose the sweep axis, updated incrementally.
    Vec3 centreSum_ = Vec3::Zero();
    Vec3 centreSquareSum_ = Vec3::Zero();
    Vec3 centreReference_ = Vec3::Zero();
    Real largeThreshold_ = 0;  ///< extent along the sweep axis above which a proxy is large (m)
    Real reach_ = 0;           ///< >= the extent of every ordinary proxy along the sweep axis (m)
};

/// The O(n^2) reference: every overlapping pair that passes the filter, sorted.
std::vector<ProxyPair> bruteForcePairs(const std::vector<Aabb>& boxes,
                                       const std::vector<ProxyFilter>& filters);

// ---- templates ------------------------------------------------------------------------------

template <typename Visit>
void SweepAndPrune::query(const Aabb& box, Visit&& visit) const {
    for (const std::uint32_t proxy : large_) {
        if (proxies_[proxy].box.overlaps(box)) {
            visit(proxy);
        }
    }
    const std::vector<Endpoint>& list = endpoints_[axis_];
    const std::size_t end = walkEnd(box.upper[axis_]);
    for (std::size_t i = walkStart(box.lower[axis_]); i < end; ++i) {
        const Endpoint& endpoint = list[i];
        if (endpoint.isUpper()) {
            continue;
        }
        const Proxy& proxy = proxies_[endpoint.proxy()];
        if (!proxy.isLarge && proxy.box.overlaps(box)) {
            visit(endpoint.proxy());
        }
    }
}

template <typename Visit>
void SweepAndPrune::raycast(const Vec3& origin, const Vec3& direction, Real maxFraction,
                            Visit&& visit) const {
    checkRay(origin, direction, maxFraction);
    for (const std::uint32_t proxy : large_) {
        if (maxFraction <= 0) {
            return;
        }
        if (rayEntryFraction(origin, direction, maxFraction, proxies_[proxy].box) >= 0) {
            maxFraction = visit(proxy, maxFraction);
        }
    }
    // Walk the sweep axis in the ray's direction. A box is entered along this axis no earlier
    // than t = (near face - origin) / direction; once that exceeds maxFraction for one endpoint
    // it does for all further ones (the expression is monotonic in the endpoint value even in
    // floating point), so the walk stops there.
    const std::vector<Endpoint>& list = endpoints_[axis_];
    const Real o = origin[axis_];
    const Real d = direction[axis_];
    auto tryProxy = [&](const Endpoint& endpoint) {
        const Proxy& proxy = proxies_[endpoint.proxy()];
        if (!proxy.isLarge && rayEntryFraction(origin, direction, maxFraction, proxy.box) >= 0) {
            maxFraction = visit(endpoint.proxy(), maxFraction);
        }
    };
    if (d >= 0) {
        // Boxes reaching past the origin start at most reach_ before it.
        const std::size_t end = d == 0 ? walkEnd(o) : list.size();
        for (std::size_t i = walkStart(o); i < end && maxFraction > 0; ++i) {
            if (list[i].isUpper()) {
                continue;
            }
            if (d > 0 && (list[i].value - o) / d > maxFraction) {
                return;
            }
            tryProxy(list[i]);
        }
        return;
    }
    // Walking backwards over upper endpoints: boxes whose lower end lies behind the origin
    // have their upper end at most reach_ beyond it.
    for (std::size_t i = walkEnd(o + reachWithSlack(o)); i-- > 0 && maxFraction > 0;) {
        if (!list[i].isUpper()) {
            continue;
        }
        if ((list[i].value - o) / d > maxFraction) {
            return;
        }
        tryProxy(list[i]);
    }
}

}  // namespace tumble
