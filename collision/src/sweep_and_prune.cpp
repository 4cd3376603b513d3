// Incremental sweep-and-prune over three sorted axes.
//
// Invariants between updates:
// - endpoints_[axis] holds the lower and upper endpoint of every indexed proxy, sorted by
//   (value, lower before upper). Under that order "lower(a) precedes upper(b)" holds exactly when
//   lower(a) <= upper(b), so touching boxes overlap, as in Aabb::overlaps.
// - proxies_[p].endpoint[axis][upper] is the index of p's endpoint in that list (back-pointer).
// - pairs_ is the sorted set of pairs of indexed proxies whose boxes overlap on all three axes
//   and which mayPair() (filter both ways, not both static, not excluded).
//
// The update. Each moved endpoint is given its new value (in the endpoint and in the proxy's
// box) and bubbled to its place (one step of insertion sort). Think of the pair set as following
// the configuration through every single swap: the 3D overlap of two proxies can only change when
// one's lower endpoint swaps with the other's upper endpoint on some axis, and then only if their
// boxes overlap on the two other axes at that moment (the boxes hold the current values, which
// agree with the order on every axis but the one being settled). Such swaps make the pair a
// candidate; any pair whose overlap differs between the start and end of the update changed at
// least once on the way, so it is among the candidates. Swaps with far-away boxes, the bulk of
// them, are rejected by the two-axis test without leaving a trace. Each candidate is then decided
// against the final boxes and the old pair set (binary search), so the result does not depend on
// the order in which moves were applied. New proxies (and ones with a new filter) are paired by
// one sweep along the sweep axis that tests only pairs involving them. Cost of an update:
// O(swaps + candidates log candidates + pairs), and O(1) if nothing moved. Swaps grow with how far
// boxes move and how many endpoints lie in between; with fat boxes the engine moves a proxy
// rarely and by about the margin. Scaling caveat: in a volume filled uniformly at fixed density,
// an axis holds n^(2/3) endpoints per metre, so swaps per moved proxy (and the new-proxy sweep's
// active list) grow as n^(2/3) and the update as ~n^(5/3) (measured exponent 1.65-1.84 from 1k
// to 50k, bench/broadphase_bench.cpp). Linear cost needs spatial partitioning (a SAP per grid
// cell, or a BVH); flat worlds and scenes spread along one axis fare much better.
//
// Determinism: all orders are decided by values and ids (ties in the lists by the order of
// operations, which is itself deterministic); candidates are sorted before they are decided.
// Ids are reused smallest first, and only after the update that reported the removed pairs.

#include <algorithm>
#include <cmath>
#include <functional>
#include <iterator>

#include "tumble/collision/sweep_and_prune.h"

#include "pair_set.h"
#include "tumble/core/error.h"

