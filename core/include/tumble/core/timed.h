#pragma once
/// The stage timer of the step and of the solve (Profile, SolverProfile): wall-clock time only,
/// it never touches what it times.

#include <chrono>

namespace tumble {

/// Runs `stage` and returns the wall-clock time it took (s).
template <typename Stage>
double timed(Stage&& stage) {
    const auto start = std::chrono::steady_clock::now();
    stage();
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

}  // namespace tumble
