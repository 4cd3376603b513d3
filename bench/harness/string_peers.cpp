// The hanging string in the peers (string_peers.h). The scene is validation/cases/string.cpp's:
// 30 nodes of 0.01 kg, hanging unstretched from a fixed point at z = 1.6 m on 30 threads of rest
// length 0.05 m (EA = 1000 N, c = 0.05 N s/m per thread), node 14 struck sideways (x) at 2 m/s.
// The thread law is Tumble's explicit one (engine/src/springs.cpp): T = k (L - L0) + c dL/dt,
// none when L <= L0 and never compressive.
//
// string-peers-transient.csv: each engine's node 14 and free-end x at 50 Hz over the record, at
// the study's h = 5e-4 s. string-peers-cost.csv: for EA = 1e2 .. 1e7 N at h = 0.9 / omega_e
// (the largest step explicit threads survive with a margin: spring_stability.cpp), the wall and
// CPU time per simulated second (median of 3 runs of 1 s) and the free end's x after 1 s.

#include "string_peers.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "peer.h"
#include "timing.h"

namespace tumble::bench {
namespace {

constexpr int kNodes = 30;
constexpr double kSegment = 0.05;  // rest length (m)
constexpr double kMass = 0.01;     // per node (kg)
constexpr double kDamping = 0.05;  // per thread (N s/m)
constexpr double kTop = 1.6;       // the fixed point's height (m)
constexpr int kStruck = 14;
constexpr double kStrikeSpeed = 2;  // (m/s)
constexpr double kSampleRate = 50;  // (Hz): the modes of interest are below 60 rad/s

class PeerString {
public:
    PeerString(const Peer& peer, double axialRigidity, double h)
        : stiffness_(axialRigidity / kSegment),
          world_(peer.create(SceneSettings{.timeStep = h, .iterations = 1})) {
        for (int j = 0; j < kNodes; ++j) {
            const Vec3 velocity = j == kStruck ? Vec3(kStrikeSpeed, 0, 0) : Vec3::Zero();
            world_->addPointMass(Vec3(0, 0, kTop - kSegment * (j + 1)), velocity, kMass, 0.01);
        }
        force_.resize(kNodes);
    }

    // Thread j joins node j - 1 (the fixed point for j = 0) to node j.
    void step() {
        std::fill(force_.begin(), force_.end(), Vec3::Zero());
        for (int j = 0; j < kNodes; ++j) {
            const Vec3 upper = j == 0 ? Vec3(0, 0, kTop) : world_->position(j - 1);
            const Vec3 upperVelocity = j == 0 ? Vec3::Zero() : world_->velocity(j - 1);
            const Vec3 d = world_->position(j) - upper;
            const Real length = d.norm();
            if (length <= kSegment)
                continue;
            const Vec3 n = d / length;
            const Real rate = n.dot(world_->velocity(j) - upperVelocity);
            const Real tension =
                std::max<Real>(0, stiffness_ * (length - kSegment) + kDamping * rate);
            force_[static_cast<std::size_t>(j)] -= tension * n;
            if (j > 0)
                force_[static_cast<std::size_t>(j - 1)] += tension * n;
        }
        for (int j = 0; j < kNodes; ++j)
            world_->applyForce(j, force_[static_cast<std::size_t>(j)]);
        world_->step();
    }

    Vec3 node(int j) const { return world_->position(j); }
    bool finite() const {
        for (int j = 0; j < kNodes; ++j) {
            if (!world_->position(j).allFinite())
                return false;
        }
        return true;
    }

private:
    Real stiffness_;
    std::unique_ptr<PeerWorld> world_;
    std::vector<Vec3> force_;
};

// The study's strike at h = 5e-4; returns whether the record stayed finite.
bool strike(const Peer& peer, double duration, std::ofstream& csv) {
    const double h = 5e-4;
    PeerString string(peer, 1000, h);
    const long steps = std::lround(duration / h);
    const long decimate = std::lround(1 / (kSampleRate * h));
    double swing = 0;
    for (long i = 1; i <= steps; ++i) {
        string.step();
        if (i % decimate != 0)
            continue;
        if (!string.finite())
            return false;
        const double end = string.node(kNodes - 1).x();
        swing = std::max(swing, std::abs(end));
        csv << peer.name << "," << static_cast<double>(i) * h << "," << string.node(kStruck).x()
            << "," << end << "\n";
    }
    std::printf("%-7s strike: %.0f s at h = 5e-4, free end swings %.2f cm\n", peer.name.c_str(),
                duration, 100 * swing);
    return true;
}

void cost(const Peer& peer, std::ofstream& csv) {
    constexpr int kRuns = 3;
    for (const double ea : {1e2, 1e3, 1e4, 1e5, 1e6, 1e7}) {
        const double omega = std::sqrt(ea / kSegment / kMass);
        const double h = 0.9 / omega;
        const long steps = std::lround(1 / h);
        std::vector<double> wall, cpu;
        bool finite = true;
        double endX = 0;
        for (int r = 0; r < kRuns; ++r) {
            PeerString string(peer, ea, h);
            const auto start = std::chrono::steady_clock::now();
            const double cpuStart = cpuNow();
            for (long i = 0; i < steps; ++i)
                string.step();
            const double simulated = static_cast<double>(steps) * h;
            cpu.push_back((cpuNow() - cpuStart) / simulated);
            wall.push_back(
                std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count() /
                simulated);
            finite = finite && string.finite();
            endX = string.node(kNodes - 1).x();
        }
        csv << peer.name << "," << ea << "," << omega << "," << h << "," << median(wall) << ","
            << median(cpu) << "," << endX << "," << (finite ? 1 : 0) << "\n";
        std::printf("%-7s EA = %-6g h = %.3g s: %.4g s/s wall, %.4g s/s CPU%s\n", peer.name.c_str(),
                    ea, h, median(wall), median(cpu), finite ? "" : ", went non-finite");
    }
}

}  // namespace

int runStringPeers(const StringPeerOptions& options) {
    std::filesystem::create_directories(options.outDir);
    std::ofstream transient(options.outDir + "/string-peers-transient.csv");
    std::ofstream costs(options.outDir + "/string-peers-cost.csv");
    transient.precision(10);
    costs.precision(10);
    transient << "engine,t,x_node14_m,x_end_m\n";
    costs << "engine,EA_N,omega_e,h,wall_s_per_s,cpu_s_per_s,end_x_m,finite\n";
    int ran = 0;
    bool ok = true;
    for (const Peer& peer : peers()) {
        // Tumble's own string (its thread elements, not these forces) is tumble-validate's;
        // Box2D is planar.
        if (peer.name == "tumble" || peer.name == "box2d" ||
            !engineChosen(options.engines, peer.name))
            continue;
        ++ran;
        if (!strike(peer, options.duration, transient)) {
            std::printf("%s: the struck string went non-finite\n", peer.name.c_str());
            ok = false;
        }
        cost(peer, costs);
    }
    if (ran == 0) {
        std::printf("no 3-D peer engine compiled in (or selected): nothing to run\n");
        return 1;
    }
    std::printf("wrote %s/string-peers-transient.csv and string-peers-cost.csv\n",
                options.outDir.c_str());
    return ok ? 0 : 1;
}

}  // namespace tumble::bench
