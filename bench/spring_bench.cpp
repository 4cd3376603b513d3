// Nets: the cost of lumped-mass strings and nets, against the ESA study's Blender/Bullet net that
// ran about 4x slower than real time.
//
// An n x n net (mesh 0.05 m, nodes 0.01 kg) at h = 1/60 dropped onto a cylinder (collisions on:
// every node a sphere, and the target) or falling freely (collisions off: point masses, no
// target). Threads tension-only and undamped, either
// - implicit at omega_e h = 20 (k = 14,400 N/m), ten times past the explicit limit, or
// - explicit at omega_e h = 0.5 (k = 9 N/m), the stiffest an explicit net may be at this step
//   with margin (the limit is h < 1 / omega_e), or implicit at the same stiffness for a like
//   for like comparison.
// The first second (the fall and the landing) is stepped before timing, so the timed steps are
// the draped net's. Counters: wall time per simulated second, and the real-time factor.

#include <benchmark/benchmark.h>

#include "tumble/lumped.h"
#include "tumble/tumble.h"

namespace {

using namespace tumble;

constexpr Real kH = 1.0 / 60;

void BM_Net(benchmark::State& state) {
    const int n = static_cast<int>(state.range(0));
    const bool collide = state.range(1) != 0;
    const bool implicit = state.range(2) != 0;
    const Real omegaEH = static_cast<Real>(state.range(3)) / 10;
    World world(WorldDef{.timeStep = kH, .enableSleep = false});
    if (collide) {
        BodyDef fixed{.type = BodyType::Static};
        world.createShape(world.createBody(fixed), ShapeDef{.geometry = HalfSpace{}});
        fixed.position = Vec3(0, 0, 0.4);
        world.createShape(world.createBody(fixed), ShapeDef{.geometry = Cylinder{0.4, 0.4}});
    }
    NetDef net;
    net.rows = n;
    net.columns = n;
    net.meshSize = 0.05;
    net.center = Vec3(0, 0, 1);
    net.node.mass = 0.01;
    net.node.radius = 0.01;
    net.node.collide = collide;
    const Real omegaE = omegaEH / kH;
    net.thread.axialRigidity = omegaE * omegaE * net.node.mass * net.meshSize;
    net.thread.formulation = implicit ? SpringFormulation::Implicit : SpringFormulation::Explicit;
    createNet(world, net);
    for (int i = 0; i < 60; ++i) {
        if (!world.step().ok()) {
            state.SkipWithError("the net went unstable");
            return;
        }
    }
    for (auto _ : state)
        benchmark::DoNotOptimize(world.step());
    const double simulated = static_cast<double>(state.iterations()) * kH;
    state.counters["wall_s_per_sim_s"] =
        benchmark::Counter(simulated, benchmark::Counter::kIsRate | benchmark::Counter::kInvert);
    state.counters["real_time_factor"] = benchmark::Counter(simulated, benchmark::Counter::kIsRate);
    state.counters["nodes"] = n * n;
}
// Arguments: n, collisions, implicit, 10 omega_e h.
BENCHMARK(BM_Net)
    ->ArgNames({"n", "collide", "implicit", "omegaEh_x10"})
    ->ArgsProduct({{10, 20, 40}, {0, 1}, {1}, {200}})
    ->ArgsProduct({{10, 20, 40}, {0, 1}, {0, 1}, {5}})
    ->Unit(benchmark::kMillisecond);

}  // namespace
