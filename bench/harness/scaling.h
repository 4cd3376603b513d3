#pragma once
/// Scaling: the CPU time of one step against the body count -- piles of 1,000 to 20,000
/// (optionally 50,000) mixed bodies, nets of 100 to 10,000 nodes -- in each 3-D engine, and the
/// exponent p of time ~ count^p fitted by least squares on the log-log points.

#include <string>
#include <vector>

namespace tumble::bench {

struct ScalingOptions {
    bool enabled = false;
    bool with50k = false;              ///< add the 50,000-body pile (minutes per engine)
    std::vector<std::string> engines;  ///< only these; empty: every 3-D engine compiled in
    std::vector<std::string> kinds;    ///< only these of "pile", "net"; empty: both
    std::string outPrefix;             ///< writes PREFIX-scaling.csv unless empty
    bool colouredContacts = false;     ///< Tumble's coloured contact sweeps
    std::vector<int> piles;            ///< body counts; empty: the default list
};

/// Runs the scaling study, prints the table and the fitted exponents; returns the exit code.
int runScaling(const ScalingOptions& options);

/// The least-squares slope of log(y) against log(x): the exponent p of y ~ x^p. Needs at least
/// two distinct positive x; NaN otherwise.
double fitExponent(const std::vector<double>& x, const std::vector<double>& y);

}  // namespace tumble::bench
