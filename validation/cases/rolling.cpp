// rolling-resistance: a solid ball (r = 0.1 m, 1000 kg/m^3) on a static half-space, h = 1/60,
// Coulomb mu = 0.5, with the contact's torsional friction length c_s = 0.01 m and rolling
// resistance length c_r = 0.005 m (Material::spinningFriction, rollingFriction). A rigid point
// contact resists neither; these model the patch a real contact has. The torques are limited to
// c N, and the ball's moment of inertia is I = 2/5 m r^2, so:
//
// - spin-down: a ball spinning at omega0 about the normal, not moving, decelerates at
//   c_s m g / I and stops at t = omega0 I / (c_s m g), in a straight line of omega against time;
// - roll-out: a ball rolling at v0 (omega = v0 / r) decelerates at a = 5/7 g c_r / r (friction at
//   the point and the resisting torque together; rolling without slip) and stops after
//   v0^2 / (2 a);
// - incline: on a slope theta the ball stays put while tan(theta) <= c_r / r and otherwise rolls
//   down with a = 5/7 g (sin theta - (c_r / r) cos theta).
//
// Claims: the spin-down's deceleration within 1e-6 and its stop time within one step; the
// roll-out's distance within 0.1 % of the discrete answer (v0 h / 2 short of the continuous one,
// as for the slide case's box); on the slope at 0.8 c_r / r the ball moves less than 1 mm in
// 5 s, and at 2 c_r / r the fitted acceleration is within 1e-6 (fitted as incline's: a parabola
// through the position from 0.5 s to 3 s). Each run also checks that without the lengths the
// ball spins and rolls on undisturbed (the reason for them).

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "../case.h"
#include "scenes.h"

