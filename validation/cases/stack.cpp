// stack: 20 unit cubes (1 kg each, mu = 0.5) built face to face on a static half-space, h = 1/60,
// 10 PGS iterations, sleeping off (there is none yet), 20 s. The peers on this machine
// (DESIGN.md section 6): Bullet 3.24 collapses at 2.8 s, ODE at 3.7 s; Box2D (planar) stands.
//
// Claims:
// - standing after 20 s: every cube within 0.1 m of where it was built horizontally, and
//   vertically within 0.1 m beyond the (level + 1) x (slop + 1 mm) its contacts may sink
//   (scenes::Standing);
// - the deepest penetration the solver sees in any step of the last 10 s is below slop + 1 mm;
// - the top cube never drifts more than 1 cm horizontally (largest offset over the whole run).
//
// Reported in the full run only, not claimed: how long a 40-cube stack stands (until its top
// cube moves 0.5 m horizontally or falls 0.5 m), over at most 60 s; Bullet's stands 1.7 s. The
// fast run (ctest) is the same 20-cube, 20 s scene: the claims are cheap enough to keep whole.
// Times of events that never happened are reported as -1.

#include <string>

#include "../case.h"
#include "scenes.h"

namespace tumble::validation {
namespace {

constexpr double kFriction = 0.5;

scenes::PileRun runStack(int count, double duration, double lateFrom) {
    World world(scenes::stackWorld());
    scenes::addGround(world, scenes::material(kFriction));
    const std::vector<BodyId> cubes = scenes::buildStack(world, count, scenes::material(kFriction));
    std::vector<int> levels;
    for (int i = 0; i < count; ++i)
        levels.push_back(i);
    const scenes::Standing standing = scenes::recordStanding(world, cubes, levels);
    return scenes::runPile(world, cubes, standing, cubes.size() - 1, duration, lateFrom);
}

void addRow(CaseResult& result, int count, const scenes::PileRun& run) {
    result.table.push_back({{{"cubes", static_cast<double>(count)},
                             {"run_s", run.duration},
                             {"top_fell_s", run.topFell},
                             {"lost_standing_s", run.lostStanding},
                             {"top_drift_max_m", run.topDriftMax},
                             {"deepest_late_m", run.deepestLate}}});
}

CaseResult run(const CaseOptions& options) {
    CaseResult result;
    const double slop = SolverSettings{}.slop;
    const double kPenetration = slop + 1e-3;  // (m)
    const double kTopDrift = 0.01;            // (m)
    result.tolerance("deepest_penetration_last_10_s_max_m", kPenetration);
    result.tolerance("top_drift_max_m", kTopDrift);
    result.tolerance("standing_horizontal_m", scenes::Standing::kHorizontal);
    result.tolerance("standing_vertical_beyond_sink_m", scenes::Standing::kVertical);

    const scenes::PileRun stack = runStack(20, 20.0, 10.0);
    addRow(result, 20, stack);
    result.metric("standing_at_20_s", stack.standingAtEnd ? 1 : 0);
    result.metric("lost_standing_at_s", stack.lostStanding);
    result.metric("top_fell_at_s", stack.topFell);
    result.metric("horizontal_offset_at_end_m", stack.horizontalAtEnd);
    result.metric("vertical_excess_at_end_m", stack.verticalAtEnd);
    result.metric("deepest_penetration_last_10_s_m", stack.deepestLate);
    result.metric("top_drift_max_m", stack.topDriftMax);
    result.check(stack.finite, "a step failed");
    result.check(stack.standingAtEnd, "the 20-stack does not stand after 20 s");
    result.check(stack.deepestLate < kPenetration,
                 "deepest penetration in the last 10 s not below slop + 1 mm");
    result.check(stack.topDriftMax < kTopDrift, "top cube drifts 1 cm or more");

    if (!options.fast) {
        const scenes::PileRun tall = runStack(40, 60.0, 30.0);
        addRow(result, 40, tall);
        result.metric("stack_40_top_fell_at_s", tall.topFell);
        result.metric("stack_40_run_s", tall.duration);
    }
    return result;
}

}  // namespace

ValidationCase stackCase() {
    return {"stack",
            "20 unit cubes, h 1/60, 10 iterations: standing after 20 s, penetration < slop + 1 mm, "
            "top drift < 1 cm; full run reports how long 40 stand",
            run};
}

}  // namespace tumble::validation
