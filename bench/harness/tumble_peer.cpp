// Tumble behind the harness interface, with the settings of the validation cases.

#include <algorithm>

#include "peer.h"
#include "tumble/tumble.h"

namespace tumble::bench {
namespace {

class TumbleWorld final : public PeerWorld {
public:
    explicit TumbleWorld(const SceneSettings& s) : world_(worldDef(s)), friction_(s.friction) {
        density_ = s.boxMass;  // a unit cube: density = mass
    }
    void addGround() override {
        const BodyId ground = world_.createBody(BodyDef{.type = BodyType::Static});
        world_.createShape(ground, ShapeDef{.geometry = HalfSpace{}, .material = material()});
    }
    int addCube(const Vec3& position) override {
        const BodyId cube = world_.createBody(BodyDef{.position = position});
        world_.createShape(cube,
                           ShapeDef{.geometry = Box{Vec3::Constant(0.5)}, .material = material()});
        cubes_.push_back(cube);
        return static_cast<int>(cubes_.size()) - 1;
    }
    void step() override { world_.step(); }
    Vec3 position(int cube) const override { return world_.position(cubes_[cube]); }
    Real deepestPenetration() const override { return world_.solverStats().deepestPenetration; }

private:
    static WorldDef worldDef(const SceneSettings& s) {
        WorldDef def{.gravity = Vec3(0, 0, -9.81), .timeStep = s.timeStep};
        def.solver.iterations = s.iterations;
        // As many split-impulse sweeps as velocity sweeps, as Bullet runs its split-impulse pass.
        def.solver.relaxIterations = s.iterations;
        def.enableSleep = false;  // every engine simulates every body
        return def;
    }
    // Tumble mixes friction as sqrt(muA muB): mu on both gives mu.
    Material material() const {
        return Material{.friction = friction_, .restitution = 0, .density = density_};
    }
    World world_;
    Real friction_;
    Real density_ = 1;
    std::vector<BodyId> cubes_;
};

}  // namespace

std::unique_ptr<PeerWorld> createTumble(const SceneSettings& settings) {
    return std::make_unique<TumbleWorld>(settings);
}

}  // namespace tumble::bench
