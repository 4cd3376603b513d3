// What only GridBroadphase has: far-away boxes in clamped cells, and its refusal of bad cells.
// What it shares with SweepAndPrune (the randomised comparisons with the brute force, a small
// hand-checked case) is tested on both in broadphase_test.cpp.

#include <gtest/gtest.h>

#include <cstdint>
#include <limits>
#include <vector>

#include "tumble/collision/grid_broadphase.h"
#include "tumble/collision/sweep_and_prune.h"
#include "tumble/core/error.h"

namespace tumble {
namespace {

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

TEST(GridBroadphase, RefusesBadCells) {
    // Braces: with parentheses Clang reads the second as the declaration of a variable.
    EXPECT_THROW(GridBroadphase{0.0}, InvalidArgument);
    EXPECT_THROW(GridBroadphase{std::numeric_limits<Real>::infinity()}, InvalidArgument);
    EXPECT_THROW((GridBroadphase{1.0, 0}), InvalidArgument);
}

}  // namespace
}  // namespace tumble
