// five-body-pendulum: the multi-body pendulum of the Newton engine's paper -- a base link, three
// links and a ball joined by ball-and-socket joints -- swings undamped for 10 s at h = 1/240; its
// mechanical energy must drift by less than 1 %.
//
// Base: a static box; links: boxes 0.5 x 0.05 x 0.05 m of 1 kg; ball: a 2 kg sphere of radius
// 0.1 m. The chain starts straight and horizontal (every joint on the x axis, the ball's centre
// 0.1 m beyond the last joint), at rest, and falls: a chaotic, whipping motion. Energy:
// kinetic plus m g z, measured against its initial value and scaled by what the chain can give
// up, E0 - E_rest (E_rest: everything hanging straight down at rest), so the drift does not
// depend on where z = 0 is.
//
// One step of 1/240 s is not enough (semi-implicit Euler, first order): the energy deviates by
// 9.0 % at worst and ends 2.1 % off, and more iterations do not help. Most of it is one whip
// event at t = 4.37 s, where the ball hands its swing to the links within three steps (the
// ball's |omega| h falls from 0.19 to 0.002 rad, the middle link's rises to 0.16): the energy
// spikes by 7.3 % in one step and settles 1.3 % lower than before. No body turns by more than 0.31
// rad in a step, so it is the fast exchange, not a large rotation, that h does not resolve. The
// claim is checked with kSubsteps substeps per step (WorldDef::substeps), which for this scene give
// exactly the trajectory of h / kSubsteps; the one-substep figures are reported as information.

#include <algorithm>
#include <cmath>
#include <ctime>
#include <string>
#include <vector>

#include "../case.h"
#include "tumble/tumble.h"

