// tumble-validate: runs named validation cases, prints a table (or JSON with --json) and exits 1
// when any case fails.

#include <CLI/CLI.hpp>
#include <cmath>
#include <cstdio>
#include <iostream>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "case.h"
#include "report.h"
#include "testkit/scenes.h"

namespace {

using tumble::validation::CaseResult;
using tumble::validation::Metric;
using tumble::validation::ValidationCase;
using Json = nlohmann::ordered_json;

Json metricsJson(const std::vector<Metric>& metrics) {
    Json object = Json::object();
    for (const auto& [name, value] : metrics) {
        object[name] = std::isfinite(value) ? Json(value) : Json(std::to_string(value));
    }
    return object;
}

void printText(const ValidationCase& c, const CaseResult& r) {
    std::printf("\n== %s: %s\n   %s\n", c.name.c_str(), r.passed() ? "PASSED" : "FAILED",
                c.claim.c_str());
    if (!r.table.empty()) {
        std::printf("   ");
        for (const auto& [name, value] : r.table.front().values)
            std::printf("%16s", name.c_str());
        std::printf("\n");
        for (const auto& row : r.table) {
            std::printf("   ");
            for (const auto& [name, value] : row.values)
                std::printf("%16.6g", value);
            std::printf("\n");
        }
    }
    for (const auto& [name, value] : r.metrics)
        std::printf("   %-40s %.6g\n", name.c_str(), value);
    for (const auto& [name, value] : r.tolerances) {
        std::printf("   tolerance %-30s %.6g\n", name.c_str(), value);
    }
    for (const auto& failure : r.failures)
        std::printf("   FAIL: %s\n", failure.c_str());
}

}  // namespace

int main(int argc, char** argv) {
    CLI::App app{"tumble-validate: Tumble's physical claims against analytic answers"};
    std::vector<std::string> names;
    bool json = false;
    bool fast = false;
    bool list = false;
    app.add_option("cases", names, "Cases to run (default: all)");
    app.add_flag("--json", json, "Print the results as JSON");
    app.add_flag("--fast", fast, "Shorter sweeps (as run under ctest)");
    app.add_flag("--list", list, "List the cases and exit");
    std::string reportDir;
    app.add_option("--report", reportDir,
                   "Also write report.md, each table as CSV and the study's figures as PNG to "
                   "this directory (default cases: oscillator bounce string string-cost "
                   "stack-cost)");
    int softStep = 0;
    app.add_option("--soft-step", softStep,
                   "Run the contact cases' worlds with the soft step of this many substeps "
                   "(SolverSettings::softSubsteps; worlds made by the scene kit and bounce)")
        ->check(CLI::PositiveNumber);
    double softHertz = tumble::SolverSettings{}.contactHertz;
    app.add_option("--soft-hertz", softHertz, "With --soft-step: SolverSettings::contactHertz")
        ->check(CLI::PositiveNumber)
        ->capture_default_str();
    CLI11_PARSE(app, argc, argv);
    tumble::testkit::forceSoftStep(softStep, softHertz);

    const std::vector<ValidationCase> cases = tumble::validation::allCases();
    if (list) {
        for (const auto& c : cases)
            std::printf("%-14s %s\n", c.name.c_str(), c.claim.c_str());
        return 0;
    }
    if (names.empty() && !reportDir.empty())
        // The study's Fig. 4, 5, 7, 10 and 11.
        names = {"oscillator", "bounce", "string", "string-cost", "stack-cost"};
    std::vector<const ValidationCase*> selected;
    for (const auto& name : names) {
        const ValidationCase* found = nullptr;
        for (const auto& c : cases) {
            if (c.name == name)
                found = &c;
        }
        if (found == nullptr) {
            std::cerr << "tumble-validate: unknown case '" << name << "' (see --list)\n";
            return 2;
        }
        selected.push_back(found);
    }
    if (names.empty()) {
        for (const auto& c : cases)
            selected.push_back(&c);
    }

    std::vector<std::pair<const ValidationCase*, CaseResult>> reported;
    Json report = {{"cases", Json::array()}};
    int passed = 0;
    int failed = 0;
    for (const ValidationCase* c : selected) {
        const CaseResult result = c->run({fast});
        (result.passed() ? passed : failed) += 1;
        if (json) {
            Json entry = {{"name", c->name},
                          {"passed", result.passed()},
                          {"metrics", metricsJson(result.metrics)},
                          {"tolerances", metricsJson(result.tolerances)}};
            if (!result.failures.empty())
                entry["failures"] = result.failures;
            if (!result.table.empty()) {
                Json rows = Json::array();
                for (const auto& row : result.table)
                    rows.push_back(metricsJson(row.values));
                entry["table"] = rows;
            }
            report["cases"].push_back(entry);
        } else {
            printText(*c, result);
        }
        if (!reportDir.empty())
            reported.emplace_back(c, result);
    }
    if (json) {
        report["passed"] = passed;
        report["failed"] = failed;
        std::cout << report.dump(2) << '\n';
    } else {
        std::printf("\n%d passed, %d failed\n", passed, failed);
    }
    if (!reportDir.empty() && !tumble::validation::writeReport(reportDir, reported)) {
        std::cerr << "tumble-validate: cannot write the report to '" << reportDir << "'\n";
        return 2;
    }
    return failed == 0 ? 0 : 1;
}
