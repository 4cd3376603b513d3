// What only GridBroadphase has: pairs across cell planes and the oversized list in a small
// hand-checked case, and far-away boxes in clamped cells. The randomised comparisons with the
// brute force, shared with SweepAndPrune, are in broadphase_test.cpp.

#include <gtest/gtest.h>

#include <cstdint>
#include <limits>
#include <vector>

#include "tumble/collision/grid_broadphase.h"
#include "tumble/core/error.h"

namespace tumble {
namespace {

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

TEST(GridBroadphase, RefusesBadCells) {
    EXPECT_THROW(GridBroadphase(0.0), InvalidArgument);
    EXPECT_THROW(GridBroadphase(std::numeric_limits<Real>::infinity()), InvalidArgument);
    EXPECT_THROW(GridBroadphase(1.0, 0), InvalidArgument);
}

}  // namespace
}  // namespace tumble
