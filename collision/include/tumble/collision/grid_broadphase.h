#pragma once
/// GridBroadphase: multi-box pruning. Space is cut into a uniform grid of cubic cells; each cell
/// that some proxy's box touches holds a SweepAndPrune of those proxies, and a proxy touching
/// several cells is in each of them. A SAP's update cost grows with how many endpoints a moving
/// endpoint passes, i.e. with the number of boxes per metre of axis; a cell bounds that number,
/// so at a fixed density the total cost grows linearly with the number of proxies (a single SAP
/// over a volume grows as n^(5/3), see sweep_and_prune.cpp).
///
/// Pairs: two proxies sharing k cells are found by each of the k cells. A global count per pair
/// (cells + the oversized SAP + the oversized-vs-ordinary test) decides: a pair is overlapping
/// while its count is positive. Exclusions are applied on top of the counts, globally.
///
/// Oversized proxies (touching more than maxCellsPerProxy cells, e.g. a ground box) are not put
/// into cells: they live in one SweepAndPrune of their own (pairs among them), and pairs of an
/// oversized proxy with an ordinary one are tested directly whenever either of them is added,
/// moved, re-filtered or removed (few oversized proxies: cost moved x oversized, plus n per moved
/// oversized proxy).
///
/// The interface mirrors SweepAndPrune's, so the engine can switch by changing a type. Same
/// semantics: ids are dense, the smallest free one is reused, and only after the update that
/// reported the removed proxy's pairs; everything takes effect at update(); outputs are sorted.
///
/// Determinism: cells are keyed by integer coordinates in a std::map and indexed in creation
/// order; every pair list is sorted before it is used. Empty cells are kept (with their buffers)
/// so that bodies returning to a region cost no allocation; memory grows with the region ever
/// visited, (cellSize)^3 per ~1 KB.

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <map>
#include <vector>

#include "tumble/collision/aabb.h"
#include "tumble/collision/sweep_and_prune.h"

namespace tumble {

class GridBroadphase {
    friend struct CheckpointAccess;  ///< the engine's checkpoint saves and restores the state
public:
    /// Default cell edge (m): a few times the size of a typical body (0.5-2 m), so most proxies
    /// touch 1-8 cells and a cell holds tens to hundreds of proxies.
    static constexpr Real kDefaultCellSize = 8;
    /// Default limit on the cells a proxy may touch before it counts as oversized.
    static constexpr std::uint32_t kDefaultMaxCellsPerProxy = 64;

    /// cellSize: edge of the cubic cells (m), finite and > 0. maxCellsPerProxy: a proxy touching
    /// more cells than this goes to the oversized list, >= 1. Throws InvalidArgument otherwise.
    explicit GridBroadphase(Real cellSize = kDefaultCellSize,
                            std::uint32_t maxCellsPerProxy = kDefaultMaxCellsPerProxy);

    /// As SweepAndPrune::add: returns the smallest free id; the proxy joins at the next update().
    std::uint32_t add(const Aabb& box, const ProxyFilter& filter);
    /// As SweepAndPrune::remove.
    void remove(std::uint32_t proxy);
    /// As SweepAndPrune::move.
    void move(std::uint32_t proxy, const Aabb& box);
    /// As SweepAndPrune::setFilter.
    void setFilter(std::uint32_t proxy, const ProxyFilter& filter);
    /// As SweepAndPrune::setPairExcluded.
    void setPairExcluded(std::uint32_t a, std::uint32_t b, bool excluded);
    /// Updates the cells touched since the last update and the pair set. Allocates nothing once
    /// buffers have grown (creating a cell allocates).
    void update();

    const std::vector<ProxyPair>& pairs() const { return pairs_; }  ///< overlapping, sorted
    /// Pairs that appeared at the last update(), sorted.
    const std::vector<ProxyPair>& addedPairs() const { return added_; }
    /// Pairs that disappeared at the last update(), sorted.
    const std::vector<ProxyPair>& removedPairs() const { return removed_; }
    /// The box of a proxy as of the last update() (m).
    const Aabb& box(std::uint32_t proxy) const { return proxies_[proxy].publishedBox; }
    /// Number of proxies as of the last update().
    std::uint32_t proxyCount() const { return liveCount_; }
    /// Cell edge (m).
    Real cellSize() const { return cellSize_; }
    /// Number of cells created so far (empty ones included).
    std::size_t cellCount() const { return cells_.size(); }
    /// Number of proxies in the oversized list as of the last update().
    std::size_t oversizedCount() const { return oversizedPublished_.size(); }

