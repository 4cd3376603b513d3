// Speed versus error (issue 7, item 3). For each scene, engine, time step h and iteration count:
// the wall time per simulated second and the scene's error, then each engine's Pareto front.
//
// Errors:
// - stack, pyramid: the analytic answer is rest, so the error is the largest horizontal
//   displacement of any cube at any step (m). Vertical settling is left out: it is each engine's
//   penetration allowance (Tumble's slop, Bullet's margin), a setting rather than an accuracy;
//   the deepest penetration is in the CSV beside it.
// - chain (Tumble only; Bullet has no implicit springs): validation/cases/hanging_chain.cpp's
//   lumped chain (N = 30 beads, EA = 1e6 N, implicit springs) started 1 mm off in each of its
//   first three modes; the error is the largest sideways difference of any bead from the
//   converged reference run (the smallest h with the most iterations), sampled every 0.1 s (m).

#include "sweep.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <limits>
#include <numbers>
#include <set>
#include <string>
#include <vector>

#include "lumped.h"
#include "peer.h"
#include "scene.h"
#include "tumble/tumble.h"

namespace tumble::bench {
namespace {

constexpr double kTimeSteps[] = {1.0 / 30,  1.0 / 60,   1.0 / 120, 1.0 / 240,
                                 1.0 / 480, 1.0 / 1000, 1.0 / 2000};
constexpr int kIterations[] = {4, 10, 20, 50, 100};
constexpr double kSampleInterval = 0.1;  // (s): a whole number of steps of every h above

struct Point {
    std::string scene;
    std::string engine;
    double h = 0;
    int iterations = 0;
    double wallPerSimulatedSecond = 0;  // (s/s)
    double error = 0;                   // (m), see the file comment
    double deepest = 0;                 // deepest penetration over the run (m), cubes only
    bool reference = false;             // the run the others were measured against
    bool front = false;
};

bool wanted(const SweepOptions& options, const std::string& scene) {
    return options.scenes.empty() ||
           std::find(options.scenes.begin(), options.scenes.end(), scene) != options.scenes.end();
}

int stepsFor(double duration, double h) {
    return static_cast<int>(std::lround(duration / h));
}

Point runCubes(const Peer& peer, const Scene& scene, const std::string& label, double h,
               int iterations, double duration) {
    SceneSettings settings;
    settings.timeStep = h;
    settings.iterations = iterations;
    auto world = peer.create(settings);
    const std::vector<Vec3> start = build(*world, scene);
    Point p{.scene = label, .engine = peer.name, .h = h, .iterations = iterations};
    double busy = 0;
    const int steps = stepsFor(duration, h);
    for (int s = 0; s < steps; ++s) {
        const auto t0 = std::chrono::steady_clock::now();
        world->step();
        busy += std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
        p.deepest = std::max(p.deepest, world->deepestPenetration());
        for (std::size_t i = 0; i < start.size(); ++i) {
            const double drift = (world->position(static_cast<int>(i)) - start[i]).head<2>().norm();
            // A NaN (an engine blown up) counts as the worst error, not as none.
            p.error = std::isfinite(drift) ? std::max(p.error, drift) : INFINITY;
        }
    }
    p.wallPerSimulatedSecond = busy / duration;
    return p;
}

// The hanging chain of validation/cases/hanging_chain.cpp: sideways bead positions every
// kSampleInterval, and the busy time.
struct ChainRun {
    std::vector<double> samples;
    double busy = 0;
};

ChainRun runChain(double h, int iterations, double duration) {
    constexpr int kBeads = 30;
    constexpr double kLength = 1, kDensity = 1, kGravity = 9.81, kAxialRigidity = 1e6;
    constexpr double kZeros[3] = {2.404825557695773, 5.520078110286311, 8.653727912911013};
    const double a = kLength / kBeads;
    WorldDef def;
    def.gravity = Vec3(0, 0, -kGravity);
    def.timeStep = h;
    def.enableSleep = false;
    def.solver.iterations = iterations;
    def.solver.relaxIterations = iterations;
    World world(def);
    std::vector<BodyId> beads;
    for (int j = 1; j <= kBeads; ++j) {
        const double depth = a * (j - 0.5);
        const double s = kLength - depth;  // from the free end
        double x = 0;
        for (const double zero : kZeros)
            x += 1e-3 * std::cyl_bessel_j(0.0, zero * std::sqrt(s / kLength));
        beads.push_back(validation::addPointMass(world, Vec3(x, 0, -depth), kDensity * a));
    }
    SpringDef spring;
    spring.formulation = SpringFormulation::Implicit;
    for (int j = 0; j < kBeads; ++j) {
        spring.restLength = j == 0 ? 0.5 * a : a;
        spring.stiffness = axialStiffness(kAxialRigidity, 1, spring.restLength);
        spring.bodyA = beads[j];
        spring.bodyB = j == 0 ? BodyId{} : beads[j - 1];
        world.createSpring(spring);
    }
    ChainRun run;
    const int steps = stepsFor(duration, h);
    const int every = static_cast<int>(std::lround(kSampleInterval / h));
    for (int s = 1; s <= steps; ++s) {
        const auto t0 = std::chrono::steady_clock::now();
        const bool ok = world.step().ok();
        run.busy += std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
        if (!ok) {
            run.samples.assign(run.samples.size(), INFINITY);
            break;
        }
        if (s % every == 0) {
            for (const BodyId bead : beads)
                run.samples.push_back(world.position(bead).x());
        }
    }
    return run;
}

// Marks the points of each (scene, engine) no other point beats in both cost and error.
void markFronts(std::vector<Point>& points) {
    for (Point& p : points) {
        if (p.reference || !std::isfinite(p.error))
            continue;
        p.front = std::none_of(points.begin(), points.end(), [&](const Point& q) {
            return &q != &p && !q.reference && q.scene == p.scene && q.engine == p.engine &&
                   q.wallPerSimulatedSecond <= p.wallPerSimulatedSecond && q.error <= p.error &&
                   (q.wallPerSimulatedSecond < p.wallPerSimulatedSecond || q.error < p.error);
        });
    }
}

std::string fraction(double h) {
    char text[32];
    std::snprintf(text, sizeof text, "1/%.0f", 1 / h);
    return text;
}

// The least error an engine reaches on a scene within a budget of wall time, or infinity.
double bestWithin(const std::vector<Point>& points, const std::string& scene,
                  const std::string& engine, double budget) {
    double best = INFINITY;
    for (const Point& p : points) {
        if (p.scene == scene && p.engine == engine && !p.reference &&
            p.wallPerSimulatedSecond <= budget)
            best = std::min(best, p.error);
    }
    return best;
}

void writeCsv(const std::string& path, const std::vector<Point>& points) {
    std::ofstream out(path);
    out << "scene,engine,h_s,iterations,wall_s_per_sim_s,error_m,deepest_penetration_m,"
           "reference,pareto\n";
    out.precision(6);
    for (const Point& p : points) {
        out << p.scene << ',' << p.engine << ',' << p.h << ',' << p.iterations << ','
            << p.wallPerSimulatedSecond << ',' << p.error << ',' << p.deepest << ','
            << (p.reference ? 1 : 0) << ',' << (p.front ? 1 : 0) << '\n';
    }
}

void writeMarkdown(const std::string& path, const std::vector<Point>& points,
                   const SweepOptions& options) {
    std::ofstream out(path);
    out << "# Speed versus error\n\n"
        << "h in {1/30 ... 1/2000} s, iterations in {4, 10, 20, 50, 100} (Tumble: as many "
           "split-impulse sweeps again; Bullet: its split-impulse pass), "
        << options.duration
        << " s simulated per run, one run per point. Error: largest "
           "horizontal drift of any cube (stack, pyramid; analytic answer 0), largest bead "
           "deviation from the converged run h = 1/2000, 100 iterations (chain).\n";
    std::set<std::string> scenes;
    for (const Point& p : points)
        scenes.insert(p.scene);
    for (const std::string& scene : scenes) {
        out << "\n## " << scene << "\n\n| engine | h (s) | iterations | wall s per sim s | "
            << "error (m) |\n|---|---|---|---|---|\n";
        std::vector<Point> front;
        std::set<std::string> engines;
        for (const Point& p : points) {
            if (p.scene == scene && p.front)
                front.push_back(p);
            if (p.scene == scene)
                engines.insert(p.engine);
        }
        std::sort(front.begin(), front.end(), [](const Point& a, const Point& b) {
            return a.engine != b.engine ? a.engine > b.engine
                                        : a.wallPerSimulatedSecond < b.wallPerSimulatedSecond;
        });
        for (const Point& p : front) {
            char row[160];
            std::snprintf(row, sizeof row, "| %s | %s | %d | %.4g | %.3g |\n", p.engine.c_str(),
                          fraction(p.h).c_str(), p.iterations, p.wallPerSimulatedSecond, p.error);
            out << row;
        }
        if (engines.size() < 2)
            continue;
        // Both fronts side by side at each front point's cost: the least error each engine
        // reaches within that wall time.
        out << "\nAt equal budget (least error within the wall time of each front point):\n\n"
            << "| budget (s per sim s) | tumble error (m) | bullet error (m) | lower |\n"
            << "|---|---|---|---|\n";
        int tumbleAbove = 0, total = 0;
        for (const Point& p : front) {
            const double t = bestWithin(points, scene, "tumble", p.wallPerSimulatedSecond);
            const double b = bestWithin(points, scene, "bullet", p.wallPerSimulatedSecond);
            const char* lower = t < b ? "tumble" : (b < t ? "bullet" : "equal");
            tumbleAbove += b < t;
            ++total;
            char row[160];
            std::snprintf(row, sizeof row, "| %.4g | %.3g | %.3g | %s |\n",
                          p.wallPerSimulatedSecond, t, b, lower);
            out << row;
        }
        out << "\nTumble's front is above Bullet's at " << tumbleAbove << " of " << total
            << " budgets (inf: no run that cheap).\n";
    }
}

}  // namespace

int runSweep(const SweepOptions& options) {
    std::filesystem::create_directories(options.outDir);
    std::vector<Point> points;
    const auto progress = [](const Point& p) {
        std::printf("%-10s %-7s h = %-7s it = %3d: %9.4g s per sim s, error %.3g m\n",
                    p.scene.c_str(), p.engine.c_str(), fraction(p.h).c_str(), p.iterations,
                    p.wallPerSimulatedSecond, p.error);
        std::fflush(stdout);
    };
    const std::vector<std::pair<std::string, Scene>> cubeScenes = {
        {"stack",
         {"stack-" + std::to_string(options.stackSize), options.stackSize, SceneKind::Stack}},
        {"pyramid",
         {"pyramid-" + std::to_string(options.pyramidBase), options.pyramidBase,
          SceneKind::Pyramid}}};
    for (const auto& [key, scene] : cubeScenes) {
        if (!wanted(options, key))
            continue;
        for (const Peer& peer : peers()) {
            for (const double h : kTimeSteps) {
                for (const int iterations : kIterations) {
                    points.push_back(
                        runCubes(peer, scene, scene.name, h, iterations, options.duration));
                    progress(points.back());
                }
            }
        }
    }
    if (wanted(options, "chain")) {
        const double hRef = kTimeSteps[std::size(kTimeSteps) - 1];
        const int itRef = kIterations[std::size(kIterations) - 1];
        const ChainRun reference = runChain(hRef, itRef, options.duration);
        for (const double h : kTimeSteps) {
            for (const int iterations : kIterations) {
                const bool isRef = h == hRef && iterations == itRef;
                const ChainRun run = isRef ? reference : runChain(h, iterations, options.duration);
                Point p{.scene = "chain-30", .engine = "tumble", .h = h, .iterations = iterations};
                p.reference = isRef;
                p.wallPerSimulatedSecond = run.busy / options.duration;
                for (std::size_t i = 0; i < reference.samples.size(); ++i) {
                    const double d = i < run.samples.size()
                                         ? std::abs(run.samples[i] - reference.samples[i])
                                         : INFINITY;
                    p.error = std::isfinite(d) ? std::max(p.error, d) : INFINITY;
                }
                points.push_back(p);
                progress(p);
            }
        }
    }
    markFronts(points);
    const std::string csv = options.outDir + "/sweep.csv";
    const std::string md = options.outDir + "/pareto.md";
    writeCsv(csv, points);
    writeMarkdown(md, points, options);
    std::printf("\nwrote %s and %s\n", csv.c_str(), md.c_str());
#ifdef TUMBLE_BENCH_PLOT_SCRIPT
    const std::string command = std::string("/usr/bin/python3 ") + TUMBLE_BENCH_PLOT_SCRIPT + " " +
                                csv + " " + options.outDir + "/pareto.png";
    if (options.plot && std::filesystem::exists("/usr/bin/python3")) {
        if (std::system(command.c_str()) != 0)
            std::printf("plotting failed (python3-matplotlib missing?): %s\n", command.c_str());
    } else {
        std::printf("to plot: %s\n", command.c_str());
    }
#endif
    return 0;
}

}  // namespace tumble::bench
