// Micro-benchmarks of the general convex path (GJK; separating axes or libccd EPA when overlapping;
// face clipping), through the public dispatch `collide`. ns_per_pair is the cost of one call.

#include <benchmark/benchmark.h>

#include <cmath>
#include <numbers>
#include <vector>

#include "pair_bench.h"
#include "tumble/collision/narrowphase.h"

namespace {

using namespace tumble;

using bench::about;
using bench::kMargin;
using bench::runPair;

ConvexHull cubeHull(Real half) {
    std::vector<Vec3> corners;
    for (int i = 0; i < 8; ++i)
        corners.emplace_back(i & 1 ? half : -half, i & 2 ? half : -half, i & 4 ? half : -half);
    return ConvexHull::fromPoints(corners);
}

/// A 12-sided prism of radius 0.5 and half height 0.2 (24 vertices, 14 faces).
ConvexHull prismHull() {
    std::vector<Vec3> vertices;
    for (int i = 0; i < 12; ++i)
        for (Real z : {-0.2, 0.2})
            vertices.emplace_back(0.5 * std::cos(2 * std::numbers::pi * i / 12),
                                  0.5 * std::sin(2 * std::numbers::pi * i / 12), z);
    return ConvexHull::fromPoints(vertices);
}

// A cube hull resting 1 mm deep on another, twisted: GJK finds overlap, the separating-axis pass
// the depth, clipping an 8-gon reduced to 4 points.
void BM_HullHullResting(benchmark::State& state) {
    runPair(state, cubeHull(0.5), {Vec3::Zero(), Quat::Identity()}, cubeHull(0.5),
            {Vec3(0.1, 0.05, 0.999), about(Vec3::UnitZ(), 0.5)});
}
// The same 5 mm apart (a speculative contact): GJK distance only, then clipping.
void BM_HullHullSeparated(benchmark::State& state) {
    runPair(state, cubeHull(0.5), {Vec3::Zero(), Quat::Identity()}, cubeHull(0.5),
            {Vec3(0.1, 0.05, 1.005), about(Vec3::UnitZ(), 0.5)});
}
// Two 12-sided prisms stacked 1 mm deep.
void BM_PrismPrismResting(benchmark::State& state) {
    runPair(state, prismHull(), {Vec3::Zero(), Quat::Identity()}, prismHull(),
            {Vec3(0.05, 0.02, 0.399), about(Vec3::UnitZ(), 0.2)});
}
// A cylinder standing 1 mm deep on a box: a 16-gon cap reduced to 4 points.
void BM_CylinderOnBox(benchmark::State& state) {
    runPair(state, Box{Vec3(2, 2, 0.5)}, {Vec3::Zero(), Quat::Identity()}, Cylinder{0.3, 0.4},
            {Vec3(0.2, 0.1, 0.899), Quat::Identity()});
}

BENCHMARK(BM_HullHullResting);
BENCHMARK(BM_HullHullSeparated);
BENCHMARK(BM_PrismPrismResting);
BENCHMARK(BM_CylinderOnBox);

}  // namespace
