// GridBroadphase against the brute-force reference: pair sets, their changes, queries and rays,
// with cells small enough that boxes cross cell planes all the time.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <iterator>
#include <limits>
#include <random>
#include <vector>

#include "tumble/collision/grid_broadphase.h"
#include "tumble/collision/sweep_and_prune.h"
#include "tumble/core/error.h"

namespace tumble {
namespace {

std::vector<ProxyPair> difference(const std::vector<ProxyPair>& a,
                                  const std::vector<ProxyPair>& b) {
    std::vector<ProxyPair> out;
    std::set_difference(a.begin(), a.end(), b.begin(), b.end(), std::back_inserter(out));
    return out;
}

Aabb boxAt(const Vec3& centre, const Vec3& half) {
    return {centre - half, centre + half};
}

// Cells of 2.5 m: ordinary fat boxes (0.6-2.4 m) touch 1-8 cells; the big ones (6.4-12.4 m)
// touch 27-216, so some are oversized (> 64 cells) and some are not.
constexpr Real kCellSize = 2.5;

// Moving boxes with the engine's fat-box policy; ids are GridBroadphase ids.
struct Scene {
    std::mt19937 rng{4242};
    Real side = 30;     // boxes live in [0, side]^3 (m)
    Real margin = 0.2;  // fat-box margin (m)
    std::vector<Aabb> tight;
    std::vector<Aabb> fat;
    std::vector<Vec3> velocity;
    std::vector<ProxyFilter> filters;
    std::vector<bool> live;
    std::vector<ProxyPair> excluded;
    GridBroadphase grid{kCellSize};

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
        const std::uint32_t id = grid.add(box, filter);
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

    std::uint32_t addBox(int kind) {
        const bool big = kind % 97 == 5;
        const Real half = big ? uniform(3, 6) : uniform(0.1, 1.0);
        const Vec3 halfExtents(half * uniform(0.5, 1.5), half * uniform(0.5, 1.5), half);
        return addProxy(boxAt(randomPoint(), halfExtents).fattened(margin), randomFilter(kind));
    }

    // A static ground slab under the whole scene: oversized.
    std::uint32_t addGround() {
        ProxyFilter filter;
        filter.isStatic = true;
        return addProxy({Vec3(-1, -1, -2), Vec3(side + 1, side + 1, 1)}, filter);
    }

    void removeBox(std::uint32_t id) {
        grid.remove(id);
        live[id] = false;
        std::erase_if(excluded, [id](ProxyPair p) { return p.first == id || p.second == id; });
    }

    void toggleExclusion(ProxyPair pair) {
        const auto at = std::lower_bound(excluded.begin(), excluded.end(), pair);
        const bool present = at != excluded.end() && *at == pair;
        grid.setPairExcluded(pair.first, pair.second, !present);
        if (present) {
            excluded.erase(at);
        } else {
            excluded.insert(at, pair);
        }
    }

    void setBox(std::uint32_t id, const Aabb& box) {
        fat[id] = box;
        tight[id] = {box.lower.array() + margin, box.upper.array() - margin};
        grid.move(id, box);
    }

    // Random-walk velocities, reflected at the walls; occasionally a teleport (a big jump).
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
                grid.move(id, fat[id]);
            }
        }
    }

    // Brute force over the live proxies (ids ascending, so the mapping keeps pairs sorted),
    // minus the excluded pairs.
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
};

// Updates and checks the pair set and its changes against the brute force; returns the number
// of changes.
std::size_t updateAndCompare(Scene& scene, std::vector<ProxyPair>& previous, int step) {
    scene.grid.update();
    const std::vector<ProxyPair> expected = scene.reference();
    EXPECT_EQ(scene.grid.pairs(), expected) << "step " << step;
    EXPECT_EQ(scene.grid.addedPairs(), difference(expected, previous)) << "step " << step;
    EXPECT_EQ(scene.grid.removedPairs(), difference(previous, expected)) << "step " << step;
    const std::size_t changes = scene.grid.addedPairs().size() + scene.grid.removedPairs().size();
    previous = expected;
    return changes;
}

