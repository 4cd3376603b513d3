// The scene kit (testkit/scenes.h). The builders keep the order of their bodies and shapes and
// the arithmetic of their positions as the copies they replaced had them: the validation
// table, the golden trajectories and the soak's figures depend on it bit for bit.

#include "testkit/scenes.h"

#include <algorithm>
#include <cmath>

namespace tumble::testkit {

namespace {
int softSubstepsOverride = 0;                            // forceSoftStep
Real softHertzOverride = SolverSettings{}.contactHertz;  // forceSoftStep
}  // namespace

void forceSoftStep(int substeps, Real contactHertz) {
    softSubstepsOverride = substeps;
    softHertzOverride = contactHertz;
}

void applyForcedSoftStep(SolverSettings& settings) {
    if (softSubstepsOverride == 0)
        return;
    settings.softSubsteps = softSubstepsOverride;
    settings.contactHertz = softHertzOverride;
}

void applyStep(SolverSettings& settings, const StepChoice& step) {
    settings.softSubsteps = step.softSubsteps;
    if (step.softSubsteps > 0)
        settings.contactHertz = step.contactHertz;
}

int integratorStepsPerStep(const StepChoice& step) {
    return std::max(1, step.softSubsteps);
}

std::string stepName(const StepChoice& step) {
    if (step.softSubsteps == 0)
        return "Default";
    return "Soft" + std::to_string(step.softSubsteps) + "x" +
           std::to_string(static_cast<int>(step.contactHertz));
}

WorldDef quietWorld(Real timeStep, const Vec3& gravity) {
    WorldDef def;
    applyForcedSoftStep(def.solver);
    def.gravity = gravity;
    def.timeStep = timeStep;
    def.enableSleep = false;
    return def;
}

WorldDef weightlessWorld(Real timeStep) {
    return quietWorld(timeStep, Vec3::Zero());
}

WorldDef stackWorld(Real timeStep, int iterations) {
    WorldDef def = quietWorld(timeStep);
    def.solver.iterations = iterations;
    return def;
}

Material material(Real friction, Real restitution, Real density) {
    return Material{.friction = friction, .restitution = restitution, .density = density};
}

BodyId addGround(World& world, const Material& surface, const Quat& tilt) {
    const BodyId ground = world.createBody(BodyDef{.type = BodyType::Static, .orientation = tilt});
    world.createShape(ground, ShapeDef{.geometry = HalfSpace{}, .material = surface});
    return ground;
}

BodyId addBox(World& world, const BodyDef& body, const Vec3& halfExtents, const Material& surface) {
    const BodyId box = world.createBody(body);
    world.createShape(box, ShapeDef{.geometry = Box{halfExtents}, .material = surface});
    return box;
}

BodyId addBox(World& world, const Vec3& position, const Vec3& halfExtents,
              const Material& surface) {
    return addBox(world, BodyDef{.position = position}, halfExtents, surface);
}

std::vector<BodyId> buildStack(World& world, int count, const Material& surface) {
    std::vector<BodyId> cubes;
    for (int i = 0; i < count; ++i)
        cubes.push_back(addBox(world, Vec3(0, 0, 0.5 + i), Vec3::Constant(0.5), surface));
    return cubes;
}

std::vector<BodyId> buildPyramid(World& world, int base, Real gap, const Material& surface,
                                 std::vector<int>& levels) {
    std::vector<BodyId> cubes;
    const Real pitch = 1 + gap;
    for (int row = 0; row < base; ++row) {
        const int n = base - row;
        for (int i = 0; i < n; ++i) {
            const Real x = (i - 0.5 * (n - 1)) * pitch;
            cubes.push_back(addBox(world, Vec3(x, 0, 0.5 + row), Vec3::Constant(0.5), surface));
            levels.push_back(row);
        }
    }
    return cubes;
}

int Rain::perSide() const {
    return std::max(1, static_cast<int>((2 * half - pitch) / pitch));
}

int Rain::perWave() const {
    return perSide() * perSide();
}

BodyId Rain::addContainer(World& world) const {
    const BodyId container = world.createBody(BodyDef{.type = BodyType::Static});
    world.createShape(container, ShapeDef{.geometry = HalfSpace{}});
    for (int side = 0; side < 4; ++side) {
        const Real sign = side % 2 == 0 ? 1 : -1;
        const bool alongX = side < 2;
        // Built whole rather than assigned into a default ShapeDef: GCC 12 at -O1 (the ASan
        // build) warns that the variant's old alternative may be used uninitialised.
        const Transform pose{.position = alongX ? Vec3(sign * (half + 0.1), 0, 3)
                                                : Vec3(0, sign * (half + 0.1), 3)};
        world.createShape(
            container, ShapeDef{.geometry = Box{alongX ? Vec3(0.1, half, 3) : Vec3(half, 0.1, 3)},
                                .localPose = pose});
    }
    return container;
}

namespace {

Shape rainShape(int index) {
    switch (index % 4) {
        case 0:
            return Sphere{0.15};
        case 1:
            return Box{Vec3(0.15, 0.12, 0.1)};
        case 2:
            return Capsule{0.1, 0.1};
        default:
            return Cylinder{0.14, 0.1};
    }
}

}  // namespace

BodyId Rain::addBody(World& world, int index) const {
    const int slot = index % perWave();
    const int across = perSide();
    BodyDef def;
    def.position = Vec3(-half + pitch + pitch * (slot % across),
                        -half + pitch + pitch * (slot / across), height);
    def.orientation = Quat(Eigen::AngleAxis<Real>(0.6 * index, Vec3(1, 2, 3).normalized()));
    def.linearVelocity = Vec3(0, 0, -speed);
    const BodyId body = world.createBody(def);
    world.createShape(body, ShapeDef{.geometry = rainShape(index), .material = material});
    return body;
}

Material soakMaterial() {
    return Material{
        .friction = 0.5, .density = 700, .spinningFriction = 0.002, .rollingFriction = 0.002};
}

PileUnderNet::PileUnderNet(World& world, int side, Real mesh) : netSide(side), netMesh(mesh) {
    rain.addContainer(world);
}

void PileUnderNet::feed(World& world, int step) {
    constexpr int kBodies = 60;
    if (step % 30 == 0)
        for (int k = 0; k < rain.perWave() && bodies.size() < kBodies; ++k)
            bodies.push_back(rain.addBody(world, static_cast<int>(bodies.size())));
    if (step == kNetStep) {
        net = createNet(world, captureNet(netSide, netMesh, Vec3(0, 0, 3)));
        for (const BodyId node : net.nodes)
            world.setDrag(node, Drag{.linear = world.massProperties(node).mass});
    }
}

NetDef captureNet(int nodesPerSide, Real meshSize, const Vec3& center) {
    NetDef net;
    net.rows = nodesPerSide;
    net.columns = nodesPerSide;
    net.meshSize = meshSize;
    net.center = center;
    net.node.mass = 0.02;
    net.node.radius = 0.03;
    net.node.collide = true;
    net.cornerMass = 0.5;
    net.thread.axialRigidity = 2000;
    net.thread.damping = 0.5;
    return net;
}

bool simulate(World& world, int steps) {
    for (int i = 0; i < steps; ++i) {
        if (!world.step().ok())
            return false;
    }
    return true;
}

bool simulateFor(World& world, Real seconds) {
    return simulate(world, static_cast<int>(std::lround(seconds / world.settings().timeStep)));
}

}  // namespace tumble::testkit