    /// Calls visit(proxy) once for each proxy whose box overlaps `box` (touching counts), as of
    /// the last update(). A proxy in several cells is visited in one of them only: the first
    /// cell (lowest coordinates) shared by its cell range and the query's, a stateless rule.
    template <typename Visit>
    void query(const Aabb& box, Visit&& visit) const;

    /// As SweepAndPrune::raycast: visit(proxy, maxFraction) for each box the segment (clipped to
    /// the current maxFraction) hits, returning the new maxFraction. Cells are walked along the
    /// segment, front to back; each proxy is visited at most once. Uses a scratch mark per
    /// proxy: not safe to call from several threads at once.
    template <typename Visit>
    void raycast(const Vec3& origin, const Vec3& direction, Real maxFraction, Visit&& visit) const;

    /// Checks the pair set against an O(n^2) test and every cell against its own invariants; for
    /// tests and debug builds.
    bool isConsistent() const;

private:
    static constexpr std::uint32_t kNone = 0xFFFFFFFF;
    /// Cell coordinates are clamped to +-kCoordinateLimit (the clamp keeps floor monotonic, so
    /// far-away boxes share edge cells but no pair is lost).
    static constexpr std::int32_t kCoordinateLimit = 1 << 29;
    enum class State : std::uint8_t { Free, Pending, Live, Removing };
    using CellKey = std::array<std::int32_t, 3>;

    struct CellRange {
        CellKey lower{};
        CellKey upper{};
        bool contains(const CellKey& key) const;
    };

    struct Cell {
        SweepAndPrune sap;
        std::vector<std::uint32_t> globalId;  ///< global id of each local id
        CellKey key{};
        bool isDirty = false;
    };

    struct Membership {
        std::uint32_t cell;
        std::uint32_t local;
    };

    struct Proxy {
        Aabb box;           ///< latest box given (m)
        Aabb publishedBox;  ///< as of the last update (m)
        ProxyFilter filter;
        CellRange range;           ///< cells it is in now (ordinary proxies)
        CellRange publishedRange;  ///< cells it was indexed in at the last update
        std::vector<Membership> cells;
        std::uint32_t oversizedLocal = kNone;  ///< id in oversized_ while oversized
        State state = State::Free;
        bool isOversized = false;
        bool wasOversized = false;  ///< as of the last update
        bool isDirty = false;       ///< in dirty_ (its cross pairs are re-tested)
        bool wasLive = false;       ///< counted in liveCount_
    };

    struct PairDelta {
        ProxyPair pair;
        std::int32_t delta;
    };
    struct PairCount {
        ProxyPair pair;
        std::uint32_t count;
    };

    // Proxy placement (grid_broadphase.cpp).
    CellRange rangeOf(const Aabb& box) const;
    std::int32_t coordinateOf(Real value) const;
    bool isOversizedRange(const CellRange& range) const;
    void place(std::uint32_t id);
    void unplace(std::uint32_t id);
    void moveWithinCells(std::uint32_t id, const CellRange& newRange);
    std::uint32_t cellAt(const CellKey& key);
    void markCell(std::uint32_t cell);
    void markDirty(std::uint32_t id);
    void checkId(std::uint32_t proxy, const char* what) const;

    // Update stages, in order.
    void collectCellDeltas();
    void collectOversizedDeltas();
    void collectCrossDeltas();
    void applyDeltas();
    void decideReportedPairs();
    void publish();

    bool filtersPass(std::uint32_t a, std::uint32_t b) const;
    bool isExcluded(ProxyPair pair) const;
    /// Calls visitCell(index) for every existing cell the segment origin + t direction,
    /// t in [0, maxFraction], passes through (maxFraction read anew after each visit), in
    /// order along the segment; a cell may be visited more than once.
    template <typename VisitCell>
    void walkRay(const Vec3& origin, const Vec3& direction, const Real& maxFraction,
                 VisitCell&& visitCell) const;
    template <typename VisitCell>
    void visitEveryCellHit(const Vec3& origin, const Vec3& direction, const Real& maxFraction,
                           VisitCell&& visitCell) const;
    template <typename VisitCell>
    void visitRange(const CellRange& range, VisitCell&& visitCell) const;

