#pragma once
/// The `tumble` command line, as a function so that tests can run it without a process.

#include <iosfwd>
#include <string>
#include <vector>

namespace tumble::cli {

/// Runs `tumble args...` (args[0] is the program name). Returns the exit status: 0 success,
/// 1 a simulation failure (a step reported a non-finite state), 2 bad input (command line,
/// scene file, output path); nothing is written on status 2. `terminal` enables the progress bar.
int runCommand(const std::vector<std::string>& args, std::ostream& out, std::ostream& err,
               bool terminal = false);

}  // namespace tumble::cli
