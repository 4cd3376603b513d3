#pragma once
/// The study's Fig. 4 (undamped oscillator) and Fig. 5 (bouncing ball) scenes in the peer engines,
/// beside Tumble's (tumble-validate's oscillator and bounce cases): the same grids and the same
/// measurements (validation/cases/fig45.h), with matched settings -- same h, 10 iterations, no
/// sleeping, each engine's default collision margins.

#include <string>
#include <vector>

namespace tumble::bench {

struct StudyPeerOptions {
    std::string outDir;                ///< writes study-peers-{oscillator,bounce}.csv here
    std::vector<std::string> engines;  ///< only these; empty: every 3-D peer compiled in
};

/// Runs both sweeps in each peer, prints a summary; returns the exit code.
int runStudyPeers(const StudyPeerOptions& options);

}  // namespace tumble::bench
