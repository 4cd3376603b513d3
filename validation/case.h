#pragma once
/// A validation case: a physical claim checked against an analytic answer or a converged
/// reference, with its tolerances written down next to the numbers it measured.

#include <functional>
#include <string>
#include <utility>
#include <vector>

namespace tumble::validation {

struct CaseOptions {
    bool fast = false;  ///< a shorter sweep for ctest; the claims checked are the same
};

/// A named number. Kept in insertion order so reports read the way the case computed them.
using Metric = std::pair<std::string, double>;

/// One row of a case's table (e.g. one value of omega*h in the oscillator sweep).
struct TableRow {
    std::vector<Metric> values;
};

struct CaseResult {
    std::vector<Metric> metrics;
    std::vector<Metric> tolerances;
    std::vector<std::string> failures;  ///< one line per broken claim; empty means passed
    std::vector<TableRow> table;
    /// Long series for the report's figures only (a transient, a spectrum): written by --report
    /// as <case>-<name>.csv, never printed or put in report.md.
    std::vector<std::pair<std::string, std::vector<TableRow>>> series;

    bool passed() const { return failures.empty(); }
    void metric(const std::string& name, double value) { metrics.emplace_back(name, value); }
    void tolerance(const std::string& name, double value) { tolerances.emplace_back(name, value); }
    /// Records a claim: passes when `holds`; otherwise `what` goes into the failures.
    void check(bool holds, const std::string& what) {
        if (!holds)
            failures.push_back(what);
    }
};

struct ValidationCase {
    std::string name;
    std::string claim;  ///< one line: what is being shown
    std::function<CaseResult(const CaseOptions&)> run;
};

ValidationCase freeFallCase();
ValidationCase oscillatorCase();
ValidationCase torqueFreeCase();
ValidationCase bounceCase();
ValidationCase inclineCase();
ValidationCase slideCase();
ValidationCase stackCase();
ValidationCase pyramidCase();
ValidationCase massRatioCase();
ValidationCase tableCase();
ValidationCase tunnelCase();
ValidationCase springStabilityCase();
ValidationCase springSchemeCase();
ValidationCase tautStringCase();
ValidationCase hangingChainCase();
ValidationCase stiffNetCase();
ValidationCase netEnergyCase();
ValidationCase pendulumCase();
ValidationCase jointChainCase();
ValidationCase fiveBodyPendulumCase();
ValidationCase motorCase();
ValidationCase pdArmCase();
ValidationCase stringCase();
ValidationCase stringCostCase();
ValidationCase stackCostCase();
ValidationCase rollingCase();

/// Every case, in the order the runner lists them.
inline std::vector<ValidationCase> allCases() {
    return {freeFallCase(),
            oscillatorCase(),
            torqueFreeCase(),
            bounceCase(),
            inclineCase(),
            slideCase(),
            stackCase(),
            pyramidCase(),
            massRatioCase(),
            tableCase(),
            tunnelCase(),
            springStabilityCase(),
            springSchemeCase(),
            tautStringCase(),
            hangingChainCase(),
            stiffNetCase(),
            pendulumCase(),
            jointChainCase(),
            fiveBodyPendulumCase(),
            motorCase(),
            pdArmCase(),
            stringCase(),
            stringCostCase(),
            stackCostCase(),
            rollingCase(),
            netEnergyCase()};
}

/// Least-squares slope of log(y) against log(x): the order of convergence.
double logLogSlope(const std::vector<double>& x, const std::vector<double>& y);
/// Least-squares slope of y against x.
double fitSlope(const std::vector<double>& x, const std::vector<double>& y);
/// Least-squares acceleration a of s(t) = s0 + v0 t + a t^2 / 2 through the samples.
double fitAcceleration(const std::vector<double>& t, const std::vector<double>& s);

}  // namespace tumble::validation
