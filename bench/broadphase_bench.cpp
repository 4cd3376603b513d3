// Broadphase micro-benchmarks: the cost of one step's broadphase (move the bodies, refit fat
// boxes, update the pair set) for SweepAndPrune against the brute-force reference.
//
// Scenes keep a fixed density as n grows: n boxes (half extents 0.25..0.75 m) in a cube of side
// cbrt(n * volumePerBox). Sparse: 8 m^3 per box (~0.5 overlapping pairs per box); dense: 1.5 m^3
// per box (~4 pairs per box). Each box drifts at a constant speed in a random direction and
// bounces off the walls: slow = 5 mm per step (0.3 m/s at 60 Hz), fast = 10 cm per step
// (6 m/s). Fat-box margin 0.1 m, so a slow box calls move() about every 20 steps, a fast one
// every step. Read off the crossover n where SAP beats brute force, and the exponent of cost
// against n from the 1k/10k/50k runs.

#include <benchmark/benchmark.h>

#include <cmath>
#include <cstdint>
#include <random>
#include <vector>

#include "tumble/collision/grid_broadphase.h"
#include "tumble/collision/sweep_and_prune.h"

namespace {

using namespace tumble;

constexpr Real kMargin = 0.1;       // fat-box margin (m)
constexpr Real kSparseVolume = 8;   // m^3 per box
constexpr Real kDenseVolume = 1.5;  // m^3 per box
constexpr Real kSlowStep = 0.005;   // m per step
constexpr Real kFastStep = 0.1;     // m per step
// Past the first refits: boxes of one speed all leave their fat boxes 20-35 steps in, and a
// timing window that starts inside that burst overstates the steady cost (most at 50k, where
// few iterations are timed).
constexpr int kWarmupSteps = 60;
constexpr std::int64_t kBruteCap = 4096;  // brute force above this is pointlessly slow

struct MovingBoxes {
    Real side = 0;
    std::vector<Aabb> tight;
    std::vector<Aabb> fat;
    std::vector<Vec3> velocity;
    std::vector<ProxyFilter> filters;

    MovingBoxes(std::int64_t count, bool dense, bool fast) {
        std::mt19937 rng(7);
        std::uniform_real_distribution<Real> unit(0, 1);
        side = std::cbrt(static_cast<Real>(count) * (dense ? kDenseVolume : kSparseVolume));
        const Real speed = fast ? kFastStep : kSlowStep;
        for (std::int64_t i = 0; i < count; ++i) {
            const Vec3 centre(unit(rng) * side, unit(rng) * side, unit(rng) * side);
            const Vec3 half(0.25 + 0.5 * unit(rng), 0.25 + 0.5 * unit(rng), 0.25 + 0.5 * unit(rng));
            tight.push_back({centre - half, centre + half});
            fat.push_back(tight.back().fattened(kMargin));
            const Vec3 direction(unit(rng) - 0.5, unit(rng) - 0.5, unit(rng) - 0.5);
            velocity.push_back(speed * direction.normalized());
            filters.push_back({});
        }
    }

