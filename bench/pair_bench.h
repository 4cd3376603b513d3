#pragma once
/// Shared pieces of the narrowphase benchmarks: one pair collided repeatedly, reported in ns per
/// pair with the manifold's point count.

#include <benchmark/benchmark.h>

#include "tumble/collision/narrowphase.h"

namespace tumble::bench {

constexpr Real kMargin = 0.02;  // speculative margin (m), the world's default

inline Quat about(const Vec3& axis, Real angle) {
    return Quat(Eigen::AngleAxis<Real>(angle, axis.normalized()));
}

inline void runPair(benchmark::State& state, const Shape& a, const Transform& poseA, const Shape& b,
                    const Transform& poseB) {
    Manifold manifold;
    for (auto _ : state) {
        collide(a, poseA, b, poseB, kMargin, manifold);
        benchmark::DoNotOptimize(manifold);
    }
    state.counters["points"] = manifold.pointCount;
    state.counters["ns_per_pair"] =
        benchmark::Counter(static_cast<double>(state.iterations()),
                           benchmark::Counter::kIsRate | benchmark::Counter::kInvert);
}

}  // namespace tumble::bench
