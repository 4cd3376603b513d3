// The sweep's fronts and files (sweep_report.h).

#include "sweep_report.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <map>
#include <set>

namespace tumble::bench {
namespace {

// The engines in a fixed order, Tumble first, then as peers() lists them.
std::vector<std::string> enginesOf(const std::vector<Point>& points, const std::string& scene) {
    std::vector<std::string> engines;
    for (const Point& p : points) {
        if (p.scene == scene &&
            std::find(engines.begin(), engines.end(), p.engine) == engines.end())
            engines.push_back(p.engine);
    }
    return engines;
}

// The least cost (s per sim s) at which an engine's sound runs reach an error of at most
// `error`, or infinity.
double costToReach(const std::vector<Point>& points, const std::string& scene,
                   const std::string& engine, double error) {
    double best = INFINITY;
    for (const Point& p : points) {
        if (p.scene == scene && p.engine == engine && p.status == RunStatus::Ok && p.error <= error)
            best = std::min(best, p.wallPerSimulatedSecond);
    }
    return best;
}

std::string number(const char* format, double x) {
    if (!std::isfinite(x))
        return "--";
    char text[32];
    std::snprintf(text, sizeof text, format, x);
    return text;
}

void writeFront(std::ofstream& out, const std::vector<Point>& points, const std::string& scene) {
    std::vector<Point> front;
    for (const Point& p : points) {
        if (p.scene == scene && p.front)
            front.push_back(p);
    }
    std::stable_sort(front.begin(), front.end(), [](const Point& a, const Point& b) {
        return a.engine != b.engine ? a.engine > b.engine
                                    : a.wallPerSimulatedSecond < b.wallPerSimulatedSecond;
    });
    out << "\nFronts:\n\n| engine | h (s) | iterations | wall s per sim s | error (m) |\n"
        << "|---|---|---|---|---|\n";
    for (const Point& p : front) {
        out << "| " << p.engine << " | " << fraction(p.h) << " | " << p.iterations << " | "
            << number("%.3g", p.wallPerSimulatedSecond) << " | " << number("%.3g", p.error)
            << " |\n";
    }
}

// The least cost each engine needs for each decade of error its front spans.
void writeCostTable(std::ofstream& out, const std::vector<Point>& points, const std::string& scene,
                    const std::vector<std::string>& engines) {
    double largest = 0, smallest = INFINITY;
    for (const Point& p : points) {
        if (p.scene == scene && p.front) {
            largest = std::max(largest, p.error);
            smallest = std::min(smallest, std::max(p.error, 1e-12));
        }
    }
    if (!std::isfinite(smallest))
        return;
    out << "\nLeast wall s per sim s to reach an error of at most E (--: no run of the grid "
           "does; a level that costs every engine what the one above did is left out):\n\n"
           "| E (m) |";
    for (const std::string& e : engines)
        out << ' ' << e << " |";
    out << " cheapest |\n|---|";
    for (std::size_t i = 0; i <= engines.size(); ++i)
        out << "---|";
    out << '\n';
    // Tumble against each peer over the levels both reach: how often Tumble is cheaper.
    std::map<std::string, std::pair<int, int>> tally;  // peer: (Tumble cheaper, both reach)
    std::map<std::string, double> previous;
    const int top = static_cast<int>(std::ceil(std::log10(largest)));
    const int bottom = static_cast<int>(std::floor(std::log10(smallest)));
    for (int k = top; k >= bottom; --k) {
        const double level = std::pow(10.0, k);
        std::string cheapest = "--";
        double least = INFINITY;
        std::map<std::string, double> cost;
        for (const std::string& e : engines) {
            cost[e] = costToReach(points, scene, e, level);
            if (cost[e] < least) {
                least = cost[e];
                cheapest = e;
            }
        }
        // A level no cheaper to reach for anyone than the one above adds nothing (a column
        // that stays exactly aligned reaches every level at its first cost).
        if (cost == previous)
            continue;
        previous = cost;
        out << "| 1e" << k << " |";
        for (const std::string& e : engines)
            out << ' ' << number("%.3g", cost[e]) << " |";
        out << ' ' << cheapest << " |\n";
        for (const std::string& e : engines) {
            if (e != "tumble" && std::isfinite(cost[e]) && std::isfinite(cost["tumble"])) {
                tally[e].second += 1;
                tally[e].first += cost["tumble"] < cost[e];
            }
        }
    }
    for (const auto& [peer, count] : tally) {
        out << "\nTumble is cheaper than " << peer << " at " << count.first << " of the "
            << count.second << " levels both reach.";
    }
    out << '\n';
}

// The runs kept off the fronts, grouped by engine and h.
void writeUnsound(std::ofstream& out, const std::vector<Point>& points, const std::string& scene) {
    std::map<std::pair<std::string, double>, std::vector<const Point*>> bad;
    for (const Point& p : points) {
        if (p.scene == scene && p.status != RunStatus::Ok)
            bad[{p.engine, p.h}].push_back(&p);
    }
    if (bad.empty()) {
        out << "\nEvery run stayed sound (no collapse, nothing non-finite or blown up).\n";
        return;
    }
    out << "\nRuns that collapsed or blew up (kept off the fronts and drawn as crosses on the "
           "plot's top edge):\n\n";
    for (const auto& [key, runs] : bad) {
        out << "- " << key.first << ", h = " << fraction(key.second) << ": "
            << statusName(runs.front()->status) << " at iterations";
        for (const Point* p : runs)
            out << ' ' << p->iterations;
        out << '\n';
    }
}

}  // namespace

std::string fraction(double h) {
    char text[32];
    std::snprintf(text, sizeof text, "1/%.0f", 1 / h);
    return text;
}

void markFronts(std::vector<Point>& points) {
    for (Point& p : points) {
        if (p.status != RunStatus::Ok || !std::isfinite(p.error))
            continue;
        p.front = std::none_of(points.begin(), points.end(), [&](const Point& q) {
            return &q != &p && q.status == RunStatus::Ok && q.scene == p.scene &&
                   q.engine == p.engine && q.wallPerSimulatedSecond <= p.wallPerSimulatedSecond &&
                   q.error <= p.error &&
                   (q.wallPerSimulatedSecond < p.wallPerSimulatedSecond || q.error < p.error);
        });
    }
}

void writeCsv(const std::string& path, const std::vector<Point>& points,
              const std::string& preamble, const std::vector<SceneNote>& notes) {
    std::ofstream out(path);
    out << "# " << preamble << '\n';
    for (const SceneNote& note : notes)
        out << "# " << note.scene << ": " << note.text << '\n';
    out << "# status: ok, collapsed (a cube moved > 0.5 m), blew-up (non-finite, energy x10, or a "
           "bead 1 m off); only ok runs have a meaningful error_m and can be on a front\n";
    out << "scene,engine,h_s,iterations,wall_s_per_sim_s,error_m,deepest_penetration_m,status,"
           "pareto\n";
    out.precision(6);
    for (const Point& p : points) {
        out << p.scene << ',' << p.engine << ',' << p.h << ',' << p.iterations << ','
            << p.wallPerSimulatedSecond << ',' << p.error << ',' << p.deepest << ','
            << statusName(p.status) << ',' << (p.front ? 1 : 0) << '\n';
    }
}

void writeMarkdown(const std::string& path, const std::vector<Point>& points,
                   const std::string& preamble, const std::vector<SceneNote>& notes) {
    std::ofstream out(path);
    out << "# Speed versus error\n\n" << preamble << '\n';
    std::set<std::string> scenes;
    for (const Point& p : points)
        scenes.insert(p.scene);
    for (const std::string& scene : scenes) {
        out << "\n## " << scene << "\n\n";
        for (const SceneNote& note : notes) {
            if (note.scene == scene)
                out << note.text << '\n';
        }
        const std::vector<std::string> engines = enginesOf(points, scene);
        writeFront(out, points, scene);
        writeCostTable(out, points, scene, engines);
        writeUnsound(out, points, scene);
    }
}

}  // namespace tumble::bench
