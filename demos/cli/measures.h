#pragma once
/// What a study keeps of each run (docs/sweeps.md): summary figures and measures of bodies taken
/// while the scene runs (through RunOptions::observe), among them the net capture criterion.

#include <limits>
#include <string>
#include <vector>

#include "run.h"
#include "study.h"

namespace tumble::cli {

/// The summary figure `key` ("deepestPenetration", "energy.end.total"...) of `s`; false for an
/// unknown key.
bool summaryValue(const Summary& s, const std::string& key, Real& value);
/// The known keys, comma-separated, for messages.
std::string summaryKeys();
/// The quantities a measure reads of a body: x y z (centre of mass, m), vx vy vz, speed (m/s).
std::vector<std::string> quantityNames();

/// The capture criterion (docs/sweeps.md): the net's four corners below the top of the target's
/// bounding box, and the target's centre (x, y) inside the convex hull, seen from above, of the
/// net nodes at or above that top: the net has closed under a target it covers.
bool netCaptures(const BuiltScene& built, const std::vector<int>& nodes,
                 const std::vector<int>& corners, int target);

/// The measures of one run: fed every state of the run, read at the end.
class RunMeasures {
public:
    /// `scene` is the run's scene; its bodies are looked up by the outputs' names.
    RunMeasures(const Study& study, const Scene& scene);
    /// The state after each step (the start included); `end` marks the last.
    void observe(const BuiltScene& built, bool end);
    /// One value per study output; NaN for a measure that never happened (first-below).
    std::vector<Real> values(const Summary& summary) const;

private:
    struct Track {
        std::vector<int> bodies;  ///< the measured body; Captured: the net's nodes
        std::vector<int> corners;
        Real value = std::numeric_limits<Real>::quiet_NaN();
        Real previous = 0, previousTime = 0;
        bool started = false;
    };
    const Study& study_;
    std::vector<Track> tracks_;
};

}  // namespace tumble::cli