namespace tumble::validation {
namespace {

constexpr double kRadius = 0.1;     // (m)
constexpr double kDensity = 1000;   // (kg/m^3)
constexpr double kSpinning = 0.01;  // c_s (m)
constexpr double kRolling = 0.005;  // c_r (m)
constexpr double kFriction = 0.5;
constexpr int kStepsPerSecond = 60;
constexpr double kH = 1.0 / kStepsPerSecond;

struct Ball {
    World world;
    BodyId body;
};

// The soft step's substeps (tumble-validate --soft-step), 1 without it: the integrator's step
// is h / n, and the discrete closed forms hold with it (docs/ARCHITECTURE.md, "The soft step").
int integratorSubsteps() {
    return std::max(1, scenes::stackWorld(kH).solver.softSubsteps);
}

// Under the soft step a resting contact is a spring at its static sag g cos(theta) / w^2, w =
// 2 pi x twice contactHertz against the ground, capped at a quarter of the substep rate
// (soft_contacts.cpp): the ball starts there. From zero depth it sank for its first ~10 steps
// with less than its weight on the ground, so less torque (spin-down 24.38 against 24.525 rad/s^2).
double softSag(const SolverSettings& s, double theta) {
    if (s.softSubsteps == 0)
        return 0;
    const double hertz = 2 * std::min(s.contactHertz, 0.25 * s.softSubsteps / kH);
    const double w = 2 * M_PI * hertz;
    return scenes::kG * std::cos(theta) / (w * w);
}

// A ball resting exactly on the ground (gravity along -normal of a slope tilted by theta).
Ball makeBall(double theta, bool resist) {
    WorldDef def = scenes::stackWorld(kH);
    def.gravity = scenes::kG * Vec3(std::sin(theta), 0, -std::cos(theta));
    const double sag = softSag(def.solver, theta);
    Ball ball{World(def), {}};
    Material surface = scenes::material(kFriction, 0, kDensity);
    if (resist) {
        surface.spinningFriction = kSpinning;
        surface.rollingFriction = kRolling;
    }
    scenes::addGround(ball.world, scenes::material(kFriction));
    ball.body = ball.world.createBody(BodyDef{.position = Vec3(0, 0, kRadius - sag)});
    ball.world.createShape(ball.body, ShapeDef{.geometry = Sphere{kRadius}, .material = surface});
    return ball;
}

struct SpinDown {
    double deceleration = 0;  // fitted from the first half of the spin-down (rad/s^2)
    double stopTime = NAN;    // first time the spin is below 1e-9 rad/s (s)
};

SpinDown spinDown(double omega0, bool resist, double duration) {
    Ball ball = makeBall(0, resist);
    ball.world.setAngularVelocity(ball.body, Vec3(0, 0, omega0));
    SpinDown result;
    std::vector<double> times, spins;
    const int steps = static_cast<int>(std::lround(duration * kStepsPerSecond));
    for (int i = 1; i <= steps; ++i) {
        if (!ball.world.step().ok())
            return {NAN, NAN};
        const double spin = ball.world.angularVelocity(ball.body).z();
        if (std::isnan(result.stopTime) && std::abs(spin) < 1e-9)
            result.stopTime = ball.world.time();
        if (spin > 0.5 * omega0) {
            times.push_back(ball.world.time());
            spins.push_back(spin);
        }
    }
    result.deceleration = times.size() >= 2 ? -fitSlope(times, spins) : 0;
    return result;
}

// Distance rolled (m) before the ball stops, and whether it stopped.
std::pair<double, bool> rollOut(double v0, bool resist, double duration) {
    Ball ball = makeBall(0, resist);
    ball.world.setLinearVelocity(ball.body, Vec3(v0, 0, 0));
    ball.world.setAngularVelocity(ball.body, Vec3(0, v0 / kRadius, 0));
    const int steps = static_cast<int>(std::lround(duration * kStepsPerSecond));
    for (int i = 1; i <= steps; ++i) {
        if (!ball.world.step().ok())
            return {NAN, false};
    }
    const bool stopped = ball.world.linearVelocity(ball.body).norm() < 1e-6;
    return {ball.world.position(ball.body).x(), stopped};
}

struct Slope {
    double creep = 0;         // largest distance from the start (m)
    double acceleration = 0;  // fitted along the slope (m/s^2)
};

Slope slope(double theta, double duration, bool fit) {
    Ball ball = makeBall(theta, true);
    Slope result;
    std::vector<double> times, positions;
    const int steps = static_cast<int>(std::lround(duration * kStepsPerSecond));
    for (int i = 1; i <= steps; ++i) {
        if (!ball.world.step().ok())
            return {NAN, NAN};
        const Vec3 position = ball.world.position(ball.body);
        result.creep = std::max(result.creep, std::hypot(position.x(), position.y()));
        if (fit && ball.world.time() >= 0.5 - 1e-9) {
            times.push_back(ball.world.time());
            positions.push_back(position.x());
        }
    }
    if (fit)
        result.acceleration = fitAcceleration(times, positions);
    return result;
}

CaseResult run(const CaseOptions&) {
    CaseResult result;
    const double mass = kDensity * 4.0 / 3.0 * M_PI * std::pow(kRadius, 3);
    const double inertia = 0.4 * mass * kRadius * kRadius;

    // Spin-down.
    const double omega0 = 10;
    const double spinRate = kSpinning * mass * scenes::kG / inertia;
    const double stopTime = omega0 / spinRate;
    const SpinDown spin = spinDown(omega0, true, stopTime + 0.5);
    const SpinDown free = spinDown(omega0, false, 1);
    const double spinError = spin.deceleration / spinRate - 1;
    result.tolerance("spin_deceleration_rel_err", 1e-6);
    result.tolerance("spin_stop_time_err_s", kH);
    result.metric("spin_deceleration_expected_rad_s2", spinRate);
    result.metric("spin_deceleration_rad_s2", spin.deceleration);
    result.metric("spin_stop_time_expected_s", stopTime);
    result.metric("spin_stop_time_s", spin.stopTime);
    result.check(std::abs(spinError) <= 1e-6, "spin-down deceleration off by more than 1e-6");
    result.check(std::abs(spin.stopTime - stopTime) <= kH, "spin-down stops off by over a step");
    result.check(std::abs(free.deceleration) < 1e-9, "a point contact without c_s slowed the spin");

    // Roll-out.
    const double v0 = 1;
    const double rollRate = 5.0 / 7.0 * scenes::kG * kRolling / kRadius;
    const double distance = v0 * v0 / (2 * rollRate);
    // Semi-implicit Euler under a constant deceleration travels sum h (v0 - n a h): v0 h / 2
    // short of the continuous distance (as the slide case's box); h the integrator's step.
    const double discrete = distance - 0.5 * v0 * kH / integratorSubsteps();
    const auto [rolled, stopped] = rollOut(v0, true, v0 / rollRate + 1);
    const auto [freeRolled, freeStopped] = rollOut(v0, false, v0 / rollRate + 1);
    const double rollError = rolled / discrete - 1;
    result.tolerance("roll_distance_rel_err", 1e-3);
    result.metric("roll_distance_expected_m", distance);
    result.metric("roll_distance_expected_discrete_m", discrete);
    result.metric("roll_distance_m", rolled);
    result.metric("roll_distance_without_m", freeRolled);
    result.check(stopped && std::abs(rollError) <= 1e-3,
                 "roll-out distance off the discrete answer by more than 0.1 %");
    result.check(!freeStopped, "a point contact without c_r stopped the rolling ball");

    // Slope.
    const double critical = std::atan(kRolling / kRadius);
    const double stick = std::atan(0.8 * kRolling / kRadius);
    const double roll = std::atan(2 * kRolling / kRadius);
    const double expected =
        5.0 / 7.0 * scenes::kG * (std::sin(roll) - kRolling / kRadius * std::cos(roll));
    const Slope stuck = slope(stick, 5, false);
    const Slope rolling = slope(roll, 3, true);
    const double slopeError = rolling.acceleration / expected - 1;
    result.tolerance("slope_creep_max_m", 1e-3);
    result.tolerance("slope_acceleration_rel_err", 1e-6);
    result.metric("critical_angle_deg", critical * 180 / M_PI);
    result.metric("slope_creep_m", stuck.creep);
    result.metric("slope_acceleration_expected_m_s2", expected);
    result.metric("slope_acceleration_m_s2", rolling.acceleration);
    result.check(stuck.creep < 1e-3, "ball rolls >= 1 mm in 5 s below the critical slope");
    result.check(std::abs(slopeError) <= 1e-6, "acceleration down the slope off by more than 1e-6");

    // One row per claim: 0 spin-down rate, 1 roll-out distance, 2 slope acceleration.
    const double errors[] = {spinError, rollError, slopeError};
    for (int claim = 0; claim < 3; ++claim)
        result.table.push_back({{{"claim", claim}, {"rel_err", errors[claim]}}});
    return result;
}

}  // namespace

ValidationCase rollingCase() {
    return {"rolling-resistance",
            "ball with torsional (c_s) and rolling (c_r) friction lengths: spin-down rate c_s m g "
            "/ I within 1e-6 and stop within a step; roll-out distance 7 r v0^2 / (10 g c_r) "
            "- v0 h / 2 within 0.1 %; rests on slopes below atan(c_r / r), rolls with 5/7 g (sin - "
            "c_r / r "
            "cos) within 1e-6 above",
            run};
}

}  // namespace tumble::validation
