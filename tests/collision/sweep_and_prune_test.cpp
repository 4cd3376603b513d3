// SweepAndPrune against the brute-force reference: pair sets, their changes, queries and rays.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <iterator>
#include <limits>
#include <random>
#include <set>
#include <vector>

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

// A population of moving boxes with the engine's fat-box policy. Ids are SweepAndPrune ids;
// `live` marks which are in use.
struct Scene {
    std::mt19937 rng{12345};
    Real side = 30;     // boxes live in [0, side]^3 (m)
    Real margin = 0.2;  // fat-box margin (m)
    std::vector<Aabb> tight;
    std::vector<Aabb> fat;
    std::vector<Vec3> velocity;
    std::vector<ProxyFilter> filters;
    std::vector<bool> live;
    std::vector<ProxyPair> excluded;
    SweepAndPrune sap;

    Real uniform(Real lo, Real hi) { return std::uniform_real_distribution<Real>(lo, hi)(rng); }
    Vec3 randomPoint() { return Vec3(uniform(0, side), uniform(0, side), uniform(0, side)); }

    ProxyFilter randomFilter(int kind) {
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

    std::uint32_t addBox(int kind) {
        const bool big = kind % 97 == 5;
        const Real half = big ? uniform(3, 6) : uniform(0.1, 1.0);
        const Vec3 halfExtents(half * uniform(0.5, 1.5), half * uniform(0.5, 1.5), half);
        const Aabb box = boxAt(randomPoint(), halfExtents);
        const ProxyFilter filter = randomFilter(kind);
        const std::uint32_t id = sap.add(box.fattened(margin), filter);
        if (id >= tight.size()) {
            tight.resize(id + 1);
            fat.resize(id + 1);
            velocity.resize(id + 1);
            filters.resize(id + 1);
            live.resize(id + 1);
        }
        tight[id] = box;
        fat[id] = box.fattened(margin);
        velocity[id] = Vec3::Zero();
        filters[id] = filter;
        live[id] = true;
        return id;
    }

    void removeBox(std::uint32_t id) {
        sap.remove(id);
        live[id] = false;
        std::erase_if(excluded, [id](ProxyPair p) { return p.first == id || p.second == id; });
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
                sap.move(id, fat[id]);
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
    scene.sap.update();
    const std::vector<ProxyPair> expected = scene.reference();
    EXPECT_EQ(scene.sap.pairs(), expected) << "step " << step;
    EXPECT_EQ(scene.sap.addedPairs(), difference(expected, previous)) << "step " << step;
    EXPECT_EQ(scene.sap.removedPairs(), difference(previous, expected)) << "step " << step;
    const std::size_t changes = scene.sap.addedPairs().size() + scene.sap.removedPairs().size();
    previous = expected;
    return changes;
}

TEST(SweepAndPrune, ThousandMovingBoxesMatchBruteForceEveryStep) {
    Scene scene;
    for (int i = 0; i < 1000; ++i) {
        scene.addBox(i);
    }
    // Bodies "joined by joints": excluded pairs, one of which we later re-admit.
    for (std::uint32_t id = 0; id + 1 < 1000; id += 50) {
        scene.sap.setPairExcluded(id, id + 1, true);
        scene.excluded.push_back({id, id + 1});
    }
    std::vector<ProxyPair> previous;
    std::size_t changes = 0;
    std::size_t pairCount = 0;
    for (int step = 0; step < 200; ++step) {
        scene.step(step < 100 ? 0.02 : 0.15);  // slow, then fast
        if (step == 120) {
            scene.sap.setPairExcluded(0, 1, false);
            scene.excluded.erase(scene.excluded.begin());
        }
        changes += updateAndCompare(scene, previous, step);
        pairCount += scene.sap.pairs().size();
        if (step % 20 == 0) {
            EXPECT_TRUE(scene.sap.isConsistent()) << "step " << step;
        }
        if (testing::Test::HasFailure()) {
            break;
        }
    }
    // The run must exercise the incremental path: many pairs and many changes.
    EXPECT_GT(pairCount / 200, 300u);
    EXPECT_GT(changes, 2000u);
}

TEST(SweepAndPrune, AddRemoveAndRefilterMidRun) {
    Scene scene;
    for (int i = 0; i < 300; ++i) {
        scene.addBox(i);
    }
    std::vector<ProxyPair> previous;
    int kind = 300;
    for (int step = 0; step < 150; ++step) {
        scene.step(0.05);
        // Remove a few live proxies; add a few (some removed again before the update).
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
                scene.sap.move(id, scene.fat[id]);  // moved before it was ever indexed
            }
            if (k == 1 && step % 7 == 0) {
                scene.removeBox(id);  // never seen by an update
            }
        }
        if (step % 10 == 5) {
            // Re-filter a live proxy: its pairs must be re-decided.
            for (std::uint32_t id = 0; id < scene.tight.size(); ++id) {
                if (scene.live[id] && !scene.filters[id].isStatic) {
                    scene.filters[id].mask = step % 20 == 5 ? 0u : 0xFFFFFFFFu;
                    scene.sap.setFilter(id, scene.filters[id]);
                    break;
                }
            }
        }
        updateAndCompare(scene, previous, step);
        if (testing::Test::HasFailure()) {
            break;
        }
    }
    EXPECT_TRUE(scene.sap.isConsistent());
    // A removed id is reused, smallest first, once an update has reported its pairs.
    scene.removeBox(7);
    scene.removeBox(3);
    scene.sap.update();
    EXPECT_EQ(scene.addBox(0), 3u);
    EXPECT_EQ(scene.addBox(0), 7u);
}

