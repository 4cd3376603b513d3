// The sweep's runs (sweep_scenes.h). Every run is timed over the engine's steps only (for the
// peers' chains and nets that includes the harness's thread forces, which they need to move);
// measuring and sampling are not timed.

#include "sweep_scenes.h"

#include <algorithm>
#include <chrono>
#include <cmath>

#include "lumped.h"
#include "tumble/tumble.h"

namespace tumble::bench {
namespace {

using Clock = std::chrono::steady_clock;

constexpr int kChainBeads = 30;
constexpr double kChainLength = 1, kChainDensity = 1, kChainRigidity = 1e6;  // m, kg/m, N
constexpr double kGravity = 9.81;                                            // (m/s^2)
constexpr double kNodeRadius = 0.005;  // (m) the peers' point masses: inertia only

int stepsFor(double duration, double h) {
    return static_cast<int>(std::lround(duration / h));
}

double seconds(Clock::time_point since) {
    return std::chrono::duration<double>(Clock::now() - since).count();
}

}  // namespace

const char* statusName(RunStatus status) {
    switch (status) {
        case RunStatus::Ok:
            return "ok";
        case RunStatus::Collapsed:
            return "collapsed";
        case RunStatus::BlewUp:
        default:
            return "blew-up";
    }
}

Point runCubes(const Peer& peer, const Scene& scene, double h, int iterations, double duration) {
    SceneSettings settings;
    settings.timeStep = h;
    settings.iterations = iterations;
    auto world = peer.create(settings);
    const std::vector<Vec3> start = build(*world, scene);
    Point p{.scene = scene.name, .engine = peer.name, .h = h, .iterations = iterations};
    double busy = 0;
    const int steps = stepsFor(duration, h);
    for (int s = 0; s < steps; ++s) {
        const auto t0 = Clock::now();
        world->step();
        busy += seconds(t0);
        p.deepest = std::max(p.deepest, world->deepestPenetration());
        for (std::size_t i = 0; i < start.size(); ++i) {
            const Vec3 offset = world->position(static_cast<int>(i)) - start[i];
            if (!offset.allFinite()) {
                p.status = RunStatus::BlewUp;
            } else if (offset.norm() > 0.5 && p.status == RunStatus::Ok) {
                p.status = RunStatus::Collapsed;
            }
            p.error = std::max(p.error, offset.allFinite() ? offset.head<2>().norm() : INFINITY);
        }
    }
    p.wallPerSimulatedSecond = busy / duration;
    return p;
}

void MassSpringModel::threadForces(const std::vector<Vec3>& x, std::vector<Vec3>& force) const {
    force.assign(x.size(), Vec3::Zero());
    for (const Thread& t : threads) {
        const Vec3 d = (t.b < 0 ? anchor : x[static_cast<std::size_t>(t.b)]) -
                       x[static_cast<std::size_t>(t.a)];
        const Real length = d.norm();
        if (tensionOnly && length <= t.restLength)
            continue;
        // Tension k (L - L0) pulls a towards b and b towards a.
        const Vec3 f = (t.stiffness * (length - t.restLength) / length) * d;
        force[static_cast<std::size_t>(t.a)] += f;
        if (t.b >= 0)
            force[static_cast<std::size_t>(t.b)] -= f;
    }
}

MassSpringModel chainModel() {
    constexpr double kZeros[3] = {2.404825557695773, 5.520078110286311, 8.653727912911013};
    const double a = kChainLength / kChainBeads;
    MassSpringModel model;
    model.mass = kChainDensity * a;
    model.gravity = Vec3(0, 0, -kGravity);
    for (int j = 1; j <= kChainBeads; ++j) {
        const double depth = a * (j - 0.5);
        const double s = kChainLength - depth;  // from the free end
        double x = 0;
        for (const double zero : kZeros)
            x += 1e-3 * std::cyl_bessel_j(0.0, zero * std::sqrt(s / kChainLength));
        model.position.push_back(Vec3(x, 0, -depth));
        model.velocity.push_back(Vec3::Zero());
    }
    for (int j = 0; j < kChainBeads; ++j) {
        const Real rest = j == 0 ? 0.5 * a : a;
        model.threads.push_back({.a = j,
                                 .b = j - 1,
                                 .restLength = rest,
                                 .stiffness = axialStiffness(kChainRigidity, 1, rest)});
    }
    return model;
}

MassSpringModel netModel(const NetSpec& spec) {
    const int n = spec.n;
    MassSpringModel model;
    model.mass = spec.nodeMass;
    model.tensionOnly = true;
    const Real cornerDistance = 0.5 * spec.mesh * std::hypot(n - 1, n - 1);
    for (int i = 0; i < n; ++i) {
        for (int j = 0; j < n; ++j) {
            const Vec3 offset = spec.mesh * Vec3(i - 0.5 * (n - 1), j - 0.5 * (n - 1), 0);
            model.position.push_back(offset);
            model.velocity.push_back((spec.spreadSpeed / cornerDistance) * offset);
            const MassSpringModel::Thread thread{.restLength = spec.mesh,
                                                 .stiffness = spec.stiffness};
            if (j + 1 < n) {
                model.threads.push_back(thread);
                model.threads.back().a = i * n + j;
                model.threads.back().b = i * n + j + 1;
            }
            if (i + 1 < n) {
                model.threads.push_back(thread);
                model.threads.back().a = i * n + j;
                model.threads.back().b = (i + 1) * n + j;
            }
        }
    }
    return model;
}

Trajectory integrateReference(const MassSpringModel& model, double h, double duration) {
    std::vector<Vec3> x = model.position, v = model.velocity, f;
    const auto kick = [&] {  // half a step of the forces f at x
        for (std::size_t i = 0; i < v.size(); ++i)
            v[i] += (0.5 * h) * (f[i] / model.mass + model.gravity);
    };
    Trajectory run;
    const int steps = stepsFor(duration, h);
    const int every = static_cast<int>(std::lround(kSampleInterval / h));
    model.threadForces(x, f);
    for (int s = 1; s <= steps; ++s) {
        kick();
        for (std::size_t i = 0; i < x.size(); ++i)
            x[i] += h * v[i];
        model.threadForces(x, f);
        kick();
        if (s % every == 0)
            run.samples.insert(run.samples.end(), x.begin(), x.end());
    }
    run.simulated = steps * h;
    return run;
}

Trajectory runChain(const Peer& peer, double h, int iterations, double duration,
                    bool explicitSprings) {
    const MassSpringModel model = chainModel();
    const std::size_t n = model.position.size();
    const int steps = stepsFor(duration, h);
    const int every = static_cast<int>(std::lround(kSampleInterval / h));
    Trajectory run;
    if (peer.name == "tumble") {
        // As validation/cases/hanging_chain.cpp: the beads joined by implicit springs.
        WorldDef def;
        def.gravity = model.gravity;
        def.timeStep = h;
        def.enableSleep = false;
        def.solver.iterations = iterations;
        def.solver.relaxIterations = iterations;
        def.solver.linkIterations = iterations;
        def.solver.linkRelaxIterations = iterations;
        World world(def);
        std::vector<BodyId> beads;
        for (const Vec3& p : model.position)
            beads.push_back(validation::addPointMass(world, p, model.mass));
        for (const MassSpringModel::Thread& t : model.threads) {
            SpringDef spring;
            spring.formulation =
                explicitSprings ? SpringFormulation::Explicit : SpringFormulation::Implicit;
            spring.restLength = t.restLength;
            spring.stiffness = t.stiffness;
            spring.bodyA = beads[static_cast<std::size_t>(t.a)];
            spring.bodyB = t.b < 0 ? BodyId{} : beads[static_cast<std::size_t>(t.b)];
            spring.localAnchorB = t.b < 0 ? model.anchor : Vec3::Zero();
            world.createSpring(spring);
        }
        for (int s = 1; s <= steps && !run.blewUp; ++s) {
            const auto t0 = Clock::now();
            run.blewUp = !world.step().ok();
            run.busy += seconds(t0);
            run.simulated = s * h;
            for (std::size_t i = 0; i < n && s % every == 0; ++i) {
                run.samples.push_back(world.position(beads[i]));
                run.blewUp = run.blewUp || !run.samples.back().allFinite();
            }
        }
        return run;
    }
    // A peer: point masses, the harness's explicit spring forces before each step.
    SceneSettings settings;
    settings.timeStep = h;
    settings.iterations = iterations;
    settings.gravity = model.gravity;
    auto world = peer.create(settings);
    for (std::size_t i = 0; i < n; ++i) {
        if (world->addPointMass(model.position[i], model.velocity[i], model.mass, kNodeRadius) <
            0) {
            run.blewUp = true;  // cannot run it; the sweep skips such peers before
            return run;
        }
    }
    std::vector<Vec3> x(n), f;
    for (int s = 1; s <= steps && !run.blewUp; ++s) {
        const auto t0 = Clock::now();
        for (std::size_t i = 0; i < n; ++i)
            x[i] = world->position(static_cast<int>(i));
        model.threadForces(x, f);
        for (std::size_t i = 0; i < n; ++i)
            world->applyForce(static_cast<int>(i), f[i]);
        world->step();
        run.busy += seconds(t0);
        run.simulated = s * h;
        for (std::size_t i = 0; i < n; ++i) {
            x[i] = world->position(static_cast<int>(i));
            run.blewUp = run.blewUp || !x[i].allFinite();
        }
        if (s % every == 0)
            run.samples.insert(run.samples.end(), x.begin(), x.end());
    }
    return run;
}

Trajectory runNet(const Peer& peer, const Scene& scene, double h, int iterations, double duration) {
    SceneSettings settings;
    settings.timeStep = h;
    settings.iterations = iterations;
    SceneRun net(peer, scene, settings);
    Trajectory run;
    if (!net.skipped().empty()) {
        run.blewUp = true;  // cannot run it; the sweep skips such peers before
        return run;
    }
    const int nodes = scene.size * scene.size;
    const int steps = stepsFor(duration, h);
    const int every = static_cast<int>(std::lround(kSampleInterval / h));
    for (int s = 1; s <= steps && !run.blewUp; ++s) {
        const auto t0 = Clock::now();
        net.step();
        run.busy += seconds(t0);
        run.simulated = s * h;
        net.measure(s * h);
        // Non-finite, or the energy grew tenfold (scene.h's collapsedAt for nets).
        run.blewUp = net.metrics().collapsedAt >= 0;
        for (int i = 0; i < nodes && s % every == 0; ++i)
            run.samples.push_back(net.position(i));
    }
    return run;
}

double deviation(const Trajectory& run, const Trajectory& reference, bool sidewaysOnly) {
    if (run.blewUp || run.samples.size() < reference.samples.size())
        return INFINITY;
    double largest = 0;
    for (std::size_t i = 0; i < reference.samples.size(); ++i) {
        const Vec3 d = run.samples[i] - reference.samples[i];
        const double e = sidewaysOnly ? std::abs(d.x()) : d.norm();
        if (!std::isfinite(e))
            return INFINITY;
        largest = std::max(largest, e);
    }
    return largest;
}

}  // namespace tumble::bench
