// The constraint solver: whole steps of the stack and pyramid scenes the validation cases check
// (same builders: the scene kit, testkit/), and the PGS sweep alone, per row and iteration.

#include <benchmark/benchmark.h>

#include <ctime>
#include <vector>

#include "harness/scene.h"
#include "scenes.h"
#include "testkit/solver_scenes.h"
#include "tumble/solver/constraint_solver.h"
#include "tumble/tumble.h"

namespace {

using namespace tumble;
namespace scenes = tumble::validation::scenes;

constexpr Real kFriction = 0.5;
constexpr int kSettleSteps =
    120;  // past the first contacts, so warm starting is in its steady state

void stepScene(benchmark::State& state, World& world, int bodies) {
    for (int i = 0; i < kSettleSteps; ++i)
        world.step();
    for (auto _ : state)
        benchmark::DoNotOptimize(world.step());
    state.counters["bodies"] = bodies;
    state.counters["contacts"] = static_cast<double>(world.contacts().size());
    // Simulated seconds per wall second at h = 1/60: above 1 is faster than real time.
    state.counters["realtime_factor"] =
        benchmark::Counter(static_cast<double>(state.iterations()) * world.settings().timeStep,
                           benchmark::Counter::kIsRate);
}

// A column of N unit cubes at h = 1/60, 10 iterations (the `stack` case).
void BM_StackStep(benchmark::State& state) {
    World world(scenes::stackWorld());
    scenes::addGround(world, scenes::material(kFriction));
    const int count = static_cast<int>(state.range(0));
    scenes::buildStack(world, count, scenes::material(kFriction));
    stepScene(state, world, count);
}
BENCHMARK(BM_StackStep)->Arg(5)->Arg(10)->Arg(20)->Arg(40)->Unit(benchmark::kMicrosecond);

// A planar pyramid of unit cubes with the given base (the `pyramid` case: 210 cubes for 20).
void BM_PyramidStep(benchmark::State& state) {
    World world(scenes::stackWorld());
    scenes::addGround(world, scenes::material(kFriction));
    std::vector<int> levels;
    const std::vector<BodyId> cubes = scenes::buildPyramid(
        world, static_cast<int>(state.range(0)), 0.05, scenes::material(kFriction), levels);
    stepScene(state, world, static_cast<int>(cubes.size()));
}
BENCHMARK(BM_PyramidStep)->Arg(20)->Arg(40)->Unit(benchmark::kMillisecond);

// The PGS sweep alone: N unit boxes (2 kg) each resting on four corners on a static ground,
// coupled friction, split impulse off the table (Baumgarte, no relax sweeps), so the time is
// `iterations` sweeps over 3 rows per point (normal, two friction) plus one preparation.
void BM_PgsRowIteration(benchmark::State& state) {
    const int boxes = static_cast<int>(state.range(0));
    const int iterations = static_cast<int>(state.range(1));
    constexpr Real kH = 1.0 / 60;
    std::vector<SolverBody> bodies(boxes + 1);
    std::vector<ContactConstraint> constraints(boxes);
    for (int k = 0; k < boxes; ++k) {
        bodies[k + 1].inverseMass = 0.5;
        bodies[k + 1].inverseInertia = Mat3::Identity() * 3;
        constraints[k] = testkit::cubeOnGround(static_cast<std::uint32_t>(k + 1), kFriction);
    }
    SolverSettings settings;
    settings.iterations = iterations;
    settings.stabilisation = Stabilisation::Baumgarte;
    ConstraintSolver solver;
    std::vector<PseudoVelocity> pseudo;
    for (auto _ : state) {
        // Each box sliding a little and falling, so every row has work to do.
        for (int k = 0; k < boxes; ++k) {
            bodies[k + 1].linearVelocity = Vec3(0.1, 0.05 * (k % 3), -9.81 * kH);
            bodies[k + 1].angularVelocity = Vec3::Zero();
        }
        benchmark::DoNotOptimize(solver.solve(bodies, constraints, pseudo, kH, settings));
    }
    const double rows = 3.0 * 4 * boxes;
    state.counters["ns_per_row_iteration"] =
        benchmark::Counter(static_cast<double>(state.iterations()) * rows * iterations * 1e-9,
                           benchmark::Counter::kIsRate | benchmark::Counter::kInvert);
}
BENCHMARK(BM_PgsRowIteration)->Args({1000, 10})->Args({1000, 40})->Unit(benchmark::kMicrosecond);

// The contact sweeps on tumble-bench's own scenes, as its Tumble peer sets them up: ns per
// contact row per sweep, from the solver's stage times (biased and relax sweeps) over the rows
// of the contacts each step solved (a normal and, with friction, two tangent rows per point).
const bench::PeerWorld* watched = nullptr;
std::unique_ptr<bench::PeerWorld> createWatched(const bench::SceneSettings& settings) {
    std::unique_ptr<bench::PeerWorld> world = bench::createTumble(settings);
    watched = world.get();
    return world;
}

double threadSeconds() {
    timespec t{};
    clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
    return static_cast<double>(t.tv_sec) + 1e-9 * static_cast<double>(t.tv_nsec);
}

// The stage times are wall-clock: on a shared machine the step's CPU time is split in their
// proportions, so the figure is the sweeps' CPU time.
void BM_SceneSweepRow(benchmark::State& state, bench::SceneKind kind, int size,
                      bool coloured = false) {
    const bench::SceneSettings settings{.colouredContacts = coloured};
    bench::SceneRun run({"tumble", &createWatched},
                        bench::Scene{.name = "sweep", .size = size, .kind = kind}, settings);
    const World& world = *bench::tumbleWorld(*watched);
    for (int i = 0; i < 3 * kSettleSteps; ++i)
        run.step();
    double seconds = 0;
    double rowSweeps = 0;
    double rows = 0;
    double manifolds = 0;
    for (auto _ : state) {
        const double start = threadSeconds();
        run.step();
        const double cpu = threadSeconds() - start;
        const SolverProfile& p = world.profile().solveStages;
        seconds += cpu * (p.velocity + p.relax) / world.profile().total;
        rows = 0;
        manifolds = 0;
        for (const Contact& c : world.contacts()) {
            rows += c.manifold.pointCount * (settings.friction > 0 ? 3.0 : 1.0);
            manifolds += c.manifold.pointCount > 0 ? 1 : 0;
        }
        rowSweeps +=
            rows * (world.solverStats().iterations + world.settings().solver.relaxIterations);
    }
    state.counters["contact_rows"] = rows;
    // Points per manifold: the scalar sweep's compact rows store only these (sweep_rows.h).
    state.counters["points_per_manifold"] =
        manifolds > 0 ? rows / (settings.friction > 0 ? 3.0 : 1.0) / manifolds : 0;
    state.counters["ns_per_row_sweep"] = rowSweeps > 0 ? 1e9 * seconds / rowSweeps : 0;
}
BENCHMARK_CAPTURE(BM_SceneSweepRow, pyramid20, bench::SceneKind::Pyramid, 20)
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_SceneSweepRow, pile4000, bench::SceneKind::Pile, 4000)
    ->Unit(benchmark::kMillisecond);
// The same on coloured wide rows (contact_rows.h).
BENCHMARK_CAPTURE(BM_SceneSweepRow, pyramid20Coloured, bench::SceneKind::Pyramid, 20, true)
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_SceneSweepRow, pile4000Coloured, bench::SceneKind::Pile, 4000, true)
    ->Unit(benchmark::kMillisecond);

}  // namespace