    // Advances every box one step; calls onRefit(i) when its fat box had to be replaced.
    template <typename OnRefit>
    void step(OnRefit&& onRefit) {
        for (std::size_t i = 0; i < tight.size(); ++i) {
            const Vec3 centre = tight[i].center() + velocity[i];
            for (int axis = 0; axis < 3; ++axis) {
                if ((centre[axis] < 0 && velocity[i][axis] < 0) ||
                    (centre[axis] > side && velocity[i][axis] > 0)) {
                    velocity[i][axis] = -velocity[i][axis];
                }
            }
            tight[i] = {tight[i].lower + velocity[i], tight[i].upper + velocity[i]};
            if (refitFatBox(fat[i], tight[i], kMargin)) {
                onRefit(i);
            }
        }
    }
};

void setCounters(benchmark::State& state, std::int64_t count, double pairs, double moved) {
    state.counters["ns_per_proxy"] =
        benchmark::Counter(static_cast<double>(state.iterations() * count),
                           benchmark::Counter::kIsRate | benchmark::Counter::kInvert);
    state.counters["pairs"] = pairs;
    state.counters["moved_per_step"] = moved;
}

void BM_SapUpdate(benchmark::State& state) {
    const std::int64_t count = state.range(0);
    MovingBoxes boxes(count, state.range(1) != 0, state.range(2) != 0);
    SweepAndPrune sap;
    for (std::size_t i = 0; i < boxes.fat.size(); ++i) {
        sap.add(boxes.fat[i], boxes.filters[i]);
    }
    sap.update();
    std::int64_t moved = 0;
    auto onRefit = [&](std::size_t i) {
        sap.move(static_cast<std::uint32_t>(i), boxes.fat[i]);
        ++moved;
    };
    for (int i = 0; i < kWarmupSteps; ++i) {
        boxes.step(onRefit);
        sap.update();
    }
    moved = 0;
    for (auto _ : state) {
        boxes.step(onRefit);
        sap.update();
        benchmark::DoNotOptimize(sap.pairs().data());
    }
    setCounters(state, count, static_cast<double>(sap.pairs().size()),
                static_cast<double>(moved) / static_cast<double>(state.iterations()));
}

void BM_BruteForceUpdate(benchmark::State& state) {
    const std::int64_t count = state.range(0);
    MovingBoxes boxes(count, state.range(1) != 0, state.range(2) != 0);
    std::int64_t moved = 0;
    auto onRefit = [&](std::size_t) { ++moved; };
    std::size_t pairs = 0;
    for (auto _ : state) {
        boxes.step(onRefit);
        const std::vector<ProxyPair> found = bruteForcePairs(boxes.fat, boxes.filters);
        pairs = found.size();
        benchmark::DoNotOptimize(found.data());
    }
    setCounters(state, count, static_cast<double>(pairs),
                static_cast<double>(moved) / static_cast<double>(state.iterations()));
}

// The first update of a fresh SweepAndPrune: sort three axes and sweep for all pairs.
void BM_SapBuild(benchmark::State& state) {
    const std::int64_t count = state.range(0);
    const MovingBoxes boxes(count, state.range(1) != 0, false);
    for (auto _ : state) {
        SweepAndPrune sap;
        for (std::size_t i = 0; i < boxes.fat.size(); ++i) {
            sap.add(boxes.fat[i], boxes.filters[i]);
        }
        sap.update();
        benchmark::DoNotOptimize(sap.pairs().data());
    }
    setCounters(state, count, 0, static_cast<double>(count));
}

// Args: n, dense (0/1), fast (0/1).
void sapArgs(benchmark::internal::Benchmark* bench) {
    bench->ArgNames({"n", "dense", "fast"});
    for (const std::int64_t n : {16, 64, 256, 1000, 10000, 50000}) {
        for (const int dense : {0, 1}) {
            for (const int fast : {0, 1}) {
                bench->Args({n, dense, fast});
            }
        }
    }
}

void bruteArgs(benchmark::internal::Benchmark* bench) {
    bench->ArgNames({"n", "dense", "fast"});
    for (const std::int64_t n :
         {std::int64_t{16}, std::int64_t{64}, std::int64_t{256}, std::int64_t{1000}, kBruteCap}) {
        for (const int dense : {0, 1}) {
            bench->Args({n, dense, 1});  // its cost does not depend on the speed
        }
    }
}

BENCHMARK(BM_SapUpdate)->Apply(sapArgs)->Unit(benchmark::kMicrosecond)->MinTime(0.1);
BENCHMARK(BM_BruteForceUpdate)->Apply(bruteArgs)->Unit(benchmark::kMicrosecond)->MinTime(0.1);
BENCHMARK(BM_SapBuild)
    ->ArgNames({"n", "dense"})
    ->Args({1000, 1})
    ->Args({10000, 1})
    ->Args({50000, 1})
    ->Unit(benchmark::kMillisecond)
    ->MinTime(0.1);

// GridBroadphase (a SweepAndPrune per cubic cell) on the same scenes as BM_SapUpdate; its cost
// should grow about linearly with n. Args: n, dense (0/1), fast (0/1), cell edge (m).
void BM_GridUpdate(benchmark::State& state) {
    const std::int64_t count = state.range(0);
    MovingBoxes boxes(count, state.range(1) != 0, state.range(2) != 0);
    GridBroadphase grid(static_cast<Real>(state.range(3)));
    for (std::size_t i = 0; i < boxes.fat.size(); ++i) {
        grid.add(boxes.fat[i], boxes.filters[i]);
    }
    grid.update();
    std::int64_t moved = 0;
    auto onRefit = [&](std::size_t i) {
        grid.move(static_cast<std::uint32_t>(i), boxes.fat[i]);
        ++moved;
    };
    for (int i = 0; i < kWarmupSteps; ++i) {
        boxes.step(onRefit);
        grid.update();
    }
    moved = 0;
    for (auto _ : state) {
        boxes.step(onRefit);
        grid.update();
        benchmark::DoNotOptimize(grid.pairs().data());
    }
    setCounters(state, count, static_cast<double>(grid.pairs().size()),
                static_cast<double>(moved) / static_cast<double>(state.iterations()));
    state.counters["cells"] = static_cast<double>(grid.cellCount());
}

void gridArgs(benchmark::internal::Benchmark* bench) {
    bench->ArgNames({"n", "dense", "fast", "cell"});
    for (const std::int64_t n : {1000, 10000, 50000}) {
        for (const int dense : {0, 1}) {
            for (const int fast : {0, 1}) {
                bench->Args(
                    {n, dense, fast, static_cast<std::int64_t>(GridBroadphase::kDefaultCellSize)});
            }
        }
    }
    // Cell edge sweep on the hardest scene (dense, fast) at 10k.
    for (const std::int64_t cell : {2, 4, 16}) {
        bench->Args({10000, 1, 1, cell});
    }
}

BENCHMARK(BM_GridUpdate)->Apply(gridArgs)->Unit(benchmark::kMicrosecond)->MinTime(0.1);

}  // namespace
