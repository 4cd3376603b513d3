// Scaling (scaling.h). Each point builds the scene, steps it untimed until it is in its working
// state -- the pile landed (1 s: the top layer falls about 2.5 m), the net opened (0.25 s) -- and
// then times 30 steps one by one on the thread's CPU clock (on a shared machine wall time also
// counts the other processes); the figure is their median. The nets are the soft ones
// (omega_e h = 0.5), the stiffest every engine's threads stay stable at. For Tumble the step's
// own stage timers (wall clock, Profile) are summed too, to show which stage grows.

#include "scaling.h"

#include <time.h>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <limits>

#include "tumble/world.h"

#include "peer.h"
#include "scene.h"

namespace tumble::bench {
namespace {

constexpr int kTimedSteps = 30;

struct Point {
    std::string engine;
    std::string scene;
    int count = 0;        // bodies or nodes
    double stepTime = 0;  // median wall time of a step (s)
    double spreadLo = 0;  // first quartile (s)
    double spreadHi = 0;  // third quartile (s)
    // Tumble: shares of the timed steps' summed stage times (wall clock); negative otherwise.
    double broadphase = -1, narrowphase = -1, solve = -1, sweeps = -1, rest = -1;
};

double threadSeconds() {
    timespec t{};
    clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
    return static_cast<double>(t.tv_sec) + 1e-9 * static_cast<double>(t.tv_nsec);
}

double quantile(std::vector<double> v, double q) {
    std::sort(v.begin(), v.end());
    const double at = q * static_cast<double>(v.size() - 1);
    const auto i = static_cast<std::size_t>(at);
    const std::size_t j = std::min(i + 1, v.size() - 1);
    return v[i] + (at - static_cast<double>(i)) * (v[j] - v[i]);
}

bool measure(const Peer& peer, const Scene& scene, int count, double settle, bool coloured,
             Point& point) {
    const SceneSettings settings{.colouredContacts = coloured};
    SceneRun run(peer, scene, settings);
    if (!run.skipped().empty())
        return false;
    const int settleSteps = static_cast<int>(settle / run.timeStep() + 0.5);
    for (int s = 0; s < settleSteps; ++s)
        run.step();
    std::vector<double> times;
    const World* tumble = tumbleWorld(run.world());
    Profile sum;
    for (int s = 0; s < kTimedSteps; ++s) {
        const double t0 = threadSeconds();
        run.step();
        times.push_back(threadSeconds() - t0);
        if (tumble != nullptr) {
            const Profile& p = tumble->profile();
            sum.broadphase += p.broadphase;
            sum.narrowphase += p.narrowphase;
            sum.solve += p.solve;
            sum.solveStages += p.solveStages;
            sum.total += p.total;
        }
    }
    point = Point{.engine = peer.name,
                  .scene = scene.name,
                  .count = count,
                  .stepTime = quantile(times, 0.5),
                  .spreadLo = quantile(times, 0.25),
                  .spreadHi = quantile(times, 0.75)};
    if (tumble != nullptr && sum.total > 0) {
        point.broadphase = sum.broadphase / sum.total;
        point.narrowphase = sum.narrowphase / sum.total;
        point.solve = sum.solve / sum.total;
        point.sweeps = (sum.solveStages.velocity + sum.solveStages.relax) / sum.total;
        point.rest = 1 - point.broadphase - point.narrowphase - point.solve;
    }
    return true;
}

}  // namespace

double fitExponent(const std::vector<double>& x, const std::vector<double>& y) {
    const std::size_t n = std::min(x.size(), y.size());
    double sx = 0, sy = 0, sxx = 0, sxy = 0;
    for (std::size_t i = 0; i < n; ++i) {
        if (!(x[i] > 0 && y[i] > 0))
            return std::numeric_limits<double>::quiet_NaN();
        const double lx = std::log(x[i]);
        const double ly = std::log(y[i]);
        sx += lx;
        sy += ly;
        sxx += lx * lx;
        sxy += lx * ly;
    }
    const double dn = static_cast<double>(n);
    const double denominator = dn * sxx - sx * sx;
    if (n < 2 || !(denominator > 1e-12))
        return std::numeric_limits<double>::quiet_NaN();
    return (dn * sxy - sx * sy) / denominator;
}

int runScaling(const ScalingOptions& options) {
    for (const std::string& kind : options.kinds) {
        if (kind != "pile" && kind != "net") {
            std::fprintf(stderr, "--scaling --scene %s: the scaling study has only pile and net\n",
                         kind.c_str());
            return 2;
        }
    }
    std::vector<int> piles = {1000, 2000, 4000, 10000, 20000};
    if (options.with50k)
        piles.push_back(50000);
    if (!options.piles.empty())
        piles = options.piles;
    const std::vector<int> netSides = {10, 20, 40, 70, 100};  // 100 .. 10,000 nodes
    std::vector<Point> points;
    std::printf("CPU time per step: median [IQR] of %d timed steps; Tumble's stage shares\n\n",
                kTimedSteps);
    std::printf(
        "| engine | scene | count | CPU ms per step: median [q1, q3] | broadphase / "
        "narrowphase / solve (sweeps) / rest |\n|---|---|---|---|---|\n");
    std::vector<std::string> fits;
    for (const Peer& peer : peers()) {
        if (!engineChosen(options.engines, peer.name))
            continue;
        for (const bool pile : {true, false}) {
            const std::string kind = pile ? "pile" : "net";
            if (!options.kinds.empty() &&
                std::find(options.kinds.begin(), options.kinds.end(), kind) == options.kinds.end())
                continue;
            std::vector<double> counts, times;
            for (const int size : pile ? piles : netSides) {
                const Scene scene =
                    pile
                        ? Scene{"pile-" + std::to_string(size), size, SceneKind::Pile}
                        : Scene{"net-" + std::to_string(size) + "-soft", size, SceneKind::Net, 0.5};
                const int count = pile ? size : size * size;
                Point p;
                if (!measure(peer, scene, count, pile ? 1.0 : 0.25, options.colouredContacts, p))
                    break;  // a planar engine: no 3-D scene
                std::printf("| %s | %s | %d | %.4g [%.4g, %.4g] | ", p.engine.c_str(),
                            p.scene.c_str(), p.count, 1e3 * p.stepTime, 1e3 * p.spreadLo,
                            1e3 * p.spreadHi);
                if (p.solve >= 0)
                    std::printf("%.0f / %.0f / %.0f (%.0f) / %.0f %% |\n", 100 * p.broadphase,
                                100 * p.narrowphase, 100 * p.solve, 100 * p.sweeps, 100 * p.rest);
                else
                    std::printf("|\n");
                std::fflush(stdout);
                counts.push_back(count);
                times.push_back(p.stepTime);
                points.push_back(p);
            }
            if (counts.size() >= 2) {
                char line[160];
                std::snprintf(line, sizeof line, "%s %s: time per step ~ count^%.2f (%zu points)",
                              peer.name.c_str(), pile ? "pile" : "net", fitExponent(counts, times),
                              counts.size());
                fits.emplace_back(line);
            }
        }
    }
    std::printf("\nfitted exponents (log-log least squares):\n");
    for (const std::string& f : fits)
        std::printf("  %s\n", f.c_str());
    if (!options.outPrefix.empty()) {
        std::ofstream csv(options.outPrefix + "-scaling.csv");
        csv << "engine,scene,count,step_s_median,step_s_q1,step_s_q3\n";
        for (const Point& p : points)
            csv << p.engine << "," << p.scene << "," << p.count << "," << p.stepTime << ","
                << p.spreadLo << "," << p.spreadHi << "\n";
        std::printf("wrote %s-scaling.csv\n", options.outPrefix.c_str());
    }
    return 0;
}

}  // namespace tumble::bench
