#pragma once
/// Broadphase: which pairs of proxies have overlapping fat bounding boxes.
///
/// SweepAndPrune keeps the proxies' interval endpoints sorted along one axis across updates
/// (insertion sort, so a scene that barely moves costs little) and maintains the overlapping pair
/// set incrementally, reporting pairs added and removed by each update. BruteForcePairs is the
/// O(n^2) reference it is tested against.

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

class SweepAndPrune {
public:
    /// Adds a proxy with its fat box; returns its id (dense, reused after removal).
    std::uint32_t add(const Aabb& box, const ProxyFilter& filter);
    void remove(std::uint32_t proxy);
    /// Moves a proxy's box. Takes effect at the next update().
    void move(std::uint32_t proxy, const Aabb& box);
    /// Re-sorts the endpoints and updates the pair set; addedPairs()/removedPairs() then hold
    /// what changed, in a deterministic order.
    void update();

    const std::vector<ProxyPair>& pairs() const;  ///< current overlapping pairs, sorted
    const std::vector<ProxyPair>& addedPairs() const;
    const std::vector<ProxyPair>& removedPairs() const;
    /// The sweep axis in use (0 = x, 1 = y, 2 = z).
    int axis() const;

    /// Calls visit(proxy) for each proxy whose box overlaps `box` (queries).
    template <typename Visit>
    void query(const Aabb& box, Visit&& visit) const;

private:
    // Implementation chosen by the broadphase work; see sweep_and_prune.cpp.
};

/// The O(n^2) reference: every overlapping pair that passes the filter, sorted.
std::vector<ProxyPair> bruteForcePairs(const std::vector<Aabb>& boxes,
                                       const std::vector<ProxyFilter>& filters);

}  // namespace tumble
