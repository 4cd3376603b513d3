// tumble-bench: the stack and pyramid scenes in Tumble and in each peer engine found at configure
// time, with matched settings, side by side: wall time per simulated second (median of several
// runs, with the spread), real-time factor, and each scene's error metric (top drift, deepest
// penetration, whether it collapsed). Prints a Markdown table; --json writes the same figures.

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <fstream>
#include <string>
#include <vector>

#include "peer.h"

namespace {

using namespace tumble;
using namespace tumble::bench;

struct Scene {
    std::string name;
    int size;  // cubes in the column, or the pyramid's base
    bool pyramid;
};

struct Outcome {
    std::vector<double> wallPerSimulatedSecond;  // one per run (s/s)
    double topDrift = 0;                         // largest horizontal offset of the top cube (m)
    double deepest = 0;                          // deepest penetration over the run (m)
    double collapsedAt = -1;                     // when any cube first moved 0.5 m (s), or -1
};

// Builds the scene, returns the cubes' start positions (the top cube last).
std::vector<Vec3> build(PeerWorld& world, const Scene& scene) {
    world.addGround();
    std::vector<Vec3> start;
    if (!scene.pyramid) {
        for (int i = 0; i < scene.size; ++i)
            start.push_back(Vec3(0, 0, 0.5 + i));
    } else {
        constexpr double kPitch = 1.05;  // 5 cm between neighbours, as in the `pyramid` case
        for (int row = 0; row < scene.size; ++row) {
            const int n = scene.size - row;
            for (int i = 0; i < n; ++i)
                start.push_back(Vec3((i - 0.5 * (n - 1)) * kPitch, 0, 0.5 + row));
        }
    }
    for (const Vec3& p : start)
        world.addCube(p);
    return start;
}

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
    CLI11_PARSE(app, argc, argv);

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
