// What only SweepAndPrune has: the sweep axis that follows the boxes' spread, and a small
// hand-checked case of filters, static pairs, touching faces and exclusion. The randomised
// comparisons with the brute force, shared with GridBroadphase, are in broadphase_test.cpp.

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <set>
#include <vector>

#include "collision/broadphase_harness.h"
#include "tumble/collision/broadphase.h"
#include "tumble/core/error.h"

namespace tumble {
namespace {

using test::boxAt;
using test::BroadphaseScene;

TEST(SweepAndPrune, SweepAxisFollowsTheSpreadWithHysteresis) {
    BroadphaseScene<SweepAndPrune> scene;
    std::vector<Vec3> spreadX;
    for (int i = 0; i < 200; ++i) {
        const std::uint32_t id = scene.addBox(1);
        spreadX.push_back(Vec3(scene.uniform(0, 100), scene.uniform(0, 10), scene.uniform(0, 10)));
        scene.fat[id] = boxAt(spreadX.back(), Vec3(0.5, 0.5, 0.5));
        scene.broadphase.move(id, scene.fat[id]);
    }
    std::vector<ProxyPair> previous;
    scene.updateAndCompare(previous, 0);
    EXPECT_EQ(scene.broadphase.axis(), 0);
    // Spread y so its variance exceeds x's by ~1.2: below the switching factor, no switch.
    for (std::uint32_t id = 0; id < 200; ++id) {
        const Vec3& c = spreadX[id];
        scene.fat[id] =
            boxAt(Vec3(c.x(), c.x() * std::sqrt(1.2) + 0.1 * c.y(), c.z()), Vec3(0.5, 0.5, 0.5));
        scene.broadphase.move(id, scene.fat[id]);
    }
    scene.updateAndCompare(previous, 1);
    EXPECT_EQ(scene.broadphase.axis(), 0);
    // Now spread along z, well beyond the factor: the axis switches and pairs stay exact.
    for (std::uint32_t id = 0; id < 200; ++id) {
        const Vec3& c = spreadX[id];
        scene.fat[id] = boxAt(Vec3(0.1 * c.x(), c.y(), 2 * c.x()), Vec3(0.5, 0.5, 0.5));
        scene.broadphase.move(id, scene.fat[id]);
    }
    scene.updateAndCompare(previous, 2);
    EXPECT_EQ(scene.broadphase.axis(), 2);
    EXPECT_TRUE(scene.broadphase.isConsistent());
    std::set<std::uint32_t> found;
    scene.broadphase.query(boxAt(Vec3(5, 5, 100), Vec3(3, 10, 10)), [&](std::uint32_t id) {
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

TEST(SweepAndPrune, BruteForceRefusesMismatchedFilters) {
    EXPECT_THROW(bruteForcePairs({Aabb{}}, {}), InvalidArgument);
}

}  // namespace
}  // namespace tumble
