#pragma once
/// The sorted pair-set update shared by the broadphases (internal to collision/).

#include <algorithm>
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
    if ((added.size() + removed.size()) * 16 <= pairs.size()) {
        // Few changes (a step's, in a pile: tens among ~30,000 pairs): each is found by binary
        // search and the unchanged pairs between two changes are copied as one block, where the
        // loop below copied them one by one.
        auto from = pairs.begin();
        while (removedAt != removed.end() || addedAt != added.end()) {
            const bool removal =
                addedAt == added.end() || (removedAt != removed.end() && *removedAt < *addedAt);
            const auto at = std::lower_bound(from, pairs.end(), removal ? *removedAt : *addedAt);
            scratch.insert(scratch.end(), from, at);
            if (removal) {
                from = at != pairs.end() && *at == *removedAt ? at + 1 : at;
                ++removedAt;
            } else {
                scratch.push_back(*addedAt++);
                from = at;
            }
        }
        scratch.insert(scratch.end(), from, pairs.end());
        std::swap(pairs, scratch);
        return;
    }
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
