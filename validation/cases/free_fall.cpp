// free-fall: a body thrown under gravity, against the closed form of semi-implicit Euler (which
// the integrator must reproduce to rounding) and against the continuous parabola (error O(h)).
//
// Semi-implicit Euler with constant g:  v_n = v_0 + n h g,
//   x_n = x_0 + h sum_{k=1..n} v_k = x_0 + n h v_0 + h^2 g n (n + 1) / 2,
// while the parabola gives x_0 + t v_0 + g t^2 / 2 at t = n h: the difference is g t h / 2.
// h is the integrator's step: the world's step on the default step, the step's over softSubsteps
// on the soft step (tumble-validate --soft-step n), which integrates in n substeps.

#include <algorithm>
#include <cmath>
#include <string>

#include "../case.h"
#include "scenes.h"
#include "tumble/tumble.h"

namespace tumble::validation {
namespace {

constexpr double kDuration = 2.0;  // (s)
const Vec3 kGravity(0, 0, -9.81);
const Vec3 kStart(0, 0, 10);
const Vec3 kVelocity(1.5, -0.5, 4);

struct Fall {
    double discreteError;    // |x - closed form of semi-implicit Euler| (m)
    double discreteVError;   // same for the velocity (m/s)
    double continuousError;  // |x - parabola| (m)
};

// The integrator's steps in one World::step: the soft step's substeps, else 1.
int integratorStepsPerStep() {
    SolverSettings settings;
    testkit::applyForcedSoftStep(settings);
    return std::max(1, settings.softSubsteps);
}

Fall fall(int stepsPerSecond) {
    WorldDef worldDef{.gravity = kGravity, .timeStep = 1.0 / stepsPerSecond};
    testkit::applyForcedSoftStep(worldDef.solver);  // tumble-validate --soft-step
    World world(worldDef);
    BodyDef def;
    def.position = kStart;
    def.linearVelocity = kVelocity;
    const BodyId body = world.createBody(def);
    const int steps = static_cast<int>(std::lround(kDuration * stepsPerSecond));
    for (int i = 0; i < steps; ++i)
        world.step();

    const double h = 1.0 / (stepsPerSecond * integratorStepsPerStep());
    const int n = steps * integratorStepsPerStep();
    const double t = n * h;
    const Vec3 discreteX = kStart + n * h * kVelocity + h * h * kGravity * (n * (n + 1.0) / 2);
    const Vec3 discreteV = kVelocity + n * h * kGravity;
    const Vec3 parabola = kStart + t * kVelocity + 0.5 * t * t * kGravity;
    return {(world.position(body) - discreteX).norm(),
            (world.linearVelocity(body) - discreteV).norm(),
            (world.position(body) - parabola).norm()};
}

CaseResult run(const CaseOptions&) {
    CaseResult result;
    const double kExact = 1e-12;
    const Fall at60 = fall(60);
    result.metric("position_error_vs_discrete_closed_form_m", at60.discreteError);
    result.metric("velocity_error_vs_discrete_closed_form_m_s", at60.discreteVError);
    result.tolerance("discrete_closed_form_abs", kExact);
    result.check(at60.discreteError <= kExact && at60.discreteVError <= kExact,
                 "semi-implicit Euler closed form not reproduced to 1e-12");

    std::vector<double> hs, errors;
    for (int rate : {60, 120, 240, 480, 960}) {
        const Fall f = fall(rate);
        const double h = 1.0 / (rate * integratorStepsPerStep());
        hs.push_back(h);
        errors.push_back(f.continuousError);
        // The O(h) error is known exactly: |g| t h / 2.
        const double expected = kGravity.norm() * kDuration * h / 2;
        result.table.push_back({{{"h", h},
                                 {"error_m", f.continuousError},
                                 {"gth_over_2_m", expected},
                                 {"discrete_err_m", f.discreteError}}});
        result.check(std::abs(f.continuousError - expected) <= 1e-9,
                     "continuous error differs from g t h / 2 at h = 1/" + std::to_string(rate));
        result.check(f.discreteError <= kExact,
                     "closed form not reproduced at h = 1/" + std::to_string(rate));
    }
    const double slope = logLogSlope(hs, errors);
    result.metric("continuous_error_at_h_1_60_m", errors.front());
    result.metric("continuous_error_order", slope);
    result.tolerance("continuous_error_order_min", 0.95);
    result.tolerance("continuous_error_order_max", 1.05);
    result.tolerance("continuous_error_vs_g_t_h_over_2_abs", 1e-9);
    result.check(slope >= 0.95 && slope <= 1.05, "error against the parabola is not O(h)");
    return result;
}

}  // namespace

ValidationCase freeFallCase() {
    return {
        "free-fall",
        "a thrown body follows semi-implicit Euler's closed form exactly; error vs the parabola "
        "is g t h / 2 = O(h)",
        run};
}

}  // namespace tumble::validation
