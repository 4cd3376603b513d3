// Micro-benchmarks of the world's stepping stages. Later issues add broadphase, narrowphase and
// solver benchmarks beside these.

#include <benchmark/benchmark.h>

#include "tumble/tumble.h"

namespace {

using namespace tumble;

// N free bodies spinning and falling: the cost of the integrator alone, per step.
void BM_StepFreeBodies(benchmark::State& state) {
    const int count = static_cast<int>(state.range(0));
    World world;
    for (int i = 0; i < count; ++i) {
        BodyDef def;
        def.position = Vec3(i % 100, (i / 100) % 100, i / 10000);
        def.angularVelocity = Vec3(0.1 * (i % 7), 0.2, 0.3);
        def.mass.inertia = Vec3(1, 2, 3).asDiagonal();
        world.createBody(def);
    }
    for (auto _ : state) {
        benchmark::DoNotOptimize(world.step());
    }
    state.SetItemsProcessed(state.iterations() * count);
    state.counters["ns_per_body"] =
        benchmark::Counter(static_cast<double>(state.iterations() * count),
                           benchmark::Counter::kIsRate | benchmark::Counter::kInvert);
}
BENCHMARK(BM_StepFreeBodies)->Arg(1000)->Arg(10000)->Unit(benchmark::kMicrosecond);

}  // namespace
