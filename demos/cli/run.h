#pragma once
/// Running a scene headless: the step loop, the summary, CSV trajectories and the picture.

#include <cstdint>
#include <functional>
#include <iosfwd>
#include <string>
#include <vector>

#include "tumble/scene/scene.h"

namespace tumble::cli {

/// Where the outputs go (the scene's "outputs" merged with the command line).
struct RunOptions {
    std::string record;              ///< CSV file ("" = none)
    Real recordRate = 0;             ///< samples per second (Hz); 0 = every step
    std::string summary;             ///< JSON file ("" = none)
    std::string picture;             ///< SVG file ("" = none)
    std::vector<Real> pictureTimes;  ///< moments drawn (s); empty: start, middle and end
    std::string view = "side";
    std::vector<int> trace;         ///< body indices traced in the picture
    std::vector<int> recordBodies;  ///< body indices the CSV holds; empty: every non-static one
    bool quiet = false;             ///< no table, no progress bar
    bool terminal = false;          ///< stdout is a terminal: a progress bar for long runs
    /// Checkpoint file ("" = none): written before the first step, every checkpointEvery of
    /// simulated time, and at the end (docs/checkpoint.md).
    std::string checkpoint;
    Real checkpointEvery = 0;  ///< (s), > 0; 0 = only at the start and the end
    std::string resume;        ///< checkpoint to continue from ("" = start at t = 0)
    /// Called with the state at the start, after every step, and once more at the end
    /// (end = true): how a study measures a run (measures.h) without a step loop of its own.
    std::function<void(const BuiltScene&, bool end)> observe;
    std::string replay;    ///< replay file for the viewer ("" = none; docs/replay.md)
    std::string gltf;      ///< animated glTF binary, .glb ("" = none)
    Real replayRate = 60;  ///< frames per second (Hz) of the replay and the glTF, > 0
};

/// Energy of the dynamic bodies and springs (J). Potential is -m g.c with each body's gravity
/// scale; elastic is that of every spring and thread (k (L - L0)^2 / 2, none for a slack thread).
struct Energy {
    Real kinetic = 0;
    Real potential = 0;
    Real elastic = 0;
    Real total() const { return kinetic + potential + elastic; }
};

struct Summary {
    std::string scene;
    std::string status = "ok";  ///< "ok" or what failed
    int failedBody = -1;        ///< scene index of the body a failed step named
    std::uint64_t steps = 0;
    Real timeStep = 0;          ///< (s)
    Real simulatedTime = 0;     ///< (s)
    double wallTime = 0;        ///< in the step loop (s)
    double realTimeFactor = 0;  ///< simulated time / wall time
    int bodies = 0;
    int bodiesAsleep = 0;  ///< dynamic bodies asleep at the end
    Energy start, end;
    Real deepestPenetration = 0;  ///< max over the run of the solver's deepest penetration (m)
    Real lastResidual = 0;        ///< complementarity residual of the last step (m/s)
    int lastIterations = 0;
    /// The world's warnings at the end (tumble/warnings.h), described; also printed to err.
    std::vector<std::string> warnings;
};

Energy energyOf(const BuiltScene& built);

/// Runs `scene` for scene.duration, printing the summary table to `out` (unless quiet) and a
/// failed step to `err`. Returns 0, or 1 when a step failed (the outputs are still
/// written, the summary saying what failed). Output files that cannot be opened are refused
/// (InvalidArgument) before the first step.
int runScene(const Scene& scene, const RunOptions& options, std::ostream& out, std::ostream& err,
             Summary* result = nullptr);

/// The summary's figures that are not finite numbers, by their JSON names ("energy.end.total"):
/// JSON has no infinity, so they are written as null and each is also warned of.
std::vector<std::string> nonFiniteFigures(const Summary& s);

/// The summary as JSON text.
std::string summaryJson(const Summary& s);

}  // namespace tumble::cli
