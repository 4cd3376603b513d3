// tumble-bench: the harness's scenes -- stacks, pyramids, nets, piles -- in Tumble and in each peer
// engine found at configure time, with matched settings, side by side: wall time per simulated
// second (median of several runs, with the spread), real-time factor, and each scene's error
// metric (top drift, deepest penetration, energy error, whether and when it collapsed). Prints a
// Markdown table and writes it as Markdown and CSV; --json writes the runs too.
// --sweep DIR instead sweeps h and iterations for the speed-versus-error fronts (sweep.h);
// --scaling times a step against the body count (scaling.h); --string DIR runs the study's
// hanging string in the peers (string_peers.h); --study DIR the study's oscillator and bouncing
// ball (study_peers.h).

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <ctime>
#include <fstream>
#include <limits>
#include <memory>
#include <sstream>
#include <string>
#include <vector>

#include "peer.h"
#include "scaling.h"
#include "scene.h"
#include "string_peers.h"
#include "study_peers.h"
#include "sweep.h"
#include "timing.h"

namespace {

using namespace tumble;
using namespace tumble::bench;

struct Row {
    std::string scene;
    std::string engine;
    std::string skipped;                         // why the engine did not run it, or empty
    std::vector<double> wallPerSimulatedSecond;  // one per run (s/s)
    std::vector<double> cpuPerSimulatedSecond;   // this thread's CPU time, one per run (s/s)
    double median = 0;
    double cpuMedian = 0;
    double ratio = 0;     // this engine's median wall time over Tumble's
    double cpuRatio = 0;  // and CPU time
    Metrics metrics{};
};

// Times the scene `runs` times: from scratch each time, timing the steps only; the metrics come
// from the first run (the engines are deterministic: every run is the same). A pile is built
// once instead -- rebuilding thousands of bodies five times would take minutes -- and stepped
// untimed through its landing (kPileLanding, measured for the error), then timed over `runs`
// consecutive windows of `duration` each: the figures are the settled pile's.
constexpr double kPileLanding = 1;  // (s): the top layer falls about 2.5 m

struct Timing {
    double wall;  // per simulated second (s/s)
    double cpu;
};

Timing timedSteps(SceneRun& sceneRun, double start, double duration, bool measure) {
    const int steps = static_cast<int>(duration / sceneRun.timeStep() + 0.5);
    double busy = 0;
    double cpu = 0;
    for (int s = 0; s < steps; ++s) {
        const auto t0 = std::chrono::steady_clock::now();
        const double c0 = cpuNow();
        sceneRun.step();
        cpu += cpuNow() - c0;
        busy += std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
        if (measure)
            sceneRun.measure(start + (s + 1) * sceneRun.timeStep());
    }
    return {busy / duration, cpu / duration};
}

Row run(const Peer& peer, const Scene& scene, const SceneSettings& settings, double duration,
        int runs) {
    Row row;
    row.scene = scene.name;
    row.engine = peer.name;
    const bool pile = scene.pile();
    std::unique_ptr<SceneRun> sceneRun;
    double time = 0;
    for (int r = 0; r < runs; ++r) {
        if (!pile || r == 0) {
            sceneRun = std::make_unique<SceneRun>(peer, scene, settings);
            if (!sceneRun->skipped().empty()) {
                row.skipped = sceneRun->skipped();
                return row;
            }
            time = 0;
            if (pile) {
                timedSteps(*sceneRun, 0, kPileLanding, true);
                time = kPileLanding;
            }
        }
        const Timing timing = timedSteps(*sceneRun, time, duration, r == 0 || pile);
        row.wallPerSimulatedSecond.push_back(timing.wall);
        row.cpuPerSimulatedSecond.push_back(timing.cpu);
        time += duration;
        if (r == 0 || pile)
            row.metrics = sceneRun->metrics();
    }
    row.median = median(row.wallPerSimulatedSecond);
    row.cpuMedian = median(row.cpuPerSimulatedSecond);
    return row;
}

std::string number(double x, const char* format = "%.3g") {
    if (std::isnan(x))
        return "-";
    char buffer[64];
    std::snprintf(buffer, sizeof buffer, format, x);
    return buffer;
}

std::string markdownRow(const Row& r) {
    std::ostringstream out;
    out << "| " << r.scene << " | " << r.engine << " | ";
    if (!r.skipped.empty()) {
        out << "skipped: " << r.skipped << " | | | | | | | | |";
        return out.str();
    }
    const auto [lo, hi] =
        std::minmax_element(r.wallPerSimulatedSecond.begin(), r.wallPerSimulatedSecond.end());
    out << number(r.median, "%.4g") << " [" << number(*lo, "%.4g") << ", " << number(*hi, "%.4g")
        << "] | " << number(1 / r.median, "%.3g") << " | " << number(r.metrics.topDrift) << " | "
        << number(r.metrics.deepest) << " | " << number(r.metrics.energyError) << " | "
        << (r.metrics.collapsedAt < 0 ? std::string("no") : number(r.metrics.collapsedAt, "%.2f"))
        << " | " << number(r.ratio, "%.2f") << " | " << number(r.cpuMedian, "%.4g") << " | "
        << number(r.cpuRatio, "%.2f") << " |";
    return out.str();
}

std::string csvRow(const Row& r) {
    std::ostringstream out;
    out << r.scene << "," << r.engine << ","
        << (r.skipped.empty() ? "ran" : "skipped: " + r.skipped);
    if (r.skipped.empty()) {
        const auto [lo, hi] =
            std::minmax_element(r.wallPerSimulatedSecond.begin(), r.wallPerSimulatedSecond.end());
        out << "," << number(r.median, "%.6g") << "," << number(*lo, "%.6g") << ","
            << number(*hi, "%.6g") << "," << number(1 / r.median, "%.6g") << ","
            << number(r.metrics.topDrift, "%.6g") << "," << number(r.metrics.deepest, "%.6g") << ","
            << number(r.metrics.energyError, "%.6g") << "," << number(r.metrics.collapsedAt, "%.6g")
            << "," << number(r.ratio, "%.4g") << "," << number(r.cpuMedian, "%.6g") << ","
            << number(r.cpuRatio, "%.4g");
    } else {
        out << ",,,,,,,,,,,,";
    }
    return out.str();
}

bool selected(const std::vector<std::string>& filter, const std::string& name) {
    if (filter.empty())
        return true;
    return std::any_of(filter.begin(), filter.end(), [&](const std::string& f) {
        return name == f || name.rfind(f + "-", 0) == 0;  // "pile" selects pile-1000, ...
    });
}

// Tumble's sweeps in the header: "B biased + R relax sweeps".
std::string budget(const SceneSettings& s) {
    const int biased = s.tumbleIterations >= 0 ? s.tumbleIterations : s.iterations;
    const int relax = s.tumbleRelaxIterations >= 0 ? s.tumbleRelaxIterations : s.iterations;
    const SolverSettings links;
    return std::to_string(biased) + " biased + " + std::to_string(relax) + " relax sweeps" +
           " (with links at least " + std::to_string(links.linkIterations) + " + " +
           std::to_string(links.linkRelaxIterations) + ")" +
           (s.colouredContacts ? ", coloured" : "");
}

// Default simulated time per run: long enough for a stack to fall if it will, a pile to land
// and a net to open and spring back, short enough for the whole run to take a few minutes.
double defaultDuration(const Scene& scene, bool quick) {
    if (quick)
        return scene.pile() ? 0.25 : 1;
    if (scene.pile())
        return 0.5;  // per timed window, after the landing (see run)
    return scene.kind == SceneKind::Stack ? 5 : 2;
}

}  // namespace

