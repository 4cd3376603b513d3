#pragma once
/// Scene pieces shared by the contact validation cases: a ground, boxes, stacks and pyramids of
/// unit cubes and a "still standing" test (the bounce's apex tracker is fig45.h's). Header-only:
/// each case is one translation unit and these are small.

#include <algorithm>
#include <cmath>
#include <utility>
#include <vector>

#include "tumble/tumble.h"

namespace tumble::validation::scenes {

constexpr Real kG = 9.81;  ///< |g| used by every contact case (m/s^2)

/// The settings of the study's and the peers' stack scenes (DESIGN.md section 6): h = 1/60,
/// 10 PGS iterations, gravity -Z; everything else the engine default except sleeping, which is
/// off: the claims are the solver's, and a sleeping stack would hide a slow lean or creep.
inline WorldDef stackWorld(Real timeStep = 1.0 / 60.0, int iterations = 10) {
    WorldDef def{.gravity = Vec3(0, 0, -kG), .timeStep = timeStep};
    def.solver.iterations = iterations;
    def.enableSleep = false;
    return def;
}

inline Material material(Real friction, Real restitution = 0, Real density = 1) {
    return Material{.friction = friction, .restitution = restitution, .density = density};
}

/// A static half-space whose surface passes through the origin with outward normal
/// `tilt * +Z`. Returns the static body.
inline BodyId addGround(World& world, const Material& surface,
                        const Quat& tilt = Quat::Identity()) {
    const BodyId ground = world.createBody(BodyDef{.type = BodyType::Static, .orientation = tilt});
    world.createShape(ground, ShapeDef{.geometry = HalfSpace{}, .material = surface});
    return ground;
}

/// A dynamic box whose mass comes from its material's density.
inline BodyId addBox(World& world, const Vec3& position, const Quat& orientation,
                     const Vec3& halfExtents, const Material& surface,
                     const Vec3& velocity = Vec3::Zero()) {
    const BodyId box = world.createBody(
        BodyDef{.position = position, .orientation = orientation, .linearVelocity = velocity});
    world.createShape(box, ShapeDef{.geometry = Box{halfExtents}, .material = surface});
    return box;
}

/// A column of `count` unit cubes standing face to face on the ground (z = 0), each placed
/// exactly touching the one below. Bottom first.
inline std::vector<BodyId> buildStack(World& world, int count, const Material& surface) {
    std::vector<BodyId> cubes;
    for (int i = 0; i < count; ++i) {
        cubes.push_back(
            addBox(world, Vec3(0, 0, 0.5 + i), Quat::Identity(), Vec3::Constant(0.5), surface));
    }
    return cubes;
}

/// A planar pyramid of unit cubes in the x-z plane: row j (from 0 at the ground) holds
/// base - j cubes, centred on x = 0, neighbours `gap` apart (m) so that cubes of one row touch
/// only the two below and above them. Rows touch exactly. Returns the cubes row by row with
/// their rows in `levels`.
inline std::vector<BodyId> buildPyramid(World& world, int base, Real gap, const Material& surface,
                                        std::vector<int>& levels) {
    std::vector<BodyId> cubes;
    const Real pitch = 1 + gap;
    for (int row = 0; row < base; ++row) {
        const int n = base - row;
        for (int i = 0; i < n; ++i) {
            const Real x = (i - 0.5 * (n - 1)) * pitch;
            cubes.push_back(addBox(world, Vec3(x, 0, 0.5 + row), Quat::Identity(),
                                   Vec3::Constant(0.5), surface));
            levels.push_back(row);
        }
    }
    return cubes;
}

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
    bool standingAtEnd = false;
    Real horizontalAtEnd = 0;  ///< Standing::horizontalOffset at the end (m)
    Real verticalAtEnd = 0;    ///< Standing::verticalExcess at the end (m)
};

/// Steps `world` for `duration` seconds watching the cubes; `top` indexes the top cube. The
/// top "falls" when it moves 0.5 m horizontally or sinks 0.5 m beyond its allowed sink.
inline PileRun runPile(World& world, const std::vector<BodyId>& cubes, const Standing& standing,
                       std::size_t top, Real duration, Real lateFrom) {
    constexpr Real kFall = 0.5;  // (m)
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
