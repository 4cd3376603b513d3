// Both broadphases, SweepAndPrune and GridBroadphase, against the brute-force reference on the
// same randomised scenes (broadphase_harness.h): pair sets and their changes over moving, added,
// removed, re-filtered and resized boxes, queries, rays, and the refusals of bad input. The
// grid's cells are small enough (2.5 m) that boxes cross cell planes all the time; what only
// one of them has is tested in sweep_and_prune_test.cpp and grid_broadphase_test.cpp.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <type_traits>
#include <vector>

#include "collision/broadphase_harness.h"
#include "tumble/collision/grid_broadphase.h"
#include "tumble/collision/sweep_and_prune.h"
#include "tumble/core/error.h"

namespace tumble {
namespace {

using test::boxAt;
using test::BroadphaseScene;
using test::kCellSize;
using test::referenceEntry;

template <class Broadphase>
class Broadphases : public ::testing::Test {};
using BroadphaseTypes = ::testing::Types<SweepAndPrune, GridBroadphase>;
TYPED_TEST_SUITE(Broadphases, BroadphaseTypes);

TYPED_TEST(Broadphases, ThousandMovingBoxesMatchBruteForceEveryStep) {
    BroadphaseScene<TypeParam> scene;
    scene.addGround();
    for (int i = 0; i < 1000; ++i) {
        scene.addBox(i);
    }
    // Bodies "joined by joints": excluded pairs, one of which we later re-admit.
    for (std::uint32_t id = 1; id + 1 < 1000; id += 50) {
        scene.broadphase.setPairExcluded(id, id + 1, true);
        scene.excluded.push_back({id, id + 1});
    }
    std::vector<ProxyPair> previous;
    std::size_t changes = 0;
    std::size_t pairCount = 0;
    for (int step = 0; step < 200; ++step) {
        scene.step(step < 100 ? 0.02 : 0.15);  // slow, then fast
        if (step == 120) {
            scene.broadphase.setPairExcluded(1, 2, false);
            scene.excluded.erase(scene.excluded.begin());
        }
        changes += scene.updateAndCompare(previous, step);
        pairCount += scene.broadphase.pairs().size();
        if (step % 20 == 0) {
            EXPECT_TRUE(scene.broadphase.isConsistent()) << "step " << step;
        }
        if (testing::Test::HasFailure()) {
            break;
        }
    }
    EXPECT_EQ(scene.broadphase.proxyCount(), 1001u);
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
    // The run must exercise the incremental path (and the grid's oversized list and many cells).
    EXPECT_GT(pairCount / 200, 300u);
    EXPECT_GT(changes, 2000u);
    if constexpr (std::is_same_v<TypeParam, GridBroadphase>) {
        EXPECT_GE(scene.broadphase.oversizedCount(), 2u);  // the ground and some big boxes
        EXPECT_GT(scene.broadphase.cellCount(), 1000u);
    }
}

TYPED_TEST(Broadphases, AddRemoveRefilterAndResizeMidRun) {
    BroadphaseScene<TypeParam> scene;
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
                    scene.broadphase.setFilter(id, scene.filters[id]);
                    break;
                }
            }
        }
        if (step == 60) {
            // Re-filter the oversized ground: it may now pair with static boxes' categories
            // only through the same rules; make it dynamic to pair with statics too.
            scene.filters[0].isStatic = false;
            scene.broadphase.setFilter(0, scene.filters[0]);
        }
        if (step % 10 == 0) {
            for (std::uint32_t a = 0; a + 1 < scene.tight.size(); a += 37) {
                if (scene.live[a] && scene.live[a + 1]) {
                    scene.toggleExclusion({a, a + 1});
                }
            }
        }
        scene.updateAndCompare(previous, step);
        if (testing::Test::HasFailure()) {
            break;
        }
    }
    EXPECT_TRUE(scene.broadphase.isConsistent());
    // A removed id is reused, smallest first, once an update has reported its pairs.
    scene.removeBox(7);
    scene.removeBox(3);
    scene.broadphase.update();
    EXPECT_EQ(scene.addBox(0), 3u);
    EXPECT_EQ(scene.addBox(0), 7u);
}

// A scene for queries: random boxes, a few large, then some moved (one grown oversized).
template <class Broadphase>
BroadphaseScene<Broadphase> queryScene() {
    BroadphaseScene<Broadphase> scene;
    scene.side = 50;
    for (int i = 0; i < 2000; ++i) {
        scene.addBox(i);
    }
    scene.broadphase.update();
    for (std::uint32_t id = 0; id < 2000; id += 13) {
        const Real grow = id == 26 ? 20 : 0.5;
        scene.setBox(id, {scene.fat[id].lower.array() - grow, scene.fat[id].upper.array() + grow});
    }
    scene.broadphase.update();
    return scene;
}

