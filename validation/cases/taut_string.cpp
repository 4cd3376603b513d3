// taut-string: transverse modes of a string under tension T between fixed ends, lumped into N
// point masses joined by N + 1 springs, against omega_n = (n pi / L) sqrt(T / rho).
//
// The string: L = 1 m, rho = 0.01 kg/m, T = 10 N, so omega_1 = 99.3 rad/s. Each spring is
// stretched 10 % past its rest length to carry T. The masses start displaced across the string
// by 1 mm in each of the first three mode shapes sin(n pi x / L), at rest (a small free response:
// geometric nonlinearity shifts frequencies by ~1e-5). The modal coordinate
// q_n(t) = sum_j y_j(t) sin(n pi x_j / L) is recorded every step and its frequency is the peak of
// its Hann-windowed spectrum (lumped.h). Expected errors: lumping, 2 sin(n pi / (2(N + 1))) vs
// n pi / (N + 1), i.e. -(n pi / (N + 1))^2 / 24, 0.15 % for n = 3, N = 49; time stepping
// (omega h)^2 / 24, ~3e-5. Both formulations are run; each must meet the 1 % claim.

#include <algorithm>
#include <cmath>
#include <numbers>
#include <string>
#include <vector>

#include "../case.h"
#include "lumped.h"

namespace tumble::validation {
namespace {

constexpr double kPi = std::numbers::pi;
constexpr double kLength = 1;
constexpr double kDensity = 0.01;
constexpr double kTension = 10;

std::vector<double> modeFrequencies(int n, SpringFormulation formulation, double h,
                                    double periods) {
    const double spacing = kLength / (n + 1);
    const double m = kDensity * spacing;
    const double rest = spacing / 1.1;
    const double k = kTension / (spacing - rest);
    WorldDef settings;
    settings.gravity = Vec3::Zero();
    settings.timeStep = h;
    settings.enableSleep = false;
    World world(settings);
    std::vector<BodyId> masses;
    std::vector<double> x;
    for (int j = 1; j <= n; ++j) {
        const double xj = spacing * j;
        double y = 0;
        for (int mode = 1; mode <= 3; ++mode)
            y += 1e-3 * std::sin(mode * kPi * xj / kLength);
        masses.push_back(addPointMass(world, Vec3(xj, y, 0), m));
        x.push_back(xj);
    }
    SpringDef def;
    def.restLength = rest;
    def.stiffness = k;
    def.formulation = formulation;
    for (int j = 0; j <= n; ++j) {
        def.bodyA = j == n ? masses.back() : masses[j];
        def.bodyB = (j == 0 || j == n) ? BodyId{} : masses[j - 1];
        def.localAnchorB = j == 0 ? Vec3::Zero() : (j == n ? Vec3(kLength, 0, 0) : Vec3::Zero());
        world.createSpring(def);
    }
    const double omega1 = kPi / kLength * std::sqrt(kTension / kDensity);
    const int steps = static_cast<int>(periods * 2 * kPi / omega1 / h);
    std::vector<std::vector<double>> q(3, std::vector<double>());
    for (auto& series : q)
        series.reserve(steps);
    for (int i = 0; i < steps; ++i) {
        if (!world.step().ok())
            return {};
        for (int mode = 1; mode <= 3; ++mode) {
            double sum = 0;
            for (int j = 0; j < n; ++j)
                sum += world.position(masses[j]).y() * std::sin(mode * kPi * x[j] / kLength);
            q[mode - 1].push_back(sum);
        }
    }
    std::vector<double> omegas;
    for (int mode = 1; mode <= 3; ++mode)
        omegas.push_back(peakFrequency(q[mode - 1], h, mode * omega1));
    return omegas;
}

CaseResult run(const CaseOptions& options) {
    CaseResult result;
    const int n = 49;
    const double h = 1e-4;
    const double periods = options.fast ? 12 : 40;
    const double omega1 = kPi / kLength * std::sqrt(kTension / kDensity);
    double worst = 0;
    for (const SpringFormulation f : {SpringFormulation::Explicit, SpringFormulation::Implicit}) {
        const std::string tag = f == SpringFormulation::Explicit ? "explicit" : "implicit";
        const std::vector<double> omegas = modeFrequencies(n, f, h, periods);
        if (omegas.size() != 3) {
            result.check(false, tag + " string went non-finite");
            continue;
        }
        for (int mode = 1; mode <= 3; ++mode) {
            const double exact = mode * omega1;
            const double lumped =
                2 * std::sqrt(kTension / (kDensity * kLength / (n + 1) * kLength / (n + 1))) *
                std::sin(mode * kPi / (2.0 * (n + 1)));
            const double error = omegas[mode - 1] / exact - 1;
            result.table.push_back({{{"implicit", f == SpringFormulation::Implicit ? 1 : 0},
                                     {"mode", mode},
                                     {"omega", omegas[mode - 1]},
                                     {"omega_exact", exact},
                                     {"rel_error", error},
                                     {"rel_error_lumped_theory", lumped / exact - 1}}});
            result.metric(tag + "_mode" + std::to_string(mode) + "_rel_error", error);
            worst = std::max(worst, std::abs(error));
        }
    }
    result.metric("max_abs_rel_error", worst);
    result.tolerance("rel_error_max", 0.01);
    result.check(worst <= 0.01, "a mode is off the string's frequency by more than 1 %");
    return result;
}

}  // namespace

ValidationCase tautStringCase() {
    return {"taut-string",
            "lumped string under tension, explicit and implicit springs: first three transverse "
            "modes within 1 % of (n pi / L) sqrt(T / rho)",
            run};
}

}  // namespace tumble::validation
