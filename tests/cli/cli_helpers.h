#pragma once
// Running the `tumble` command in-process from the tests, and reading what it wrote.

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include <unistd.h>

#include "command.h"

namespace tumble::cli::test {

struct Outcome {
    int status = -1;
    std::string out, err;
};

inline Outcome tumbleRun(std::vector<std::string> args) {
    args.insert(args.begin(), "tumble");
    std::ostringstream out, err;
    Outcome o;
    o.status = runCommand(args, out, err);
    o.out = out.str();
    o.err = err.str();
    return o;
}

/// A fresh scratch directory per test.
inline std::filesystem::path scratch(const std::string& name) {
    // The process id keeps test runs of several build trees at once (presets, worktrees) apart.
    const std::filesystem::path dir =
        std::filesystem::temp_directory_path() /
        ("tumble_cli_test_" + std::to_string(::getpid()) + "_" + name);
    std::filesystem::remove_all(dir);
    std::filesystem::create_directories(dir);
    return dir;
}

inline std::string slurp(const std::filesystem::path& path) {
    std::ifstream in(path);
    std::stringstream s;
    s << in.rdbuf();
    return s.str();
}

inline const std::string kFixtures = TUMBLE_CLI_TEST_DIR;

}  // namespace tumble::cli::test
