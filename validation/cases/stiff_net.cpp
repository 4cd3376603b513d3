// stiff-net: a 40 x 40 net whose threads are far too stiff for its step (omega_e h = 20 at h =
// 1/60, ten times the explicit limit) falls onto a cylinder on the ground.
//
// With implicit threads it must stay bounded and never gain energy: the total mechanical energy
// -- kinetic, gravitational (datum at the ground, the lowest any node can reach, so the energy
// the fall can release is the initial value) and elastic -- is never above its initial value by
// more than 1 %. With explicit threads the same scene is unstable; the step must report it with
// the element and the time, never leave a silent NaN in the world.
//
// Net: mesh 0.05 m (1.95 m across), nodes 0.01 kg of radius 0.01 m, colliding; threads k = 14400
// N/m (omega_e = sqrt(k / m) = 1200 rad/s), tension-only, undamped. Target: a cylinder of radius
// 0.4 m and height 0.8 m standing on the ground; the net starts flat 0.2 m above its top.

#include <algorithm>
#include <cmath>
#include <string>

#include "../case.h"
#include "tumble/lumped.h"
#include "tumble/tumble.h"

namespace tumble::validation {
namespace {

constexpr double kH = 1.0 / 60;
constexpr double kNodeMass = 0.01;
constexpr double kOmegaEH = 20;
constexpr double kMesh = 0.05;
constexpr double kTargetTop = 0.8;

struct Scene {
    World world;
    Lumped net;
};

void build(Scene& scene, SpringFormulation formulation, int size) {
    // Shape definitions built whole: assigning the variant tripped GCC 12's
    // -Wmaybe-uninitialized at -O1 (a false positive).
    const ShapeDef ground{.geometry = HalfSpace{Vec3::UnitZ(), 0}};
    BodyDef fixed;
    fixed.type = BodyType::Static;
    scene.world.createShape(scene.world.createBody(fixed), ground);
    fixed.position = Vec3(0, 0, 0.5 * kTargetTop);
    const ShapeDef target{.geometry = Cylinder{0.4, 0.5 * kTargetTop}};
    scene.world.createShape(scene.world.createBody(fixed), target);

    NetDef net;
    net.rows = size;
    net.columns = size;
    net.meshSize = kMesh;
    net.center = Vec3(0, 0, kTargetTop + 0.2);
    net.node.mass = kNodeMass;
    net.node.radius = 0.01;
    net.node.collide = true;
    const double omegaE = kOmegaEH / kH;
    net.thread.axialRigidity = omegaE * omegaE * kNodeMass * kMesh;  // k L0
    net.thread.formulation = formulation;
    scene.net = createNet(scene.world, net);
}

double totalEnergy(const Scene& scene) {
    double potential = 0;
    for (const BodyId node : scene.net.nodes)
        potential += kNodeMass * 9.81 * scene.world.position(node).z();
    return scene.world.kineticEnergy() + potential + scene.world.springPotentialEnergy();
}

WorldDef settings() {
    WorldDef def;
    def.timeStep = kH;
    def.enableSleep = false;
    return def;
}

CaseResult run(const CaseOptions& options) {
    CaseResult result;
    const int size = 40;
    const double duration = options.fast ? 1.5 : 4;
    const int steps = static_cast<int>(duration / kH);

    // Implicit: bounded, no energy gained.
    Scene implicit{World(settings()), {}};
    build(implicit, SpringFormulation::Implicit, size);
    const double e0 = totalEnergy(implicit);
    double worstGain = 0;
    double lowest = INFINITY;
    bool finite = true;
    for (int i = 0; i < steps && finite; ++i) {
        finite = implicit.world.step().ok();
        worstGain = std::max(worstGain, totalEnergy(implicit) / e0 - 1);
    }
    double longest = 0;
    for (const SpringId thread : implicit.net.threads)
        longest = std::max(longest, implicit.world.springState(thread).length / kMesh);
    for (const BodyId node : implicit.net.nodes)
        lowest = std::min(lowest, implicit.world.position(node).z());
    const BodyId middle = implicit.net.nodes[(size / 2) * size + size / 2];
    result.metric("nodes", size * size);
    result.metric("omega_e_h", kOmegaEH);
    result.metric("implicit_initial_energy_J", e0);
    result.metric("implicit_final_energy_J", totalEnergy(implicit));
    result.metric("implicit_max_energy_gain", worstGain);
    result.metric("implicit_longest_thread_over_mesh", longest);
    result.metric("implicit_middle_node_height_m", implicit.world.position(middle).z());
    result.metric("implicit_lowest_node_height_m", lowest);
    result.tolerance("energy_gain_max", 0.01);
    result.check(finite, "implicit net went non-finite");
    result.check(worstGain <= 0.01, "implicit net gained more than 1 % energy");
    // It wrapped the target: the middle rests on top, the edges hang below it.
    result.check(std::abs(implicit.world.position(middle).z() - (kTargetTop + 0.01)) < 0.02,
                 "the net's middle does not rest on the target's top");
    result.check(lowest < kTargetTop - 0.3, "the net's edges do not hang down the target");
    result.check(longest < 1.1, "a thread is stretched by more than 10 %");

    // Explicit: unstable, and reported.
    Scene explicitNet{World(settings()), {}};
    build(explicitNet, SpringFormulation::Explicit, size);
    StepStatus failure;
    int failedStep = -1;
    for (int i = 0; i < steps; ++i) {
        failure = explicitNet.world.step();
        if (!failure.ok()) {
            failedStep = i + 1;
            break;
        }
    }
    result.check(failedStep > 0, "explicit net at omega_e h = 20 was not reported unstable");
    if (failedStep > 0) {
        const bool named = !failure.spring.isNull() && explicitNet.world.isValid(failure.spring);
        result.metric("explicit_failure_time_s", failedStep * kH);
        result.check(named, "the failure does not name the spring that drove it");
        // The world keeps its last finite state.
        bool keptFinite = true;
        for (const BodyId node : explicitNet.net.nodes)
            keptFinite = keptFinite && explicitNet.world.position(node).allFinite();
        result.check(keptFinite, "the failed world holds a non-finite state");
    }
    return result;
}

}  // namespace

ValidationCase stiffNetCase() {
    return {"stiff-net",
            "40 x 40 net, omega_e h = 20 at h = 1/60, falls on a cylinder: implicit threads "
            "bounded with energy never 1 % above the start; explicit ones reported unstable",
            run};
}

}  // namespace tumble::validation
