#pragma once
/// The randomised harness both broadphases (SweepAndPrune, GridBroadphase) are tested with
/// against the brute-force reference: a population of moving boxes with the engine's fat-box
/// policy, the reference pair set, and the reference ray-box test.

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <iterator>
#include <random>
#include <vector>

#include "tumble/collision/grid_broadphase.h"
#include "tumble/collision/sweep_and_prune.h"

namespace tumble::test {

inline std::vector<ProxyPair> difference(const std::vector<ProxyPair>& a,
                                         const std::vector<ProxyPair>& b) {
    std::vector<ProxyPair> out;
    std::set_difference(a.begin(), a.end(), b.begin(), b.end(), std::back_inserter(out));
    return out;
}

inline Aabb boxAt(const Vec3& centre, const Vec3& half) {
    return {centre - half, centre + half};
}

/// Cells of 2.5 m for the grid: ordinary fat boxes (0.6-2.4 m) touch 1-8 cells; the big ones
/// (6.4-12.4 m) touch 27-216, so some are oversized (> 64 cells) and some are not.
constexpr Real kCellSize = 2.5;

/// How each broadphase is made for the harness.
template <class Broadphase>
Broadphase makeBroadphase() {
    return Broadphase{};
}
template <>
inline GridBroadphase makeBroadphase<GridBroadphase>() {
    return GridBroadphase{kCellSize};
}

/// Moving boxes with the engine's fat-box policy; ids are the broadphase's, `live` marks which
/// are in use.
template <class Broadphase>
struct BroadphaseScene {
    std::mt19937 rng{4242};
    Real side = 30;     ///< boxes live in [0, side]^3 (m)
    Real margin = 0.2;  ///< fat-box margin (m)
    std::vector<Aabb> tight;
    std::vector<Aabb> fat;
    std::vector<Vec3> velocity;
    std::vector<ProxyFilter> filters;
    std::vector<bool> live;
    std::vector<ProxyPair> excluded;  ///< sorted
    Broadphase broadphase = makeBroadphase<Broadphase>();

    Real uniform(Real lo, Real hi) { return std::uniform_real_distribution<Real>(lo, hi)(rng); }
    Vec3 randomPoint() { return Vec3(uniform(0, side), uniform(0, side), uniform(0, side)); }

    static ProxyFilter randomFilter(int kind) {
        ProxyFilter filter;
        if (kind % 20 == 0) {
            filter.isStatic = true;
        } else if (kind % 10 == 3) {
            filter.category = 2;
            filter.mask = ~2u;  // category 2 ignores its own kind
        } else if (kind % 10 == 7) {
            filter.category = 4;
            filter.mask = 1;  // meets only category 1: one-way masks must be checked both ways
        }
        return filter;
    }

    std::uint32_t addProxy(const Aabb& box, const ProxyFilter& filter) {
        const std::uint32_t id = broadphase.add(box, filter);
        if (id >= tight.size()) {
            tight.resize(id + 1);
            fat.resize(id + 1);
            velocity.resize(id + 1);
            filters.resize(id + 1);
            live.resize(id + 1);
        }
        tight[id] = {box.lower.array() + margin, box.upper.array() - margin};
        fat[id] = box;
        velocity[id] = Vec3::Zero();
        filters[id] = filter;
        live[id] = true;
        return id;
    }

    /// A random box, 1 in 97 big (3-6 m); `kind` picks its filter.
    std::uint32_t addBox(int kind) {
        const bool big = kind % 97 == 5;
        const Real half = big ? uniform(3, 6) : uniform(0.1, 1.0);
        const Vec3 halfExtents(half * uniform(0.5, 1.5), half * uniform(0.5, 1.5), half);
        return addProxy(boxAt(randomPoint(), halfExtents).fattened(margin), randomFilter(kind));
    }

    /// A static ground slab under the whole scene (oversized in the grid).
    std::uint32_t addGround() {
        ProxyFilter filter;
        filter.isStatic = true;
        return addProxy({Vec3(-1, -1, -2), Vec3(side + 1, side + 1, 1)}, filter);
    }

    void removeBox(std::uint32_t id) {
        broadphase.remove(id);
        live[id] = false;
        std::erase_if(excluded, [id](ProxyPair p) { return p.first == id || p.second == id; });
    }