TEST(GridBroadphase, ThousandMovingBoxesMatchBruteForceEveryStep) {
    Scene scene;
    scene.addGround();
    for (int i = 0; i < 1000; ++i) {
        scene.addBox(i);
    }
    // Bodies "joined by joints": excluded pairs, one of which we later re-admit.
    for (std::uint32_t id = 1; id + 1 < 1000; id += 50) {
        scene.grid.setPairExcluded(id, id + 1, true);
        scene.excluded.push_back({id, id + 1});
    }
    std::vector<ProxyPair> previous;
    std::size_t changes = 0;
    std::size_t pairCount = 0;
    for (int step = 0; step < 200; ++step) {
        scene.step(step < 100 ? 0.02 : 0.15);  // slow, then fast
        if (step == 120) {
            scene.grid.setPairExcluded(1, 2, false);
            scene.excluded.erase(scene.excluded.begin());
        }
        changes += updateAndCompare(scene, previous, step);
        pairCount += scene.grid.pairs().size();
        if (step % 50 == 0) {
            EXPECT_TRUE(scene.grid.isConsistent()) << "step " << step;
        }
        if (testing::Test::HasFailure()) {
            break;
        }
    }
    EXPECT_EQ(scene.grid.proxyCount(), 1001u);
    // Most boxes straddle cell planes: count the cells each live fat box touches.
    int multiCell = 0;
    int upToEight = 0;
    for (std::uint32_t id = 0; id < scene.fat.size(); ++id) {
        const Vec3 lower = (scene.fat[id].lower / kCellSize).array().floor();
        const Vec3 upper = (scene.fat[id].upper / kCellSize).array().floor();
        const Real cells = (upper - lower + Vec3::Ones()).prod();
        multiCell += cells >= 2 ? 1 : 0;
        upToEight += cells <= 8 ? 1 : 0;
    }
    EXPECT_GT(multiCell, 500);
    EXPECT_GT(upToEight, 900);
    // The run must exercise the incremental path, the oversized list and many cells.
    EXPECT_GT(pairCount / 200, 300u);
    EXPECT_GT(changes, 2000u);
    EXPECT_GE(scene.grid.oversizedCount(), 2u);  // the ground and some big boxes
    EXPECT_GT(scene.grid.cellCount(), 1000u);
}

TEST(GridBroadphase, AddRemoveRefilterAndResizeMidRun) {
    Scene scene;
    scene.addGround();
    for (int i = 0; i < 300; ++i) {
        scene.addBox(i);
    }
    std::vector<ProxyPair> previous;
    int kind = 300;
    for (int step = 0; step < 150; ++step) {
        scene.step(0.1);
        for (int k = 0; k < 3; ++k) {
            const auto id = static_cast<std::uint32_t>(scene.uniform(0, 1) *
                                                       static_cast<Real>(scene.tight.size()));
            if (id < scene.tight.size() && scene.live[id]) {
                scene.removeBox(id);
            }
        }
        for (int k = 0; k < 3; ++k) {
            const std::uint32_t id = scene.addBox(kind++);
            if (k == 0 && step % 5 == 0) {
                scene.setBox(id, scene.fat[id]);  // moved before it was ever indexed
            }
            if (k == 1 && step % 7 == 0) {
                scene.removeBox(id);  // never seen by an update
            }
        }
        // Grow a live dynamic box into an oversized one, or shrink it back: it changes class.
        for (std::uint32_t id = static_cast<std::uint32_t>(step) % 40; id < scene.tight.size();
             ++id) {
            if (scene.live[id] && !scene.filters[id].isStatic) {
                const Vec3 centre = scene.fat[id].center();
                scene.setBox(id, boxAt(centre, Vec3::Constant(step % 2 == 0 ? 8.0 : 0.7)));
                break;
            }
        }
        if (step % 10 == 5) {
            for (std::uint32_t id = 0; id < scene.tight.size(); ++id) {
                if (scene.live[id] && !scene.filters[id].isStatic) {
                    scene.filters[id].mask = step % 20 == 5 ? 0u : 0xFFFFFFFFu;
                    scene.grid.setFilter(id, scene.filters[id]);
                    break;
                }
            }
        }
        if (step == 60) {
            // Re-filter the oversized ground: it may now pair with static boxes' categories
            // only through the same rules; make it dynamic to pair with statics too.
            scene.filters[0].isStatic = false;
            scene.grid.setFilter(0, scene.filters[0]);
        }
        if (step % 10 == 0) {
            for (std::uint32_t a = 0; a + 1 < scene.tight.size(); a += 37) {
                if (scene.live[a] && scene.live[a + 1]) {
                    scene.toggleExclusion({a, a + 1});
                }
            }
        }
        updateAndCompare(scene, previous, step);
        if (testing::Test::HasFailure()) {
            break;
        }
    }
    EXPECT_TRUE(scene.grid.isConsistent());
    // A removed id is reused, smallest first, once an update has reported its pairs.
    scene.removeBox(7);
    scene.removeBox(3);
    scene.grid.update();
    EXPECT_EQ(scene.addBox(0), 3u);
    EXPECT_EQ(scene.addBox(0), 7u);
}