TEST(SweepAndPrune, SweepAxisFollowsTheSpreadWithHysteresis) {
    Scene scene;
    std::vector<Vec3> spreadX;
    for (int i = 0; i < 200; ++i) {
        const std::uint32_t id = scene.addBox(1);
        spreadX.push_back(Vec3(scene.uniform(0, 100), scene.uniform(0, 10), scene.uniform(0, 10)));
        scene.fat[id] = boxAt(spreadX.back(), Vec3(0.5, 0.5, 0.5));
        scene.sap.move(id, scene.fat[id]);
    }
    std::vector<ProxyPair> previous;
    updateAndCompare(scene, previous, 0);
    EXPECT_EQ(scene.sap.axis(), 0);
    // Spread y so its variance exceeds x's by ~1.2: below the switching factor, no switch.
    for (std::uint32_t id = 0; id < 200; ++id) {
        const Vec3& c = spreadX[id];
        scene.fat[id] =
            boxAt(Vec3(c.x(), c.x() * std::sqrt(1.2) + 0.1 * c.y(), c.z()), Vec3(0.5, 0.5, 0.5));
        scene.sap.move(id, scene.fat[id]);
    }
    updateAndCompare(scene, previous, 1);
    EXPECT_EQ(scene.sap.axis(), 0);
    // Now spread along z, well beyond the factor: the axis switches and pairs stay exact.
    for (std::uint32_t id = 0; id < 200; ++id) {
        const Vec3& c = spreadX[id];
        scene.fat[id] = boxAt(Vec3(0.1 * c.x(), c.y(), 2 * c.x()), Vec3(0.5, 0.5, 0.5));
        scene.sap.move(id, scene.fat[id]);
    }
    updateAndCompare(scene, previous, 2);
    EXPECT_EQ(scene.sap.axis(), 2);
    EXPECT_TRUE(scene.sap.isConsistent());
    std::set<std::uint32_t> found;
    scene.sap.query(boxAt(Vec3(5, 5, 100), Vec3(3, 10, 10)), [&](std::uint32_t id) {
        EXPECT_TRUE(found.insert(id).second) << "visited twice: " << id;
    });
    std::set<std::uint32_t> expected;
    for (std::uint32_t id = 0; id < 200; ++id) {
        if (scene.fat[id].overlaps(boxAt(Vec3(5, 5, 100), Vec3(3, 10, 10)))) {
            expected.insert(id);
        }
    }
    EXPECT_EQ(found, expected);
    EXPECT_FALSE(expected.empty());
}

// A scene for queries: random boxes, a few of them large, then some moved (one grown large).
Scene queryScene() {
    Scene scene;
    scene.side = 50;
    for (int i = 0; i < 2000; ++i) {
        scene.addBox(i);
    }
    scene.sap.update();
    for (std::uint32_t id = 0; id < 2000; id += 13) {
        const Real grow = id == 26 ? 20 : 0.5;
        scene.fat[id] = {scene.fat[id].lower.array() - grow, scene.fat[id].upper.array() + grow};
        scene.sap.move(id, scene.fat[id]);
    }
    scene.sap.update();
    return scene;
}