    Real cellSize_;
    Real inverseCellSize_;
    std::uint32_t maxCellsPerProxy_;
    std::vector<Proxy> proxies_;
    std::vector<Cell> cells_;
    std::map<CellKey, std::uint32_t> cellIndex_;
    SweepAndPrune oversized_;
    std::vector<std::uint32_t> oversizedGlobal_;     ///< global id of each oversized local id
    std::vector<std::uint32_t> oversizedList_;       ///< oversized proxies now, sorted
    std::vector<std::uint32_t> oversizedPublished_;  ///< as of the last update, sorted
    bool oversizedDirty_ = false;
    std::vector<std::uint32_t> dirtyCells_;
    std::vector<std::uint32_t> dirty_;    ///< proxies added, moved, re-filtered or removed
    std::vector<std::uint32_t> freeIds_;  ///< min-heap
    std::vector<ProxyPair> excluded_;     ///< sorted
    std::vector<ProxyPair> toggled_;      ///< exclusions changed since the last update
    std::vector<ProxyPair> crossPairs_;   ///< oversized-ordinary overlaps (filters applied), sorted
    std::vector<PairCount> counts_;       ///< pairs with positive count, sorted
    std::vector<PairDelta> deltas_;
    std::vector<ProxyPair> crossCandidates_;
    std::vector<ProxyPair> crossAdded_;
    std::vector<ProxyPair> crossRemoved_;
    std::vector<ProxyPair> countChanged_;  ///< pairs whose count went 0 -> + or + -> 0
    std::vector<PairCount> scratchCounts_;
    std::vector<ProxyPair> scratchPairs_;
    std::vector<ProxyPair> pairs_;
    std::vector<ProxyPair> added_;
    std::vector<ProxyPair> removed_;
    std::uint32_t liveCount_ = 0;
    mutable std::vector<std::uint32_t> visitMark_;  ///< raycast: last ray that visited a proxy
    mutable std::uint32_t rayStamp_ = 0;
};

// ---- templates ------------------------------------------------------------------------------

template <typename Visit>
void GridBroadphase::query(const Aabb& box, Visit&& visit) const {
    oversized_.query(box, [&](std::uint32_t local) { visit(oversizedGlobal_[local]); });
    const CellRange range = rangeOf(box);
    auto queryCell = [&](const Cell& cell) {
        cell.sap.query(box, [&](std::uint32_t local) {
            const std::uint32_t id = cell.globalId[local];
            const CellRange& own = proxies_[id].publishedRange;
            // Visit in the lowest cell shared by both ranges: it exists (the proxy is in it)
            // and the query reaches it.
            for (int axis = 0; axis < 3; ++axis) {
                if (cell.key[axis] != std::max(own.lower[axis], range.lower[axis])) {
                    return;
                }
            }
            visit(id);
        });
    };
    Real volume = 1;
    for (int axis = 0; axis < 3; ++axis) {
        volume *= static_cast<Real>(range.upper[axis]) - range.lower[axis] + 1;
    }
    if (volume > static_cast<Real>(cells_.size())) {
        for (const Cell& cell : cells_) {  // a huge query: cheaper to filter the cells
            if (range.contains(cell.key)) {
                queryCell(cell);
            }
        }
        return;
    }
    visitRange(range, [&](std::uint32_t index) { queryCell(cells_[index]); });
}

template <typename VisitCell>
void GridBroadphase::visitRange(const CellRange& range, VisitCell&& visitCell) const {
    CellKey key;
    for (key[0] = range.lower[0]; key[0] <= range.upper[0]; ++key[0]) {
        for (key[1] = range.lower[1]; key[1] <= range.upper[1]; ++key[1]) {
            for (key[2] = range.lower[2]; key[2] <= range.upper[2]; ++key[2]) {
                const auto found = cellIndex_.find(key);
                if (found != cellIndex_.end()) {
                    visitCell(found->second);
                }
            }
        }
    }
}

template <typename Visit>
void GridBroadphase::raycast(const Vec3& origin, const Vec3& direction, Real maxFraction,
                             Visit&& visit) const {
    if (visitMark_.size() < proxies_.size()) {
        visitMark_.resize(proxies_.size(), 0);
    }
    if (++rayStamp_ == 0) {  // wrapped: forget all marks
        std::fill(visitMark_.begin(), visitMark_.end(), 0);
        rayStamp_ = 1;
    }
    oversized_.raycast(origin, direction, maxFraction, [&](std::uint32_t local, Real fraction) {
        maxFraction = visit(oversizedGlobal_[local], fraction);
        return maxFraction;
    });
    walkRay(origin, direction, maxFraction, [&](std::uint32_t index) {
        const Cell& cell = cells_[index];
        cell.sap.raycast(origin, direction, maxFraction, [&](std::uint32_t local, Real fraction) {
            const std::uint32_t id = cell.globalId[local];
            if (visitMark_[id] != rayStamp_) {
                visitMark_[id] = rayStamp_;
                maxFraction = visit(id, fraction);
            }
            return maxFraction;
        });
    });
}

template <typename VisitCell>
void GridBroadphase::visitEveryCellHit(const Vec3& origin, const Vec3& direction,
                                       const Real& maxFraction, VisitCell&& visitCell) const {
    // A walk longer than the cell list: test every cell's (slightly grown) box instead; the
    // order is not front to back, which clipping tolerates.
    for (std::uint32_t index = 0; index < cells_.size() && maxFraction > 0; ++index) {
        const CellKey& key = cells_[index].key;
        const Vec3 lower(key[0], key[1], key[2]);
        const Aabb cellBox{(lower.array() - 1e-6) * cellSize_,
                           (lower.array() + 1 + 1e-6) * cellSize_};
        if (rayEntryFraction(origin, direction, maxFraction, cellBox) >= 0) {
            visitCell(index);
        }
    }
}

template <typename VisitCell>
void GridBroadphase::walkRay(const Vec3& origin, const Vec3& direction, const Real& maxFraction,
                             VisitCell&& visitCell) const {
    if (!(maxFraction > 0)) {
        return;
    }
    const Real limit = static_cast<Real>(kCoordinateLimit - 1) * cellSize_;
    Real crossings = 0;
    for (int axis = 0; axis < 3; ++axis) {
        crossings += std::abs(direction[axis]) * maxFraction * inverseCellSize_;
        if (std::abs(origin[axis]) > limit ||
            std::abs(origin[axis] + maxFraction * direction[axis]) > limit) {
            crossings = kNone;  // beyond the clamped grid: the walk below would be wrong
        }
    }
    if (crossings > static_cast<Real>(cells_.size()) + 8) {
        visitEveryCellHit(origin, direction, maxFraction, visitCell);
        return;
    }
    // Amanatides-Woo: the segment is cut where it crosses cell planes; each piece lies in one
    // cell. Floating point may put a piece's end points a hair across a plane, so each piece
    // visits the cells of its end points' box grown by `slack` (usually one cell, two or more
    // near a plane); the last cells visited are remembered so that neighbours are not redone.
    std::array<std::int32_t, 3> boundary{};
    std::array<Real, 3> nextTime{};
    std::array<Real, 3> slack{};
    for (int axis = 0; axis < 3; ++axis) {
        const Real d = direction[axis];
        const std::int32_t cell = coordinateOf(origin[axis]);
        boundary[axis] = d > 0 ? cell + 1 : cell;
        nextTime[axis] = d == 0 ? std::numeric_limits<Real>::infinity()
                                : (boundary[axis] * cellSize_ - origin[axis]) / d;
        slack[axis] = 1e-9 * (std::abs(origin[axis]) + std::abs(d) * maxFraction + cellSize_);
    }
    std::array<std::uint32_t, 16> recent;
    recent.fill(kNone);
    std::size_t recentAt = 0;
    Real start = 0;
    while (maxFraction > 0) {
        int axis = 0;
        for (int other = 1; other < 3; ++other) {
            axis = nextTime[other] < nextTime[axis] ? other : axis;
        }
        const Real end = std::max(start, std::min(nextTime[axis], maxFraction));
        CellRange piece;
        for (int k = 0; k < 3; ++k) {
            const Real a = origin[k] + start * direction[k];
            const Real b = origin[k] + end * direction[k];
            piece.lower[k] = coordinateOf(std::min(a, b) - slack[k]);
            piece.upper[k] = coordinateOf(std::max(a, b) + slack[k]);
        }
        visitRange(piece, [&](std::uint32_t index) {
            if (std::find(recent.begin(), recent.end(), index) == recent.end()) {
                recent[recentAt++ % recent.size()] = index;
                visitCell(index);
            }
        });
        if (nextTime[axis] >= maxFraction) {
            return;
        }
        start = end;
        boundary[axis] += direction[axis] > 0 ? 1 : -1;
        nextTime[axis] = (boundary[axis] * cellSize_ - origin[axis]) / direction[axis];
    }
}

}  // namespace tumble