namespace tumble {
namespace {

// Relative widening of the sweep-axis reach against rounding, many ulps of double.
constexpr Real kReachSlack = 1e-12;

// The list order: by value, a lower endpoint before an upper one at equal value.
template <typename Endpoint>
bool precedes(const Endpoint& a, const Endpoint& b) {
    return a.value < b.value || (a.value == b.value && !a.isUpper() && b.isUpper());
}

// A total order (ties broken by id), so sorting new endpoints gives one result.
template <typename Endpoint>
bool precedesTotal(const Endpoint& a, const Endpoint& b) {
    if (a.value != b.value) {
        return a.value < b.value;
    }
    if (a.isUpper() != b.isUpper()) {
        return b.isUpper();
    }
    return a.tag < b.tag;
}

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

// Overlap (touching counts) on axes j and k. Evaluated without short-circuits (a bitwise and of
// the truths as integers): in the bubbling loop a single, mostly-false branch is cheaper than a
// chain of unpredictable ones.
bool overlapsOn(const Aabb& a, const Aabb& b, int j, int k) {
    const unsigned onJ = unsigned{a.lower[j] <= b.upper[j]} & unsigned{b.lower[j] <= a.upper[j]};
    const unsigned onK = unsigned{a.lower[k] <= b.upper[k]} & unsigned{b.lower[k] <= a.upper[k]};
    return (onJ & onK) != 0;
}

Real extentAlong(const Aabb& box, int axis) {
    return box.upper[axis] - box.lower[axis];
}

}  // namespace

Real rayEntryFraction(const Vec3& origin, const Vec3& direction, Real maxFraction,
                      const Aabb& box) {
    // Slab test: intersect the parameter intervals in which the segment lies within each slab.
    Real entry = 0;
    Real exit = maxFraction;
    for (int axis = 0; axis < 3; ++axis) {
        const Real o = origin[axis];
        const Real d = direction[axis];
        if (d == 0) {
            if (o < box.lower[axis] || o > box.upper[axis]) {
                return -1;
            }
            continue;
        }
        Real near = (box.lower[axis] - o) / d;
        Real far = (box.upper[axis] - o) / d;
        if (d < 0) {
            std::swap(near, far);
        }
        entry = std::max(entry, near);
        exit = std::min(exit, far);
        if (entry > exit) {
            return -1;
        }
    }
    return entry;
}

std::uint32_t SweepAndPrune::add(const Aabb& box, const ProxyFilter& filter) {
    checkBox(box, "SweepAndPrune::add");
    std::uint32_t id = 0;
    if (!freeIds_.empty()) {
        std::pop_heap(freeIds_.begin(), freeIds_.end(), std::greater<>());
        id = freeIds_.back();
        freeIds_.pop_back();
    } else {
        if (proxies_.size() >= (kNone >> 1)) {
            fail("SweepAndPrune::add: proxy count ", proxies_.size(), " must stay below ",
                 kNone >> 1);
        }
        id = static_cast<std::uint32_t>(proxies_.size());
        proxies_.emplace_back();
    }
    Proxy& proxy = proxies_[id];
    proxy = Proxy{};
    proxy.box = box;
    proxy.filter = filter;
    proxy.state = State::Pending;
    proxy.isNew = true;
    pending_.push_back(id);
    return id;
}

void SweepAndPrune::checkId(std::uint32_t proxy, const char* what) const {
    if (proxy >= proxies_.size() ||
        (proxies_[proxy].state != State::Pending && proxies_[proxy].state != State::Live)) {
        fail("SweepAndPrune::", what, ": proxy = ", proxy, " is not a proxy in use");
    }
}

void SweepAndPrune::remove(std::uint32_t proxy) {
    checkId(proxy, "remove");
    Proxy& removed = proxies_[proxy];
    if (removed.state == State::Pending) {
        pending_.erase(std::find(pending_.begin(), pending_.end(), proxy));
    }
    removed.state = State::Removing;
    removing_.push_back(proxy);
    std::erase_if(excluded_,
                  [proxy](ProxyPair pair) { return pair.first == proxy || pair.second == proxy; });
}

void SweepAndPrune::move(std::uint32_t proxy, const Aabb& box) {
    checkBox(box, "SweepAndPrune::move");
    checkId(proxy, "move");
    Proxy& moved = proxies_[proxy];
    if (moved.state == State::Pending) {
        moved.box = box;  // not indexed yet: inserted with its latest box
        return;
    }
    if (moved.moveSlot == kNone) {
        moved.moveSlot = static_cast<std::uint32_t>(moves_.size());
        moves_.push_back({proxy, box});
    } else {
        moves_[moved.moveSlot].box = box;
    }
}

void SweepAndPrune::setFilter(std::uint32_t proxy, const ProxyFilter& filter) {
    checkId(proxy, "setFilter");
    proxies_[proxy].filter = filter;
    // Re-paired by the sweep: it finds every pair the proxy overlaps, and the pairs it stops
    // overlapping are candidates through their swaps anyway.
    proxies_[proxy].isNew = true;
    sweepNeeded_ = true;
}

void SweepAndPrune::setPairExcluded(std::uint32_t a, std::uint32_t b, bool excluded) {
    checkId(a, "setPairExcluded");
    checkId(b, "setPairExcluded");
    if (a == b) {
        fail("SweepAndPrune::setPairExcluded: a = b = ", a, "; a pair needs two proxies");
    }
    const ProxyPair pair = makePair(a, b);
    const auto at = std::lower_bound(excluded_.begin(), excluded_.end(), pair);
    const bool present = at != excluded_.end() && *at == pair;
    if (excluded && !present) {
        excluded_.insert(at, pair);
    } else if (!excluded && present) {
        excluded_.erase(at);
    }
    candidates_.push_back(pair);  // decided again at the next update
}

void SweepAndPrune::update() {
    dropRemovedEndpoints();    // O(n), only if something was removed
    insertPendingEndpoints();  // O(n + k log k), only if k proxies were added
    if (structureChanged_) {
        reindex();
    }
    applyMoves();  // O(swaps)
    chooseAxis();  // O(1); O(n) when the axis changes
    if (structureChanged_) {
        rescanExtents();
    }
    if (sweepNeeded_) {
        sweepNewProxies();  // O(n + new proxies x their neighbours along the axis)
    }
    resolveCandidates();         // O(c log c)
    collectRemovedProxyPairs();  // O(pairs), only if something was removed
    mergePairs();                // O(pairs), only if something changed
    releaseIds();
    structureChanged_ = false;
}

void SweepAndPrune::dropRemovedEndpoints() {
    bool anyIndexed = false;
    for (const std::uint32_t id : removing_) {
        const Proxy& proxy = proxies_[id];
        if (proxy.isIndexed) {
            addCentre(proxy.box, -1);
            --liveCount_;
            anyIndexed = true;
        }
    }
    if (!anyIndexed) {
        return;
    }
    for (std::vector<Endpoint>& list : endpoints_) {
        std::erase_if(list, [this](const Endpoint& endpoint) {
            return proxies_[endpoint.proxy()].state == State::Removing;
        });
    }
    structureChanged_ = true;
}

void SweepAndPrune::insertPendingEndpoints() {
    if (pending_.empty()) {
        return;
    }
    for (int axis = 0; axis < 3; ++axis) {
        scratchEndpoints_.clear();
        for (const std::uint32_t id : pending_) {
            const Aabb& box = proxies_[id].box;
            scratchEndpoints_.push_back({box.lower[axis], id * 2});
            scratchEndpoints_.push_back({box.upper[axis], id * 2 + 1});
        }
        std::sort(scratchEndpoints_.begin(), scratchEndpoints_.end(),
                  [](const Endpoint& a, const Endpoint& b) { return precedesTotal(a, b); });
        // Merge from the back, in place: O(n + k).
        std::vector<Endpoint>& list = endpoints_[axis];
        std::size_t oldIndex = list.size();
        std::size_t newIndex = scratchEndpoints_.size();
        list.resize(oldIndex + newIndex);
        std::size_t out = list.size();
        while (newIndex > 0) {
            if (oldIndex > 0 && precedes(scratchEndpoints_[newIndex - 1], list[oldIndex - 1])) {
                list[--out] = list[--oldIndex];
            } else {
                list[--out] = scratchEndpoints_[--newIndex];
            }
        }
    }
    for (const std::uint32_t id : pending_) {
        Proxy& proxy = proxies_[id];
        proxy.state = State::Live;
        proxy.isIndexed = true;
        addCentre(proxy.box, +1);
        ++liveCount_;
    }
    pending_.clear();
    structureChanged_ = true;
    sweepNeeded_ = true;
}

void SweepAndPrune::reindex() {
    for (int axis = 0; axis < 3; ++axis) {
        const std::vector<Endpoint>& list = endpoints_[axis];
        for (std::size_t i = 0; i < list.size(); ++i) {
            proxies_[list[i].proxy()].endpoint[axis][list[i].isUpper()] =
                static_cast<std::uint32_t>(i);
        }
    }
}

void SweepAndPrune::applyMoves() {
    for (const Move& move : moves_) {
        Proxy& proxy = proxies_[move.proxy];
        proxy.moveSlot = kNone;
        if (proxy.state != State::Live) {
            continue;  // removed after it was moved
        }
        addCentre(proxy.box, -1);
        for (int axis = 0; axis < 3; ++axis) {
            // Back-pointers change while bubbling: read each index just before its move. The
            // box takes the new values one by one (moveEndpoint).
            moveEndpoint(axis, proxy.endpoint[axis][0], move.box.lower[axis]);
            moveEndpoint(axis, proxy.endpoint[axis][1], move.box.upper[axis]);
        }
        addCentre(proxy.box, +1);
        classifyExtent(move.proxy);
    }
    moves_.clear();
}

void SweepAndPrune::moveEndpoint(int axis, std::uint32_t index, Real value) {
    std::vector<Endpoint>& list = endpoints_[axis];
    Endpoint moving = list[index];
    moving.value = value;
    Aabb& box = proxies_[moving.proxy()].box;
    (moving.isUpper() ? box.upper : box.lower)[axis] = value;
    // A swap of a lower with an upper endpoint of another proxy changes that pair's overlap iff
    // the two overlap on the other axes.
    const int j = (axis + 1) % 3;
    const int k = (axis + 2) % 3;
    auto pass = [&](const Endpoint& other, std::uint32_t otherIndex) {
        Proxy& otherProxy = proxies_[other.proxy()];
        const bool changes = (unsigned{other.isUpper() != moving.isUpper()} &
                              unsigned{other.proxy() != moving.proxy()} &
                              unsigned{overlapsOn(box, otherProxy.box, j, k)}) != 0;
        if (changes) {
            candidates_.push_back(makePair(other.proxy(), moving.proxy()));
        }
        list[otherIndex] = other;
        otherProxy.endpoint[axis][other.isUpper()] = otherIndex;
    };
    while (index > 0 && precedes(moving, list[index - 1])) {
        pass(list[index - 1], index);
        --index;
    }
    while (index + 1 < list.size() && precedes(list[index + 1], moving)) {
        pass(list[index + 1], index);
        ++index;
    }
    list[index] = moving;
    proxies_[moving.proxy()].endpoint[axis][moving.isUpper()] = index;
}

void SweepAndPrune::sweepNewProxies() {
    // Sort-and-sweep along the sweep axis, testing only pairs with at least one new proxy:
    // a new proxy's lower endpoint meets every open interval, an old one's only the new ones.
    activeOld_.clear();
    activeNew_.clear();
    // Both open on the sweep axis means they overlap on it; test the other two.
    const int j = (axis_ + 1) % 3;
    const int k = (axis_ + 2) % 3;
    auto testAgainst = [&](std::uint32_t id, const std::vector<std::uint32_t>& active) {
        const Aabb& box = proxies_[id].box;
        for (const std::uint32_t other : active) {
            if (overlapsOn(box, proxies_[other].box, j, k)) {
                candidates_.push_back(makePair(id, other));
            }
        }
    };
    for (const Endpoint& endpoint : endpoints_[axis_]) {
        const std::uint32_t id = endpoint.proxy();
        Proxy& proxy = proxies_[id];
        std::vector<std::uint32_t>& active = proxy.isNew ? activeNew_ : activeOld_;
        if (endpoint.isUpper()) {
            const std::uint32_t last = active.back();
            active[proxy.activeSlot] = last;
            proxies_[last].activeSlot = proxy.activeSlot;
            active.pop_back();
            proxy.activeSlot = kNone;
            proxy.isNew = false;  // its upper end comes after its lower: done with it
            continue;
        }
        if (proxy.isNew) {
            testAgainst(id, activeOld_);
        }
        testAgainst(id, activeNew_);
        proxy.activeSlot = static_cast<std::uint32_t>(active.size());
        active.push_back(id);
    }
    sweepNeeded_ = false;
}

bool SweepAndPrune::mayPair(std::uint32_t a, std::uint32_t b) const {
    const ProxyFilter& filterA = proxies_[a].filter;
    const ProxyFilter& filterB = proxies_[b].filter;
    if ((filterA.isStatic && filterB.isStatic) || (filterA.category & filterB.mask) == 0 ||
        (filterB.category & filterA.mask) == 0) {
        return false;
    }
    return excluded_.empty() ||
           !std::binary_search(excluded_.begin(), excluded_.end(), makePair(a, b));
}

void SweepAndPrune::resolveCandidates() {
    added_.clear();
    removedByTest_.clear();
    std::sort(candidates_.begin(), candidates_.end());
    candidates_.erase(std::unique(candidates_.begin(), candidates_.end()), candidates_.end());
    for (const ProxyPair pair : candidates_) {
        const Proxy& first = proxies_[pair.first];
        const Proxy& second = proxies_[pair.second];
        if (first.state != State::Live || second.state != State::Live) {
            continue;  // pairs of removed proxies are collected from pairs_
        }
        const bool was = std::binary_search(pairs_.begin(), pairs_.end(), pair);
        const bool is = first.box.overlaps(second.box) && mayPair(pair.first, pair.second);
        if (is && !was) {
            added_.push_back(pair);
        } else if (was && !is) {
            removedByTest_.push_back(pair);
        }
    }
    candidates_.clear();
}

void SweepAndPrune::collectRemovedProxyPairs() {
    removedByProxy_.clear();
    if (removing_.empty()) {
        return;
    }
    for (const ProxyPair pair : pairs_) {
        if (proxies_[pair.first].state == State::Removing ||
            proxies_[pair.second].state == State::Removing) {
            removedByProxy_.push_back(pair);
        }
    }
}

void SweepAndPrune::mergePairs() {
    removed_.clear();
    std::merge(removedByProxy_.begin(), removedByProxy_.end(), removedByTest_.begin(),
               removedByTest_.end(), std::back_inserter(removed_));
    if (added_.empty() && removed_.empty()) {
        return;
    }
    detail::applyPairChanges(pairs_, added_, removed_, scratchPairs_);
}

void SweepAndPrune::releaseIds() {
    for (const std::uint32_t id : removing_) {
        proxies_[id] = Proxy{};
        freeIds_.push_back(id);
        std::push_heap(freeIds_.begin(), freeIds_.end(), std::greater<>());
    }
    removing_.clear();
}

void SweepAndPrune::addCentre(const Aabb& box, Real sign) {
    const Vec3 centre = box.center() - centreReference_;
    centreSum_ += sign * centre;
    centreSquareSum_ += sign * centre.cwiseProduct(centre);
}

void SweepAndPrune::chooseAxis() {
    if (liveCount_ < 2) {
        return;
    }
    const Real count = static_cast<Real>(liveCount_);
    const Vec3 mean = centreSum_ / count;
    const Vec3 variance = centreSquareSum_ / count - mean.cwiseProduct(mean);
    int best = 0;
    variance.maxCoeff(&best);
    if (best != axis_ && variance[best] > kAxisSwitchFactor * variance[axis_]) {
        axis_ = best;
        structureChanged_ = true;  // extents along the new axis: rescanExtents()
    }
}

void SweepAndPrune::rescanExtents() {
    // Also re-centres the variance sums, so their rounding does not accumulate.
    Real extentSum = 0;
    Vec3 centreTotal = Vec3::Zero();
    for (const Proxy& proxy : proxies_) {
        if (proxy.state == State::Live) {
            extentSum += extentAlong(proxy.box, axis_);
            centreTotal += proxy.box.center();
        }
    }
    const Real count = std::max<Real>(1, static_cast<Real>(liveCount_));
    largeThreshold_ = kLargeExtentFactor * extentSum / count;
    centreReference_ = centreTotal / count;
    centreSum_.setZero();
    centreSquareSum_.setZero();
    large_.clear();
    reach_ = 0;
    for (std::uint32_t id = 0; id < proxies_.size(); ++id) {
        Proxy& proxy = proxies_[id];
        if (proxy.state != State::Live) {
            continue;
        }
        addCentre(proxy.box, +1);
        const Real extent = extentAlong(proxy.box, axis_);
        proxy.isLarge = extent > largeThreshold_;
        if (proxy.isLarge) {
            large_.push_back(id);
        } else {
            reach_ = std::max(reach_, extent);
        }
    }
}

void SweepAndPrune::classifyExtent(std::uint32_t id) {
    Proxy& proxy = proxies_[id];
    if (proxy.isLarge) {
        return;  // stays large until the next rescan: only costs a direct test per query
    }
    const Real extent = extentAlong(proxy.box, axis_);
    if (extent > largeThreshold_) {
        proxy.isLarge = true;
        large_.insert(std::lower_bound(large_.begin(), large_.end(), id), id);
    } else {
        reach_ = std::max(reach_, extent);
    }
}

Real SweepAndPrune::reachWithSlack(Real value) const {
    return reach_ + kReachSlack * (std::abs(value) + reach_);
}

std::size_t SweepAndPrune::walkStart(Real value) const {
    const std::vector<Endpoint>& list = endpoints_[axis_];
    const Real bound = value - reachWithSlack(value);
    return static_cast<std::size_t>(
        std::lower_bound(list.begin(), list.end(), bound,
                         [](const Endpoint& e, Real v) { return e.value < v; }) -
        list.begin());
}

std::size_t SweepAndPrune::walkEnd(Real value) const {
    const std::vector<Endpoint>& list = endpoints_[axis_];
    return static_cast<std::size_t>(
        std::upper_bound(list.begin(), list.end(), value,
                         [](Real v, const Endpoint& e) { return v < e.value; }) -
        list.begin());
}

void SweepAndPrune::checkRay(const Vec3& origin, const Vec3& direction, Real maxFraction) {
    if (!isFinite(origin) || !isFinite(direction) || !std::isfinite(maxFraction)) {
        fail("SweepAndPrune::raycast: origin = [", origin.transpose(), "], direction = [",
             direction.transpose(), "], maxFraction = ", maxFraction, " must be finite");
    }
}

bool SweepAndPrune::isConsistent() const {
    std::vector<std::uint32_t> live;
    for (std::uint32_t id = 0; id < proxies_.size(); ++id) {
        if (proxies_[id].isIndexed && proxies_[id].state != State::Pending) {
            live.push_back(id);
        }
    }
    if (live.size() != liveCount_) {
        return false;
    }
    for (int axis = 0; axis < 3; ++axis) {
        const std::vector<Endpoint>& list = endpoints_[axis];
        if (list.size() != 2 * live.size()) {
            return false;
        }
        for (std::size_t i = 0; i < list.size(); ++i) {
            const Proxy& proxy = proxies_[list[i].proxy()];
            const Real expected = list[i].isUpper() ? proxy.box.upper[axis] : proxy.box.lower[axis];
            if (list[i].value != expected || proxy.endpoint[axis][list[i].isUpper()] != i ||
                (i > 0 && precedes(list[i], list[i - 1]))) {
                return false;
            }
        }
    }
    std::vector<ProxyPair> expected;
    for (std::size_t i = 0; i < live.size(); ++i) {
        const Proxy& proxy = proxies_[live[i]];
        if (!proxy.isLarge && extentAlong(proxy.box, axis_) > reach_) {
            return false;
        }
        for (std::size_t j = i + 1; j < live.size(); ++j) {
            if (proxy.box.overlaps(proxies_[live[j]].box) && mayPair(live[i], live[j])) {
                expected.push_back({live[i], live[j]});
            }
        }
    }
    return expected == pairs_;
}

}  // namespace tumble
