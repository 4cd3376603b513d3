// Applied forces under the soft step (soft_step.cpp: their impulse in the first substep): a
// spring applied through the force API steps by the default step's semi-implicit Euler map and
// keeps its shadow energy, and a constant torque about a principal axis turns the body by the
// default step's closed form.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <random>

#include "tumble/world.h"

namespace tumble {
namespace {

constexpr int kSubstepCounts[] = {2, 3, 5};

struct Oscillator {
    Real h = 0;      // step (s)
    Real omega = 0;  // rad/s
    Real mass = 0;   // kg
    Vec3 x0 = Vec3::Zero();
    Vec3 v0 = Vec3::Zero();
};

// omega h in 0.01..1, h in 1/240..1/30 s, mass 0.1..10 kg, start within a metre and 1 m/s.
Oscillator randomOscillator(std::mt19937& rng) {
    std::uniform_real_distribution<Real> unit(0, 1);
    std::uniform_real_distribution<Real> coordinate(-1, 1);
    Oscillator o;
    o.h = 1 / (30 + 210 * unit(rng));
    o.omega = (0.01 + 0.99 * unit(rng)) / o.h;
    o.mass = 0.1 * std::pow(100.0, unit(rng));
    o.x0 = Vec3(coordinate(rng), coordinate(rng), coordinate(rng));
    o.v0 = Vec3(coordinate(rng), coordinate(rng), coordinate(rng));
    return o;
}

WorldDef softWorld(Real h, int substeps) {
    WorldDef def{.gravity = Vec3::Zero(), .timeStep = h, .enableSleep = false};
    def.solver.softSubsteps = substeps;
    return def;
}

BodyId addPointMass(World& world, const Oscillator& o) {
    MassProperties mass;
    mass.mass = o.mass;
    mass.inertia = Mat3::Identity();
    return world.createBody(BodyDef{.position = o.x0, .linearVelocity = o.v0, .mass = mass});
}

// F = -m w^2 x through the force API, before the step: an explicit spring.
void applySpring(World& world, BodyId body, const Oscillator& o) {
    world.applyForceToCenter(body, -o.mass * o.omega * o.omega * world.position(body));
}

// `draws` random oscillators at each substep count, each in its own soft world.
void forEachOscillator(unsigned seed, int draws,
                       const std::function<void(int, const Oscillator&, World&, BodyId)>& check) {
    std::mt19937 rng(seed);
    for (const int n : kSubstepCounts) {
        for (int draw = 0; draw < draws; ++draw) {
            const Oscillator o = randomOscillator(rng);
            World world(softWorld(o.h, n));
            check(n, o, world, addPointMass(world, o));
        }
    }
}

// v' = v - h w^2 x, x' = x + h v': the default step's map, whatever the substeps.
TEST(SoftStepForces, ASpringStepsByTheDefaultStepsSemiImplicitEuler) {
    forEachOscillator(2127, 20, [](int n, const Oscillator& o, World& world, BodyId body) {
        applySpring(world, body, o);
        ASSERT_TRUE(world.step().ok());
        const Real wh2 = o.omega * o.omega * o.h * o.h;
        const Vec3 v = o.v0 - o.h * o.omega * o.omega * o.x0;
        const Vec3 x = o.x0 + o.h * v;
        const Real xScale = o.x0.norm() + o.h * o.v0.norm() + wh2 * o.x0.norm();
        const Real vScale = o.v0.norm() + o.h * o.omega * o.omega * o.x0.norm();
        EXPECT_LE((world.position(body) - x).norm(), 1e-12 * xScale)
            << "n " << n << " omega h " << o.omega * o.h;
        EXPECT_LE((world.linearVelocity(body) - v).norm(), 1e-12 * vScale)
            << "n " << n << " omega h " << o.omega * o.h;
    });
}

// Symplectic Euler keeps Q = v^2 + w^2 x^2 - h w^2 x.v exactly (per unit of m / 2), so the
// energy E = v^2 + w^2 x^2 stays within Q / (1 +- w h / 2) (|w x.v| <= E / 2) over any run.
// The soft step's former map (the force spread over the substeps) has det 1 + (n - 1) / (2n)
// (w h)^2: Q grew by 3.3e-5 a step at w h = 0.01, n = 3. Tolerances set before measuring: Q to
// 1e-11 relative over 1000 steps (rounding, a few 1e-16 a step), the band to 1e-12.
TEST(SoftStepForces, ASpringKeepsSymplecticEulersShadowEnergy) {
    forEachOscillator(2128, 5, [](int n, const Oscillator& o, World& world, BodyId body) {
        const Real w2 = o.omega * o.omega;
        const auto shadow = [&](const Vec3& x, const Vec3& v) {
            return v.squaredNorm() + w2 * x.squaredNorm() - o.h * w2 * x.dot(v);
        };
        const Real q0 = shadow(o.x0, o.v0);
        const Real wh = o.omega * o.h;
        Real worstShadow = 0;
        Real lowest = 1e300;
        Real highest = 0;
        for (int step = 0; step < 1000; ++step) {
            applySpring(world, body, o);
            ASSERT_TRUE(world.step().ok());
            const Vec3 x = world.position(body);
            const Vec3 v = world.linearVelocity(body);
            worstShadow = std::max(worstShadow, std::abs(shadow(x, v) / q0 - 1));
            const Real energy = v.squaredNorm() + w2 * x.squaredNorm();
            lowest = std::min(lowest, energy);
            highest = std::max(highest, energy);
        }
        EXPECT_LE(worstShadow, 1e-11) << "n " << n << " omega h " << wh;
        EXPECT_GE(lowest, q0 / (1 + wh / 2) * (1 - 1e-12)) << "n " << n << " omega h " << wh;
        EXPECT_LE(highest, q0 / (1 - wh / 2) * (1 + 1e-12)) << "n " << n << " omega h " << wh;
    });
}

// A constant torque about a principal axis from rest: w_N = N h tau / I and, as in the default
// step, theta_N = h^2 (tau / I) N (N + 1) / 2. Spread over the substeps it turned
// N h^2 (tau / I) (n - 1) / (2n) less.
TEST(SoftStepForces, ATorqueAboutAPrincipalAxisTurnsByTheDefaultStepsClosedForm) {
    const Real h = 1.0 / 60;
    const Real inertia = 0.4;
    const Real torque = 1.6;  // alpha = 4 rad/s^2
    const int steps = 30;
    MassProperties mass;
    mass.mass = 2;
    mass.inertia = Vec3(0.3, inertia, 0.5).asDiagonal();
    for (const int n : kSubstepCounts) {
        World world(softWorld(h, n));
        const BodyId body = world.createBody(BodyDef{.mass = mass});
        for (int i = 0; i < steps; ++i) {
            world.applyTorque(body, Vec3(0, torque, 0));
            ASSERT_TRUE(world.step().ok());
        }
        const Real alpha = torque / inertia;
        EXPECT_TRUE(world.angularVelocity(body).isApprox(Vec3(0, steps * h * alpha, 0), 1e-12))
            << "n " << n;
        const Eigen::AngleAxis<Real> turned(world.orientation(body));
        const Real expected = h * h * alpha * steps * (steps + 1) / 2.0;
        EXPECT_NEAR(turned.angle(), expected, 1e-12 * expected) << "n " << n;
        EXPECT_TRUE(turned.axis().isApprox(Vec3::UnitY(), 1e-12)) << "n " << n;
    }
}

}  // namespace
}  // namespace tumble
