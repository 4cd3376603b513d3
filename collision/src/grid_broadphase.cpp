// Multi-box pruning: a SweepAndPrune per grid cell, pair counts across cells.
//
// Placement. A proxy's cells are floor(lower / cellSize) .. floor(upper / cellSize) per axis.
// If two boxes overlap (touching counts) they share a point p, and floor(p / cellSize) lies in
// both ranges because division by a positive number and floor are monotonic, also in floating
// point; so every overlapping pair of ordinary proxies shares at least one cell and is found
// there. Placement changes at add/move/remove time (the cells' SAPs defer the work to their own
// update); update() updates only the cells touched since the last one.
//
// Counting. The overlap set O is the set of pairs with a positive count, the count of a pair
// being the number of sources that report it: each cell where both are (its SAP applies the
// filters), the oversized SAP, and the oversized-vs-ordinary test (crossPairs_). Each source
// reports only its changes (+1 added, -1 removed); summed per pair over one update they give the
// new counts, and a pair enters or leaves O exactly when its count leaves or reaches 0. A box
// that moves from one cell to the next yields +1 and -1 for its pairs, which cancel.
//
// Reporting. pairs() = O minus the excluded pairs. It can change only for pairs whose count
// crossed 0 or whose exclusion was toggled; each of those is decided again (binary searches)
// and the sorted changes are merged into pairs_. Cost of an update: the touched cells' SAP
// updates + O(d log d) for d pair changes + O(pairs) for the merges.
//
// Cross pairs (oversized x ordinary). Their status changes only when one of the two is added,
// moved, re-filtered, removed or changes class; all of those mark the proxy dirty. A dirty
// proxy that is or was oversized is tested against every proxy; an ordinary one against the
// oversized proxies of before and after the update.

#include <algorithm>
#include <cmath>
#include <functional>
#include <iterator>

#include "tumble/collision/grid_broadphase.h"

#include "pair_set.h"
#include "tumble/core/error.h"

