// Micro-benchmarks of the world's stepping stages. Later issues add broadphase, narrowphase and
// solver benchmarks beside these.

#include <benchmark/benchmark.h>

#include <cmath>

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

// One awake box resting on the ground (it may not sleep) beside N unit boxes on a grid 1.1 m
// apart -- close enough that neighbours' fat boxes overlap, so each has broadphase pairs with
// its neighbours as well as its ground contact -- that have settled and fallen asleep. A
// sleeping island costs nothing per step, so the time should not depend on N: compare N = 0
// with N = 10,000. The second argument 0 turns sleeping off: what the same scene costs awake.
void BM_StepOneAwakeAmongSleeping(benchmark::State& state) {
    const int sleeping = static_cast<int>(state.range(0));
    const bool enableSleep = state.range(1) != 0;
    World world(WorldDef{.enableSleep = enableSleep});
    const BodyId ground = world.createBody(BodyDef{.type = BodyType::Static});
    world.createShape(ground, ShapeDef{.geometry = HalfSpace{}});
    const int side = std::max(1, static_cast<int>(std::ceil(std::sqrt(sleeping))));
    for (int i = 0; i < sleeping; ++i) {
        BodyDef def;
        def.position = Vec3(1.1 * (i % side), 1.1 * (i / side), 0.5);
        world.createShape(world.createBody(def), ShapeDef{.geometry = Box{}});
    }
    BodyDef restless;
    restless.position = Vec3(-10, -10, 0.5);
    restless.allowSleep = false;
    world.createShape(world.createBody(restless), ShapeDef{.geometry = Box{}});
    for (int i = 0; i < 600 && world.awakeBodyCount() > 1 && enableSleep; ++i)
        world.step();
    if (enableSleep && world.awakeBodyCount() != 1) {
        state.SkipWithError("the grid did not fall asleep");
        return;
    }
    for (auto _ : state) {
        benchmark::DoNotOptimize(world.step());
    }
    state.counters["bodies"] = world.bodyCount();
    state.counters["awake"] = world.awakeBodyCount();
}
BENCHMARK(BM_StepOneAwakeAmongSleeping)
    ->Args({0, 1})
    ->Args({10000, 1})
    ->Args({10000, 0})
    ->Unit(benchmark::kMicrosecond);

}  // namespace