TEST(SweepAndPrune, QueryMatchesBruteForce) {
    Scene scene = queryScene();
    std::size_t total = 0;
    for (int q = 0; q < 500; ++q) {
        const Vec3 half(scene.uniform(0, 4), scene.uniform(0, 4), scene.uniform(0, 4));
        const Aabb box = boxAt(scene.randomPoint(), q % 50 == 0 ? Vec3(0, 0, 0) : half);
        std::vector<std::uint32_t> found;
        scene.sap.query(box, [&](std::uint32_t id) { found.push_back(id); });
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

TEST(SweepAndPrune, RaycastMatchesBruteForce) {
    Scene scene = queryScene();
    int closestHits = 0;
    for (int r = 0; r < 400; ++r) {
        const Vec3 origin = scene.randomPoint();
        Vec3 direction(scene.uniform(-1, 1), scene.uniform(-1, 1), scene.uniform(-1, 1));
        if (r % 4 == 1) {
            direction[r % 3] = 0;  // rays in a coordinate plane
        } else if (r % 4 == 2) {
            direction = Vec3::Zero();
            direction[(r / 4) % 3] = r % 8 < 4 ? 1 : -1;  // axis-aligned, both senses
        }
        direction *= scene.uniform(5, 40);
        const Real maxFraction = scene.uniform(0.2, 1.5);
        // All hits: the visited set equals the boxes the segment touches.
        std::vector<std::uint32_t> found;
        scene.sap.raycast(origin, direction, maxFraction, [&](std::uint32_t id, Real fraction) {
            found.push_back(id);
            return fraction;
        });
        std::sort(found.begin(), found.end());
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
        scene.sap.raycast(origin, direction, maxFraction, [&](std::uint32_t id, Real fraction) {
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

TEST(SweepAndPrune, FilterStaticTouchingAndExclusion) {
    SweepAndPrune sap;
    const std::uint32_t a = sap.add({Vec3(0, 0, 0), Vec3(1, 1, 1)}, {});
    const std::uint32_t b = sap.add({Vec3(1, 0, 0), Vec3(2, 1, 1)}, {});  // touches a's face
    ProxyFilter staticFilter;
    staticFilter.isStatic = true;
    staticFilter.category = 1 | 2;
    const std::uint32_t c = sap.add({Vec3(0, 0, 0), Vec3(2, 2, 2)}, staticFilter);
    const std::uint32_t d = sap.add({Vec3(0, 0, 0), Vec3(2, 2, 2)}, staticFilter);
    ProxyFilter oneWay;
    oneWay.category = 2;
    oneWay.mask = 2;  // a accepts category 2, but this one does not accept category 1
    const std::uint32_t e = sap.add({Vec3(0.5, 0.5, 0.5), Vec3(0.6, 0.6, 0.6)}, oneWay);
    sap.update();
    // c-d are both static; e pairs with c and d (category 2) but, its mask refusing
    // category 1, with neither a nor b although both accept it.
    const std::vector<ProxyPair> expected{{a, b}, {a, c}, {a, d}, {b, c}, {b, d}, {c, e}, {d, e}};
    EXPECT_EQ(sap.pairs(), expected);
    EXPECT_EQ(sap.addedPairs(), expected);
    sap.setPairExcluded(b, a, true);
    sap.update();
    EXPECT_EQ(sap.removedPairs(), (std::vector<ProxyPair>{{a, b}}));
    EXPECT_TRUE(sap.addedPairs().empty());
    sap.update();  // nothing changed: nothing reported
    EXPECT_TRUE(sap.removedPairs().empty());
    EXPECT_TRUE(sap.addedPairs().empty());
    sap.setPairExcluded(a, b, false);
    sap.move(b, {Vec3(1 + 1e-9, 0, 0), Vec3(2, 1, 1)});  // now a hair apart
    sap.update();
    EXPECT_TRUE(sap.addedPairs().empty());
    sap.move(b, {Vec3(1, 0, 0), Vec3(2, 1, 1)});
    sap.update();
    EXPECT_EQ(sap.addedPairs(), (std::vector<ProxyPair>{{a, b}}));
    sap.remove(c);
    sap.update();
    EXPECT_EQ(sap.removedPairs(), (std::vector<ProxyPair>{{a, c}, {b, c}, {c, e}}));
    EXPECT_TRUE(sap.isConsistent());
}

TEST(SweepAndPrune, RefusesBadInput) {
    SweepAndPrune sap;
    const Real nan = std::numeric_limits<Real>::quiet_NaN();
    EXPECT_THROW(sap.add({Vec3(0, 0, 0), Vec3(nan, 1, 1)}, {}), InvalidArgument);
    EXPECT_THROW(sap.add({Vec3(0, 2, 0), Vec3(1, 1, 1)}, {}), InvalidArgument);
    const std::uint32_t a = sap.add({Vec3(0, 0, 0), Vec3(1, 1, 1)}, {});
    EXPECT_THROW(sap.move(a + 1, {Vec3(0, 0, 0), Vec3(1, 1, 1)}), InvalidArgument);
    EXPECT_THROW(sap.move(a, {Vec3(0, 0, 0), Vec3(1, -1, 1)}), InvalidArgument);
    EXPECT_THROW(sap.setPairExcluded(a, a, true), InvalidArgument);
    sap.update();
    EXPECT_THROW(
        sap.raycast(Vec3(nan, 0, 0), Vec3(1, 0, 0), 1, [](std::uint32_t, Real f) { return f; }),
        InvalidArgument);
    sap.remove(a);
    EXPECT_THROW(sap.remove(a), InvalidArgument);
    EXPECT_THROW(bruteForcePairs({Aabb{}}, {}), InvalidArgument);
}

}  // namespace
}  // namespace tumble
