// A column of upright cylinders, each tilted a little, under a heavy box: the caps must support
// each other over an area (a multi-point manifold), so the column settles shallow and sleeps.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>

#include "tumble/world.h"

namespace tumble {
namespace {

// Cylinders as in the 5,000-body soak (radius 0.14 m, half-length 0.1 m, 6.2 kg), tilted 1.5-2
// degrees about different axes and dropped from 1 mm, under a 24 kg box. With a one-point
// contact between tilted caps the column rocked and sank 8-11 mm without sleeping (measured
// before the cap manifold, after the first second); with the cap polygon the deepest contact
// after the first second was 7.1 mm (8.9 mm during the first second, as the column lands).
TEST(CylinderStack, TiltedColumnUnderAHeavyBoxRestsShallowAndSleeps) {
    World world;
    const BodyId ground = world.createBody(BodyDef{.type = BodyType::Static});
    world.createShape(ground, ShapeDef{.geometry = HalfSpace{}});
    const Real r = 0.14, h = 0.1, degree = std::numbers::pi / 180;
    const Real tilts[4] = {1.5 * degree, 2 * degree, 1.75 * degree, 2 * degree};
    const Vec3 axes[4] = {Vec3::UnitX(), Vec3::UnitY(), Vec3(1, 1, 0).normalized(),
                          Vec3(1, -1, 0).normalized()};
    BodyId column[5];
    Real z = 0;
    for (int i = 0; i < 4; ++i) {
        const Real half = h * std::cos(tilts[i]) + r * std::sin(tilts[i]);
        BodyDef def;
        def.position = Vec3(0, 0, z + half + 1e-3);
        def.orientation = Quat(Eigen::AngleAxis<Real>(tilts[i], axes[i]));
        column[i] = world.createBody(def);
        world.createShape(column[i], ShapeDef{.geometry = Cylinder{r, h}});
        z += 2 * half + 1e-3;
    }
    BodyDef boxDef;
    boxDef.position = Vec3(0, 0, z + 0.1 + 1e-3);
    column[4] = world.createBody(boxDef);
    ShapeDef boxShape{.geometry = Box{Vec3(0.2, 0.2, 0.1)}};
    boxShape.material.density = 3000;  // 24 kg
    world.createShape(column[4], boxShape);

    const Real slop = world.settings().solver.slop;
    Real deepest = 0;
    for (int step = 0; step < 240; ++step) {
        ASSERT_TRUE(world.step().ok());
        if (step >= 60)  // resting, after the landing
            deepest = std::max(deepest, world.solverStats().deepestPenetration);
    }
    EXPECT_LE(deepest, slop + 3e-3);
    for (const BodyId body : column)
        EXPECT_FALSE(world.isAwake(body));
    // Still a column: the box on top, nothing slid off.
    EXPECT_GT(world.position(column[4]).z(), z);
    EXPECT_LT(world.position(column[4]).head<2>().norm(), 0.01);
}

}  // namespace
}  // namespace tumble
