// The harness's scenes (scene.h). Piles: boxes, spheres and capsules in turn, 700 kg/m^3,
// dropped in layers of a grid into a walled container about five layers deep, or onto
// terrain.h's bowl (terrain piles). Nets: lumped.h's
// net thrown open in free space, so the exact answer conserves the kinetic plus thread energy.

#include "scene.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace tumble::bench {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr Real kPileDensity = 700;  // (kg/m^3), as tumble-soak
constexpr Real kPilePitch = 0.45;   // grid spacing (m): a turned box (0.43 m diagonal) fits
constexpr int kPileLayers = 5;      // about this many layers deep
constexpr Real kWall = 0.1;         // half the walls' thickness (m)
constexpr Real kWallHeight = 3;     // (m), above the highest layer

BodySpec pileBody(int k, const Vec3& position) {
    BodySpec b;
    b.kind = static_cast<ShapeKind>(k % 3);
    b.halfExtents = Vec3(0.15, 0.12, 0.1);
    b.radius = b.kind == ShapeKind::Sphere ? 0.15 : 0.1;
    b.halfLength = 0.1;
    b.mass = kPileDensity * volume(b);
    b.position = position;
    // Deterministic, varied orientations, as tumble-soak's rain.
    b.orientation = Quat(Eigen::AngleAxis<Real>(0.6 * k, Vec3(1, 2, 3).normalized()));
    return b;
}

bool finite(const Vec3& v) {
    return v.allFinite();
}

}  // namespace

std::vector<Vec3> build(PeerWorld& world, const Scene& scene) {
    world.addGround();
    std::vector<Vec3> start;
    if (scene.kind == SceneKind::Stack) {
        for (int i = 0; i < scene.size; ++i)
            start.push_back(Vec3(0, 0, 0.5 + i));
    } else {
        constexpr double kPitch = 1.05;  // 5 cm between neighbours, as in the `pyramid` case
        for (int row = 0; row < scene.size; ++row) {
            const int n = scene.size - row;
            for (int i = 0; i < n; ++i)
                start.push_back(Vec3((i - 0.5 * (n - 1)) * kPitch, 0, 0.5 + row));
        }
    }
    for (const Vec3& p : start) {
        if (world.addCube(p) < 0)
            return {};  // the engine refused it (see PeerWorld::refusal)
    }
    return start;
}

SceneSettings settingsFor(const Scene& scene, const SceneSettings& base) {
    SceneSettings s = base;
    if (scene.kind == SceneKind::Net)
        s.gravity = Vec3::Zero();
    return s;
}

SceneRun::SceneRun(const Peer& peer, const Scene& scene, const SceneSettings& base)
    : scene_(scene), settings_(settingsFor(scene, base)), world_(peer.create(settings_)) {
    metrics_ = Metrics{.topDrift = kNaN, .deepest = 0, .energyError = kNaN};
    if (world_->planar() && !scene.planar()) {
        skipped_ = "planar engine, 3-D scene";
        return;
    }
    switch (scene.kind) {
        case SceneKind::Stack:
        case SceneKind::Pyramid:
            start_ = build(*world_, scene);
            if (start_.empty()) {
                skipped_ = world_->refusal();
                return;
            }
            metrics_.topDrift = 0;
            break;
        case SceneKind::Pile:
            buildPile();
            break;
        case SceneKind::TerrainPile:
        case SceneKind::MeshPile:
            buildTerrainPile();
            break;
        case SceneKind::Net:
            buildNet();
            break;
    }
}

SceneRun::~SceneRun() = default;

void SceneRun::buildPile() {
    const int perSide =
        static_cast<int>(std::ceil(std::sqrt(static_cast<double>(scene_.size) / kPileLayers)));
    containerHalf_ = 0.5 * perSide * kPilePitch;
    world_->addGround();
    const Real h = containerHalf_ + kWall;
    const Real top = kPileLayers * kPilePitch + kWallHeight;
    world_->addStaticBox(Vec3(h, 0, 0.5 * top), Vec3(kWall, h + kWall, 0.5 * top));
    world_->addStaticBox(Vec3(-h, 0, 0.5 * top), Vec3(kWall, h + kWall, 0.5 * top));
    world_->addStaticBox(Vec3(0, h, 0.5 * top), Vec3(h + kWall, kWall, 0.5 * top));
    world_->addStaticBox(Vec3(0, -h, 0.5 * top), Vec3(h + kWall, kWall, 0.5 * top));
    const int perLayer = perSide * perSide;
    for (int k = 0; k < scene_.size; ++k) {
        const int cell = k % perLayer;
        const Vec3 p(-containerHalf_ + kPilePitch * (0.5 + cell % perSide),
                     -containerHalf_ + kPilePitch * (0.5 + cell / perSide),
                     kPilePitch * (0.6 + k / perLayer));
        start_.push_back(p);
        if (world_->addBody(pileBody(k, p)) < 0) {
            skipped_ = world_->refusal();
            return;
        }
    }
}

// The pile's bodies in layers over the middle of the bowl, each 0.4 m above the terrain under
// it plus a pitch per layer; no walls: the bowl holds them.
void SceneRun::buildTerrainPile() {
    terrain_ = rollingTerrain();
    const bool made = scene_.kind == SceneKind::TerrainPile
                          ? world_->addHeightField(terrain_)
                          : world_->addTriangleMesh(terrainMesh(terrain_));
    if (!made) {
        skipped_ = world_->terrainRefusal();
        return;
    }
    constexpr int kPerSide = 12;
    const Real middle = 0.5 * (terrain_.columns - 1) * terrain_.spacingX;
    for (int k = 0; k < scene_.size; ++k) {
        const int cell = k % (kPerSide * kPerSide);
        const Real x = middle + kPilePitch * (cell % kPerSide - 0.5 * (kPerSide - 1));
        const Real y = middle + kPilePitch * (cell / kPerSide - 0.5 * (kPerSide - 1));
        const Vec3 p(
            x, y, terrainHeight(terrain_, x, y) + 0.4 + kPilePitch * (k / (kPerSide * kPerSide)));
        start_.push_back(p);
        if (world_->addBody(pileBody(k, p)) < 0) {
            skipped_ = world_->refusal();
            return;
        }
    }
}