// A scene for queries: random boxes, a few large, then some moved (one grown oversized).
Scene queryScene() {
    Scene scene;
    scene.side = 50;
    for (int i = 0; i < 2000; ++i) {
        scene.addBox(i);
    }
    scene.grid.update();
    for (std::uint32_t id = 0; id < 2000; id += 13) {
        const Real grow = id == 26 ? 20 : 0.5;
        scene.setBox(id, {scene.fat[id].lower.array() - grow, scene.fat[id].upper.array() + grow});
    }
    scene.grid.update();
    return scene;
}

TEST(GridBroadphase, QueryMatchesBruteForce) {
    Scene scene = queryScene();
    EXPECT_GE(scene.grid.oversizedCount(), 1u);
    std::size_t total = 0;
    for (int q = 0; q < 500; ++q) {
        const Vec3 half(scene.uniform(0, 4), scene.uniform(0, 4), scene.uniform(0, 4));
        Aabb box = boxAt(scene.randomPoint(), q % 50 == 0 ? Vec3(0, 0, 0) : half);
        if (q % 100 == 1) {
            box = boxAt(Vec3(25, 25, 25), Vec3(40, 40, 40));  // more cells than exist
        } else if (q % 50 == 2) {
            // Exactly on cell planes.
            box = {Vec3(5, 10, 15), Vec3(7.5, 12.5, 15)};
        }
        std::vector<std::uint32_t> found;
        scene.grid.query(box, [&](std::uint32_t id) { found.push_back(id); });
        std::sort(found.begin(), found.end());
        EXPECT_EQ(std::adjacent_find(found.begin(), found.end()), found.end()) << "duplicate";
        std::vector<std::uint32_t> expected;
        for (std::uint32_t id = 0; id < 2000; ++id) {
            if (scene.fat[id].overlaps(box)) {
                expected.push_back(id);
            }
        }
        ASSERT_EQ(found, expected) << "query " << q;
        total += found.size();
    }
    EXPECT_GT(total, 1000u);
}

