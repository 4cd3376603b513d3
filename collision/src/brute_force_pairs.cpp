// The O(n^2) reference broadphase: every pair tested, nothing remembered. Kept beside
// SweepAndPrune so tests can compare against it and benchmarks can show where SAP pays off.

#include "tumble/collision/sweep_and_prune.h"
#include "tumble/core/error.h"

namespace tumble {

std::vector<ProxyPair> bruteForcePairs(const std::vector<Aabb>& boxes,
                                       const std::vector<ProxyFilter>& filters) {
    if (boxes.size() != filters.size()) {
        fail("bruteForcePairs: boxes.size() = ", boxes.size(),
             " must equal filters.size() = ", filters.size());
    }
    std::vector<ProxyPair> pairs;
    const auto count = static_cast<std::uint32_t>(boxes.size());
    for (std::uint32_t i = 0; i < count; ++i) {
        const ProxyFilter& filterA = filters[i];
        for (std::uint32_t j = i + 1; j < count; ++j) {
            const ProxyFilter& filterB = filters[j];
            if ((filterA.isStatic && filterB.isStatic) || (filterA.category & filterB.mask) == 0 ||
                (filterB.category & filterA.mask) == 0) {
                continue;
            }
            if (boxes[i].overlaps(boxes[j])) {
                pairs.push_back({i, j});  // i, then j ascending: sorted as produced
            }
        }
    }
    return pairs;
}

}  // namespace tumble
