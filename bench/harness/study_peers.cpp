// Fig. 4 and Fig. 5 in the peers (study_peers.h). The scenes are validation/cases/oscillator.cpp's
// and bounce.cpp's; their grids, constants and measurements come from fig45.h, so both sides
// sweep the same points and measure them the same way.
//
// study-peers-oscillator.csv: a 1 kg point mass (colliding with nothing) in zero gravity at
// x_0 = 1 m, pulled by -k x (k = 1 N/m) applied before each step -- an explicit spring, as in
// Tumble's case -- for 200 periods at each omega h; amplitude and period error as Tumble's.
//
// study-peers-bounce.csv: a sphere (r = 0.1 m, 4.19 kg: Tumble's density 1000) dropped from centre
// height 1 m onto the static plane z = 0, restitution 0.8 for the pair (each engine's combine rule
// undone in its peer file), mu 0.5, 10 iterations, no sleeping; the relative errors of the first
// five apexes against r + (H - r) e^(2k) at each h. Margins are the engines' defaults: Bullet's
// sphere is a point with its radius as the margin and its plane has none, so the geometry is exact
// either way, and its contacts start 2 cm before touching (the breaking threshold) -- a zero margin
// would change nothing here. Bullet runs five times: its default correction (split impulse only
// beyond 4 cm of penetration, Baumgarte ERP 0.2 below), Baumgarte alone (m_splitImpulse = 0) and
// split impulse for every contact, the last two again with its speculative contacts (the 2 cm
// before touching) left out of the solve, which separates their effect from the correction's;
// ODE has only Baumgarte (ERP 0.2, 5 mm surface layer).

#include "study_peers.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <memory>
#include <numbers>
#include <string>
#include <vector>

#include "fig45.h"
#include "peer.h"

