#pragma once
/// The sweep's runs (sweep.h): one scene in one engine at one (h, iterations), timed, with what
/// the error is measured from; and the converged reference of the lumped scenes (chain, net),
/// which the harness integrates itself so that every engine is measured against the same one.

#include <string>
#include <vector>

#include "peer.h"
#include "scene.h"

namespace tumble::bench {

/// Samples of the lumped scenes are taken every this long (s): a whole number of steps of every
/// swept h and of the references'.
inline constexpr double kSampleInterval = 0.1;

/// What became of a run. Only Ok runs have an error that means anything; the others are reported
/// as such and kept off the fronts and the plot.
enum class RunStatus {
    Ok,
    Collapsed,  ///< stacks, pyramids: a cube moved more than 0.5 m (the column fell)
    BlewUp,     ///< non-finite, or the net's energy grew tenfold, or a bead 1 m off (chain)
};

const char* statusName(RunStatus status);

/// One timed run of the sweep.
struct Point {
    std::string scene;
    std::string engine;
    double h = 0;
    int iterations = 0;
    /// Busy (step) time over the simulated time reached (s/s): a run that blew up stops early.
    double wallPerSimulatedSecond = 0;
    double error = 0;    ///< (m), see sweep.cpp's file comment
    double deepest = 0;  ///< deepest penetration over the run (m), cubes only
    RunStatus status = RunStatus::Ok;
    bool front = false;
};

/// A stack or pyramid: the largest horizontal drift of any cube at any step is the error.
Point runCubes(const Peer& peer, const Scene& scene, double h, int iterations, double duration);

/// Point masses joined by linear springs, integrated from explicit forces: the continuous model
/// of the chain and the net that the peers run (the harness applies the forces) and the
/// reference integrates with a small step.
struct MassSpringModel {
    struct Thread {
        int a = 0;
        int b = -1;  ///< -1: the world point `anchor`
        Real restLength = 1;
        Real stiffness = 0;  ///< (N/m)
    };
    Real mass = 1;  ///< of each node (kg)
    std::vector<Vec3> position;
    std::vector<Vec3> velocity;
    std::vector<Thread> threads;
    Vec3 anchor = Vec3::Zero();
    bool tensionOnly = false;
    Vec3 gravity = Vec3::Zero();  ///< the engines apply it themselves; the reference adds it

    /// The threads' forces on the nodes at positions `x` into `force` (resized, N).
    void threadForces(const std::vector<Vec3>& x, std::vector<Vec3>& force) const;
};

/// validation/cases/hanging_chain.cpp's chain: N = 30 beads of 1/30 kg on 1 m, EA = 1e6 N, hung
/// from the origin, started 1 mm off in each of its first three modes.
MassSpringModel chainModel();
/// scene.cpp's net for `spec`, laid out and thrown open as lumped.h's createNet does.
MassSpringModel netModel(const NetSpec& spec);

/// A run's node positions every kSampleInterval (node-major within a sample) and its cost.
struct Trajectory {
    std::vector<Vec3> samples;
    double busy = 0;       ///< (s) in the engine's steps (and the harness's thread forces)
    double simulated = 0;  ///< (s) reached
    bool blewUp = false;
};

/// The model by velocity Verlet with step h (s), untimed.
Trajectory integrateReference(const MassSpringModel& model, double h, double duration);

/// The chain: in Tumble with its implicit springs (as the validation case; explicit ones when
/// `explicitSprings`), in a peer as point masses pulled by the harness's explicit forces.
Trajectory runChain(const Peer& peer, double h, int iterations, double duration,
                    bool explicitSprings = false);

/// scene.cpp's net (Tumble: implicit tension-only threads; peers: explicit, the harness's).
Trajectory runNet(const Peer& peer, const Scene& scene, double h, int iterations, double duration);

/// The largest difference between two trajectories' nodes over the common samples (m): of the
/// x coordinate only when `sidewaysOnly`, else of the whole position. Infinity when `run` is
/// shorter than `reference` or non-finite.
double deviation(const Trajectory& run, const Trajectory& reference, bool sidewaysOnly);

}  // namespace tumble::bench