    void toggleExclusion(ProxyPair pair) {
        const auto at = std::lower_bound(excluded.begin(), excluded.end(), pair);
        const bool present = at != excluded.end() && *at == pair;
        broadphase.setPairExcluded(pair.first, pair.second, !present);
        if (present) {
            excluded.erase(at);
        } else {
            excluded.insert(at, pair);
        }
    }

    void setBox(std::uint32_t id, const Aabb& box) {
        fat[id] = box;
        tight[id] = {box.lower.array() + margin, box.upper.array() - margin};
        broadphase.move(id, box);
    }

    /// Random-walk velocities, reflected at the walls; occasionally a teleport (a big jump).
    void step(Real speed) {
        for (std::uint32_t id = 0; id < tight.size(); ++id) {
            if (!live[id] || filters[id].isStatic) {
                continue;
            }
            velocity[id] += speed * Vec3(uniform(-1, 1), uniform(-1, 1), uniform(-1, 1));
            velocity[id] *= 0.9;
            Vec3 shift = velocity[id];
            if (uniform(0, 1) < 0.002) {
                shift = randomPoint() - tight[id].center();
            }
            for (int axis = 0; axis < 3; ++axis) {
                if ((tight[id].center()[axis] + shift[axis] < 0 && shift[axis] < 0) ||
                    (tight[id].center()[axis] + shift[axis] > side && shift[axis] > 0)) {
                    shift[axis] = -shift[axis];
                    velocity[id][axis] = -velocity[id][axis];
                }
            }
            tight[id] = {tight[id].lower + shift, tight[id].upper + shift};
            if (refitFatBox(fat[id], tight[id], margin)) {
                broadphase.move(id, fat[id]);
            }
        }
    }

    /// Brute force over the live proxies (ids ascending, so the mapping keeps pairs sorted),
    /// minus the excluded pairs.
    std::vector<ProxyPair> reference() const {
        std::vector<Aabb> boxes;
        std::vector<ProxyFilter> liveFilters;
        std::vector<std::uint32_t> ids;
        for (std::uint32_t id = 0; id < tight.size(); ++id) {
            if (live[id]) {
                boxes.push_back(fat[id]);
                liveFilters.push_back(filters[id]);
                ids.push_back(id);
            }
        }
        std::vector<ProxyPair> pairs;
        for (const ProxyPair pair : bruteForcePairs(boxes, liveFilters)) {
            const ProxyPair mapped{ids[pair.first], ids[pair.second]};
            if (!std::binary_search(excluded.begin(), excluded.end(), mapped)) {
                pairs.push_back(mapped);
            }
        }
        return pairs;
    }

    /// Updates and checks the pair set and its changes against the brute force; returns the
    /// number of changes.
    std::size_t updateAndCompare(std::vector<ProxyPair>& previous, int step) {
        broadphase.update();
        const std::vector<ProxyPair> expected = reference();
        EXPECT_EQ(broadphase.pairs(), expected) << "step " << step;
        EXPECT_EQ(broadphase.addedPairs(), difference(expected, previous)) << "step " << step;
        EXPECT_EQ(broadphase.removedPairs(), difference(previous, expected)) << "step " << step;
        const std::size_t changes =
            broadphase.addedPairs().size() + broadphase.removedPairs().size();
        previous = expected;
        return changes;
    }
};

/// The reference segment test, written independently: clip [0, maxFraction] slab by slab;
/// the entry fraction, or -1 for a miss.
inline Real referenceEntry(const Vec3& origin, const Vec3& direction, Real maxFraction,
                           const Aabb& box) {
    Real lo = 0;
    Real hi = maxFraction;
    for (int axis = 0; axis < 3; ++axis) {
        if (direction[axis] == 0) {
            if (origin[axis] < box.lower[axis] || origin[axis] > box.upper[axis]) {
                return -1;
            }
            continue;
        }
        const Real t1 = (box.lower[axis] - origin[axis]) / direction[axis];
        const Real t2 = (box.upper[axis] - origin[axis]) / direction[axis];
        lo = std::max(lo, std::min(t1, t2));
        hi = std::min(hi, std::max(t1, t2));
    }
    return lo <= hi ? lo : -1;
}

}  // namespace tumble::test
