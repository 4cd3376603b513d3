// stack-cost (the study's Fig. 11): wall and CPU time per simulated second of a column of N unit
// cubes (N = 5..40) in the stack case's scene (h = 1/60, 10 PGS iterations, mu = 0.5, sleeping
// off; scenes.h) -- the harness's stack scene (bench/harness), so that tumble-bench's peers'
// rows in bench/results/harness/tumble-bench.csv can be drawn beside it (report.cpp). Each N is
// built afresh and timed over 5 simulated seconds, 5 times; the median and spread are reported.
// Timing is a benchmark: reported, never checked. Checked: every column still stands at the
// end of every run (scenes::Standing), so the cost is that of a standing stack.

#include <algorithm>
#include <string>
#include <vector>

#include "../case.h"
#include "scenes.h"
#include "timing.h"

namespace tumble::validation {
namespace {

CaseResult run(const CaseOptions& options) {
    CaseResult result;
    const double duration = options.fast ? 1 : 5;  // simulated seconds per timed run
    const int runs = options.fast ? 1 : 5;
    std::vector<double> counts, costs;
    for (const int count : {5, 10, 15, 20, 25, 30, 35, 40}) {
        std::vector<double> wall, cpu;
        bool standing = true;
        for (int r = 0; r < runs; ++r) {
            World world(scenes::stackWorld());
            scenes::addGround(world, scenes::material(0.5));
            const std::vector<BodyId> cubes =
                scenes::buildStack(world, count, scenes::material(0.5));
            std::vector<int> levels;
            for (int i = 0; i < count; ++i)
                levels.push_back(i);
            const scenes::Standing start = scenes::recordStanding(world, cubes, levels);
            const Cost cost = timeSteps(world, duration);
            wall.push_back(cost.wall);
            cpu.push_back(cost.cpu);
            standing = standing && cost.finite && start.holds(world, cubes);
        }
        counts.push_back(count);
        costs.push_back(median(cpu));
        result.table.push_back({{{"cubes", count},
                                 {"wall_s_per_s", median(wall)},
                                 {"wall_min", *std::min_element(wall.begin(), wall.end())},
                                 {"wall_max", *std::max_element(wall.begin(), wall.end())},
                                 {"cpu_s_per_s", median(cpu)},
                                 {"standing", standing ? 1 : 0}}});
        result.check(standing, std::to_string(count) + " cubes: not standing at the end");
    }
    result.metric("cpu_slope_vs_cubes", logLogSlope(counts, costs));
    result.metric("simulated_s_per_run", duration);
    result.metric("runs", runs);
    return result;
}

}  // namespace

ValidationCase stackCostCase() {
    return {"stack-cost",
            "a column of N = 5..40 unit cubes at h = 1/60, 10 iterations: cost per simulated "
            "second, all standing (study Fig. 11; timings reported, not checked)",
            run};
}

}  // namespace tumble::validation
