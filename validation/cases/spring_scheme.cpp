// spring-scheme: a mass on one implicit spring (omega = 1 rad/s, no gravity) against the
// discrete theory of the springs' default scheme (spring_row.h).
//
// Theory. With x_{n-1} = x_n - h v_n (the engine's velocity is the step's mean), a resolved
// element ((omega h)^2 <= 1.5) takes the symmetric weights beta = 1/12, 1 - 2 beta, beta:
// (x_{n+1} - 2 x_n + x_{n-1}) / h^2 = -omega^2 (beta x_{n+1} + (1 - 2 beta) x_n + beta x_{n-1}),
// whose roots are exp(+-i theta), cos theta = (1 - (1 - 2 beta) (omega h)^2 / 2) / (1 + beta
// (omega h)^2): nothing decays or grows, and the phase is right to fourth order. From x_0 = 1 at
// rest (x_{-1} = x_0) the motion is A cos((n + 1/2) theta), A = 1 / cos(theta / 2).
// Multiplying the scheme by x_{n+1} - x_{n-1} telescopes to the invariant
//     E = m v_{n+1}^2 / 2 + k (beta (x_{n+1}^2 + x_n^2) + (1 - 2 beta) x_n x_{n+1}) / 2.
// An unresolved element ((omega h)^2 >= 4) is damped, rho = 4 / (omega h)^2: undamped, its
// positions would swing by ~omega h / 2 times the amplitude (measured: a 0.1 m stretch at
// omega h = 100 swung the mass by 9 m).
//
// Tolerances, set before measuring: period and amplitude within 1e-4 of the theory (the
// measurement of oscillator.cpp, 200 periods), growth within 1e-4 of 1; E within 1e-9 of E_0 at
// omega h = 0.1 and 1 over 2,000 steps; at omega h = 10 and 100 the mass never further than
// 1.01 from rest and the energy never above its start. Damped (zeta = 0.05, omega h = 0.1):
// the amplitude's decay per period within 1 % of exp(-2 pi zeta / sqrt(1 - zeta^2)).
// Numerical damping (SpringDef::numericalDamping = 0.1): the energy never above its start, and
// the unresolved motion (omega h = 10) loses more per step than the resolved one (0.1).
// Backward Euler (the former default) is recorded beside it.

#include <algorithm>
#include <cmath>
#include <numbers>
#include <string>
#include <vector>

#include "../case.h"
#include "fig45.h"
#include "lumped.h"

