#include "tumble/solver/solver_body.h"

#include <gtest/gtest.h>

namespace tumble {
namespace {

SolverBody unitSphere() {
    SolverBody body;
    body.inverseMass = 1;
    body.inverseInertia = Mat3::Identity() / 0.4;  // solid sphere, m = 1, r = 1
    return body;
}

TEST(SolverBody, ImpulseAtOffsetChangesLinearAndAngularMomentum) {
    SolverBody body = unitSphere();
    applyImpulse(body, Vec3(0, 2, 0), Vec3(1, 0, 0));
    EXPECT_TRUE(body.linearVelocity.isApprox(Vec3(0, 2, 0)));
    // r x p = (1,0,0) x (0,2,0) = (0,0,2); w = I^-1 (r x p) = 5.
    EXPECT_TRUE(body.angularVelocity.isApprox(Vec3(0, 0, 5)));
    EXPECT_TRUE(body.velocityAt(Vec3(1, 0, 0)).isApprox(Vec3(0, 7, 0)));
}

TEST(SolverBody, EffectiveMassOfHeadOnPairIsReducedMass) {
    SolverBody a = unitSphere();
    SolverBody b = unitSphere();
    b.inverseMass = 0.5;
    // Through both centres: no rotation, so 1 / (1/m_a + 1/m_b).
    EXPECT_DOUBLE_EQ(effectiveMass(a, Vec3(1, 0, 0), b, Vec3(-1, 0, 0), Vec3(1, 0, 0)), 1 / 1.5);
}

TEST(SolverBody, EffectiveMassAppliedAsImpulseStopsRelativeVelocity) {
    SolverBody a = unitSphere();
    SolverBody b;  // static: zero inverse mass
    a.linearVelocity = Vec3(0, 0, -3);
    const Vec3 rA(0.3, 0, -1);
    const Vec3 n(0, 0, 1);
    const Real mass = effectiveMass(a, rA, b, Vec3::Zero(), n);
    const Real approach = a.velocityAt(rA).dot(n);
    applyImpulse(a, -mass * approach * n, rA);
    EXPECT_NEAR(a.velocityAt(rA).dot(n), 0, 1e-12);
    EXPECT_EQ(effectiveMass(b, Vec3::Zero(), b, Vec3::Zero(), n), 0);
}

}  // namespace
}  // namespace tumble