namespace tumble::bench {
namespace {

namespace fig45 = validation::fig45;

void oscillator(const Peer& peer, std::ofstream& csv) {
    double worstTheory = 0;  // relative deviation from semi-implicit Euler's discrete solution
    for (const double omegaH : fig45::oscillatorSweep(false)) {
        const std::unique_ptr<PeerWorld> world =
            peer.create(SceneSettings{.timeStep = omegaH, .gravity = Vec3::Zero()});
        const int body = world->addPointMass(Vec3(1, 0, 0), Vec3::Zero(), 1, 0.01);
        const int steps = fig45::oscillatorSteps(omegaH);
        std::vector<double> x;
        x.reserve(static_cast<std::size_t>(steps) + 1);
        x.push_back(1.0);
        for (int i = 0; i < steps; ++i) {
            world->applyForce(body, Vec3(-world->position(body).x(), 0, 0));  // k = 1 N/m
            world->step();
            x.push_back(world->position(body).x());
            if (!std::isfinite(x.back()) || std::abs(x.back()) > fig45::kOscillatorBlowUp)
                break;
        }
        const fig45::Oscillation r = fig45::measureOscillation(x, omegaH);
        const double amplitudeError = r.amplitude - 1;
        const double periodError = r.period > 0 ? r.period / (2 * std::numbers::pi) - 1 : NAN;
        csv << peer.name << "," << omegaH << "," << amplitudeError << "," << periodError << ","
            << r.growth << "\n";
        if (omegaH < 2) {
            const double theoryAmplitude = 1 / std::sqrt(1 - omegaH * omegaH / 4);
            const double theoryPeriod =
                2 * std::numbers::pi * omegaH / std::acos(1 - omegaH * omegaH / 2);
            worstTheory = std::max({worstTheory, std::abs(r.amplitude / theoryAmplitude - 1),
                                    std::abs(r.period / theoryPeriod - 1)});
        }
        std::printf(
            "%-7s oscillator omega h = %-5g amplitude error %+.3e, period error %+.3e, "
            "growth %.3g\n",
            peer.name.c_str(), omegaH, amplitudeError, periodError, r.growth);
    }
    std::printf(
        "%-7s oscillator: largest deviation from semi-implicit Euler's theory for "
        "omega h < 2: %.2e\n",
        peer.name.c_str(), worstTheory);
}

const char* correctionName(SceneSettings::Correction c) {
    switch (c) {
        case SceneSettings::Correction::Baumgarte:
            return "baumgarte";
        case SceneSettings::Correction::SplitImpulse:
            return "split_impulse";
        case SceneSettings::Correction::Default:
        default:
            return "default";
    }
}

void bounce(const Peer& peer, SceneSettings::Correction correction, bool speculative,
            std::ofstream& csv) {
    for (const int rate : fig45::bounceRates(false)) {
        SceneSettings settings{.timeStep = 1.0 / rate};
        settings.restitution = fig45::kRestitution;
        settings.correction = correction;
        settings.speculativeContacts = speculative;
        const std::unique_ptr<PeerWorld> world = peer.create(settings);
        world->addGround();
        BodySpec ball;
        ball.kind = ShapeKind::Sphere;
        ball.radius = fig45::kBallRadius;
        ball.position = Vec3(0, 0, fig45::kDropHeight);
        ball.mass = 1000 * volume(ball);
        const int body = world->addBody(ball);
        fig45::ApexTracker tracker;
        tracker.sample(world->position(body).z());
        const int steps = static_cast<int>(fig45::kBounceTime * rate);
        for (int i = 0; i < steps && !tracker.complete(); ++i) {
            world->step();
            tracker.sample(world->position(body).z());
        }
        csv << peer.name << "," << correctionName(correction) << "," << (speculative ? 1 : 0) << ","
            << settings.timeStep;
        double worst = 0;
        for (const double e : tracker.errors()) {
            csv << "," << e;
            worst = std::isfinite(e) && std::isfinite(worst) ? std::max(worst, std::abs(e)) : NAN;
        }
        csv << "," << worst << "\n";
        std::printf("%-7s bounce (%s%s) h = 1/%-4d apex errors:", peer.name.c_str(),
                    correctionName(correction), speculative ? "" : ", touching contacts only",
                    rate);
        for (const double e : tracker.errors())
            std::printf(" %+.4f", e);
        std::printf("\n");
    }
}

}  // namespace

int runStudyPeers(const StudyPeerOptions& options) {
    std::filesystem::create_directories(options.outDir);
    std::ofstream oscillators(options.outDir + "/study-peers-oscillator.csv");
    std::ofstream bounces(options.outDir + "/study-peers-bounce.csv");
    oscillators.precision(10);
    bounces.precision(10);
    oscillators << "engine,omega_h,ampl_err,period_err,growth\n";
    bounces << "engine,correction,speculative,h,apex1_err,apex2_err,apex3_err,apex4_err,apex5_err,"
               "max_abs_err\n";
    int ran = 0;
    for (const Peer& peer : peers()) {
        // Tumble's own runs are tumble-validate's (the oscillator and bounce cases); Box2D and
        // MuJoCo have no restitution here.
        if (peer.name == "tumble" || peer.name == "box2d" || peer.name == "mujoco" ||
            !engineChosen(options.engines, peer.name))
            continue;
        ++ran;
        oscillator(peer, oscillators);
        bounce(peer, SceneSettings::Correction::Default, true, bounces);
        if (peer.name == "bullet") {  // the only peer with the choices
            for (const bool speculative : {true, false}) {
                bounce(peer, SceneSettings::Correction::Baumgarte, speculative, bounces);
                bounce(peer, SceneSettings::Correction::SplitImpulse, speculative, bounces);
            }
        }
    }
    if (ran == 0) {
        std::printf("no 3-D peer engine compiled in (or selected): nothing to run\n");
        return 1;
    }
    std::printf("wrote %s/study-peers-oscillator.csv and study-peers-bounce.csv\n",
                options.outDir.c_str());
    return 0;
}

}  // namespace tumble::bench
