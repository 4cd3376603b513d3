// Tumble behind the harness interface, with the settings of the validation cases. Nets use
// Tumble's own generator (lumped.h) with implicit, tension-only threads.

#include <algorithm>

#include "peer.h"
#include "tumble/lumped.h"
#include "tumble/tumble.h"

namespace tumble::bench {
namespace {

class TumbleWorld final : public PeerWorld {
public:
    explicit TumbleWorld(const SceneSettings& s, bool soft = false)
        : world_(worldDef(s, soft)),
          friction_(s.friction),
          restitution_(s.restitution),
          cubeMass_(s.boxMass) {}
    void addGround() override {
        const BodyId ground = world_.createBody(BodyDef{.type = BodyType::Static});
        world_.createShape(ground, ShapeDef{.geometry = HalfSpace{}, .material = material(1)});
    }
    int addCube(const Vec3& position) override {
        // A unit cube: density = mass.
        return add(BodyDef{.position = position}, Box{Vec3::Constant(0.5)}, cubeMass_);
    }
    void addStaticBox(const Vec3& center, const Vec3& halfExtents) override {
        const BodyId wall =
            world_.createBody(BodyDef{.type = BodyType::Static, .position = center});
        world_.createShape(wall, ShapeDef{.geometry = Box{halfExtents}, .material = material(1)});
    }
    int addBody(const BodySpec& b) override {
        Shape shape = Box{b.halfExtents};
        if (b.kind == ShapeKind::Sphere)
            shape = Sphere{b.radius};
        else if (b.kind == ShapeKind::Capsule)
            shape = Capsule{b.radius, b.halfLength};
        return add(BodyDef{.position = b.position, .orientation = b.orientation}, shape,
                   b.mass / volume(b));
    }
    int addNet(const NetSpec& spec) override {
        NetDef net;
        net.rows = spec.n;
        net.columns = spec.n;
        net.meshSize = spec.mesh;
        net.node.mass = spec.nodeMass;
        net.node.radius = spec.nodeRadius;
        net.thread.axialRigidity = spec.stiffness * spec.mesh;  // k = E A / L0
        net.thread.tensionOnly = true;
        net.thread.formulation =
            spec.explicitThreads ? SpringFormulation::Explicit : SpringFormulation::Implicit;
        net.spreadSpeed = spec.spreadSpeed;
        const Lumped lumped = createNet(world_, net);
        const int first = static_cast<int>(bodies_.size());
        bodies_.insert(bodies_.end(), lumped.nodes.begin(), lumped.nodes.end());
        return first;
    }
    // Both at the origin: Tumble's height field already puts sample (i, j) at (i dx, j dy, h).
    bool addHeightField(const HeightFieldData& field) override {
        addStatic(HeightField::fromData(field));
        return true;
    }
    bool addTriangleMesh(const TriangleMeshData& mesh) override {
        addStatic(TriangleMesh::fromData(mesh));
        return true;
    }
    void step() override { world_.step(); }
    const World& world() const { return world_; }
    Vec3 position(int body) const override { return world_.position(bodies_[body]); }
    Vec3 velocity(int body) const override { return world_.linearVelocity(bodies_[body]); }
    Real deepestPenetration() const override { return world_.solverStats().deepestPenetration; }

private:
    static WorldDef worldDef(const SceneSettings& s, bool soft) {
        WorldDef def{.gravity = s.gravity, .timeStep = s.timeStep};
        if (soft) {
            def.solver.softSubsteps = s.tumbleSoftSubsteps;
            def.solver.contactHertz = s.tumbleSoftHertz;
        }
        def.solver.iterations = s.tumbleIterations >= 0 ? s.tumbleIterations : s.iterations;
        def.solver.relaxIterations =
            s.tumbleRelaxIterations >= 0 ? s.tumbleRelaxIterations : s.iterations;
        if (s.tumbleIterations < 0) {  // matched to the peers': the links' too
            def.solver.linkIterations = s.iterations;
            def.solver.linkRelaxIterations = s.iterations;
        }
        def.solver.tolerance = s.tumbleTolerance;
        def.enableSleep = false;  // every engine simulates every body
        def.solver.colouredContacts = s.colouredContacts;
        def.solver.frictionAnchors = s.frictionAnchors;
        if (s.correction == SceneSettings::Correction::Baumgarte)
            def.solver.stabilisation = Stabilisation::Baumgarte;
        else if (s.correction == SceneSettings::Correction::SplitImpulse)
            def.solver.stabilisation = Stabilisation::SplitImpulse;
        return def;
    }
    void addStatic(const Shape& shape) {
        const BodyId body = world_.createBody(BodyDef{.type = BodyType::Static});
        world_.createShape(body, ShapeDef{.geometry = shape, .material = material(1)});
    }
    int add(const BodyDef& def, const Shape& shape, Real density) {
        const BodyId body = world_.createBody(def);
        world_.createShape(body, ShapeDef{.geometry = shape, .material = material(density)});
        bodies_.push_back(body);
        return static_cast<int>(bodies_.size()) - 1;
    }
    // Tumble mixes friction as sqrt(muA muB): mu on both gives mu; restitution e on both, e.
    Material material(Real density) const {
        return Material{.friction = friction_, .restitution = restitution_, .density = density};
    }
    World world_;
    Real friction_;
    Real restitution_;
    Real cubeMass_;
    std::vector<BodyId> bodies_;
};

}  // namespace

std::unique_ptr<PeerWorld> createTumble(const SceneSettings& settings) {
    return std::make_unique<TumbleWorld>(settings);
}

std::unique_ptr<PeerWorld> createTumbleSoft(const SceneSettings& settings) {
    return std::make_unique<TumbleWorld>(settings, true);
}

const World* tumbleWorld(const PeerWorld& world) {
    const auto* tumble = dynamic_cast<const TumbleWorld*>(&world);
    return tumble != nullptr ? &tumble->world() : nullptr;
}

}  // namespace tumble::bench
