// oscillator: a mass on a linear spring (omega = 1 rad/s) under semi-implicit Euler, the study's
// Fig. 4. The spring force -k x is applied through the public force API before each step, which
// is exactly an explicit spring.
//
// Theory for x_0 = 1, v_0 = 0: the map has eigenvalues exp(+-i theta) with
// cos(theta) = 1 - (omega h)^2 / 2 while omega h < 2, so the motion is x_n = A cos(n theta + phi)
// with period T = 2 pi h / theta and amplitude A = 1 / sqrt(1 - (omega h / 2)^2): both errors are
// O(h^2) (period -(omega h)^2 / 24, amplitude +(omega h)^2 / 8), bounded however long the run, and
// unbounded (A -> inf) as omega h -> 2. At omega h >= 2 an eigenvalue leaves the unit circle and
// the motion grows.
//
// Measurements (fig45.h's measureOscillation, shared with tumble-bench --study): the period from
// the mean spacing of zero crossings, the amplitude from the sinusoid through three samples around
// each positive peak, exact for a sampled sinusoid.

#include <algorithm>
#include <cmath>
#include <numbers>
#include <vector>

#include "../case.h"
#include "fig45.h"
#include "scenes.h"
#include "tumble/tumble.h"

namespace tumble::validation {
namespace {

fig45::Oscillation simulate(double omegaH) {
    const double h = omegaH;  // omega = 1
    WorldDef worldDef{.gravity = Vec3::Zero(), .timeStep = h};
    testkit::applyForcedSoftStep(worldDef.solver);  // tumble-validate --soft-step
    World world(worldDef);
    BodyDef def;
    def.position = Vec3(1, 0, 0);
    const BodyId body = world.createBody(def);

    const int steps = fig45::oscillatorSteps(h);
    std::vector<double> x;
    x.reserve(steps + 1);
    x.push_back(1.0);
    for (int i = 0; i < steps; ++i) {
        world.applyForceToCenter(body, Vec3(-world.position(body).x(), 0, 0));
        if (!world.step().ok())
            break;
        x.push_back(world.position(body).x());
        if (std::abs(x.back()) > fig45::kOscillatorBlowUp)
            break;
    }
    return fig45::measureOscillation(x, h);
}

CaseResult run(const CaseOptions& options) {
    CaseResult result;
    const std::vector<double> sweep = fig45::oscillatorSweep(options.fast);
    const double kTwoPi = 2 * std::numbers::pi;
    // Agreement of the measurement with the discrete theory: the sweep runs 200 periods, so the
    // crossing-based period is good to ~1e-6 and the three-sample amplitude to rounding.
    const double kTheoryTolerance = 1e-4;

    std::vector<double> smallH, amplitudeErrors, periodErrors;
    double worstTheory = 0;
    double worstBoundedGrowth = 0;
    double weakestUnstableGrowth = 1e300;
    for (double wh : sweep) {
        const fig45::Oscillation r = simulate(wh);
        const double amplitudeError = r.amplitude - 1;
        const double periodError = r.period > 0 ? r.period / kTwoPi - 1 : NAN;
        result.table.push_back({{{"omega_h", wh},
                                 {"ampl_err", amplitudeError},
                                 {"period_err", periodError},
                                 {"growth", r.growth}}});
        if (wh < 2) {
            const double theta = std::acos(1 - wh * wh / 2);
            const double theoryAmplitude = 1 / std::sqrt(1 - wh * wh / 4);
            const double theoryPeriod = kTwoPi * wh / theta;
            const double deviation = std::max(std::abs(r.amplitude / theoryAmplitude - 1),
                                              std::abs(r.period / theoryPeriod - 1));
            worstTheory = std::max(worstTheory, deviation);
        }
        if (wh < 1 && wh <= 0.5) {
            smallH.push_back(wh);
            amplitudeErrors.push_back(std::abs(amplitudeError));
            periodErrors.push_back(std::abs(periodError));
        }
        if (wh > 1 && wh < 2)
            worstBoundedGrowth = std::max(worstBoundedGrowth, r.growth);
        if (wh >= 2)
            weakestUnstableGrowth = std::min(weakestUnstableGrowth, r.growth);
    }
    const double amplitudeSlope = logLogSlope(smallH, amplitudeErrors);
    const double periodSlope = logLogSlope(smallH, periodErrors);
    result.metric("amplitude_error_order", amplitudeSlope);
    result.metric("period_error_order", periodSlope);
    result.metric("max_deviation_from_discrete_theory", worstTheory);
    result.metric("max_growth_1_lt_wh_lt_2", worstBoundedGrowth);
    result.metric("min_growth_wh_ge_2", weakestUnstableGrowth);
    result.tolerance("order_min", 1.8);
    result.tolerance("order_max", 2.2);
    result.tolerance("discrete_theory_rel", kTheoryTolerance);
    result.tolerance("bounded_growth_max", 1.01);
    result.tolerance("unstable_growth_min", 2);
    result.check(amplitudeSlope >= 1.8 && amplitudeSlope <= 2.2, "amplitude error not O(h^2)");
    result.check(periodSlope >= 1.8 && periodSlope <= 2.2, "period error not O(h^2)");
    result.check(worstTheory <= kTheoryTolerance, "motion departs from semi-implicit Euler theory");
    result.check(worstBoundedGrowth <= 1.01, "oscillation grows for 1 < omega h < 2");
    // At omega h = 2 exactly the growth is linear (a double eigenvalue -1), so the last tenth of
    // the run is about ten times the first; above 2 it is exponential.
    result.check(weakestUnstableGrowth >= 2, "no growth for omega h >= 2");
    return result;
}

}  // namespace

ValidationCase oscillatorCase() {
    return {"oscillator",
            "spring-mass under semi-implicit Euler: O(h^2) amplitude/period error for omega h < 1, "
            "bounded for omega h < 2, growing for omega h >= 2 (study Fig. 4)",
            run};
}

}  // namespace tumble::validation