namespace tumble {
namespace {

ProxyPair makePair(std::uint32_t a, std::uint32_t b) {
    return a < b ? ProxyPair{a, b} : ProxyPair{b, a};
}

void checkBox(const Aabb& box, const char* where) {
    if (!isFinite(box.lower) || !isFinite(box.upper)) {
        fail(where, ": box = [", box.lower.transpose(), "] .. [", box.upper.transpose(),
             "] must be finite");
    }
    if ((box.lower.array() > box.upper.array()).any()) {
        fail(where, ": box.lower = [", box.lower.transpose(), "] must be <= box.upper = [",
             box.upper.transpose(), "] componentwise");
    }
}

}  // namespace

bool GridBroadphase::CellRange::contains(const CellKey& key) const {
    for (int axis = 0; axis < 3; ++axis) {
        if (key[axis] < lower[axis] || key[axis] > upper[axis]) {
            return false;
        }
    }
    return true;
}

GridBroadphase::GridBroadphase(Real cellSize, std::uint32_t maxCellsPerProxy)
    : cellSize_(cellSize), inverseCellSize_(1 / cellSize), maxCellsPerProxy_(maxCellsPerProxy) {
    if (!std::isfinite(cellSize) || !(cellSize > 0)) {
        fail("GridBroadphase: cellSize = ", cellSize, " must be finite and > 0");
    }
    if (maxCellsPerProxy < 1) {
        fail("GridBroadphase: maxCellsPerProxy = ", maxCellsPerProxy, " must be >= 1");
    }
}

std::int32_t GridBroadphase::coordinateOf(Real value) const {
    const Real cell = std::floor(value * inverseCellSize_);
    const Real limit = kCoordinateLimit;
    return static_cast<std::int32_t>(std::clamp(cell, -limit, limit));
}

GridBroadphase::CellRange GridBroadphase::rangeOf(const Aabb& box) const {
    CellRange range;
    for (int axis = 0; axis < 3; ++axis) {
        range.lower[axis] = coordinateOf(box.lower[axis]);
        range.upper[axis] = coordinateOf(box.upper[axis]);
    }
    return range;
}

bool GridBroadphase::isOversizedRange(const CellRange& range) const {
    Real count = 1;
    for (int axis = 0; axis < 3; ++axis) {
        count *= static_cast<Real>(range.upper[axis]) - range.lower[axis] + 1;
    }
    return count > static_cast<Real>(maxCellsPerProxy_);
}

std::uint32_t GridBroadphase::cellAt(const CellKey& key) {
    const auto found = cellIndex_.find(key);
    if (found != cellIndex_.end()) {
        return found->second;
    }
    const auto index = static_cast<std::uint32_t>(cells_.size());
    cells_.emplace_back();
    cells_.back().key = key;
    cellIndex_.emplace(key, index);
    return index;
}

void GridBroadphase::markCell(std::uint32_t cell) {
    if (!cells_[cell].isDirty) {
        cells_[cell].isDirty = true;
        dirtyCells_.push_back(cell);
    }
}

void GridBroadphase::markDirty(std::uint32_t id) {
    if (!proxies_[id].isDirty) {
        proxies_[id].isDirty = true;
        dirty_.push_back(id);
    }
}

// Inserts proxy `id` (box and filter set) into its cells or the oversized list.
void GridBroadphase::place(std::uint32_t id) {
    Proxy& proxy = proxies_[id];
    proxy.range = rangeOf(proxy.box);
    proxy.isOversized = isOversizedRange(proxy.range);
    if (proxy.isOversized) {
        proxy.oversizedLocal = oversized_.add(proxy.box, proxy.filter);
        if (proxy.oversizedLocal >= oversizedGlobal_.size()) {
            oversizedGlobal_.resize(proxy.oversizedLocal + 1);
        }
        oversizedGlobal_[proxy.oversizedLocal] = id;
        oversizedList_.insert(std::lower_bound(oversizedList_.begin(), oversizedList_.end(), id),
                              id);
        oversizedDirty_ = true;
        return;
    }
    const CellRange& range = proxy.range;
    CellKey key;
    for (key[0] = range.lower[0]; key[0] <= range.upper[0]; ++key[0]) {
        for (key[1] = range.lower[1]; key[1] <= range.upper[1]; ++key[1]) {
            for (key[2] = range.lower[2]; key[2] <= range.upper[2]; ++key[2]) {
                const std::uint32_t index = cellAt(key);
                Cell& cell = cells_[index];
                const std::uint32_t local = cell.sap.add(proxy.box, proxy.filter);
                if (local >= cell.globalId.size()) {
                    cell.globalId.resize(local + 1);
                }
                cell.globalId[local] = id;
                proxy.cells.push_back({index, local});
                markCell(index);
            }
        }
    }
}

// Takes proxy `id` out of its cells or the oversized list.
void GridBroadphase::unplace(std::uint32_t id) {
    Proxy& proxy = proxies_[id];
    if (proxy.isOversized) {
        oversized_.remove(proxy.oversizedLocal);
        oversizedList_.erase(std::lower_bound(oversizedList_.begin(), oversizedList_.end(), id));
        proxy.oversizedLocal = kNone;
        oversizedDirty_ = true;
        return;
    }
    for (const Membership& membership : proxy.cells) {
        cells_[membership.cell].sap.remove(membership.local);
        markCell(membership.cell);
    }
    proxy.cells.clear();
}

// An ordinary proxy stays ordinary: moved in the cells of both ranges, removed from the cells
// it left, added to the ones it entered.
void GridBroadphase::moveWithinCells(std::uint32_t id, const CellRange& newRange) {
    Proxy& proxy = proxies_[id];
    const CellRange oldRange = proxy.range;
    std::erase_if(proxy.cells, [&](const Membership& membership) {
        Cell& cell = cells_[membership.cell];
        markCell(membership.cell);
        if (newRange.contains(cell.key)) {
            cell.sap.move(membership.local, proxy.box);
            return false;
        }
        cell.sap.remove(membership.local);
        return true;
    });
    proxy.range = newRange;
    CellKey key;
    for (key[0] = newRange.lower[0]; key[0] <= newRange.upper[0]; ++key[0]) {
        for (key[1] = newRange.lower[1]; key[1] <= newRange.upper[1]; ++key[1]) {
            for (key[2] = newRange.lower[2]; key[2] <= newRange.upper[2]; ++key[2]) {
                if (oldRange.contains(key)) {
                    continue;
                }
                const std::uint32_t index = cellAt(key);
                Cell& cell = cells_[index];
                const std::uint32_t local = cell.sap.add(proxy.box, proxy.filter);
                if (local >= cell.globalId.size()) {
                    cell.globalId.resize(local + 1);
                }
                cell.globalId[local] = id;
                proxy.cells.push_back({index, local});
                markCell(index);
            }
        }
    }
}

std::uint32_t GridBroadphase::add(const Aabb& box, const ProxyFilter& filter) {
    checkBox(box, "GridBroadphase::add");
    std::uint32_t id = 0;
    if (!freeIds_.empty()) {
        std::pop_heap(freeIds_.begin(), freeIds_.end(), std::greater<>());
        id = freeIds_.back();
        freeIds_.pop_back();
    } else {
        if (proxies_.size() >= (kNone >> 1)) {
            fail("GridBroadphase::add: proxy count ", proxies_.size(), " must stay below ",
                 kNone >> 1);
        }
        id = static_cast<std::uint32_t>(proxies_.size());
        proxies_.emplace_back();
    }
    Proxy& proxy = proxies_[id];
    proxy.box = box;
    proxy.publishedBox = box;
    proxy.filter = filter;
    proxy.state = State::Pending;
    proxy.wasOversized = false;
    proxy.publishedRange = CellRange{{1, 1, 1}, {0, 0, 0}};  // empty: in no cell yet
    place(id);
    markDirty(id);
    return id;
}

void GridBroadphase::checkId(std::uint32_t proxy, const char* what) const {
    if (proxy >= proxies_.size() ||
        (proxies_[proxy].state != State::Pending && proxies_[proxy].state != State::Live)) {
        fail("GridBroadphase::", what, ": proxy = ", proxy, " is not a proxy in use");
    }
}

void GridBroadphase::remove(std::uint32_t proxy) {
    checkId(proxy, "remove");
    unplace(proxy);
    proxies_[proxy].state = State::Removing;
    markDirty(proxy);
    std::erase_if(excluded_,
                  [proxy](ProxyPair pair) { return pair.first == proxy || pair.second == proxy; });
}

void GridBroadphase::move(std::uint32_t proxy, const Aabb& box) {
    checkBox(box, "GridBroadphase::move");
    checkId(proxy, "move");
    Proxy& moved = proxies_[proxy];
    const CellRange newRange = rangeOf(box);
    const bool oversized = isOversizedRange(newRange);
    markDirty(proxy);
    if (oversized != moved.isOversized) {
        unplace(proxy);
        moved.box = box;
        place(proxy);
        return;
    }
    moved.box = box;
    if (oversized) {
        oversized_.move(moved.oversizedLocal, box);
        oversizedDirty_ = true;
        return;
    }
    moveWithinCells(proxy, newRange);
}

void GridBroadphase::setFilter(std::uint32_t proxy, const ProxyFilter& filter) {
    checkId(proxy, "setFilter");
    Proxy& changed = proxies_[proxy];
    changed.filter = filter;
    markDirty(proxy);
    if (changed.isOversized) {
        oversized_.setFilter(changed.oversizedLocal, filter);
        oversizedDirty_ = true;
        return;
    }
    for (const Membership& membership : changed.cells) {
        cells_[membership.cell].sap.setFilter(membership.local, filter);
        markCell(membership.cell);
    }
}

void GridBroadphase::setPairExcluded(std::uint32_t a, std::uint32_t b, bool excluded) {
    checkId(a, "setPairExcluded");
    checkId(b, "setPairExcluded");
    if (a == b) {
        fail("GridBroadphase::setPairExcluded: a = b = ", a, "; a pair needs two proxies");
    }
    const ProxyPair pair = makePair(a, b);
    const auto at = std::lower_bound(excluded_.begin(), excluded_.end(), pair);
    const bool present = at != excluded_.end() && *at == pair;
    if (excluded && !present) {
        excluded_.insert(at, pair);
    } else if (!excluded && present) {
        excluded_.erase(at);
    }
    toggled_.push_back(pair);
}

void GridBroadphase::update() {
    deltas_.clear();
    collectCellDeltas();       // touched cells' SAP updates
    collectOversizedDeltas();  // the oversized SAP, if touched
    collectCrossDeltas();      // oversized x ordinary, for dirty proxies
    applyDeltas();             // O(d log d + pairs)
    decideReportedPairs();     // O(changes log pairs + pairs)
    publish();
}

void GridBroadphase::collectCellDeltas() {
    // Cell indices follow creation order, itself deterministic: sorted, they give one order.
    std::sort(dirtyCells_.begin(), dirtyCells_.end());
    for (const std::uint32_t index : dirtyCells_) {
        Cell& cell = cells_[index];
        cell.isDirty = false;
        cell.sap.update();
        for (const ProxyPair pair : cell.sap.addedPairs()) {
            deltas_.push_back({makePair(cell.globalId[pair.first], cell.globalId[pair.second]), 1});
        }
        for (const ProxyPair pair : cell.sap.removedPairs()) {
            deltas_.push_back(
                {makePair(cell.globalId[pair.first], cell.globalId[pair.second]), -1});
        }
    }
    dirtyCells_.clear();
}

void GridBroadphase::collectOversizedDeltas() {
    if (!oversizedDirty_) {
        return;
    }
    oversizedDirty_ = false;
    oversized_.update();
    for (const ProxyPair pair : oversized_.addedPairs()) {
        deltas_.push_back(
            {makePair(oversizedGlobal_[pair.first], oversizedGlobal_[pair.second]), 1});
    }
    for (const ProxyPair pair : oversized_.removedPairs()) {
        deltas_.push_back(
            {makePair(oversizedGlobal_[pair.first], oversizedGlobal_[pair.second]), -1});
    }
}

bool GridBroadphase::filtersPass(std::uint32_t a, std::uint32_t b) const {
    const ProxyFilter& filterA = proxies_[a].filter;
    const ProxyFilter& filterB = proxies_[b].filter;
    return !(filterA.isStatic && filterB.isStatic) && (filterA.category & filterB.mask) != 0 &&
           (filterB.category & filterA.mask) != 0;
}

void GridBroadphase::collectCrossDeltas() {
    crossCandidates_.clear();
    for (const std::uint32_t id : dirty_) {
        const Proxy& proxy = proxies_[id];
        if (proxy.isOversized || proxy.wasOversized) {
            for (std::uint32_t other = 0; other < proxies_.size(); ++other) {
                if (other != id && proxies_[other].state != State::Free) {
                    crossCandidates_.push_back(makePair(id, other));
                }
            }
            continue;
        }
        for (const std::uint32_t other : oversizedPublished_) {
            crossCandidates_.push_back(makePair(id, other));
        }
        for (const std::uint32_t other : oversizedList_) {
            crossCandidates_.push_back(makePair(id, other));
        }
    }
    if (crossCandidates_.empty()) {
        return;
    }
    std::sort(crossCandidates_.begin(), crossCandidates_.end());
    crossCandidates_.erase(std::unique(crossCandidates_.begin(), crossCandidates_.end()),
                           crossCandidates_.end());
    crossAdded_.clear();
    crossRemoved_.clear();
    for (const ProxyPair pair : crossCandidates_) {
        const Proxy& first = proxies_[pair.first];
        const Proxy& second = proxies_[pair.second];
        const bool bothAlive = (first.state == State::Pending || first.state == State::Live) &&
                               (second.state == State::Pending || second.state == State::Live);
        const bool is = bothAlive && first.isOversized != second.isOversized &&
                        first.box.overlaps(second.box) && filtersPass(pair.first, pair.second);
        const bool was = std::binary_search(crossPairs_.begin(), crossPairs_.end(), pair);
        if (is && !was) {
            crossAdded_.push_back(pair);
            deltas_.push_back({pair, 1});
        } else if (was && !is) {
            crossRemoved_.push_back(pair);
            deltas_.push_back({pair, -1});
        }
    }
    if (crossAdded_.empty() && crossRemoved_.empty()) {
        return;
    }
    // crossPairs_ = (crossPairs_ \ removed) u added, all sorted (candidates were).
    scratchPairs_.clear();
    std::set_difference(crossPairs_.begin(), crossPairs_.end(), crossRemoved_.begin(),
                        crossRemoved_.end(), std::back_inserter(scratchPairs_));
    crossPairs_.clear();
    std::merge(scratchPairs_.begin(), scratchPairs_.end(), crossAdded_.begin(), crossAdded_.end(),
               std::back_inserter(crossPairs_));
}

void GridBroadphase::applyDeltas() {
    countChanged_.clear();
    if (deltas_.empty()) {
        return;
    }
    std::sort(deltas_.begin(), deltas_.end(), [](const PairDelta& a, const PairDelta& b) {
        return a.pair < b.pair || (a.pair == b.pair && a.delta < b.delta);
    });
    // Merge the summed deltas into the sorted counts; pairs reaching 0 drop out.
    scratchCounts_.clear();
    auto countAt = counts_.begin();
    for (std::size_t i = 0; i < deltas_.size();) {
        const ProxyPair pair = deltas_[i].pair;
        std::int64_t sum = 0;
        for (; i < deltas_.size() && deltas_[i].pair == pair; ++i) {
            sum += deltas_[i].delta;
        }
        while (countAt != counts_.end() && countAt->pair < pair) {
            scratchCounts_.push_back(*countAt++);
        }
        std::int64_t count = sum;
        if (countAt != counts_.end() && countAt->pair == pair) {
            count += countAt->count;
            ++countAt;
        }
        const bool was = count != sum;
        if (count > 0) {
            scratchCounts_.push_back({pair, static_cast<std::uint32_t>(count)});
        }
        if (was != (count > 0)) {
            countChanged_.push_back(pair);
        }
    }
    scratchCounts_.insert(scratchCounts_.end(), countAt, counts_.end());
    std::swap(counts_, scratchCounts_);
}

bool GridBroadphase::isExcluded(ProxyPair pair) const {
    return !excluded_.empty() && std::binary_search(excluded_.begin(), excluded_.end(), pair);
}

void GridBroadphase::decideReportedPairs() {
    added_.clear();
    removed_.clear();
    if (!toggled_.empty()) {
        countChanged_.insert(countChanged_.end(), toggled_.begin(), toggled_.end());
        toggled_.clear();
        std::sort(countChanged_.begin(), countChanged_.end());
        countChanged_.erase(std::unique(countChanged_.begin(), countChanged_.end()),
                            countChanged_.end());
    }
    auto byPair = [](const PairCount& entry, ProxyPair pair) { return entry.pair < pair; };
    for (const ProxyPair pair : countChanged_) {
        const auto at = std::lower_bound(counts_.begin(), counts_.end(), pair, byPair);
        const bool counted = at != counts_.end() && at->pair == pair;
        const bool is = counted && !isExcluded(pair);
        const bool was = std::binary_search(pairs_.begin(), pairs_.end(), pair);
        if (is && !was) {
            added_.push_back(pair);
        } else if (was && !is) {
            removed_.push_back(pair);
        }
    }
    if (added_.empty() && removed_.empty()) {
        return;
    }
    detail::applyPairChanges(pairs_, added_, removed_, scratchPairs_);
}

void GridBroadphase::publish() {
    std::sort(dirty_.begin(), dirty_.end());
    for (const std::uint32_t id : dirty_) {
        Proxy& proxy = proxies_[id];
        proxy.isDirty = false;
        if (proxy.state == State::Removing) {
            proxy.state = State::Free;
            proxy.cells.clear();  // keeps its capacity for the next proxy with this id
            proxy.isOversized = false;
            proxy.wasOversized = false;
            freeIds_.push_back(id);
            std::push_heap(freeIds_.begin(), freeIds_.end(), std::greater<>());
            if (proxy.wasLive) {
                --liveCount_;
            }
            proxy.wasLive = false;
            continue;
        }
        if (proxy.state == State::Pending) {
            proxy.state = State::Live;
            proxy.wasLive = true;
            ++liveCount_;
        }
        proxy.publishedBox = proxy.box;
        proxy.publishedRange = proxy.range;
        proxy.wasOversized = proxy.isOversized;
    }
    dirty_.clear();
    oversizedPublished_ = oversizedList_;
}

bool GridBroadphase::isConsistent() const {
    for (const Cell& cell : cells_) {
        if (!cell.sap.isConsistent()) {
            return false;
        }
    }
    std::vector<std::uint32_t> live;
    for (std::uint32_t id = 0; id < proxies_.size(); ++id) {
        if (proxies_[id].state == State::Live) {
            live.push_back(id);
        }
    }
    if (live.size() != liveCount_) {
        return false;
    }
    std::vector<ProxyPair> expected;
    for (std::size_t i = 0; i < live.size(); ++i) {
        for (std::size_t j = i + 1; j < live.size(); ++j) {
            const ProxyPair pair{live[i], live[j]};
            if (proxies_[live[i]].box.overlaps(proxies_[live[j]].box) &&
                filtersPass(live[i], live[j]) && !isExcluded(pair)) {
                expected.push_back(pair);
            }
        }
    }
    return expected == pairs_;
}

}  // namespace tumble
