#pragma once
/// tumble-validate --report DIR: each case's table as CSV and Markdown, and the study's figures
/// drawn from them by validation/plot_report.py (Fig. 4 from the oscillator, Fig. 5 from bounce,
/// Fig. 7 from string, Fig. 10 from string-cost, Fig. 11 from stack-cost beside tumble-bench's
/// committed stack timings of the peers).

#include <string>
#include <utility>
#include <vector>

#include "case.h"

namespace tumble::validation {

/// Writes DIR/report.md and DIR/<case>.csv for every case with a table, then runs the plotting
/// script when /usr/bin/python3 is there. Returns false when DIR cannot be written.
bool writeReport(const std::string& dir,
                 const std::vector<std::pair<const ValidationCase*, CaseResult>>& results);

}  // namespace tumble::validation
