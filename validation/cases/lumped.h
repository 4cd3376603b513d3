#pragma once
// Helpers shared by the lumped-mass string cases: point masses (bodies without shapes, so nothing
// collides), and the frequency of a mode from a recorded free response.

#include <cmath>
#include <complex>
#include <numbers>
#include <vector>

#include "tumble/tumble.h"

namespace tumble::validation {

inline BodyId addPointMass(World& world, const Vec3& position, double mass) {
    BodyDef def;
    def.position = position;
    def.mass.mass = mass;
    // Any positive inertia: springs act at the centre, so nothing turns.
    def.mass.inertia = Mat3::Identity() * mass * 1e-6;
    return world.createBody(def);
}

// |Hann-windowed DTFT| of x (sampled every dt) at angular frequency omega.
inline double windowedSpectrum(const std::vector<double>& x, double dt, double omega) {
    const std::size_t n = x.size();
    std::complex<double> sum = 0;
    const std::complex<double> turn = std::polar(1.0, -omega * dt);
    std::complex<double> phase = 1;
    for (std::size_t k = 0; k < n; ++k) {
        const double w = 0.5 - 0.5 * std::cos(2 * std::numbers::pi * static_cast<double>(k) /
                                              (static_cast<double>(n) - 1.0));
        sum += w * x[k] * phase;
        phase *= turn;
        if ((k & 1023) == 1023)
            phase = std::polar(1.0, -omega * dt * static_cast<double>(k + 1));  // no drift
    }
    return std::abs(sum);
}

// Angular frequency of the strongest spectral peak within +-15 % of `guess`: a grid scan, then
// golden-section refinement of the windowed DTFT's maximum. For a record of many periods the
// peak of a single tone is located to far better than 1e-4 relative; other modes, an octave or
// more away, sit in the window's fast-falling sidelobes.
inline double peakFrequency(const std::vector<double>& x, double dt, double guess) {
    double lo = 0.85 * guess;
    double hi = 1.15 * guess;
    constexpr int kGrid = 120;
    double best = lo;
    double bestValue = -1;
    for (int i = 0; i <= kGrid; ++i) {
        const double w = lo + (hi - lo) * i / kGrid;
        const double v = windowedSpectrum(x, dt, w);
        if (v > bestValue) {
            bestValue = v;
            best = w;
        }
    }
    const double step = (hi - lo) / kGrid;
    double a = best - step;
    double b = best + step;
    const double ratio = (std::sqrt(5.0) - 1) / 2;
    double c = b - ratio * (b - a);
    double d = a + ratio * (b - a);
    double fc = windowedSpectrum(x, dt, c);
    double fd = windowedSpectrum(x, dt, d);
    for (int i = 0; i < 60 && b - a > 1e-12 * guess; ++i) {
        if (fc > fd) {
            b = d;
            d = c;
            fd = fc;
            c = b - ratio * (b - a);
            fc = windowedSpectrum(x, dt, c);
        } else {
            a = c;
            c = d;
            fc = fd;
            d = a + ratio * (b - a);
            fd = windowedSpectrum(x, dt, d);
        }
    }
    return 0.5 * (a + b);
}

}  // namespace tumble::validation
