// tunnel: a sphere (r = 0.05 m, 1000 kg/m^3, restitution 0) at 200 m/s toward a static wall
// 2 cm thick (a box 0.02 x 100 x 100 m, faces at x = -0.01 and +0.01), h = 1/60, no gravity. One
// step moves the sphere 3.33 m, 167 wall thicknesses: without speculative contacts it would be on
// the far side after one step. The wall is met at 8 phases of the step (start 2 m + k/8 of a step's
// travel away) and at two angles of approach (head on, and 30 deg off the wall normal).
//
// Claim: in every run the sphere's centre never gets beyond the wall's far face (x <= 0.01 m at
// every step of 0.25 s). Reported: the largest x the centre reached and the largest overlap of
// the sphere with the wall's near face.

#include <cmath>
#include <numbers>
#include <string>

#include "../case.h"
#include "scenes.h"

namespace tumble::validation {
namespace {

constexpr double kRadius = 0.05;         // (m)
constexpr double kSpeed = 200;           // (m/s)
constexpr double kHalfThickness = 0.01;  // (m)
constexpr double kDuration = 0.25;       // (s)
constexpr int kPhases = 8;
// Half the wall's height and width (m): wide enough that the oblique ball, sliding along it at up
// to 100 m/s, cannot reach an edge within kDuration and leave round it instead of through it.
constexpr double kHalfSide = 50;

struct Pass {
    double maxX = -1e300;        // largest centre x (m)
    double maxOverlap = -1e300;  // largest x + r - near face (m)
    bool finite = true;
};

Pass shoot(double approachAngle, double phase) {
    World world(WorldDef{.gravity = Vec3::Zero(), .timeStep = 1.0 / 60});
    const BodyId wall = world.createBody(BodyDef{.type = BodyType::Static});
    world.createShape(wall, ShapeDef{.geometry = Box{Vec3(kHalfThickness, kHalfSide, kHalfSide)},
                                     .material = scenes::material(0.5, 0, 1000)});
    const Vec3 direction(std::cos(approachAngle), std::sin(approachAngle), 0);
    const double distance = 2 + phase * kSpeed * world.settings().timeStep;
    // Aimed at the centre of the wall's near face.
    const Vec3 start = Vec3(-kHalfThickness - kRadius, 0, 0) - distance * direction;
    const BodyId ball =
        world.createBody(BodyDef{.position = start, .linearVelocity = kSpeed * direction});
    world.createShape(
        ball, ShapeDef{.geometry = Sphere{kRadius}, .material = scenes::material(0.5, 0, 1000)});

    Pass pass;
    const long steps = std::lround(kDuration / world.settings().timeStep);
    for (long i = 0; i < steps; ++i) {
        if (!world.step().ok()) {
            pass.finite = false;
            break;
        }
        const double x = world.position(ball).x();
        pass.maxX = std::max(pass.maxX, x);
        pass.maxOverlap = std::max(pass.maxOverlap, x + kRadius + kHalfThickness);
    }
    return pass;
}

CaseResult run(const CaseOptions&) {
    CaseResult result;
    result.tolerance("centre_x_max_m", kHalfThickness);
    double worstX = -1e300, worstOverlap = -1e300;
    for (const double angleDeg : {0.0, 30.0}) {
        for (int k = 0; k < kPhases; ++k) {
            const double phase = static_cast<double>(k) / kPhases;
            const Pass pass = shoot(angleDeg * std::numbers::pi / 180, phase);
            result.table.push_back({{{"angle_deg", angleDeg},
                                     {"phase", phase},
                                     {"max_centre_x_m", pass.maxX},
                                     {"max_overlap_m", pass.maxOverlap}}});
            result.check(pass.finite && pass.maxX <= kHalfThickness,
                         "sphere passes the wall at " + std::to_string(angleDeg) + " deg, phase " +
                             std::to_string(phase));
            worstX = std::max(worstX, pass.maxX);
            worstOverlap = std::max(worstOverlap, pass.maxOverlap);
        }
    }
    result.metric("max_centre_x_m", worstX);
    result.metric("max_overlap_with_near_face_m", worstOverlap);
    return result;
}

}  // namespace

ValidationCase tunnelCase() {
    return {"tunnel",
            "sphere r 0.05 m at 200 m/s, h 1/60, 2 cm static wall: never passes (8 phases, 2 "
            "angles)",
            run};
}

}  // namespace tumble::validation
