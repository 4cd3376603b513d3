// mass-ratio: two unit cubes stacked on a static half-space, mu = 0.5, h = 1/60, 10 iterations:
// a 100 kg cube on a 1 kg cube, and a 1 kg cube on a 100 kg cube. PGS converges slowly when a
// heavy body rests on a light one (the light cube's contact rows must carry 101 times its own
// weight), so this is where a fixed iteration budget shows.
//
// Claims, for both orders, after 5 s:
// - at rest: the fastest point of either cube (|v| + |w| sqrt(3)/2) below 1 mm/s;
// - the deepest penetration the solver sees in the last 2.5 s below slop + 1 mm;
// - neither cube drifts 1 cm or more horizontally from where it was built (largest offset over
//   the run).

#include <cmath>
#include <string>

#include "../case.h"
#include "scenes.h"

namespace tumble::validation {
namespace {

constexpr double kFriction = 0.5;
constexpr double kDuration = 5.0;  // (s)

struct Rest {
    double speed = NAN;      // fastest point of either cube at the end (m/s)
    double penetration = 0;  // max deepest penetration over the last half (m)
    double drift = 0;        // largest horizontal offset of either cube (m)
    double sinkTop = NAN;    // how far the top cube sank below where it was built (m)
};

Rest settle(double bottomMass, double topMass) {
    World world(scenes::stackWorld());
    scenes::addGround(world, scenes::material(kFriction));
    // Unit cubes: density = mass.
    const BodyId bottom = scenes::addBox(world, Vec3(0, 0, 0.5), Vec3::Constant(0.5),
                                         scenes::material(kFriction, 0, bottomMass));
    const BodyId top = scenes::addBox(world, Vec3(0, 0, 1.5), Vec3::Constant(0.5),
                                      scenes::material(kFriction, 0, topMass));
    const BodyId cubes[] = {bottom, top};
    const Vec3 start[] = {world.position(bottom), world.position(top)};

    Rest rest;
    const long steps = std::lround(kDuration / world.settings().timeStep);
    for (long i = 0; i < steps; ++i) {
        if (!world.step().ok())
            return {};
        for (int c = 0; c < 2; ++c) {
            const Vec3 d = world.position(cubes[c]) - start[c];
            rest.drift = std::max(rest.drift, std::hypot(d.x(), d.y()));
        }
        if (world.time() >= kDuration / 2 - 1e-9)
            rest.penetration = std::max(rest.penetration, world.solverStats().deepestPenetration);
    }
    rest.speed = 0;
    for (const BodyId c : cubes) {
        rest.speed = std::max(rest.speed, world.linearVelocity(c).norm() +
                                              world.angularVelocity(c).norm() * std::sqrt(3.0) / 2);
    }
    rest.sinkTop = start[1].z() - world.position(top).z();
    return rest;
}

CaseResult run(const CaseOptions&) {
    CaseResult result;
    const double kSpeed = 1e-3;                                // (m/s)
    const double kPenetration = SolverSettings{}.slop + 1e-3;  // (m)
    const double kDrift = 0.01;                                // (m)
    result.tolerance("rest_speed_max_m_s", kSpeed);
    result.tolerance("penetration_max_m", kPenetration);
    result.tolerance("drift_max_m", kDrift);

    const struct {
        double bottom, top;
        const char* name;
    } orders[] = {{1, 100, "heavy_on_light"}, {100, 1, "light_on_heavy"}};
    for (const auto& order : orders) {
        const Rest rest = settle(order.bottom, order.top);
        const std::string name = order.name;
        result.table.push_back({{{"bottom_kg", order.bottom},
                                 {"top_kg", order.top},
                                 {"speed_m_s", rest.speed},
                                 {"penetration_m", rest.penetration},
                                 {"drift_m", rest.drift},
                                 {"top_sink_m", rest.sinkTop}}});
        result.metric(name + "_speed_m_s", rest.speed);
        result.metric(name + "_penetration_m", rest.penetration);
        result.metric(name + "_drift_m", rest.drift);
        result.check(rest.speed < kSpeed, name + ": not at rest after 5 s");
        result.check(rest.penetration < kPenetration, name + ": penetration not below slop + 1 mm");
        result.check(rest.drift < kDrift, name + ": drifts 1 cm or more");
    }
    return result;
}

}  // namespace

ValidationCase massRatioCase() {
    return {"mass-ratio",
            "100 kg cube on 1 kg cube and 1 kg on 100 kg: both at rest after 5 s (< 1 mm/s), "
            "penetration < slop + 1 mm, drift < 1 cm",
            run};
}

}  // namespace tumble::validation
