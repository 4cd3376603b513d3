#pragma once
/// One engine behind the scene harness: the few calls the stack, pyramid, pile and net scenes
/// need, so the same scene runs in Tumble and in each peer with matched settings (h, iterations,
/// friction, restitution, sizes, masses). Each peer lives in its own file and is compiled only when
/// its library was found. A peer that cannot build a scene says so (see `planar`, `addBody`,
/// `addPointMass`), and the harness reports the scene as skipped for it.

#include <algorithm>
#include <memory>
#include <numbers>
#include <string>
#include <vector>

#include "tumble/collision/mesh_data.h"
#include "tumble/core/math.h"
#include "tumble/core/solver_types.h"

namespace tumble {
class World;
}

namespace tumble::bench {

/// Settings every engine gets: the study's stack settings (DESIGN.md section 6).
struct SceneSettings {
    Real timeStep = 1.0 / 60;  ///< (s)
    int iterations = 10;       ///< velocity iterations
    Real friction = 0.5;       ///< Coulomb mu of every pair, after the engine's combine rule
    Real boxMass = 1;          ///< (kg), unit cubes
    Vec3 gravity = Vec3(0, 0, -9.81);  ///< (m/s^2); the nets fly in free space (zero)
    /// Restitution of every pair, after the engine's combine rule, in [0, 1]: 0 in the scenes;
    /// only the study's bouncing ball (study_peers.h) sets it. Box2D keeps 0.
    Real restitution = 0;
    /// How penetration is corrected, where the engine has the choice (Bullet; Tumble): its own
    /// default, Baumgarte (a bias in the velocity solve, which becomes real velocity) or split
    /// impulse (a separate pseudo-velocity pass) for every penetrating contact. ODE has only
    /// Baumgarte (its ERP) and ignores this.
    enum class Correction { Default, Baumgarte, SplitImpulse } correction = Correction::Default;
    /// Bullet only: do contacts closer than its breaking threshold (2 cm) enter the solve before
    /// they touch, as its default (speculative contacts, whose target velocity Bullet sums with
    /// the restitution's)? false keeps only touching ones (a contact processing threshold of 0).
    bool speculativeContacts = true;
    /// Tumble only: its contact sweeps on coloured wide rows (SolverSettings::colouredContacts)
    /// or the scalar sweep in constraint order.
    bool colouredContacts = SolverSettings{}.colouredContacts;
    /// Tumble only: SolverSettings::frictionAnchors.
    bool frictionAnchors = SolverSettings{}.frictionAnchors;
    /// Tumble only: its biased and relax sweeps (tumble-bench's table passes Tumble's defaults);
    /// a negative count runs `iterations` of each, matched to the peers' as Bullet runs its
    /// split-impulse pass (the sweep's runs).
    int tumbleIterations = -1;
    int tumbleRelaxIterations = -1;
    /// Tumble only: SolverSettings::tolerance, the sweeps' early exit (m/s; 0 runs them all).
    Real tumbleTolerance = SolverSettings{}.tolerance;
    /// The "tumble-soft" engine only (createTumbleSoft): SolverSettings::softSubsteps.
    int tumbleSoftSubsteps = 4;
    Real tumbleSoftHertz = SolverSettings{}.contactHertz;  ///< SolverSettings::contactHertz
};

/// The pile's shapes. No cylinders: Debian's ODE is built without libccd and has no
/// cylinder-cylinder or cylinder-capsule test, so a pile with cylinders would not be the same
/// scene in every engine.
enum class ShapeKind { Box, Sphere, Capsule };

/// A dynamic body of the pile: its shape in its own frame (capsules along local z), its mass and
/// its pose. Each engine computes the inertia of its shape from the mass.
struct BodySpec {
    ShapeKind kind = ShapeKind::Box;
    Vec3 halfExtents = Vec3::Constant(0.5);  ///< boxes (m)
    Real radius = 0.5;                       ///< spheres and capsules (m)
    Real halfLength = 0.5;                   ///< capsules: half the segment (m)
    Real mass = 1;                           ///< (kg)
    Vec3 position = Vec3::Zero();
    Quat orientation = Quat::Identity();
};

/// Volume of the body's shape (m^3), for the engines that take a density.
inline Real volume(const BodySpec& b) {
    constexpr Real pi = std::numbers::pi;
    switch (b.kind) {
        case ShapeKind::Box:
            return 8 * b.halfExtents.prod();
        case ShapeKind::Sphere:
            return 4.0 / 3 * pi * b.radius * b.radius * b.radius;
        case ShapeKind::Capsule:
        default:
            return pi * b.radius * b.radius * (2 * b.halfLength + 4.0 / 3 * b.radius);
    }
}

/// A square net of n x n point masses joined to their 4 neighbours by undamped, tension-only
/// threads of stiffness k and rest length `mesh`, thrown open in free space: node (i, j) at
/// ((i - (n-1)/2) mesh, (j - (n-1)/2) mesh, 0) moving away from the centre at a speed
/// proportional to its distance, `spreadSpeed` at the corners (lumped.h's NetDef).
struct NetSpec {
    int n = 10;
    Real mesh = 0.05;         ///< (m)
    Real nodeMass = 0.01;     ///< (kg)
    Real stiffness = 9;       ///< k per thread (N/m)
    Real spreadSpeed = 0.5;   ///< (m/s)
    Real nodeRadius = 0.005;  ///< inertia only: the nodes do not collide (m)
    /// Engines with their own springs (Tumble): explicit threads, the peers' scheme, instead of
    /// their default (Tumble: implicit).
    bool explicitThreads = false;
};

class PeerWorld {
public:
    virtual ~PeerWorld() = default;
    /// The plane z = 0, static.
    virtual void addGround() = 0;
    /// A unit cube (1 m edges) of SceneSettings::boxMass at `position`, at rest; returns its index
    /// among the dynamic bodies (0, 1, ...).
    virtual int addCube(const Vec3& position) = 0;
    /// A static box (the pile's container walls). Planar engines ignore it.
    virtual void addStaticBox(const Vec3& /*center*/, const Vec3& /*halfExtents*/) {}
    /// A dynamic body; its index, or -1 when the engine cannot (planar engines; see `refusal`).
    virtual int addBody(const BodySpec& /*body*/) { return -1; }
    /// Why addBody returned -1, when the engine can say more than "cannot".
    virtual std::string refusal() const { return "cannot add the body"; }
    /// A static height field in the world frame (terrain.h: sample (i, j) at (i dx, j dy, h));
    /// false when the engine or its adapter has none (see terrainRefusal).
    virtual bool addHeightField(const HeightFieldData& /*field*/) { return false; }
    /// A static triangle mesh in the world frame (counter-clockwise seen from the outside);
    /// false when the engine or its adapter has none (see terrainRefusal).
    virtual bool addTriangleMesh(const TriangleMeshData& /*mesh*/) { return false; }
    /// Why addHeightField or addTriangleMesh returned false.
    virtual std::string terrainRefusal() const { return "no static meshes in this adapter"; }
    /// The whole net with the engine's own springs; the first node's index (row-major), or -1
    /// when the engine has none (the harness then applies the threads' forces to point masses).
    virtual int addNet(const NetSpec& /*net*/) { return -1; }
    /// A point mass that collides with nothing; its index, or -1 when the engine cannot.
    virtual int addPointMass(const Vec3& /*position*/, const Vec3& /*velocity*/, Real /*mass*/,
                             Real /*radius*/) {
        return -1;
    }
    /// A force on a point mass for the next step only (N).
    virtual void applyForce(int /*body*/, const Vec3& /*force*/) {}
    /// Does the engine simulate the x-z plane only (Box2D)? Planar scenes only, then.
    virtual bool planar() const { return false; }
    virtual void step() = 0;
    virtual Vec3 position(int body) const = 0;
    virtual Vec3 velocity(int body) const = 0;
    /// Deepest penetration among the current contacts (m), >= 0.
    virtual Real deepestPenetration() const = 0;
};

struct Peer {
    std::string name;
    std::unique_ptr<PeerWorld> (*create)(const SceneSettings&);
};

std::unique_ptr<PeerWorld> createTumble(const SceneSettings& settings);
/// Tumble with the soft step (settings.tumbleSoftSubsteps), engine "tumble-soft".
std::unique_ptr<PeerWorld> createTumbleSoft(const SceneSettings& settings);
/// The World behind one of createTumble's worlds (microbenchmarks read its profile); null for
/// another engine's.
const World* tumbleWorld(const PeerWorld& world);
#ifdef TUMBLE_HAVE_BULLET
std::unique_ptr<PeerWorld> createBullet(const SceneSettings& settings);
#endif
#ifdef TUMBLE_HAVE_ODE
std::unique_ptr<PeerWorld> createOde(const SceneSettings& settings);
#endif
#ifdef TUMBLE_HAVE_BOX2D
std::unique_ptr<PeerWorld> createBox2d(const SceneSettings& settings);
#endif
#ifdef TUMBLE_HAVE_MUJOCO
std::unique_ptr<PeerWorld> createMujoco(const SceneSettings& settings);
#endif

/// The engines compiled in, Tumble first.
inline std::vector<Peer> peers() {
    std::vector<Peer> list{{"tumble", &createTumble}};
#ifdef TUMBLE_HAVE_BULLET
    list.push_back({"bullet", &createBullet});
#endif
#ifdef TUMBLE_HAVE_ODE
    list.push_back({"ode", &createOde});
#endif
#ifdef TUMBLE_HAVE_BOX2D
    list.push_back({"box2d", &createBox2d});
#endif
#ifdef TUMBLE_HAVE_MUJOCO
    list.push_back({"mujoco", &createMujoco});
#endif
    return list;
}

/// Is engine `name` among `chosen` (the --engine filter)? An empty filter chooses every engine.
inline bool engineChosen(const std::vector<std::string>& chosen, const std::string& name) {
    return chosen.empty() || std::find(chosen.begin(), chosen.end(), name) != chosen.end();
}

/// The peers this build was configured without, for the report.
inline std::vector<std::string> skippedPeers() {
    std::vector<std::string> skipped;
#ifndef TUMBLE_HAVE_BULLET
    skipped.push_back("bullet (libbullet-dev not found at configure time)");
#endif
#ifndef TUMBLE_HAVE_ODE
    skipped.push_back("ode (libode-dev, pkg-config ode, not found at configure time)");
#endif
#ifndef TUMBLE_HAVE_BOX2D
    skipped.push_back("box2d (libbox2d-dev 2.4, CMake package box2d, not found at configure time)");
#endif
#ifndef TUMBLE_HAVE_MUJOCO
    skipped.push_back(
        "mujoco (libmujoco-dev 2.2, CMake package mujoco, not found at configure time)");
#endif
    return skipped;
}

}  // namespace tumble::bench
