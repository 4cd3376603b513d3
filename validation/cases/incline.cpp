// incline: a unit cube (1 kg) on a static half-space tilted by theta about the y axis, friction
// mu = 0.5 on both materials, h = 1/60. Coulomb's law: the cube sticks while tan(theta) <= mu and
// otherwise slides down with a = g (sin theta - mu cos theta), whatever its yaw about the plane
// normal (coupled friction is isotropic).
//
// Claims, for each of 8 yaws k * 45 deg of the cube about the plane normal:
// - theta = atan(mu) - 2 deg: the cube's displacement along the plane stays below 1 mm in 5 s,
//   counted from its release (the sinking into the slop is along the normal and not counted);
// - theta = atan(mu) + 5 deg: the acceleration along the slope is within 1 % of the formula.
//   It is fitted by least squares of s(t) = s0 + v0 t + a t^2 / 2 to the down-slope position
//   from 0.5 s (past the settling into the slop) to 3 s. Under semi-implicit Euler with constant
//   force the samples lie exactly on such a parabola, so the fit measures the friction, not the
//   integrator.

#include <cmath>
#include <numbers>
#include <string>
#include <vector>

#include "../case.h"
#include "scenes.h"

namespace tumble::validation {
namespace {

constexpr double kFriction = 0.5;
constexpr double kDegree = std::numbers::pi / 180;
constexpr double kStickTime = 5.0;  // (s)
constexpr double kFitStart = 0.5;   // (s)
constexpr double kFitEnd = 3.0;     // (s)
constexpr int kStepsPerSecond = 60;

struct Slide {
    double creep = 0;         // largest displacement along the plane from release (m)
    double acceleration = 0;  // fitted down-slope acceleration (m/s^2)
};

Slide runIncline(double theta, double yaw, double duration, bool fit) {
    World world(scenes::stackWorld(1.0 / kStepsPerSecond));
    const Quat tilt(Eigen::AngleAxis<Real>(theta, Vec3::UnitY()));
    const Material surface = scenes::material(kFriction);
    scenes::addGround(world, surface, tilt);
    const Vec3 normal = tilt * Vec3::UnitZ();
    const Vec3 downSlope = tilt * Vec3::UnitX();  // (cos theta, 0, -sin theta)
    const Quat orientation = tilt * Quat(Eigen::AngleAxis<Real>(yaw, Vec3::UnitZ()));
    const BodyId cube =
        scenes::addBox(world, BodyDef{.position = 0.5 * normal, .orientation = orientation},
                       Vec3::Constant(0.5), surface);
    const Vec3 start = world.position(cube);

    Slide slide;
    std::vector<double> times, positions;
    const int steps = static_cast<int>(std::lround(duration * kStepsPerSecond));
    for (int i = 1; i <= steps; ++i) {
        if (!world.step().ok())
            return {NAN, NAN};
        const Vec3 d = world.position(cube) - start;
        slide.creep = std::max(slide.creep, (d - d.dot(normal) * normal).norm());
        const double t = world.time();
        if (fit && t >= kFitStart - 1e-9) {
            times.push_back(t);
            positions.push_back(d.dot(downSlope));
        }
    }
    if (fit)
        slide.acceleration = fitAcceleration(times, positions);
    return slide;
}

CaseResult run(const CaseOptions&) {
    CaseResult result;
    const double kCreep = 1e-3;  // (m) in 5 s
    const double kAccelerationRel = 0.01;
    const double critical = std::atan(kFriction);
    const double stickAngle = critical - 2 * kDegree;
    const double slideAngle = critical + 5 * kDegree;
    const double expected = scenes::kG * (std::sin(slideAngle) - kFriction * std::cos(slideAngle));
    result.tolerance("creep_max_m", kCreep);
    result.tolerance("acceleration_rel_err", kAccelerationRel);

    double worstCreep = 0, worstAcceleration = 0;
    for (int k = 0; k < 8; ++k) {
        const double yaw = k * 45 * kDegree;
        const Slide stuck = runIncline(stickAngle, yaw, kStickTime, false);
        const Slide sliding = runIncline(slideAngle, yaw, kFitEnd, true);
        const double error = sliding.acceleration / expected - 1;
        result.table.push_back({{{"yaw_deg", k * 45.0},
                                 {"creep_m", stuck.creep},
                                 {"accel_m_s2", sliding.acceleration},
                                 {"accel_rel_err", error}}});
        result.check(stuck.creep < kCreep,
                     "creeps >= 1 mm in 5 s at theta = atan(mu) - 2 deg, "
                     "yaw " +
                         std::to_string(k * 45) + " deg");
        result.check(std::abs(error) <= kAccelerationRel,
                     "acceleration off by more than 1 % at yaw " + std::to_string(k * 45) + " deg");
        worstCreep = std::isnan(stuck.creep) ? NAN : std::max(worstCreep, stuck.creep);
        worstAcceleration = std::isnan(error) ? NAN : std::max(worstAcceleration, std::abs(error));
    }
    result.metric("stick_angle_deg", stickAngle / kDegree);
    result.metric("slide_angle_deg", slideAngle / kDegree);
    result.metric("expected_acceleration_m_s2", expected);
    result.metric("max_creep_m", worstCreep);
    result.metric("max_acceleration_rel_err", worstAcceleration);
    return result;
}

}  // namespace

ValidationCase inclineCase() {
    return {"incline",
            "cube on a plane, mu 0.5: sticks 2 deg below atan mu (creep < 1 mm in 5 s); 5 deg "
            "above slides with a = g (sin - mu cos) within 1 %, for 8 yaws",
            run};
}

}  // namespace tumble::validation
