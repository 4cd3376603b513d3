#pragma once
/// A study file (docs/sweeps.md): a base scene, the parameters to vary, a seed and the outputs to
/// keep per run. Run i is a pure function of (study, i): its parameter values come from a
/// counter-based generator keyed by (seed, i, parameter), never from a shared stream, so the
/// results do not depend on how many workers share the runs or in which order they finish.

#include <cstdint>
#include <string>
#include <vector>

#include "tumble/scene/scene.h"

namespace tumble::cli {

/// One varied value: a --set path and how its values are chosen.
struct StudyParameter {
    enum class Kind { Values, Uniform, Normal, LogUniform };
    std::string path;    ///< a --set path: "bodies.0.position.2"
    std::string column;  ///< its CSV column ("name", else the path)
    Kind kind = Kind::Values;
    std::vector<Json> values;  ///< a list or a grid; empty for a distribution
    Real a = 0, b = 0;         ///< min and max, or mean and standard deviation
    std::uint64_t count = 0;   ///< values along this axis of the study (>= 1)
};

/// One output column of a run.
struct StudyOutput {
    enum class Kind { Summary, Final, Min, Max, FirstBelow, FirstAbove, Captured };
    std::string name;  ///< the CSV column
    Kind kind = Kind::Summary;
    std::string summaryKey;  ///< Summary: "deepestPenetration", "energy.end.total"...
    std::string body;        ///< the measured body: a name or index (selectBodies)
    std::string quantity;    ///< x y z vx vy vz speed
    Real threshold = 0;      ///< FirstBelow / FirstAbove (m, m/s)
    std::string net;         ///< Captured: the net generator's name
    std::string target;      ///< Captured: the target body's name or index
};

struct Study {
    std::string source;             ///< the study file, for messages
    std::string scenePath;          ///< the base scene file (a built-in name resolved)
    std::vector<std::string> sets;  ///< fixed overrides, applied before the parameters
    std::uint64_t seed = 0;
    std::vector<StudyParameter> parameters;
    std::vector<StudyOutput> outputs;
    std::uint64_t runs = 1;   ///< the product of the parameters' counts
    std::string fingerprint;  ///< hash of the study and its scene's text: results belong to it
};

/// Reads and checks a study file; every parameter path and output is tried on the base scene.
/// Refusals are InvalidArgument "file:line: key: rule".
Study loadStudy(const std::string& path, const std::string& sceneDirectory);

/// The seed of run `index` (a splitmix64 hash of the study's seed and the index).
std::uint64_t runSeed(const Study& study, std::uint64_t index);

/// The values of every parameter for run `index` < study.runs, in study order.
std::vector<Json> runValues(const Study& study, std::uint64_t index);

/// The --set assignments of run `index`: the study's fixed ones, then its parameters.
std::vector<std::string> runOverrides(const Study& study, std::uint64_t index);

}  // namespace tumble::cli