// Piles: in the container (or over the terrain and above it), by more than the largest body.
bool SceneRun::pileInside(const Vec3& p) const {
    if (!finite(p))
        return false;
    if (scene_.kind == SceneKind::Pile)
        return p.head<2>().cwiseAbs().maxCoeff() < containerHalf_ && p.z() > -0.2;
    const Real side = (terrain_.columns - 1) * terrain_.spacingX;
    return p.x() > 0 && p.y() > 0 && p.x() < side && p.y() < side &&
           p.z() > terrainHeight(terrain_, p.x(), p.y()) - 0.2;
}

void SceneRun::buildNet() {
    const int n = scene_.size;
    net_.n = n;
    net_.explicitThreads = scene_.explicitThreads;
    const Real omega = scene_.omegaH / settings_.timeStep;
    net_.stiffness = scene_.stiffness > 0 ? scene_.stiffness : omega * omega * net_.nodeMass;
    for (int i = 0; i < n; ++i) {
        for (int j = 0; j < n; ++j) {
            if (j + 1 < n)
                threads_.push_back({i * n + j, i * n + j + 1});
            if (i + 1 < n)
                threads_.push_back({i * n + j, (i + 1) * n + j});
        }
    }
    if (world_->addNet(net_) < 0) {
        // As lumped.h's createNet lays the nodes out and throws them open.
        const Real cornerDistance = 0.5 * net_.mesh * std::hypot(n - 1, n - 1);
        for (int i = 0; i < n; ++i) {
            for (int j = 0; j < n; ++j) {
                const Vec3 offset = net_.mesh * Vec3(i - 0.5 * (n - 1), j - 0.5 * (n - 1), 0);
                const Vec3 velocity = (net_.spreadSpeed / cornerDistance) * offset;
                if (world_->addPointMass(offset, velocity, net_.nodeMass, net_.nodeRadius) < 0) {
                    skipped_ = "no point masses";
                    return;
                }
            }
        }
        harnessThreads_ = true;
        force_.assign(static_cast<std::size_t>(n) * n, Vec3::Zero());
    }
    energy0_ = netEnergy();
    metrics_.energyError = 0;
    metrics_.deepest = kNaN;
}

// The tension-only thread force k (L - L0) along the thread, explicit: the engines then
// integrate it semi-implicitly (v += h F / m, x += h v), stable for omega_e h below 2.
void SceneRun::step() {
    if (harnessThreads_) {
        std::fill(force_.begin(), force_.end(), Vec3::Zero());
        for (const Thread& t : threads_) {
            const Vec3 d = world_->position(t.b) - world_->position(t.a);
            const Real length = d.norm();
            if (length <= net_.mesh)
                continue;
            const Vec3 f = (net_.stiffness * (length - net_.mesh) / length) * d;
            force_[static_cast<std::size_t>(t.a)] += f;
            force_[static_cast<std::size_t>(t.b)] -= f;
        }
        for (std::size_t i = 0; i < force_.size(); ++i)
            world_->applyForce(static_cast<int>(i), force_[i]);
    }
    world_->step();
}

double SceneRun::netEnergy() const {
    double energy = 0;
    for (int i = 0; i < net_.n * net_.n; ++i)
        energy += 0.5 * net_.nodeMass * world_->velocity(i).squaredNorm();
    for (const Thread& t : threads_) {
        const Real stretch = (world_->position(t.b) - world_->position(t.a)).norm() - net_.mesh;
        if (stretch > 0)
            energy += 0.5 * net_.stiffness * stretch * stretch;
    }
    return energy;
}

void SceneRun::measure(double time) {
    const bool collapsed = metrics_.collapsedAt >= 0;
    switch (scene_.kind) {
        case SceneKind::Stack:
        case SceneKind::Pyramid: {
            metrics_.deepest = std::max(metrics_.deepest, world_->deepestPenetration());
            const int top = static_cast<int>(start_.size()) - 1;
            const Vec3 offset = world_->position(top) - start_[static_cast<std::size_t>(top)];
            metrics_.topDrift = std::max(metrics_.topDrift, offset.head<2>().norm());
            for (int i = 0; i <= top && !collapsed; ++i) {
                if (!((world_->position(i) - start_[static_cast<std::size_t>(i)]).norm() <= 0.5)) {
                    metrics_.collapsedAt = time;
                    break;
                }
            }
            break;
        }
        case SceneKind::Pile:
        case SceneKind::TerrainPile:
        case SceneKind::MeshPile: {
            metrics_.deepest = std::max(metrics_.deepest, world_->deepestPenetration());
            for (std::size_t i = 0; i < start_.size() && !collapsed; ++i) {
                if (!pileInside(world_->position(static_cast<int>(i)))) {
                    metrics_.collapsedAt = time;
                    break;
                }
            }
            break;
        }
        case SceneKind::Net: {
            const double energy = netEnergy();
            const double error = std::abs(energy - energy0_) / energy0_;
            metrics_.energyError = std::isfinite(error) ? std::max(metrics_.energyError, error)
                                                        : std::numeric_limits<double>::infinity();
            if (!collapsed && !(energy < 10 * energy0_))
                metrics_.collapsedAt = time;
            break;
        }
    }
}

}  // namespace tumble::bench
