#pragma once
/// The harness's scenes, built the same way in every engine: a column of unit cubes, a pyramid,
/// a pile of mixed bodies in a container, and a net thrown open in free space. SceneRun builds
/// one in one engine, steps it and measures the scene's error as it goes.

#include <memory>
#include <string>
#include <vector>

#include "peer.h"
#include "terrain.h"

namespace tumble::bench {

/// TerrainPile and MeshPile: the pile dropped on terrain.h's bowl, as a height field or as the
/// same surface in triangles.
enum class SceneKind { Stack, Pyramid, Pile, Net, TerrainPile, MeshPile };

struct Scene {
    std::string name;
    /// Cubes in the column, the pyramid's base, bodies in the pile, or nodes along the net's side.
    int size = 1;
    SceneKind kind = SceneKind::Stack;
    /// Nets: the threads' stiffness as omega_e h, omega_e = sqrt(k / node mass).
    Real omegaH = 0.5;
    /// Nets: the threads' stiffness k (N/m) when > 0, the same at every h (the sweep); then
    /// omegaH is ignored.
    Real stiffness = 0;
    /// Nets: an engine with its own springs makes them explicit (NetSpec::explicitThreads).
    bool explicitThreads = false;

    bool planar() const { return kind == SceneKind::Stack || kind == SceneKind::Pyramid; }
    /// Piles land once, untimed, then are timed in windows (tumble-bench's main).
    bool pile() const {
        return kind == SceneKind::Pile || kind == SceneKind::TerrainPile ||
               kind == SceneKind::MeshPile;
    }
};

/// Builds a stack or pyramid in `world`; returns the cubes' start positions (the top cube last),
/// or none when the engine refused a cube.
std::vector<Vec3> build(PeerWorld& world, const Scene& scene);

/// The settings a scene runs with: `base`, with zero gravity for the nets (they fly in space).
SceneSettings settingsFor(const Scene& scene, const SceneSettings& base);

/// The figures of one run; a metric that does not apply to the scene is NaN.
struct Metrics {
    double topDrift;     ///< stacks, pyramids: largest horizontal offset of the top cube (m)
    double deepest;      ///< deepest penetration over the run (m); NaN for nets
    double energyError;  ///< nets: largest |E - E0| / E0 over the run (E: kinetic + thread)
    /// Stacks, pyramids: when a cube first moved 0.5 m; piles: when a body first left the
    /// container (terrain piles: fell through or off the terrain) or went non-finite; nets: when a
    /// node went non-finite or the energy grew tenfold (blew up). -1: never (s).
    double collapsedAt = -1;
};

/// One scene in one engine, built, ready to step.
class SceneRun {
public:
    SceneRun(const Peer& peer, const Scene& scene, const SceneSettings& base);
    ~SceneRun();
    SceneRun(const SceneRun&) = delete;
    SceneRun& operator=(const SceneRun&) = delete;

    /// Why the engine cannot run this scene; empty when it can (then the rest may be called).
    const std::string& skipped() const { return skipped_; }
    /// One step: the harness's thread forces (point-mass nets) and the engine's step. Timed.
    void step();
    /// Updates the metrics after a step, at simulated time `time` (s). Not timed.
    void measure(double time);
    const Metrics& metrics() const { return metrics_; }
    /// A body's position (m): the cubes in build order, the net's nodes row-major.
    Vec3 position(int body) const { return world_->position(body); }
    Real timeStep() const { return settings_.timeStep; }
    const PeerWorld& world() const { return *world_; }

private:
    struct Thread {
        int a;
        int b;
    };
    void buildPile();
    void buildTerrainPile();
    void buildNet();
    bool pileInside(const Vec3& p) const;
    double netEnergy() const;

    Scene scene_;
    SceneSettings settings_;
    std::unique_ptr<PeerWorld> world_;
    std::string skipped_;
    std::vector<Vec3> start_;
    Metrics metrics_;
    Real containerHalf_ = 0;   // piles: half the container's inside width (m)
    HeightFieldData terrain_;  // terrain piles: the ground's heights
    // Nets.
    NetSpec net_;
    bool harnessThreads_ = false;  // the engine has no springs: this applies the threads
    std::vector<Thread> threads_;
    std::vector<Vec3> force_;  // per node, reused every step
    double energy0_ = 0;
};

}  // namespace tumble::bench
