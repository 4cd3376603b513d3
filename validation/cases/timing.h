#pragma once
// Timing for the report's cost figures (Fig. 10, Fig. 11): wall and CPU time of a stepping loop
// per simulated second. These are benchmarks: the cases report them and never check them.

#include <algorithm>
#include <chrono>
#include <ctime>
#include <vector>

#include "tumble/tumble.h"

namespace tumble::validation {

struct Cost {
    double wall = 0;     ///< wall time per simulated second (s/s)
    double cpu = 0;      ///< process CPU time per simulated second (s/s)
    bool finite = true;  ///< every step reported ok
};

/// Steps `world` over `duration` simulated seconds (at least one step), timing the steps only.
inline Cost timeSteps(World& world, double duration) {
    const double h = world.settings().timeStep;
    const long steps = std::max(1L, static_cast<long>(duration / h + 0.5));
    Cost cost;
    const std::clock_t cpu0 = std::clock();
    const auto wall0 = std::chrono::steady_clock::now();
    for (long i = 0; i < steps && cost.finite; ++i)
        cost.finite = world.step().ok();
    const double wall =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - wall0).count();
    const double cpu = static_cast<double>(std::clock() - cpu0) / CLOCKS_PER_SEC;
    const double simulated = static_cast<double>(steps) * h;
    cost.wall = wall / simulated;
    cost.cpu = cpu / simulated;
    return cost;
}

/// The median of a few values (the middle one; the upper middle of an even count).
inline double median(std::vector<double> values) {
    std::sort(values.begin(), values.end());
    return values.empty() ? 0 : values[values.size() / 2];
}

}  // namespace tumble::validation