namespace tumble::validation {
namespace {

constexpr double kGravity = 9.81;
constexpr double kLinkLength = 0.5;
constexpr double kLinkMass = 1;
constexpr double kBallMass = 2;
constexpr double kBallRadius = 0.1;
// Substeps per step of h = 1/240 s for the claim.
constexpr int kSubsteps = 4;

struct Drift {
    double scale = 0;       // E0 - E_rest (J)
    double final = 0;       // |E - E0| / scale at the end
    double worst = 0;       // largest |E - E0| / scale
    double separation = 0;  // largest ball-joint separation (m)
    bool finite = true;
    double worstOmegaH = 0;     // largest |omega| h of a moving body (rad)
    double worstOmegaTime = 0;  // when (s)
    int worstOmegaBody = 0;     // 0..2 links, 3 ball
    double worstJump = 0;       // largest |E change| in one step / scale
    double worstJumpTime = 0;   // when (s)
    double cpu = 0;             // CPU time of the steps (s)
};

Drift swing(double seconds, int iterations, double h = 1.0 / 240.0, int substeps = 1) {
    WorldDef settings;
    settings.gravity = Vec3(0, 0, -kGravity);
    settings.timeStep = h;
    settings.substeps = substeps;
    settings.solver.softSubsteps = 0;  // jointed: the default step, whose count is substeps
    settings.enableSleep = false;
    settings.solver.iterations = iterations;
    settings.solver.relaxIterations = iterations;
    settings.solver.linkIterations = iterations;  // the links' budget is the one studied
    settings.solver.linkRelaxIterations = iterations;
    World world(settings);
    BodyDef baseDef;
    baseDef.type = BodyType::Static;
    baseDef.position = Vec3(-0.05, 0, 0);
    const BodyId base = world.createBody(baseDef);
    world.createShape(base, ShapeDef{.geometry = Box{Vec3(0.05, 0.05, 0.05)}});

    std::vector<BodyId> moving;
    std::vector<double> masses;
    BodyId previous = base;
    double x = 0;
    for (int i = 0; i < 3; ++i) {
        BodyDef def;
        def.position = Vec3(x + 0.5 * kLinkLength, 0, 0);
        def.mass.mass = kLinkMass;
        const double a = kLinkLength;
        const double b = 0.05;
        def.mass.inertia =
            (Vec3(2 * b * b, a * a + b * b, a * a + b * b) * (kLinkMass / 12)).asDiagonal();
        const BodyId link = world.createBody(def);
        world.createJoint(JointDef{
            .type = JointType::Ball, .bodyA = link, .bodyB = previous, .anchor = Vec3(x, 0, 0)});
        moving.push_back(link);
        masses.push_back(kLinkMass);
        previous = link;
        x += kLinkLength;
    }
    BodyDef ballDef;
    ballDef.position = Vec3(x + kBallRadius, 0, 0);
    ballDef.mass.mass = kBallMass;
    ballDef.mass.inertia = Mat3::Identity() * (0.4 * kBallMass * kBallRadius * kBallRadius);
    const BodyId ball = world.createBody(ballDef);
    world.createJoint(JointDef{
        .type = JointType::Ball, .bodyA = ball, .bodyB = previous, .anchor = Vec3(x, 0, 0)});
    moving.push_back(ball);
    masses.push_back(kBallMass);

    const auto energy = [&] {
        double e = world.kineticEnergy();
        for (std::size_t i = 0; i < moving.size(); ++i)
            e += masses[i] * kGravity * world.centerOfMass(moving[i]).z();
        return e;
    };
    // Hanging straight down from the base joint at the origin.
    double restEnergy = 0;
    for (int i = 0; i < 3; ++i)
        restEnergy -= kLinkMass * kGravity * (i + 0.5) * kLinkLength;
    restEnergy -= kBallMass * kGravity * (3 * kLinkLength + kBallRadius);
    const double initial = energy();
    const double scale = initial - restEnergy;

    const int steps = static_cast<int>(std::round(seconds / h));
    double worst = 0;
    double worstSeparation = 0;
    bool finite = true;
    Drift d;
    double last = initial;
    for (int i = 1; i <= steps && finite; ++i) {
        const std::clock_t cpu0 = std::clock();
        finite = world.step().ok();
        d.cpu += static_cast<double>(std::clock() - cpu0) / CLOCKS_PER_SEC;
        const double e = energy();
        if (std::abs(e - last) / scale > d.worstJump) {
            d.worstJump = std::abs(e - last) / scale;
            d.worstJumpTime = i * h;
        }
        last = e;
        for (std::size_t k = 0; k < moving.size(); ++k) {
            const double wh = world.angularVelocity(moving[k]).norm() * h;
            if (wh > d.worstOmegaH) {
                d.worstOmegaH = wh;
                d.worstOmegaTime = i * h;
                d.worstOmegaBody = int(k);
            }
        }
        worst = std::max(worst, std::abs(energy() - initial) / scale);
        const Vec3 ballAnchor = world.transform(ball).apply(Vec3(-kBallRadius, 0, 0));
        const Vec3 linkEnd = world.transform(moving[2]).apply(Vec3(0.5 * kLinkLength, 0, 0));
        worstSeparation = std::max(worstSeparation, (ballAnchor - linkEnd).norm());
    }
    d.scale = scale;
    d.final = std::abs(energy() - initial) / scale;
    d.worst = worst;
    d.separation = worstSeparation;
    d.finite = finite;
    return d;
}

CaseResult run(const CaseOptions& options) {
    CaseResult r;
    // The whole 10 s even in the fast version (0.4 s of CPU): the first 3 s pass with one
    // substep too (0.88 %), so a shorter run would not guard the claim.
    const double seconds = 10;
    const Drift d = swing(seconds, 10, 1.0 / 240, kSubsteps);
    r.metric("simulated time (s)", seconds);
    r.metric("substeps per step of 1/240 s", kSubsteps);
    r.metric("E0 - E_rest (J)", d.scale);
    r.metric("energy drift at the end (rel.)", d.final);
    r.metric("largest energy deviation (rel.)", d.worst);
    r.metric("largest ball-joint separation (mm)", 1e3 * d.separation);
    r.metric("CPU time of the steps (s)", d.cpu);
    // Information: one substep, where the whip events break the claim (see the file comment).
    const Drift single = swing(seconds, 10, 1.0 / 240, 1);
    r.metric("1 substep: energy drift at the end (rel.)", single.final);
    r.metric("1 substep: largest energy deviation (rel.)", single.worst);
    r.metric("1 substep: largest energy change in one step (rel.)", single.worstJump);
    r.metric("1 substep: ... at t (s)", single.worstJumpTime);
    r.metric("1 substep: largest |omega| h of a body (rad)", single.worstOmegaH);
    r.metric("1 substep: CPU time of the steps (s)", single.cpu);
    if (!options.fast) {
        const auto row = [&](double rate, int iterations, int substeps) {
            const Drift other = swing(seconds, iterations, 1 / rate, substeps);
            r.table.push_back({{{"1/h (1/s)", rate},
                                {"substeps", double(substeps)},
                                {"iterations", double(iterations)},
                                {"end drift", other.final},
                                {"largest dev.", other.worst},
                                {"CPU (s)", other.cpu}}});
        };
        for (const int substeps : {1, 2, 4, 8})
            row(240, 10, substeps);
        // Converged in the sweeps: what is left is the time step's.
        for (const int iterations : {20, 40, 80})
            row(240, iterations, 1);
        // The motion is chaotic: each h follows another trajectory and meets other whip events,
        // so neighbours of 1/240 show the spread of the same error; halving h shows its order.
        for (const double rate : {200.0, 220.0, 230.0, 250.0, 260.0, 280.0, 300.0, 480.0, 960.0})
            row(rate, 10, 1);
    }
    r.tolerance("energy drift (rel.)", 0.01);
    r.check(d.finite, "the pendulum went non-finite");
    r.check(d.worst < 0.01, "energy deviated by " + std::to_string(100 * d.worst) + " % with " +
                                std::to_string(kSubsteps) + " substeps (tolerance 1 %)");
    return r;
}

}  // namespace

ValidationCase fiveBodyPendulumCase() {
    return {"five-body-pendulum",
            "base, three links and a ball on ball joints swing 10 s undamped at h = 1/240: energy "
            "within 1 %",
            run};
}

}  // namespace tumble::validation
