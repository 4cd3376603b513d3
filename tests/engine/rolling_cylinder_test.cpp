// A cylinder rolling down a box incline: a = (2/3) g sin(theta) without slip. Its side line lies on
// the box's face, the configuration whose contact once came out at a wrong normal and rolled about
// a point 2.6 mm inside the incline, slipping at 1.1e-2 m/s (issue 20, item 1).

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>

#include "tumble/world.h"

namespace tumble {
namespace {

TEST(RollingCylinder, RollsDownABoxInclineWithoutSlipAtTwoThirdsGSinTheta) {
    const Real theta = 20 * std::numbers::pi / 180, r = 0.5, g = 9.81;
    World world;
    // The incline: a long box turned by theta about y; its top face falls towards +x.
    const Quat slope(Eigen::AngleAxis<Real>(theta, Vec3::UnitY()));
    const Vec3 normal = slope * Vec3::UnitZ();
    const Vec3 downhill = slope * Vec3::UnitX();
    const BodyId incline =
        world.createBody(BodyDef{.type = BodyType::Static, .orientation = slope});
    ShapeDef boxShape{.geometry = Box{Vec3(30, 5, 0.5)}};
    boxShape.material.friction = 0.8;  // rolling needs mu >= tan(theta) / 3 = 0.12
    world.createShape(incline, boxShape);
    // The cylinder (axis along y, across the slope) touching the top face exactly, 20 m uphill.
    BodyDef def;
    def.position = slope * Vec3(-20, 0, 0.5) + r * normal;
    def.orientation = Quat(Eigen::AngleAxis<Real>(std::numbers::pi / 2, Vec3::UnitX()));
    const BodyId cylinder = world.createBody(def);
    ShapeDef cylinderShape{.geometry = Cylinder{r, 0.5}};
    cylinderShape.material.friction = 0.8;
    world.createShape(cylinder, cylinderShape);

    const Real h = world.settings().timeStep;
    const int steps = 120;
    Real worstSlip = 0, worstSinking = 0;
    for (int step = 0; step < steps; ++step) {
        ASSERT_TRUE(world.step().ok());
        const Vec3 contact = world.centerOfMass(cylinder) - r * normal;
        worstSlip = std::max(worstSlip, world.velocityAt(cylinder, contact).norm());
        const Real height = normal.dot(world.centerOfMass(cylinder) - def.position);
        worstSinking = std::max(worstSinking, -height);
    }
    // From rest, v = a t (the semi-implicit step gives velocities exact for constant a).
    const Real expected = 2.0 / 3.0 * g * std::sin(theta);
    const Real measured = world.linearVelocity(cylinder).dot(downhill) / (steps * h);
    std::printf("rolling cylinder: a / (2/3 g sin) = %.6f, slip %.3g m/s, sinking %.3g m\n",
                measured / expected, worstSlip, worstSinking);
    EXPECT_NEAR(measured / expected, 1, 0.01);
    EXPECT_LT(worstSlip, 1e-3);
    EXPECT_LT(worstSinking, world.settings().solver.slop + 1e-3);
    EXPECT_LT(std::abs(world.linearVelocity(cylinder).dot(normal)), 1e-3) << "stays on the face";
}

}  // namespace
}  // namespace tumble