int main(int argc, char** argv) {
    CLI::App app{"tumble-bench: stacks, pyramids, nets and piles in Tumble and its peers"};
    int runs = 5;
    double duration = 0;
    bool quick = false;
    std::string jsonPath;
    std::string outPrefix = "tumble-bench";
    std::vector<std::string> only;
    app.add_option("--runs", runs, "timed runs per scene and engine (median and spread)")
        ->check(CLI::PositiveNumber);
    app.add_option("--time", duration,
                   "simulated seconds per run (default: 5 for stacks, 2 for pyramids and nets; "
                   "piles: per timed window after 1 s of landing, default 0.5)")
        ->check(CLI::PositiveNumber);
    app.add_flag("--quick", quick, "the smaller scenes only, 1 s per run (a smoke test)");
    app.add_option("--scene", only,
                   "run only these scenes, by name or kind (stack-20, pyramid, net, pile-1000)");
    app.add_option("--out", outPrefix, "write the table to PREFIX.md and PREFIX.csv ('' : don't)");
    app.add_option("--json", jsonPath, "also write every run's figures as JSON to this file");
    SweepOptions sweep;
    app.add_option("--sweep", sweep.outDir,
                   "speed versus error instead: sweep h and iterations, write the Pareto fronts "
                   "(sweep.csv, pareto.md, pareto.png) to this directory");
    app.add_option("--sweep-time", sweep.duration, "simulated seconds per sweep run")
        ->check(CLI::PositiveNumber);
    app.add_option("--sweep-stack", sweep.stackSize, "cubes in the sweep's column")
        ->check(CLI::PositiveNumber);
    app.add_option("--sweep-pyramid", sweep.pyramidBase, "base of the sweep's pyramid")
        ->check(CLI::PositiveNumber);
    app.add_option("--sweep-scene", sweep.scenes, "sweep only these: stack, pyramid, chain, net")
        ->check(CLI::IsMember({"stack", "pyramid", "chain", "net"}));
    app.add_option("--sweep-repeats", sweep.repeats,
                   "timed runs per sweep point, the fastest kept (the errors do not change)")
        ->check(CLI::PositiveNumber);
    app.add_flag("!--no-plot", sweep.plot, "do not run the plotting script after the sweep");
    ScalingOptions scaling;
    app.add_flag("--scaling", scaling.enabled,
                 "time a step against the body count instead (piles of 1k-20k bodies, nets of "
                 "100-10,000 nodes) and fit the exponent");
    app.add_flag("--scaling-50k", scaling.with50k, "add a pile of 50,000 bodies to --scaling");
    app.add_option("--scaling-piles", scaling.piles,
                   "the piles' body counts instead of 1k, 2k, 4k, 10k, 20k (and 50k)")
        ->check(CLI::PositiveNumber);
    StringPeerOptions string;
    app.add_option("--string", string.outDir,
                   "the study's hanging string in the peers instead (for Fig. 7 and Fig. 10 "
                   "beside Tumble's): write string-peers-{transient,cost}.csv to this directory");
    StudyPeerOptions study;
    app.add_option("--study", study.outDir,
                   "the study's oscillator and bouncing ball in the peers instead (for Fig. 4 and "
                   "Fig. 5 beside Tumble's): write study-peers-{oscillator,bounce}.csv to this "
                   "directory");
    bool coloured = SolverSettings{}.colouredContacts;
    app.add_flag("--coloured-contacts,!--scalar-contacts", coloured,
                 "Tumble's contact sweeps on coloured wide rows (SolverSettings::colouredContacts) "
                 "or, --scalar-contacts, the scalar sweep in constraint order");
    bool anchors = SolverSettings{}.frictionAnchors;
    app.add_option("--friction-anchors", anchors,
                   "Tumble's friction anchors (SolverSettings::frictionAnchors): true or false")
        ->capture_default_str();
    // Tumble runs its own default budget, as each peer its own (a world with links -- the nets
    // -- takes SolverSettings::linkIterations' as every world does).
    int tumbleIterations = SolverSettings{}.iterations;
    int tumbleRelax = SolverSettings{}.relaxIterations;
    app.add_option("--tumble-iterations", tumbleIterations, "Tumble's biased sweeps")
        ->check(CLI::PositiveNumber)
        ->capture_default_str();
    app.add_option("--tumble-relax", tumbleRelax, "Tumble's relax sweeps")
        ->check(CLI::NonNegativeNumber)
        ->capture_default_str();
    double tumbleTolerance = SolverSettings{}.tolerance;
    app.add_option("--tumble-tolerance", tumbleTolerance,
                   "Tumble's early exit from the sweeps (SolverSettings::tolerance, m/s; 0 runs "
                   "every sweep)")
        ->check(CLI::NonNegativeNumber)
        ->capture_default_str();
    int tumbleSoft = 0;
    app.add_option("--tumble-soft", tumbleSoft,
                   "also run Tumble with the soft step of this many substeps "
                   "(SolverSettings::softSubsteps) as engine tumble-soft, beside its default")
        ->check(CLI::PositiveNumber);
    double tumbleSoftHertz = SolverSettings{}.contactHertz;
    app.add_option("--tumble-soft-hertz", tumbleSoftHertz,
                   "tumble-soft's SolverSettings::contactHertz (capped at a quarter of the "
                   "substep rate)")
        ->check(CLI::PositiveNumber)
        ->capture_default_str();
    std::vector<std::string> engines;
    app.add_option(
        "--engine", engines,
        "run only these engines (tumble, bullet, ode, box2d, mujoco); also for --scaling");
    CLI11_PARSE(app, argc, argv);
    if (!sweep.outDir.empty()) {
        sweep.engines = engines;
        return runSweep(sweep);
    }
    for (const std::string& skipped : skippedPeers())
        std::printf("skipped: %s\n", skipped.c_str());
    if (!string.outDir.empty()) {
        string.engines = engines;
        return runStringPeers(string);
    }
    if (!study.outDir.empty()) {
        study.engines = engines;
        return runStudyPeers(study);
    }
    if (scaling.enabled) {
        scaling.outPrefix = outPrefix;
        scaling.engines = engines;
        scaling.kinds = only;  // --scene pile / net
        scaling.colouredContacts = coloured;
        return runScaling(scaling);
    }

    std::vector<Scene> scenes = {
        {"stack-5", 5, SceneKind::Stack},       {"stack-10", 10, SceneKind::Stack},
        {"stack-20", 20, SceneKind::Stack},     {"stack-40", 40, SceneKind::Stack},
        {"pyramid-20", 20, SceneKind::Pyramid}, {"pyramid-40", 40, SceneKind::Pyramid}};
    for (const int n : {10, 20, 40}) {
        scenes.push_back({"net-" + std::to_string(n) + "-soft", n, SceneKind::Net, 0.5});
        scenes.push_back({"net-" + std::to_string(n) + "-stiff", n, SceneKind::Net, 20});
    }
    scenes.push_back({"pile-1000", 1000, SceneKind::Pile});
    scenes.push_back({"pile-4000", 4000, SceneKind::Pile});
    // The pile on terrain.h's bowl, as a height field and as the same triangles (issue 26).
    scenes.push_back({"terrain-pile", 1000, SceneKind::TerrainPile});
    scenes.push_back({"mesh-pile", 1000, SceneKind::MeshPile});
    if (quick && only.empty())
        only = {"stack-5", "stack-20", "pyramid-20", "net-10", "net-20", "pile-1000"};

    const SceneSettings settings{.colouredContacts = coloured,
                                 .frictionAnchors = anchors,
                                 .tumbleIterations = tumbleIterations,
                                 .tumbleRelaxIterations = tumbleRelax,
                                 .tumbleTolerance = tumbleTolerance,
                                 .tumbleSoftSubsteps = tumbleSoft,
                                 .tumbleSoftHertz = tumbleSoftHertz};
    std::vector<Peer> engineList = peers();
    if (tumbleSoft > 0)
        engineList.insert(engineList.begin() + 1, Peer{"tumble-soft", &createTumbleSoft});
    std::ostringstream header;
    header << "h = 1/" << number(1 / settings.timeStep, "%.0f") << " s, " << settings.iterations
           << " iterations (Tumble " << budget(settings)
           << "), mu = " << number(settings.friction, "%.2f") << ", restitution 0, " << runs
           << " runs per scene and engine (median [min, max]); piles: built once, " << kPileLanding
           << " s of landing untimed, then the runs are consecutive windows\n";
    const std::string tableHead =
        "| scene | engine | wall s per sim s: median [min, max] | real-time factor | top drift "
        "(m) | deepest penetration (m) | energy error | collapsed at (s) | time / Tumble | CPU s "
        "per sim s: median | CPU / "
        "Tumble |\n"
        "|---|---|---|---|---|---|---|---|---|---|---|\n";
    std::printf("%s\n%s", header.str().c_str(), tableHead.c_str());
    std::vector<Row> rows;
    for (const Scene& scene : scenes) {
        if (!selected(only, scene.name))
            continue;
        const double seconds = duration > 0 ? duration : defaultDuration(scene, quick);
        // Without Tumble in the run the ratios are NaN, printed "-".
        double tumbleMedian = std::numeric_limits<double>::quiet_NaN();
        double tumbleCpu = tumbleMedian;
        for (const Peer& peer : engineList) {
            if (!engineChosen(engines, peer.name) && peer.name != "tumble-soft")
                continue;
            Row row = run(peer, scene, settings, seconds, runs);
            if (peer.name == "tumble" && row.skipped.empty()) {
                tumbleMedian = row.median;
                tumbleCpu = row.cpuMedian;
            }
            row.ratio = row.median / tumbleMedian;
            row.cpuRatio = row.cpuMedian / tumbleCpu;
            std::printf("%s\n", markdownRow(row).c_str());
            std::fflush(stdout);
            rows.push_back(std::move(row));
        }
    }
    if (!outPrefix.empty()) {
        std::ofstream md(outPrefix + ".md");
        md << "# tumble-bench\n\n" << header.str() << "\n" << tableHead;
        for (const Row& r : rows)
            md << markdownRow(r) << "\n";
        std::ofstream csv(outPrefix + ".csv");
        csv << "scene,engine,status,median_wall_s_per_sim_s,min,max,realtime_factor,top_drift_m,"
               "deepest_penetration_m,energy_error,collapsed_at_s,time_over_tumble,"
               "median_cpu_s_per_sim_s,cpu_over_tumble\n";
        for (const Row& r : rows)
            csv << csvRow(r) << "\n";
        std::printf("\nwrote %s.md and %s.csv\n", outPrefix.c_str(), outPrefix.c_str());
    }
    if (!jsonPath.empty()) {
        nlohmann::json report = nlohmann::json::array();
        for (const Row& r : rows) {
            report.push_back({{"scene", r.scene},
                              {"engine", r.engine},
                              {"skipped", r.skipped},
                              {"wall_s_per_sim_s", r.wallPerSimulatedSecond},
                              {"median_wall_s_per_sim_s", r.median},
                              {"cpu_s_per_sim_s", r.cpuPerSimulatedSecond},
                              {"top_drift_m", r.metrics.topDrift},
                              {"deepest_penetration_m", r.metrics.deepest},
                              {"energy_error", r.metrics.energyError},
                              {"collapsed_at_s", r.metrics.collapsedAt}});
        }
        std::ofstream(jsonPath) << report.dump(2) << "\n";
    }
    return 0;
}
