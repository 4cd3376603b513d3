#pragma once
/// The sorted pair-set update shared by the broadphases (internal to collision/).

#include <vector>

#include "tumble/collision/sweep_and_prune.h"

namespace tumble::detail {

/// pairs = (pairs \ removed) u added, all three sorted; `removed` must be a subset of `pairs` and
/// `added` disjoint from it. `scratch` is reused storage, so a warm update does not allocate.
inline void applyPairChanges(std::vector<ProxyPair>& pairs, const std::vector<ProxyPair>& added,
                             const std::vector<ProxyPair>& removed,
                             std::vector<ProxyPair>& scratch) {
    scratch.clear();
    auto removedAt = removed.begin();
    auto addedAt = added.begin();
    for (const ProxyPair pair : pairs) {
        if (removedAt != removed.end() && *removedAt == pair) {
            ++removedAt;
            continue;
        }
        while (addedAt != added.end() && *addedAt < pair)
            scratch.push_back(*addedAt++);
        scratch.push_back(pair);
    }
    scratch.insert(scratch.end(), addedAt, added.end());
    std::swap(pairs, scratch);
}

}  // namespace tumble::detail