namespace tumble::validation {
namespace {

constexpr double kRest = 10;  // rest length (m): the mass moves along the spring's line
constexpr double kTheoryTolerance = 1e-4;
constexpr double kEnergyTolerance = 1e-9;
constexpr double kBeta = 1.0 / 12;

struct Run {
    std::vector<double> x;       // displacement from rest after each step (m), x[0] = 1
    std::vector<double> energy;  // the scheme's invariant after each step (J)
    bool finite = true;
};

Run simulate(double omegaH, int steps, SpringFormulation formulation, double zeta = 0,
             double numericalDamping = 0) {
    const double h = omegaH;  // omega = 1, m = 1, k = 1
    World world(WorldDef{.gravity = Vec3::Zero(), .timeStep = h});
    const BodyId body = addPointMass(world, Vec3(kRest + 1, 0, 0), 1);
    SpringDef def;
    def.bodyA = body;
    def.localAnchorB = Vec3::Zero();  // world point
    def.restLength = kRest;
    def.stiffness = 1;
    def.damping = 2 * zeta;
    def.formulation = formulation;
    def.numericalDamping = numericalDamping;
    world.createSpring(def);
    Run run;
    run.x.reserve(steps + 1);
    run.x.push_back(1);
    run.energy.push_back(0.5);
    for (int i = 0; i < steps; ++i) {
        if (!world.step().ok()) {
            run.finite = false;
            break;
        }
        const double x = world.position(body).x() - kRest;
        const double v = world.linearVelocity(body).x();
        const double last = x - h * v;
        run.x.push_back(x);
        run.energy.push_back(0.5 * v * v +
                             0.5 * (kBeta * (x * x + last * last) + (1 - 2 * kBeta) * x * last));
    }
    return run;
}

double worstEnergyDrift(const Run& run) {
    double worst = 0;
    for (const double e : run.energy)
        worst = std::max(worst, std::abs(e / run.energy.front() - 1));
    return worst;
}

void checkTheory(CaseResult& result, bool fast) {
    const double kTwoPi = 2 * std::numbers::pi;
    double worst = 0, worstGrowth = 0;
    for (const double omegaH : {0.05, 0.1, 0.2, 0.5, 1.0}) {
        const Run run = simulate(omegaH, fig45::oscillatorSteps(omegaH, fast ? 4000 : 20000),
                                 SpringFormulation::Implicit);
        const fig45::Oscillation o = fig45::measureOscillation(run.x, omegaH);
        const double o2 = omegaH * omegaH;
        const double theta = std::acos((1 - (1 - 2 * kBeta) * o2 / 2) / (1 + kBeta * o2));
        const double period = kTwoPi * omegaH / theta;
        const double amplitude = 1 / std::cos(theta / 2);
        const double theory =
            std::max(std::abs(o.period / period - 1), std::abs(o.amplitude / amplitude - 1));
        worst = std::max(worst, run.finite ? theory : INFINITY);
        worstGrowth = std::max(worstGrowth, std::abs(o.growth - 1));
        result.table.push_back({{{"omega_h", omegaH},
                                 {"period_rel_error", o.period / kTwoPi - 1},
                                 {"amplitude", o.amplitude},
                                 {"growth", o.growth},
                                 {"theory_rel_error", theory}}});
    }
    result.metric("theory_worst_rel_error", worst);
    result.metric("growth_worst_abs", worstGrowth);
    result.tolerance("theory_rel_error_max", kTheoryTolerance);
    result.check(worst <= kTheoryTolerance, "motion departs from the scheme's theory");
    result.check(worstGrowth <= kTheoryTolerance, "the undamped oscillation grows or decays");
}

void checkEnergy(CaseResult& result) {
    double worst = 0;
    for (const double omegaH : {0.1, 1.0}) {
        const Run run = simulate(omegaH, 2000, SpringFormulation::Implicit);
        const double drift = run.finite ? worstEnergyDrift(run) : INFINITY;
        result.metric(
            "energy_drift_omega_h_" + std::to_string(static_cast<int>(omegaH * 10)) + "e-1", drift);
        worst = std::max(worst, drift);
    }
    result.tolerance("energy_rel_drift_max", kEnergyTolerance);
    result.check(worst <= kEnergyTolerance, "the undamped spring's energy is not conserved");
    for (const double omegaH : {10.0, 100.0}) {
        const Run run = simulate(omegaH, 2000, SpringFormulation::Implicit);
        double farthest = 0;
        bool grows = false;
        for (std::size_t i = 0; i < run.x.size(); ++i) {
            farthest = std::max(farthest, std::abs(run.x[i]));
            const double v = i == 0 ? 0 : (run.x[i] - run.x[i - 1]) / omegaH;
            grows = grows || 0.5 * v * v + 0.5 * run.x[i] * run.x[i] > 0.5 * (1 + 1e-9);
        }
        const std::string tag = "omega_h_" + std::to_string(static_cast<int>(omegaH));
        result.metric(tag + "_farthest_m", farthest);
        result.check(run.finite && farthest <= 1.01, tag + ": the unresolved spring swings");
        result.check(!grows, tag + ": the unresolved spring gains energy");
    }
    // The former default, for comparison: what implicit Euler keeps of the energy after 20
    // periods at omega h = 0.5.
    const int steps = static_cast<int>(20 * 2 * std::numbers::pi / 0.5);
    const Run euler = simulate(0.5, steps, SpringFormulation::BackwardEuler);
    result.metric("backward_euler_energy_kept_20_periods_omega_h_0.5", euler.energy.back() / 0.5);
}

void checkDamping(CaseResult& result) {
    // Physical damping: zeta = 0.05, the peaks' decay per period against the exact one.
    const double zeta = 0.05, omegaH = 0.1;
    const double period = 2 * std::numbers::pi / std::sqrt(1 - zeta * zeta);
    const int perPeriod = static_cast<int>(std::lround(period / omegaH));
    const Run run = simulate(omegaH, 10 * perPeriod, SpringFormulation::Implicit, zeta);
    double first = 0, last = 0;
    for (int i = 0; i < perPeriod; ++i) {
        first = std::max(first, run.x[i]);
        last = std::max(last, run.x[9 * perPeriod + i]);
    }
    const double decay = std::pow(last / first, 1.0 / 9);
    const double exact = std::exp(-zeta * period);
    result.metric("damped_decay_per_period", decay);
    result.metric("damped_decay_rel_error", decay / exact - 1);
    result.tolerance("damped_decay_rel_error_max", 0.01);
    result.check(std::abs(decay / exact - 1) <= 0.01, "physical damping not as set");

    // Numerical damping: energy never grows; the unresolved mode loses more than the resolved.
    double lossResolved = 0, lossUnresolved = 0;
    bool grows = false;
    for (const double h : {0.1, 10.0}) {
        const Run damped = simulate(h, 2000, SpringFormulation::Implicit, 0, 0.1);
        for (std::size_t i = 1; i < damped.energy.size(); ++i)
            grows = grows || damped.energy[i] > damped.energy[0] * (1 + kEnergyTolerance);
        const double lossPerStep = 1 - std::pow(damped.energy.back() / 0.5, 1.0 / 2000);
        (h < 1 ? lossResolved : lossUnresolved) = lossPerStep;
    }
    result.metric("numerical_damping_0.1_loss_per_step_omega_h_0.1", lossResolved);
    result.metric("numerical_damping_0.1_loss_per_step_omega_h_10", lossUnresolved);
    result.check(!grows, "numerical damping let the energy grow");
    result.check(lossUnresolved > lossResolved,
                 "numerical damping does not favour the unresolved motion");
}

CaseResult run(const CaseOptions& options) {
    CaseResult result;
    checkTheory(result, options.fast);
    checkEnergy(result);
    checkDamping(result);
    return result;
}

}  // namespace

ValidationCase springSchemeCase() {
    return {"spring-scheme",
            "mass on an implicit spring: the scheme's period and amplitude within 1e-4, "
            "energy invariant within 1e-9 resolved, bounded and not gaining unresolved, "
            "damping as set",
            run};
}

}  // namespace tumble::validation
