#pragma once
/// The study's hanging string (validation/cases/string.cpp) in the peer engines, for the study's
/// Fig. 7 (transient of a strike) and Fig. 10 (cost against stiffness) beside Tumble's: the
/// peers have no spring elements of Tumble's kind, so the string is 30 point masses pulled by
/// the harness's tension-only spring-damper forces (Tumble's explicit thread law), applied
/// before each step -- what an application using Bullet or ODE for a tether would write.

#include <string>
#include <vector>

namespace tumble::bench {

struct StringPeerOptions {
    std::string outDir;                ///< writes string-peers-{transient,cost}.csv here
    std::vector<std::string> engines;  ///< only these; empty: every 3-D peer compiled in
    double duration = 40;              ///< simulated seconds of the struck string's record, > 0
};

/// Runs the strike and the cost sweep in each peer, prints a summary; returns the exit code.
int runStringPeers(const StringPeerOptions& options);

}  // namespace tumble::bench
