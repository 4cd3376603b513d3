// Micro-benchmarks of the closed-form narrowphase pairs, through the public dispatch `collide`.
// Each benchmark collides one fixed touching configuration; ns_per_pair is the cost of one call.

#include <benchmark/benchmark.h>

#include <numbers>
#include <vector>

#include "pair_bench.h"
#include "tumble/collision/narrowphase.h"

namespace {

using namespace tumble;

using bench::about;
using bench::kMargin;
using bench::runPair;

const Quat kTilt = about(Vec3(1, 2, 3), 0.4);

void BM_SphereSphere(benchmark::State& state) {
    runPair(state, Sphere{0.5}, {Vec3::Zero(), Quat::Identity()}, Sphere{0.4},
            {Vec3(0.3, 0.4, 0.7), Quat::Identity()});
}
void BM_SphereCapsule(benchmark::State& state) {
    runPair(state, Sphere{0.5}, {Vec3::Zero(), Quat::Identity()}, Capsule{0.3, 0.5},
            {Vec3(0.3, 0.4, 0.7), kTilt});
}
void BM_CapsuleCapsule(benchmark::State& state) {
    runPair(state, Capsule{0.3, 0.5}, {Vec3::Zero(), Quat::Identity()}, Capsule{0.3, 0.5},
            {Vec3(0.3, 0.4, 0.5), kTilt});
}
void BM_SphereBox(benchmark::State& state) {
    runPair(state, Sphere{0.5}, {Vec3(0.2, 0.6, 0.8), Quat::Identity()}, Box{},
            {Vec3::Zero(), kTilt});
}
// A box resting flat on another: 4 incident corners, nothing clipped.
void BM_BoxBoxFaceAligned(benchmark::State& state) {
    runPair(state, Box{}, {Vec3::Zero(), Quat::Identity()}, Box{},
            {Vec3(0.1, 0.05, 0.999), Quat::Identity()});
}
// Twisted by 30 degrees: an 8-gon reduced to 4 points.
void BM_BoxBoxFaceTwisted(benchmark::State& state) {
    runPair(state, Box{}, {Vec3::Zero(), Quat::Identity()}, Box{},
            {Vec3(0, 0, 0.999), about(Vec3::UnitZ(), std::numbers::pi / 6)});
}
void BM_BoxBoxEdge(benchmark::State& state) {
    const Real h = std::numbers::sqrt2 / 2;
    runPair(state, Box{}, {Vec3::Zero(), about(Vec3::UnitY(), std::numbers::pi / 4)}, Box{},
            {Vec3(0.05, -0.1, 2 * h - 0.01), about(Vec3::UnitZ(), std::numbers::pi / 9) *
                                                 about(Vec3::UnitX(), std::numbers::pi / 4)});
}
void BM_BoxHalfSpace(benchmark::State& state) {
    runPair(state, Box{}, {Vec3(0, 0, 0.499), about(Vec3::UnitZ(), 0.3)}, HalfSpace{},
            {Vec3::Zero(), Quat::Identity()});
}
// A 12-sided prism (24 vertices) lying on a face: 12 candidates reduced to 4.
void BM_HullHalfSpace(benchmark::State& state) {
    std::vector<Vec3> vertices;
    for (int i = 0; i < 12; ++i)
        for (Real z : {-0.2, 0.2})
            vertices.emplace_back(std::cos(2 * std::numbers::pi * i / 12),
                                  std::sin(2 * std::numbers::pi * i / 12), z);
    runPair(state, ConvexHull::fromPoints(vertices), {Vec3(0, 0, 0.199), Quat::Identity()},
            HalfSpace{}, {Vec3::Zero(), Quat::Identity()});
}

BENCHMARK(BM_SphereSphere);
BENCHMARK(BM_SphereCapsule);
BENCHMARK(BM_CapsuleCapsule);
BENCHMARK(BM_SphereBox);
BENCHMARK(BM_BoxBoxFaceAligned);
BENCHMARK(BM_BoxBoxFaceTwisted);
BENCHMARK(BM_BoxBoxEdge);
BENCHMARK(BM_BoxHalfSpace);
BENCHMARK(BM_HullHalfSpace);

}  // namespace
