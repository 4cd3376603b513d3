#pragma once
/// The study's Fig. 4 (undamped oscillator) and Fig. 5 (bouncing ball): their parameter grids and
/// their measurements, shared by the validation cases (oscillator.cpp, bounce.cpp) and by
/// tumble-bench --study, which runs the same scenes in the peer engines, so that both sides sweep
/// the same grid and measure the same way. Header-only and engine-free: plain samples in, numbers
/// out.

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <numbers>
#include <vector>

namespace tumble::validation::fig45 {

// --- Fig. 4: a 1 kg mass on an explicit spring k = 1 N/m (omega = 1 rad/s), x_0 = 1 m, v_0 = 0.

/// The omega h of the sweep; `fast`: the subset ctest runs.
inline std::vector<double> oscillatorSweep(bool fast) {
    if (fast)
        return {0.01, 0.03, 0.1, 0.3, 0.5, 1.5, 1.9, 2.0, 2.5};
    return {0.01, 0.02, 0.05, 0.1, 0.2,  0.3, 0.5,  0.8, 1.0,
            1.2,  1.5,  1.8,  1.9, 1.95, 2.0, 2.05, 2.2, 2.5};
}

/// Steps of a run at `omegaH` (omega = 1): 200 periods, at least `minSteps`, at most 200,000.
inline int oscillatorSteps(double omegaH, int minSteps = 20000) {
    const double periods = 200;
    return std::min(200000,
                    std::max(minSteps, static_cast<int>(periods * 2 * std::numbers::pi / omegaH)));
}

/// A run is clearly unstable once |x| passes this (m): stop before overflow.
constexpr double kOscillatorBlowUp = 1e12;

struct Oscillation {
    double amplitude = 0;  ///< measured A (m)
    double period = 0;     ///< measured (s); 0 when fewer than two zero crossings
    double growth = 0;     ///< max |x| over the last tenth / max |x| over the first tenth
};

/// Measures a sampled oscillation x_0, x_1, ... taken every h seconds. The period is the mean
/// spacing of the zero crossings (linear interpolation) over the run; the amplitude is that of the
/// sinusoid through the three samples around each positive peak,
/// A^2 = (x_k^2 - x_{k-1} x_{k+1}) / sin^2(theta'), cos(theta') = (x_{k-1} + x_{k+1}) / (2 x_k),
/// exact for a sampled sinusoid, so the measured error is the integrator's, not the sampling's.
inline Oscillation measureOscillation(const std::vector<double>& x, double h) {
    Oscillation r;
    const std::size_t n = x.size();
    const std::size_t tenth = std::max<std::size_t>(n / 10, 2);
    double early = 0, late = 0;
    for (std::size_t i = 0; i < tenth && i < n; ++i)
        early = std::max(early, std::abs(x[i]));
    for (std::size_t i = n > tenth ? n - tenth : 0; i < n; ++i)
        late = std::max(late, std::abs(x[i]));
    r.growth = late / early;

    double firstCrossing = -1, lastCrossing = -1;
    int crossings = 0;
    double amplitudeSum = 0;
    int peaks = 0;
    for (std::size_t i = 1; i + 1 < n; ++i) {
        if ((x[i - 1] > 0) != (x[i] > 0)) {
            const double t = h * (static_cast<double>(i) - 1 + x[i - 1] / (x[i - 1] - x[i]));
            if (crossings == 0)
                firstCrossing = t;
            lastCrossing = t;
            ++crossings;
        }
        if (x[i] > 0 && x[i] >= x[i - 1] && x[i] >= x[i + 1]) {
            const double cosTheta = (x[i - 1] + x[i + 1]) / (2 * x[i]);
            const double sin2 = 1 - cosTheta * cosTheta;
            if (sin2 > 1e-12) {
                amplitudeSum += std::sqrt((x[i] * x[i] - x[i - 1] * x[i + 1]) / sin2);
                ++peaks;
            }
        }
    }
    if (crossings >= 2)
        r.period = 2 * (lastCrossing - firstCrossing) / (crossings - 1);
    r.amplitude = peaks > 0 ? amplitudeSum / peaks : late;
    return r;
}

// --- Fig. 5: a sphere dropped onto a static ground.

constexpr double kBallRadius = 0.1;   ///< (m)
constexpr double kDropHeight = 1.0;   ///< of the centre (m)
constexpr double kRestitution = 0.8;  ///< of the ball-ground pair
constexpr int kBounces = 5;           ///< apexes measured
constexpr double kBounceTime = 6.0;   ///< (s) the five flights take about 2.8 s

/// Steps per second of the sweep; `fast`: the subset ctest runs.
inline std::vector<int> bounceRates(bool fast) {
    if (fast)
        return {60, 240, 1000};
    return {60, 120, 240, 480, 1000, 2000};
}

/// Newton's law with the pre-impact approach speed: the k-th apex (k >= 1) of the centre (m).
inline double analyticApex(int k) {
    return kBallRadius + (kDropHeight - kBallRadius) * std::pow(kRestitution, 2 * k);
}

/// Apexes of a bouncing body's height z(t_n), sampled once per step. In free flight
/// semi-implicit Euler puts the samples exactly on a parabola in t (see free_fall.cpp), so the
/// vertex of the parabola through the three samples around a local maximum is the apex of the
/// discrete flight, free of the up-to g h^2 / 8 error of taking the highest sample.
class ApexTracker {
public:
    /// Feeds the height after each step (m), starting with the initial height.
    void sample(double z) {
        z0_ = z1_;
        z1_ = z2_;
        z2_ = z;
        ++count_;
        if (count_ >= 3 && z1_ > z0_ && z1_ >= z2_) {
            const double curvature = z0_ - 2 * z1_ + z2_;  // = -g h^2 in flight
            apexes_.push_back(curvature < 0 ? z1_ - (z0_ - z2_) * (z0_ - z2_) / (8 * curvature)
                                            : z1_);
        }
    }
    const std::vector<double>& apexes() const { return apexes_; }
    /// Relative errors of the first kBounces apexes against analyticApex (NaN: never reached).
    std::vector<double> errors() const {
        std::vector<double> e(kBounces, NAN);
        for (int k = 0; k < kBounces && k < static_cast<int>(apexes_.size()); ++k)
            e[static_cast<std::size_t>(k)] =
                apexes_[static_cast<std::size_t>(k)] / analyticApex(k + 1) - 1;
        return e;
    }
    bool complete() const { return static_cast<int>(apexes_.size()) >= kBounces; }

private:
    double z0_ = 0, z1_ = 0, z2_ = 0;
    int count_ = 0;
    std::vector<double> apexes_;
};

}  // namespace tumble::validation::fig45
