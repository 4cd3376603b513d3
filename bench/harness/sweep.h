#pragma once
/// Speed versus error: every scene over a grid of time steps and iteration counts, in Tumble and
/// each peer; each engine's Pareto front (wall time per simulated second against the scene's
/// error) written as CSV and Markdown, and plotted to PNG by bench/plot_pareto.py.

#include <string>
#include <vector>

namespace tumble::bench {

struct SweepOptions {
    std::string outDir;                ///< where sweep.csv, pareto.md and pareto.png go (created)
    double duration = 2;               ///< simulated seconds per run, > 0
    int stackSize = 10;                ///< cubes in the column, >= 1
    int pyramidBase = 6;               ///< cubes in the pyramid's bottom row, >= 1
    std::vector<std::string> scenes;   ///< only these (stack, pyramid, chain, net); empty: all
    std::vector<std::string> engines;  ///< only these (tumble, bullet, ode, box2d); empty: all
    int repeats =
        3;  ///< timed runs per point, the fastest kept (the errors are deterministic), >= 1
    bool plot = true;  ///< run the plotting script when /usr/bin/python3 is there
};

/// Runs the sweep, prints progress and the fronts; returns the process exit code.
int runSweep(const SweepOptions& options);

}  // namespace tumble::bench
