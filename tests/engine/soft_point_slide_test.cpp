// The soft step's linear friction at a lone point while a ball sinks into its sag: a sliding
// ball slows by mu g h a step, the default step's closed form, from the first step.

#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <vector>

#include "tumble/world.h"

namespace tumble {
namespace {

constexpr Real kG = 9.81;
constexpr Real kH = 1.0 / 60.0;

struct Slide {
    bool crowd = false;
    bool fixedRotation = false;
    int substeps = 3;
    Real density = 1000;
    Real friction = 0.5;
    Real speed = 2;
};

// The ground turned by `ground` (gravity along its normal), the balls kicked along `along`, a
// unit tangent of it, from zero depth.
void slide(const Slide& s, const Quat& ground, Real along) {
    const Vec3 normal = ground * Vec3::UnitZ();
    const Vec3 e0 = ground * Vec3::UnitX();
    const Vec3 e1 = ground * Vec3::UnitY();
    const Vec3 kick = std::cos(along) * e0 + std::sin(along) * e1;
    WorldDef def{.gravity = -kG * normal, .timeStep = kH, .enableSleep = false};
    def.solver.softSubsteps = s.substeps;
    def.solver.contactHertz = 45;
    World world(def);
    Material material;
    material.density = s.density;
    material.friction = s.friction;
    const BodyId floor = world.createBody(BodyDef{.type = BodyType::Static, .orientation = ground});
    world.createShape(floor, ShapeDef{.geometry = HalfSpace{}, .material = material});
    const Real radius = 0.1;
    std::vector<BodyId> balls;
    for (int i = 0; i < (s.crowd ? 4 : 1); ++i) {
        const BodyId ball = world.createBody(BodyDef{.position = i * e0 + radius * normal,
                                                     .orientation = ground,
                                                     .fixedRotation = s.fixedRotation});
        world.createShape(ball, ShapeDef{.geometry = Sphere{radius}, .material = material});
        world.setLinearVelocity(ball, s.speed * kick);
        balls.push_back(ball);
    }
    for (int i = 0; s.crowd && i < 4; ++i) {
        const BodyId box = world.createBody(
            BodyDef{.position = i * e0 + 2 * e1 + 0.1 * normal, .orientation = ground});
        world.createShape(box,
                          ShapeDef{.geometry = Box{Vec3::Constant(0.1)}, .material = material});
    }
    // Sliding while v - w r > 0: v0 - k mu g h against (5 / 2) k mu g h for a free ball.
    const Real perStep = s.friction * kG * kH;
    const Real slipPerStep = s.fixedRotation ? perStep : 3.5 * perStep;
    const int checked = std::min(20, static_cast<int>(s.speed / slipPerStep) - 1);
    ASSERT_GT(checked, 3);
    for (int k = 1; k <= checked; ++k) {
        ASSERT_TRUE(world.step().ok());
        for (const BodyId ball : balls) {
            const Vec3 v = world.linearVelocity(ball);
            EXPECT_NEAR(v.dot(kick), s.speed - k * perStep, 1e-9 * s.speed) << "step " << k;
            EXPECT_NEAR((v - v.dot(kick) * kick).norm(), 0, 1e-9 * s.speed) << "step " << k;
        }
    }
}

// A ball placed touching the ground (zero depth), kicked along it. Under the soft step it sinks
// towards its sag over some ten steps, and each substep's biased sweep carries less than m g hs
// meanwhile; the relax sweep holds the normal velocity at zero, so each substep's whole normal
// impulse is m g hs and a sliding point's friction, mu times it, takes mu g hs off the velocity:
// mu g h a step. Before the relax sweep solved a lone point's friction after its normal row, the
// bound read the biased sweep's load: a translation-only ball took 0.98817 of mu m g h in step 1
// and 0.99976 in step 10 (3 x 45), 1 - d_k / (hs g h) for the depth d_k it sank in step k.
// Swept: substeps 2..5, density (mass), mu, speed, a free and a translation-only ball, random
// ground orientations (gravity along its normal) and kick directions; alone (the scalar rows) and
// as four balls beside four boxes (the wide rows). Tolerance, written before the sweep was run:
// 1e-9 of the speed (rounding only), along the kick and across it.
TEST(SoftSlide, ABallSlowsByMuGHFromZeroDepth) {
    std::mt19937 random(21);
    std::uniform_real_distribution<Real> unit(-1, 1);
    std::uniform_real_distribution<Real> angle(0, 2 * std::acos(Real(-1)));
    int cases = 0;
    for (const bool crowd : {false, true}) {
        for (int n = 2; n <= 5; ++n) {
            for (const bool fixedRotation : {false, true}) {
                for (const Real density : {0.5, 1000.0}) {
                    for (const Real friction : {0.2, 0.9}) {
                        const Quat ground = Quat(1 + unit(random), 0.3 * unit(random),
                                                 0.3 * unit(random), unit(random))
                                                .normalized();
                        const Real along = angle(random);
                        const Slide s{crowd, fixedRotation, n, density, friction, 3};
                        SCOPED_TRACE(testing::Message()
                                     << "crowd " << crowd << " n " << n << " fixed "
                                     << fixedRotation << " density " << density << " mu "
                                     << friction << " along " << along);
                        slide(s, ground, along);
                        ++cases;
                    }
                }
            }
        }
    }
    EXPECT_EQ(cases, 64);
}

}  // namespace
}  // namespace tumble
