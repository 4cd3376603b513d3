// The soft step's torsion (Material::spinningFriction) while a ball sinks into its sag: the
// spin-down of the default step's closed form, c m g h / I a step, from the first step.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "tumble/world.h"

namespace tumble {
namespace {

constexpr Real kG = 9.81;
constexpr Real kH = 1.0 / 60.0;

void spinDown(bool crowd, int n, Real radius, Real density, Real length, Real omega0) {
    WorldDef def{.gravity = Vec3(0, 0, -kG), .timeStep = kH, .enableSleep = false};
    def.solver.softSubsteps = n;
    def.solver.contactHertz = 45;
    World world(def);
    const BodyId floor = world.createBody(BodyDef{.type = BodyType::Static});
    world.createShape(floor, ShapeDef{.geometry = HalfSpace{}});
    std::vector<BodyId> balls;
    for (int i = 0; i < (crowd ? 4 : 1); ++i) {
        const BodyId ball = world.createBody(BodyDef{.position = Vec3(i, 0, radius)});
        world.createShape(
            ball, ShapeDef{.geometry = Sphere{radius},
                           .material = Material{.density = density, .spinningFriction = length}});
        world.setAngularVelocity(ball, Vec3(0, 0, omega0));
        balls.push_back(ball);
    }
    for (int i = 0; crowd && i < 4; ++i) {
        const BodyId box = world.createBody(BodyDef{.position = Vec3(i, 2, 0.1)});
        world.createShape(box, ShapeDef{.geometry = Box{Vec3::Constant(0.1)}});
    }
    const Real mass = world.massProperties(balls[0]).mass;
    const Real inertia = 0.4 * mass * radius * radius;
    const Real perStep = length * mass * kG * kH / inertia;
    const int stopSteps = static_cast<int>(std::ceil(omega0 / perStep));
    const int checked = std::min(20, stopSteps - 1);
    for (int k = 1; k <= checked; ++k) {
        ASSERT_TRUE(world.step().ok());
        for (const BodyId ball : balls) {
            EXPECT_NEAR(world.angularVelocity(ball).z(), omega0 - k * perStep, 1e-9 * omega0)
                << "step " << k;
        }
    }
    // Then it stops, and the torsion holds it (where that comes soon).
    if (stopSteps > 400)
        return;
    for (int k = checked + 1; k <= stopSteps + 5; ++k)
        ASSERT_TRUE(world.step().ok());
    for (const BodyId ball : balls)
        EXPECT_LT(world.angularVelocity(ball).norm(), 1e-9);
}

// A ball placed touching the ground (zero depth), spinning about the normal. Under the soft
// step it sinks towards its sag, g / w^2, over some ten steps, and each substep's biased sweep
// carries less than m g hs meanwhile; but each relax sweep holds the ball's normal velocity at
// zero (the sag is approached from above, overdamped, so no substep's push exceeds the weight),
// so each substep's whole normal impulse is m g hs, and the torsion's bound, c m g hs, takes
// c m g hs / I off the spin: c m g h / I a step, the closed form, with no need to start from
// the sagged rest. Before the relax sweep solved the torsion after its normal rows, it read the
// biased sweep's load, and the spin ran c m (the depth sunk) / (hs I) behind: 4.8e-3 rad/s
// after step 1, 0.0136 by step 10 (3 x 45, r = 0.1 m, c = 0.01).
// Swept: substeps 2..5 (45 Hz asked, the soft step caps it at a quarter of the substep rate),
// radius, density (mass), spinning-friction length, initial spin; alone (the scalar rows) and
// as four balls beside four boxes (enough points for the wide rows, colouredContacts). Tolerance,
// written before the sweep was run: 1e-9 of the initial spin, the default step's test's
// (rounding only).
TEST(SoftSpin, SpinsDownAtTheTorqueLimitFromZeroDepth) {
    int cases = 0;
    for (const bool crowd : {false, true}) {
        for (int n = 2; n <= 5; ++n) {
            for (const Real radius : {0.05, 0.2}) {
                for (const Real density : {0.5, 1000.0}) {
                    for (const Real length : {0.003, 0.02}) {
                        for (const Real omega0 : {3.0, 30.0}) {
                            SCOPED_TRACE(testing::Message()
                                         << "crowd " << crowd << " n " << n << " radius " << radius
                                         << " density " << density << " length " << length
                                         << " omega0 " << omega0);
                            spinDown(crowd, n, radius, density, length, omega0);
                            ++cases;
                        }
                    }
                }
            }
        }
    }
    EXPECT_EQ(cases, 128);
}

}  // namespace
}  // namespace tumble
