// What only SweepAndPrune has: the sweep axis that follows the boxes' spread. What it shares
// with GridBroadphase (the randomised comparisons with the brute force, a small hand-checked
// case) is tested on both in broadphase_test.cpp.

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <set>
#include <vector>

#include "collision/broadphase_harness.h"
#include "tumble/collision/sweep_and_prune.h"
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

TEST(SweepAndPrune, BruteForceRefusesMismatchedFilters) {
    EXPECT_THROW(bruteForcePairs({Aabb{}}, {}), InvalidArgument);
}

}  // namespace
}  // namespace tumble
