// tumble-bench: the stack and pyramid scenes in Tumble and in each peer engine found at configure
// time, with matched settings, side by side: wall time per simulated second (median of several
// runs, with the spread), real-time factor, and each scene's error metric (top drift, deepest
// penetration, whether it collapsed). Prints a Markdown table; --json writes the same figures.
// --sweep DIR instead sweeps h and iterations for the speed-versus-error fronts (sweep.h).

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <fstream>
#include <string>
#include <vector>

#include "peer.h"
#include "scene.h"
#include "sweep.h"

namespace {

using namespace tumble;
using namespace tumble::bench;

struct Outcome {
    std::vector<double> wallPerSimulatedSecond;  // one per run (s/s)
    double topDrift = 0;                         // largest horizontal offset of the top cube (m)
    double deepest = 0;                          // deepest penetration over the run (m)
    double collapsedAt = -1;                     // when any cube first moved 0.5 m (s), or -1
};

Outcome run(const Peer& peer, const Scene& scene, const SceneSettings& settings, double duration,
            int runs) {
    Outcome outcome;
    const int steps = static_cast<int>(duration / settings.timeStep + 0.5);
    for (int r = 0; r < runs; ++r) {
        auto world = peer.create(settings);
        const std::vector<Vec3> start = build(*world, scene);
        const int top = static_cast<int>(start.size()) - 1;
        double busy = 0;
        for (int s = 0; s < steps; ++s) {
            const auto t0 = std::chrono::steady_clock::now();
            world->step();
            busy += std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
            if (r > 0)
                continue;  // the metrics are the same every run; measure them once
            outcome.deepest = std::max(outcome.deepest, world->deepestPenetration());
            const Vec3 offset = world->position(top) - start[top];
            outcome.topDrift = std::max(outcome.topDrift, offset.head<2>().norm());
            if (outcome.collapsedAt < 0) {
                for (int i = 0; i <= top; ++i) {
                    if ((world->position(i) - start[i]).norm() > 0.5) {
                        outcome.collapsedAt = (s + 1) * settings.timeStep;
                        break;
                    }
                }
            }
        }
        outcome.wallPerSimulatedSecond.push_back(busy / duration);
    }
    return outcome;
}

double median(std::vector<double> v) {
    std::sort(v.begin(), v.end());
    const std::size_t n = v.size();
    return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

}  // namespace

int main(int argc, char** argv) {
    CLI::App app{"tumble-bench: stacks and pyramids in Tumble and its peers, side by side"};
    int runs = 5;
    double duration = 5;
    std::string jsonPath;
    std::vector<std::string> only;
    app.add_option("--runs", runs, "timed runs per scene and engine (median and spread)")
        ->check(CLI::PositiveNumber);
    app.add_option("--time", duration, "simulated seconds per run")->check(CLI::PositiveNumber);
    app.add_option("--json", jsonPath, "also write the figures as JSON to this file");
    app.add_option("--scene", only, "run only these scenes (e.g. stack-20 pyramid-20)");
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
    app.add_option("--sweep-scene", sweep.scenes, "sweep only these: stack, pyramid, chain")
        ->check(CLI::IsMember({"stack", "pyramid", "chain"}));
    app.add_flag("!--no-plot", sweep.plot, "do not run the plotting script after the sweep");
    CLI11_PARSE(app, argc, argv);
    if (!sweep.outDir.empty())
        return runSweep(sweep);

    const std::vector<Scene> scenes = {{"stack-5", 5, false},    {"stack-10", 10, false},
                                       {"stack-20", 20, false},  {"stack-40", 40, false},
                                       {"pyramid-20", 20, true}, {"pyramid-40", 40, true}};
    const SceneSettings settings;
    for (const std::string& skipped : skippedPeers())
        std::printf("skipped: %s\n", skipped.c_str());
    std::printf(
        "h = 1/%.0f s, %d iterations, mu = %.2f, unit cubes of %.0f kg, %.1f s per run, "
        "%d runs\n\n",
        1 / settings.timeStep, settings.iterations, settings.friction, settings.boxMass, duration,
        runs);
    std::printf(
        "| scene | engine | wall s per sim s: median [min, max] | real-time factor | "
        "top drift (m) | deepest penetration (m) | collapsed at (s) | time / Tumble |\n");
    std::printf("|---|---|---|---|---|---|---|---|\n");
    nlohmann::json report = nlohmann::json::array();
    for (const Scene& scene : scenes) {
        if (!only.empty() && std::find(only.begin(), only.end(), scene.name) == only.end())
            continue;
        double tumbleMedian = 0;
        for (const Peer& peer : peers()) {
            const Outcome o = run(peer, scene, settings, duration, runs);
            const double m = median(o.wallPerSimulatedSecond);
            if (peer.name == "tumble")
                tumbleMedian = m;
            const auto [lo, hi] = std::minmax_element(o.wallPerSimulatedSecond.begin(),
                                                      o.wallPerSimulatedSecond.end());
            std::printf("| %s | %s | %.4f [%.4f, %.4f] | %.1f | %.3g | %.3g | %s | %.2f |\n",
                        scene.name.c_str(), peer.name.c_str(), m, *lo, *hi, 1 / m, o.topDrift,
                        o.deepest, o.collapsedAt < 0 ? "no" : std::to_string(o.collapsedAt).c_str(),
                        m / tumbleMedian);
            std::fflush(stdout);
            report.push_back({{"scene", scene.name},
                              {"engine", peer.name},
                              {"wall_s_per_sim_s", o.wallPerSimulatedSecond},
                              {"median_wall_s_per_sim_s", m},
                              {"realtime_factor", 1 / m},
                              {"top_drift_m", o.topDrift},
                              {"deepest_penetration_m", o.deepest},
                              {"collapsed_at_s", o.collapsedAt}});
        }
    }
    if (!jsonPath.empty())
        std::ofstream(jsonPath) << report.dump(2) << "\n";
    return 0;
}
