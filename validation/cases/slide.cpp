// slide: a unit cube (1 kg) resting on a flat static half-space, mu = 0.5 on both materials, is
// launched at v = 5 m/s in 8 horizontal directions k * 45 deg, h = 1/60. Coulomb friction
// decelerates it at mu g along its velocity, so it stops after v^2 / (2 mu g) = 2.548 m in a
// straight line whatever the direction.
//
// Discretisation: under semi-implicit Euler with constant deceleration a the distance is
// h * sum_k (v - k a h) = v^2 / (2 a) - v h / 2 + O(h^2): 1.6 % short at h = 1/60, inside the
// 2 % claim, so the claim tests the friction and not the integrator's known O(h) term.
//
// Claims (coupled friction, the default): stopping distance within 2 % and heading within 0.5 deg
// of the launch direction, for each direction.
//
// Reported, not claimed: the box friction model (two tangent rows clamped independently, the
// study's Bullet). Its tangent axes for a +Z normal are the world x and y axes, so along the
// diagonals friction is mu sqrt(2) and the distance is sqrt(2) short.

#include <cmath>
#include <numbers>
#include <string>

#include "../case.h"
#include "scenes.h"

namespace tumble::validation {
namespace {

constexpr double kFriction = 0.5;
constexpr double kSpeed = 5.0;  // (m/s)
constexpr double kDegree = std::numbers::pi / 180;
constexpr double kMaxTime = 3.0;   // (s); the box stops after about 1 s
constexpr double kStopped = 1e-6;  // (m/s)

struct Stop {
    double distance = NAN;  // horizontal displacement when stopped (m)
    double heading = NAN;   // its direction minus the launch direction (deg)
};

Stop launch(double direction, FrictionModel friction) {
    WorldDef def = scenes::stackWorld();
    def.solver.friction = friction;
    World world(def);
    const Material surface = scenes::material(kFriction);
    scenes::addGround(world, surface);
    const Vec3 velocity = kSpeed * Vec3(std::cos(direction), std::sin(direction), 0);
    const BodyId cube =
        scenes::addBox(world, BodyDef{.position = Vec3(0, 0, 0.5), .linearVelocity = velocity},
                       Vec3::Constant(0.5), surface);
    const Vec3 start = world.position(cube);
    const int steps = static_cast<int>(kMaxTime / world.settings().timeStep);
    for (int i = 0; i < steps; ++i) {
        if (!world.step().ok())
            return {};
        if (world.linearVelocity(cube).norm() < kStopped)
            break;
    }
    const Vec3 d = world.position(cube) - start;
    const double distance = std::hypot(d.x(), d.y());
    double heading = std::atan2(d.y(), d.x()) - direction;
    heading = std::remainder(heading, 2 * std::numbers::pi);
    return {distance, heading / kDegree};
}

CaseResult run(const CaseOptions&) {
    CaseResult result;
    const double kDistanceRel = 0.02;
    const double kHeadingDeg = 0.5;
    const double expected = kSpeed * kSpeed / (2 * kFriction * scenes::kG);
    result.tolerance("distance_rel_err", kDistanceRel);
    result.tolerance("heading_err_deg", kHeadingDeg);
    result.metric("expected_distance_m", expected);

    double worstDistance = 0, worstHeading = 0, boxDistance = 0, boxHeading = 0;
    for (int k = 0; k < 8; ++k) {
        const double direction = k * 45 * kDegree;
        const Stop coupled = launch(direction, FrictionModel::Coupled);
        const Stop box = launch(direction, FrictionModel::Box);
        const double error = coupled.distance / expected - 1;
        const double boxError = box.distance / expected - 1;
        result.table.push_back({{{"dir_deg", k * 45.0},
                                 {"distance_m", coupled.distance},
                                 {"dist_rel_err", error},
                                 {"heading_deg", coupled.heading},
                                 {"box_dist_err", boxError},
                                 {"box_heading_deg", box.heading}}});
        const std::string where = " at " + std::to_string(k * 45) + " deg";
        result.check(std::abs(error) <= kDistanceRel, "stopping distance off by > 2 %" + where);
        result.check(std::abs(coupled.heading) <= kHeadingDeg, "heading off by > 0.5 deg" + where);
        worstDistance = std::max(worstDistance, std::abs(error));
        worstHeading = std::max(worstHeading, std::abs(coupled.heading));
        boxDistance = std::max(boxDistance, std::abs(boxError));
        boxHeading = std::max(boxHeading, std::abs(box.heading));
    }
    result.metric("max_distance_rel_err", worstDistance);
    result.metric("max_heading_err_deg", worstHeading);
    result.metric("box_model_max_distance_rel_err", boxDistance);
    result.metric("box_model_max_heading_err_deg", boxHeading);
    result.metric("one_minus_1_over_sqrt2", 1 - 1 / std::numbers::sqrt2);
    return result;
}

}  // namespace

ValidationCase slideCase() {
    return {"slide",
            "cube launched at 5 m/s, mu 0.5, 8 directions: stops after v^2/(2 mu g) within 2 %, "
            "heading within 0.5 deg; box friction model reported",
            run};
}

}  // namespace tumble::validation