// The reference segment test, written independently: clip [0, maxFraction] slab by slab.
Real referenceEntry(const Vec3& origin, const Vec3& direction, Real maxFraction, const Aabb& box) {
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

TEST(GridBroadphase, RaycastMatchesBruteForce) {
    Scene scene = queryScene();
    int closestHits = 0;
    for (int r = 0; r < 400; ++r) {
        Vec3 origin = scene.randomPoint();
        Vec3 direction(scene.uniform(-1, 1), scene.uniform(-1, 1), scene.uniform(-1, 1));
        if (r % 4 == 1) {
            direction[r % 3] = 0;  // rays in a coordinate plane
        } else if (r % 4 == 2) {
            direction = Vec3::Zero();
            direction[(r / 4) % 3] = r % 8 < 4 ? 1 : -1;  // axis-aligned, both senses
        }
        if (r % 8 == 3) {
            origin = kCellSize * origin.array().round();  // starts on a cell corner
        }
        direction *= r % 50 == 7 ? 1e5 : scene.uniform(5, 40);  // some walk past all cells
        const Real maxFraction = scene.uniform(0.2, 1.5);
        std::vector<std::uint32_t> found;
        scene.grid.raycast(origin, direction, maxFraction, [&](std::uint32_t id, Real fraction) {
            found.push_back(id);
            return fraction;
        });
        std::sort(found.begin(), found.end());
        EXPECT_EQ(std::adjacent_find(found.begin(), found.end()), found.end()) << "duplicate";
        std::vector<std::uint32_t> expected;
        Real closest = std::numeric_limits<Real>::infinity();
        std::uint32_t closestId = 0;
        for (std::uint32_t id = 0; id < 2000; ++id) {
            const Real entry = referenceEntry(origin, direction, maxFraction, scene.fat[id]);
            if (entry >= 0) {
                expected.push_back(id);
                if (entry < closest) {
                    closest = entry;
                    closestId = id;
                }
            }
        }
        ASSERT_EQ(found, expected) << "ray " << r;
        // Closest hit: clip at each box's entry fraction.
        Real best = maxFraction;
        std::uint32_t bestId = 0;
        bool hit = false;
        scene.grid.raycast(origin, direction, maxFraction, [&](std::uint32_t id, Real fraction) {
            const Real entry = rayEntryFraction(origin, direction, fraction, scene.fat[id]);
            if (entry >= 0 && (!hit || entry < best || (entry == best && id < bestId))) {
                best = entry;
                bestId = id;
                hit = true;
            }
            return hit ? std::max(best, Real(1e-300)) : fraction;  // 0 would stop the walk
        });
        EXPECT_EQ(hit, !expected.empty()) << "ray " << r;
        if (hit) {
            ++closestHits;
            EXPECT_EQ(best, closest) << "ray " << r;
            EXPECT_EQ(bestId, closestId) << "ray " << r;
        }
    }
    EXPECT_GT(closestHits, 100);
}

TEST(GridBroadphase, FilterStaticTouchingAcrossCellPlanesAndExclusion) {
    GridBroadphase grid(1.0);
    // a and b touch on the plane x = 1, which is also a cell plane.
    const std::uint32_t a = grid.add({Vec3(0, 0, 0), Vec3(1, 1, 1)}, {});
    const std::uint32_t b = grid.add({Vec3(1, 0, 0), Vec3(2, 1, 1)}, {});
    ProxyFilter staticFilter;
    staticFilter.isStatic = true;
    staticFilter.category = 1 | 2;
    const std::uint32_t c = grid.add({Vec3(0, 0, 0), Vec3(2, 2, 2)}, staticFilter);
    const std::uint32_t d = grid.add({Vec3(-20, -20, 0), Vec3(20, 20, 2)}, staticFilter);
    ProxyFilter oneWay;
    oneWay.category = 2;
    oneWay.mask = 2;
    const std::uint32_t e = grid.add({Vec3(0.5, 0.5, 0.5), Vec3(0.6, 0.6, 0.6)}, oneWay);
    grid.update();
    EXPECT_EQ(grid.oversizedCount(), 1u);  // d covers 40 x 40 x 3 cells
    const std::vector<ProxyPair> expected{{a, b}, {a, c}, {a, d}, {b, c}, {b, d}, {c, e}, {d, e}};
    EXPECT_EQ(grid.pairs(), expected);
    EXPECT_EQ(grid.addedPairs(), expected);
    grid.setPairExcluded(b, a, true);
    grid.update();
    EXPECT_EQ(grid.removedPairs(), (std::vector<ProxyPair>{{a, b}}));
    EXPECT_TRUE(grid.addedPairs().empty());
    grid.update();
    EXPECT_TRUE(grid.removedPairs().empty());
    EXPECT_TRUE(grid.addedPairs().empty());
    grid.setPairExcluded(a, b, false);
    grid.move(b, {Vec3(1 + 1e-9, 0, 0), Vec3(2, 1, 1)});  // a hair apart, now in one cell less
    grid.update();
    EXPECT_TRUE(grid.addedPairs().empty());
    EXPECT_TRUE(grid.removedPairs().empty());
    grid.move(b, {Vec3(1, 0, 0), Vec3(2, 1, 1)});
    grid.update();
    EXPECT_EQ(grid.addedPairs(), (std::vector<ProxyPair>{{a, b}}));
    // Pairs found in several cells are reported once and leave once.
    grid.move(a, {Vec3(0.5, 0.5, 0.5), Vec3(3.5, 3.5, 3.5)});
    grid.update();
    EXPECT_EQ(grid.pairs(), expected);
    grid.remove(c);
    grid.remove(d);
    grid.update();
    EXPECT_EQ(grid.removedPairs(),
              (std::vector<ProxyPair>{{a, c}, {a, d}, {b, c}, {b, d}, {c, e}, {d, e}}));
    EXPECT_EQ(grid.pairs(), (std::vector<ProxyPair>{{a, b}}));
    EXPECT_EQ(grid.proxyCount(), 3u);
    EXPECT_TRUE(grid.isConsistent());
}

TEST(GridBroadphase, FarAwayBoxesShareClampedCells) {
    GridBroadphase grid(1.0);
    const std::uint32_t a = grid.add({Vec3(1e12, 0, 0), Vec3(1e12 + 1, 1, 1)}, {});
    const std::uint32_t b = grid.add({Vec3(2e12, 0, 0), Vec3(2e12 + 1, 1, 1)}, {});
    const std::uint32_t c = grid.add({Vec3(1e12 + 1, 1, 1), Vec3(1e12 + 2, 2, 2)}, {});
    grid.update();
    EXPECT_EQ(grid.pairs(), (std::vector<ProxyPair>{{a, c}}));
    std::vector<std::uint32_t> found;
    grid.query({Vec3(1.5e12, 0, 0), Vec3(3e12, 1, 1)},
               [&](std::uint32_t id) { found.push_back(id); });
    EXPECT_EQ(found, (std::vector<std::uint32_t>{b}));
}

TEST(GridBroadphase, RefusesBadInput) {
    EXPECT_THROW(GridBroadphase(0.0), InvalidArgument);
    EXPECT_THROW(GridBroadphase(std::numeric_limits<Real>::infinity()), InvalidArgument);
    EXPECT_THROW(GridBroadphase(1.0, 0), InvalidArgument);
    GridBroadphase grid;
    const Real nan = std::numeric_limits<Real>::quiet_NaN();
    EXPECT_THROW(grid.add({Vec3(0, 0, 0), Vec3(nan, 1, 1)}, {}), InvalidArgument);
    EXPECT_THROW(grid.add({Vec3(0, 2, 0), Vec3(1, 1, 1)}, {}), InvalidArgument);
    const std::uint32_t a = grid.add({Vec3(0, 0, 0), Vec3(1, 1, 1)}, {});
    EXPECT_THROW(grid.move(a + 1, {Vec3(0, 0, 0), Vec3(1, 1, 1)}), InvalidArgument);
    EXPECT_THROW(grid.move(a, {Vec3(0, 0, 0), Vec3(1, -1, 1)}), InvalidArgument);
    EXPECT_THROW(grid.setPairExcluded(a, a, true), InvalidArgument);
    grid.update();
    EXPECT_THROW(
        grid.raycast(Vec3(nan, 0, 0), Vec3(1, 0, 0), 1, [](std::uint32_t, Real f) { return f; }),
        InvalidArgument);
    grid.remove(a);
    EXPECT_THROW(grid.remove(a), InvalidArgument);
}

}  // namespace
}  // namespace tumble
