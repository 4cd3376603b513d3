#pragma once
/// One engine behind the scene harness: the few calls a stack or pyramid scene needs, so the same
/// scene runs in Tumble and in each peer with matched settings (h, iterations, friction,
/// restitution, sizes, masses). Each peer lives in its own file and is compiled only when its
/// library was found.

#include <memory>
#include <string>
#include <vector>

#include "tumble/core/math.h"

namespace tumble::bench {

/// Settings every engine gets: the study's stack settings (DESIGN.md section 6).
struct SceneSettings {
    Real timeStep = 1.0 / 60;  ///< (s)
    int iterations = 10;       ///< velocity iterations
    Real friction = 0.5;       ///< Coulomb mu of every pair, after the engine's combine rule
    Real boxMass = 1;          ///< (kg), unit cubes
};

class PeerWorld {
public:
    virtual ~PeerWorld() = default;
    /// The plane z = 0, static.
    virtual void addGround() = 0;
    /// A unit cube (1 m edges) at `position`, at rest; returns its index (0, 1, ...).
    virtual int addCube(const Vec3& position) = 0;
    virtual void step() = 0;
    virtual Vec3 position(int cube) const = 0;
    /// Deepest penetration among the current contacts (m), >= 0.
    virtual Real deepestPenetration() const = 0;
};

struct Peer {
    std::string name;
    std::unique_ptr<PeerWorld> (*create)(const SceneSettings&);
};

std::unique_ptr<PeerWorld> createTumble(const SceneSettings& settings);
#ifdef TUMBLE_HAVE_BULLET
std::unique_ptr<PeerWorld> createBullet(const SceneSettings& settings);
#endif

/// The engines compiled in, Tumble first.
inline std::vector<Peer> peers() {
    std::vector<Peer> list{{"tumble", &createTumble}};
#ifdef TUMBLE_HAVE_BULLET
    list.push_back({"bullet", &createBullet});
#endif
    return list;
}

/// The peers this build was configured without, for the report.
inline std::vector<std::string> skippedPeers() {
    std::vector<std::string> skipped;
#ifndef TUMBLE_HAVE_BULLET
    skipped.push_back("bullet (libbullet-dev not found at configure time)");
#endif
    return skipped;
}

}  // namespace tumble::bench
