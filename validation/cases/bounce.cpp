// bounce: a sphere (r = 0.1 m, restitution 0.8 on both materials) dropped from centre height
// H = 1 m onto a static half-space; the study's Fig. 5. Newton's law with the pre-impact approach
// speed makes the k-th apex r + (H - r) e^(2k). Impact speeds of bounces 1..5 run from 4.2 to
// 1.7 m/s, all above the default 1 m/s restitution threshold, so every one of them is elastic.
//
// Claims (split-impulse stabilisation, the default): at h = 1/240 every one of the first five
// apexes is within 2 % of the analytic value; the worst apex error shrinks from h = 1/60 to 1/240
// to 1/1000; and at no h is any apex above the analytic value by more than 0.5 % (an impact may
// lose energy to the discretisation, never create it).
//
// Reported, not claimed: the same drop with Baumgarte stabilisation (k_erp = 0.2, bias depth/h in
// the real velocity), whose apexes the study found scattered above the analytic ones, the more so
// as h shrinks.
//
// Apexes are the vertices of the parabola through the three samples around each local maximum
// of the centre height (fig45.h's ApexTracker, shared with tumble-bench --study), exact for a
// ballistic flight under semi-implicit Euler.

#include <cmath>
#include <string>
#include <vector>

#include "../case.h"
#include "fig45.h"
#include "scenes.h"

namespace tumble::validation {
namespace {

/// Relative errors of the first five apexes (NaN for an apex never reached).
std::vector<double> apexErrors(int stepsPerSecond, Stabilisation stabilisation) {
    WorldDef def{.gravity = Vec3(0, 0, -scenes::kG), .timeStep = 1.0 / stepsPerSecond};
    testkit::applyForcedSoftStep(def.solver);  // tumble-validate --soft-step
    def.solver.stabilisation = stabilisation;
    World world(def);
    const Material surface = scenes::material(0.5, fig45::kRestitution, 1000);
    scenes::addGround(world, surface);
    const BodyId ball = world.createBody(BodyDef{.position = Vec3(0, 0, fig45::kDropHeight)});
    world.createShape(ball, ShapeDef{.geometry = Sphere{fig45::kBallRadius}, .material = surface});

    fig45::ApexTracker tracker;
    tracker.sample(world.position(ball).z());
    const int steps = static_cast<int>(fig45::kBounceTime * stepsPerSecond);
    for (int i = 0; i < steps && !tracker.complete(); ++i) {
        if (!world.step().ok())
            break;
        tracker.sample(world.position(ball).z());
    }
    return tracker.errors();
}

std::string rateName(int stepsPerSecond) {
    return "h_1_" + std::to_string(stepsPerSecond);
}

CaseResult run(const CaseOptions& options) {
    CaseResult result;
    const double kAccuracy = 0.02;     // every apex at h = 1/240
    const double kEnergyGain = 0.005;  // no apex above analytic by more than this, any h
    const int kAccuracyRate = 240;
    const std::vector<int> convergenceRates = fig45::bounceRates(true);
    const std::vector<int> rates = fig45::bounceRates(options.fast);
    result.tolerance("apex_rel_err_at_h_1_240", kAccuracy);
    result.tolerance("apex_above_analytic_rel_max", kEnergyGain);

    std::vector<double> convergenceErrors;
    for (const Stabilisation stabilisation :
         {Stabilisation::SplitImpulse, Stabilisation::Baumgarte}) {
        const bool baumgarte = stabilisation == Stabilisation::Baumgarte;
        const std::string prefix = baumgarte ? "baumgarte_" : "";
        for (const int rate : rates) {
            const std::vector<double> errors = apexErrors(rate, stabilisation);
            TableRow row{{{"h", 1.0 / rate}, {"baumgarte", baumgarte ? 1.0 : 0.0}}};
            double worst = 0, highest = -1e300;
            bool complete = true;
            for (int k = 0; k < fig45::kBounces; ++k) {
                row.values.emplace_back("apex" + std::to_string(k + 1) + "_err", errors[k]);
                complete = complete && std::isfinite(errors[k]);
                if (std::isfinite(errors[k])) {
                    worst = std::max(worst, std::abs(errors[k]));
                    highest = std::max(highest, errors[k]);
                }
            }
            if (!complete)
                worst = NAN;
            row.values.emplace_back("max_abs_err", worst);
            result.table.push_back(row);
            result.metric(prefix + "max_abs_apex_err_" + rateName(rate), worst);
            result.metric(prefix + "max_apex_above_analytic_" + rateName(rate), highest);
            if (baumgarte)
                continue;  // reported only

            result.check(complete, "fewer than 5 apexes at h = 1/" + std::to_string(rate));
            result.check(
                highest <= kEnergyGain,
                "an apex is more than 0.5 % above analytic at h = 1/" + std::to_string(rate));
            if (rate == kAccuracyRate)
                result.check(worst <= kAccuracy, "an apex is off by more than 2 % at h = 1/240");
            for (const int r : convergenceRates) {
                if (r == rate)
                    convergenceErrors.push_back(worst);
            }
        }
    }
    bool shrinks = convergenceErrors.size() == convergenceRates.size();
    for (std::size_t i = 1; shrinks && i < convergenceErrors.size(); ++i)
        shrinks = convergenceErrors[i] < convergenceErrors[i - 1];
    result.check(shrinks, "worst apex error does not shrink from h = 1/60 to 1/240 to 1/1000");
    return result;
}

}  // namespace

ValidationCase bounceCase() {
    return {"bounce",
            "ball (r 0.1 m, e 0.8) from 1 m: first 5 apexes within 2 % of r + (H - r) e^2k at "
            "h = 1/240, converging in h, never > 0.5 % above (study Fig. 5); Baumgarte reported",
            run};
}

}  // namespace tumble::validation