TYPED_TEST(Broadphases, QueryMatchesBruteForce) {
    BroadphaseScene<TypeParam> scene = queryScene<TypeParam>();
    if constexpr (std::is_same_v<TypeParam, GridBroadphase>) {
        EXPECT_GE(scene.broadphase.oversizedCount(), 1u);
    }
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
        scene.broadphase.query(box, [&](std::uint32_t id) { found.push_back(id); });
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

TYPED_TEST(Broadphases, RaycastMatchesBruteForce) {
    BroadphaseScene<TypeParam> scene = queryScene<TypeParam>();
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
        scene.broadphase.raycast(origin, direction, maxFraction,
                                 [&](std::uint32_t id, Real fraction) {
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
        scene.broadphase.raycast(
            origin, direction, maxFraction, [&](std::uint32_t id, Real fraction) {
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

// The hand-checked case's broadphase: the grid with 1 m cells, so that touching faces lie on
// cell planes.
template <class Broadphase>
Broadphase smallCaseBroadphase() {
    return Broadphase{};
}
template <>
GridBroadphase smallCaseBroadphase<GridBroadphase>() {
    return GridBroadphase(1.0);
}

// The case's second static box: for SweepAndPrune the first one's twin (coincident endpoints on
// every axis), for the grid a slab over 40 x 40 x 3 cells (oversized).
template <class Broadphase>
Aabb smallCaseSlab() {
    return {Vec3(0, 0, 0), Vec3(2, 2, 2)};
}
template <>
Aabb smallCaseSlab<GridBroadphase>() {
    return {Vec3(-20, -20, 0), Vec3(20, 20, 2)};
}

TYPED_TEST(Broadphases, FilterStaticTouchingAndExclusion) {
    TypeParam broadphase = smallCaseBroadphase<TypeParam>();
    // a and b touch on the plane x = 1, for the grid a cell plane.
    const std::uint32_t a = broadphase.add({Vec3(0, 0, 0), Vec3(1, 1, 1)}, {});
    const std::uint32_t b = broadphase.add({Vec3(1, 0, 0), Vec3(2, 1, 1)}, {});
    ProxyFilter staticFilter;
    staticFilter.isStatic = true;
    staticFilter.category = 1 | 2;
    const std::uint32_t c = broadphase.add({Vec3(0, 0, 0), Vec3(2, 2, 2)}, staticFilter);
    const std::uint32_t d = broadphase.add(smallCaseSlab<TypeParam>(), staticFilter);
    ProxyFilter oneWay;
    oneWay.category = 2;
    oneWay.mask = 2;
    const std::uint32_t e = broadphase.add({Vec3(0.5, 0.5, 0.5), Vec3(0.6, 0.6, 0.6)}, oneWay);
    broadphase.update();
    if constexpr (std::is_same_v<TypeParam, GridBroadphase>) {
        EXPECT_EQ(broadphase.oversizedCount(), 1u);  // d covers 40 x 40 x 3 cells
    }
    // c-d are both static; e pairs with c and d (category 2) but, its mask refusing
    // category 1, with neither a nor b although both accept it.
    const std::vector<ProxyPair> expected{{a, b}, {a, c}, {a, d}, {b, c}, {b, d}, {c, e}, {d, e}};
    EXPECT_EQ(broadphase.pairs(), expected);
    EXPECT_EQ(broadphase.addedPairs(), expected);
    broadphase.setPairExcluded(b, a, true);
    broadphase.update();
    EXPECT_EQ(broadphase.removedPairs(), (std::vector<ProxyPair>{{a, b}}));
    EXPECT_TRUE(broadphase.addedPairs().empty());
    broadphase.update();
    EXPECT_TRUE(broadphase.removedPairs().empty());
    EXPECT_TRUE(broadphase.addedPairs().empty());
    broadphase.setPairExcluded(a, b, false);
    // A hair apart (in the grid, in one cell less).
    broadphase.move(b, {Vec3(1 + 1e-9, 0, 0), Vec3(2, 1, 1)});
    broadphase.update();
    EXPECT_TRUE(broadphase.addedPairs().empty());
    EXPECT_TRUE(broadphase.removedPairs().empty());
    broadphase.move(b, {Vec3(1, 0, 0), Vec3(2, 1, 1)});
    broadphase.update();
    EXPECT_EQ(broadphase.addedPairs(), (std::vector<ProxyPair>{{a, b}}));
    // Pairs found in several cells are reported once and leave once.
    broadphase.move(a, {Vec3(0.5, 0.5, 0.5), Vec3(3.5, 3.5, 3.5)});
    broadphase.update();
    EXPECT_EQ(broadphase.pairs(), expected);
    broadphase.remove(c);
    broadphase.remove(d);
    broadphase.update();
    EXPECT_EQ(broadphase.removedPairs(),
              (std::vector<ProxyPair>{{a, c}, {a, d}, {b, c}, {b, d}, {c, e}, {d, e}}));
    EXPECT_EQ(broadphase.pairs(), (std::vector<ProxyPair>{{a, b}}));
    EXPECT_EQ(broadphase.proxyCount(), 3u);
    EXPECT_TRUE(broadphase.isConsistent());
}

TYPED_TEST(Broadphases, RefusesBadInput) {
    TypeParam broadphase;
    const Real nan = std::numeric_limits<Real>::quiet_NaN();
    EXPECT_THROW(broadphase.add({Vec3(0, 0, 0), Vec3(nan, 1, 1)}, {}), InvalidArgument);
    EXPECT_THROW(broadphase.add({Vec3(0, 2, 0), Vec3(1, 1, 1)}, {}), InvalidArgument);
    const std::uint32_t a = broadphase.add({Vec3(0, 0, 0), Vec3(1, 1, 1)}, {});
    EXPECT_THROW(broadphase.move(a + 1, {Vec3(0, 0, 0), Vec3(1, 1, 1)}), InvalidArgument);
    EXPECT_THROW(broadphase.move(a, {Vec3(0, 0, 0), Vec3(1, -1, 1)}), InvalidArgument);
    EXPECT_THROW(broadphase.setPairExcluded(a, a, true), InvalidArgument);
    broadphase.update();
    EXPECT_THROW(broadphase.raycast(Vec3(nan, 0, 0), Vec3(1, 0, 0), 1,
                                    [](std::uint32_t, Real f) { return f; }),
                 InvalidArgument);
    broadphase.remove(a);
    EXPECT_THROW(broadphase.remove(a), InvalidArgument);
}

}  // namespace
}  // namespace tumble
