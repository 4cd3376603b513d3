#pragma once
/// What the contact validation cases share beyond the scene kit (testkit/scenes.h, whose
/// ground, boxes, stacks and pyramids they build with): a "still standing" test and the run of
/// a pile (the bounce's apex tracker is fig45.h's). Header-only: each case is one translation
/// unit and these are small.

#include <algorithm>
#include <cmath>
#include <utility>
#include <vector>

#include "testkit/scenes.h"
#include "tumble/tumble.h"

namespace tumble::validation::scenes {

constexpr Real kG = testkit::kGravity;  ///< |g| used by every contact case (m/s^2)

// The ground, boxes, stacks and pyramids are the scene kit's (testkit/scenes.h): stackWorld is
// the settings of the study's and the peers' stack scenes (DESIGN.md section 6), sleeping off
// because the claims are the solver's and a sleeping stack would hide a slow lean or creep.
using testkit::addBox;
using testkit::addGround;
using testkit::buildPyramid;
using testkit::buildStack;
using testkit::material;
using testkit::stackWorld;

/// Whether a pile of cubes still stands where it was built. A cube "stands" while its centre
/// is within `kHorizontal` of its start position horizontally and has not sunk more than
/// `kVertical` beyond what the contacts beneath it may legitimately sink: (level + 1) contact
/// layers, each allowed `allowedSink` (slop + 1 mm). A toppled or sliding cube moves by half a
/// cube or more, so 0.1 m separates standing from falling with a wide margin either way.
struct Standing {
    static constexpr Real kHorizontal = 0.1;  ///< (m)
    static constexpr Real kVertical = 0.1;    ///< (m)

    std::vector<Vec3> start;
    std::vector<int> levels;
    Real allowedSink = 0;  ///< per contact layer (m)

    /// Largest horizontal offset of any cube from its start (m).
    Real horizontalOffset(const World& world, const std::vector<BodyId>& cubes) const {
        Real worst = 0;
        for (std::size_t i = 0; i < cubes.size(); ++i) {
            const Vec3 d = world.position(cubes[i]) - start[i];
            worst = std::max(worst, std::hypot(d.x(), d.y()));
        }
        return worst;
    }
    /// Largest vertical offset of any cube beyond its allowed sink (m); <= 0 while none exceeds.
    Real verticalExcess(const World& world, const std::vector<BodyId>& cubes) const {
        Real worst = -1e300;
        for (std::size_t i = 0; i < cubes.size(); ++i) {
            const Real dz = std::abs(world.position(cubes[i]).z() - start[i].z());
            worst = std::max(worst, dz - (levels[i] + 1) * allowedSink);
        }
        return worst;
    }
    bool holds(const World& world, const std::vector<BodyId>& cubes) const {
        return horizontalOffset(world, cubes) < kHorizontal &&
               verticalExcess(world, cubes) < kVertical;
    }
};

inline Standing recordStanding(const World& world, const std::vector<BodyId>& cubes,
                               std::vector<int> levels) {
    Standing s;
    for (const BodyId c : cubes)
        s.start.push_back(world.position(c));
    s.levels = std::move(levels);
    s.allowedSink = world.settings().solver.slop + 1e-3;
    return s;
}

/// What happened to a pile of cubes (stack or pyramid) over a run.
struct PileRun {
    Real duration = 0;       ///< simulated (s); shorter than asked if a step failed
    bool finite = true;      ///< every step succeeded
    Real lostStanding = -1;  ///< first time Standing failed (s); -1: it never did
    Real topFell = -1;       ///< first time the top cube moved 0.5 m (s); -1: never
    Real topDriftMax = 0;    ///< largest horizontal offset of the top cube (m)
    Real deepestLate = 0;    ///< max of the solver's deepest penetration after `lateFrom` (m)
    Real landingSpread = 0;  ///< largest Standing::horizontalOffset in the first 2 s (m)
    bool standingAtEnd = false;
    Real horizontalAtEnd = 0;  ///< Standing::horizontalOffset at the end (m)
    Real verticalAtEnd = 0;    ///< Standing::verticalExcess at the end (m)
};

/// Steps `world` for `duration` seconds watching the cubes; `top` indexes the top cube. The
/// top "falls" when it moves 0.5 m horizontally or sinks 0.5 m beyond its allowed sink.
inline PileRun runPile(World& world, const std::vector<BodyId>& cubes, const Standing& standing,
                       std::size_t top, Real duration, Real lateFrom) {
    constexpr Real kFall = 0.5;     // (m)
    constexpr Real kLanding = 2.0;  // (s)
    PileRun run;
    const long steps = std::lround(duration / world.settings().timeStep);
    const Real topSink = (standing.levels[top] + 1) * standing.allowedSink;
    for (long i = 0; i < steps; ++i) {
        if (!world.step().ok()) {
            run.finite = false;
            break;
        }
        const Real t = world.time();
        const Vec3 d = world.position(cubes[top]) - standing.start[top];
        const Real drift = std::hypot(d.x(), d.y());
        run.topDriftMax = std::max(run.topDriftMax, drift);
        if (run.topFell < 0 && (drift > kFall || -d.z() > kFall + topSink))
            run.topFell = t;
        if (run.lostStanding < 0 && !standing.holds(world, cubes))
            run.lostStanding = t;
        if (t <= kLanding + 1e-9)
            run.landingSpread =
                std::max(run.landingSpread, standing.horizontalOffset(world, cubes));
        if (t >= lateFrom - 1e-9) {
            run.deepestLate = std::max(run.deepestLate, world.solverStats().deepestPenetration);
        }
    }
    run.duration = world.time();
    run.standingAtEnd = run.finite && standing.holds(world, cubes);
    run.horizontalAtEnd = standing.horizontalOffset(world, cubes);
    run.verticalAtEnd = standing.verticalExcess(world, cubes);
    return run;
}

}  // namespace tumble::validation::scenes
