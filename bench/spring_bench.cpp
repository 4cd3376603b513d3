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
//
// BM_SpringBlockFactor / BM_SpringBlockSolve: the implicit threads' block alone (spring_block.h)
// on an n x n net of lumped nodes (0.01 kg, mesh 0.05 m, omega_e h = 20 at h = 1/60), every
// thread taut or about half of them slack (nodes jittered by a fixed rule): assembling and
// factoring K with the pattern kept (one per step), and one settled solve (two per step).

#include <benchmark/benchmark.h>

#include <cmath>
#include <vector>

#include "tumble/lumped.h"
#include "tumble/solver/spring_block.h"
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

// An n x n net of nodes 1..n^2 (0 is the world) and its 2n(n - 1) threads, prepared for a step.
struct BlockNet {
    std::vector<SolverBody> bodies;
    std::vector<SpringRow> rows;
};

BlockNet blockNet(int n, bool jitter) {
    constexpr Real kMesh = 0.05;
    constexpr Real kMass = 0.01;
    const Real omegaE = 20 / kH;
    BlockNet net;
    net.bodies.resize(1 + static_cast<std::size_t>(n) * n);
    std::vector<Vec3> at(net.bodies.size(), Vec3::Zero());
    for (int i = 0; i < n; ++i) {
        for (int j = 0; j < n; ++j) {
            const std::size_t k = 1 + static_cast<std::size_t>(i) * n + j;
            // Taut: every thread 1 % long. Jittered: +-2 % of the mesh, so some are slack.
            const Real phase = static_cast<Real>(k);
            const Real wobble = jitter ? 0.02 * kMesh * std::sin(12.9898 * phase) : 0;
            at[k] = Vec3(1.01 * kMesh * i + wobble, 1.01 * kMesh * j - wobble, 0);
            net.bodies[k].inverseMass = 1 / kMass;
            net.bodies[k].inverseInertia = Mat3::Identity() / (0.4 * kMass * 1e-4);
            net.bodies[k].linearVelocity = Vec3(0, 0, std::cos(7.233 * phase));
        }
    }
    auto link = [&](std::size_t a, std::size_t b) {
        SpringRow row;
        row.bodyA = static_cast<std::uint32_t>(a);
        row.bodyB = static_cast<std::uint32_t>(b);
        row.length = (at[b] - at[a]).norm();
        row.direction = (at[b] - at[a]) / row.length;
        row.restLength = kMesh;
        row.stiffness = omegaE * omegaE * kMass;
        row.tensionOnly = true;
        net.rows.push_back(row);
    };
    for (int i = 0; i < n; ++i) {
        for (int j = 0; j < n; ++j) {
            const std::size_t k = 1 + static_cast<std::size_t>(i) * n + j;
            if (j + 1 < n)
                link(k, k + 1);
            if (i + 1 < n)
                link(k, k + n);
        }
    }
    prepareSpringRows(net.bodies, net.rows, kH, false);
    return net;
}

void blockCounters(benchmark::State& state, const SpringBlockSolver& block, std::size_t rows) {
    state.counters["rows"] = static_cast<double>(rows);
    state.counters["factor_entries"] = static_cast<double>(block.factorSize());
}

void BM_SpringBlockFactor(benchmark::State& state) {
    BlockNet net = blockNet(static_cast<int>(state.range(0)), state.range(1) != 0);
    SpringBlockSolver block;
    block.prepare(net.bodies, net.rows);  // the analysis, once
    for (auto _ : state) {
        block.prepare(net.bodies, net.rows);
        benchmark::DoNotOptimize(block.ready());
    }
    blockCounters(state, block, net.rows.size());
}
BENCHMARK(BM_SpringBlockFactor)
    ->ArgNames({"n", "jitter"})
    ->ArgsProduct({{10, 40}, {0, 1}})
    ->Unit(benchmark::kMicrosecond);

void BM_SpringBlockSolve(benchmark::State& state) {
    BlockNet net = blockNet(static_cast<int>(state.range(0)), state.range(1) != 0);
    SpringBlockSolver block;
    block.prepare(net.bodies, net.rows);
    block.solve(net.bodies, net.rows);  // settles the active set
    for (auto _ : state)
        benchmark::DoNotOptimize(block.solve(net.bodies, net.rows));
    blockCounters(state, block, net.rows.size());
}
BENCHMARK(BM_SpringBlockSolve)
    ->ArgNames({"n", "jitter"})
    ->ArgsProduct({{10, 40}, {0, 1}})
    ->Unit(benchmark::kMicrosecond);

}  // namespace
