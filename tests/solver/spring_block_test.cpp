// The direct spring solve against a dense solve of the same equations, and its tension-only
// active set.

#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <cstring>
#include <vector>

#include "tumble/solver/constraint_solver.h"
#include "tumble/solver/spring_block.h"

namespace tumble {
namespace {

SolverBody pointMass(Real mass, const Vec3& velocity) {
    SolverBody b;
    b.inverseMass = 1 / mass;
    b.inverseInertia = Mat3::Identity() / (0.4 * mass * 0.01);
    b.linearVelocity = velocity;
    return b;
}

SpringRow link(std::uint32_t a, std::uint32_t b, const Vec3& from, const Vec3& to, Real rest,
               Real k, Real c, bool tensionOnly = false) {
    SpringRow row;
    row.bodyA = a;
    row.bodyB = b;
    row.direction = (to - from).normalized();
    row.length = (to - from).norm();
    row.restLength = rest;
    row.stiffness = k;
    row.damping = c;
    row.tensionOnly = tensionOnly;
    return row;
}

// A 3 x 3 net of masses (bodies 1..9) with its corner (1) tied to the world (body 0), anchors
// off the centres so the rows couple through rotation too.
struct Net {
    std::vector<SolverBody> bodies;
    std::vector<SpringRow> rows;
    std::vector<Vec3> at;
};

Net smallNet(bool tensionOnly) {
    Net net;
    net.bodies.push_back(SolverBody{});
    for (int j = 0; j < 9; ++j) {
        net.at.push_back(Vec3(j % 3, j / 3, 0.05 * (j % 2)));
        net.bodies.push_back(
            pointMass(0.5 + 0.1 * j, Vec3(0.3 * (j % 3) - 0.2, 0.1 * j, -0.5 + 0.05 * j)));
        net.bodies.back().angularVelocity = Vec3(0.1, -0.2, 0.3 * j);
    }
    auto add = [&](int p, int q, Real rest) {
        SpringRow row =
            link(1 + p, 1 + q, net.at[p], net.at[q], rest, 1e5 * (1 + p), 3, tensionOnly);
        row.rA = Vec3(0.01, 0, 0.02);
        row.rB = Vec3(0, -0.01, 0.01);
        net.rows.push_back(row);
    };
    for (int j = 0; j < 9; ++j) {
        if (j % 3 < 2)
            add(j, j + 1, j % 2 == 0 ? 0.9 : 1.1);  // some stretched, some slack
        if (j / 3 < 2)
            add(j, j + 3, 1.0);
    }
    net.rows.push_back(link(0, 1, Vec3(0, 0, 1), net.at[0], 0.95, 2e5, 0, tensionOnly));
    return net;
}

// J v + bias + gamma lambda of every row: zero when every row's implicit equation holds.
std::vector<Real> residuals(const Net& net) {
    std::vector<Real> r;
    for (const SpringRow& row : net.rows) {
        r.push_back(springRowSpeed(net.bodies[row.bodyA], net.bodies[row.bodyB], row) + row.bias +
                    row.softness * row.impulse);
    }
    return r;
}

TEST(SpringBlock, MeetsEveryRowsEquationAtOnce) {
    Net net = smallNet(false);
    prepareSpringRows(net.bodies, net.rows, 1.0 / 60, false);
    SpringBlockSolver block;
    block.prepare(net.bodies, net.rows);
    ASSERT_TRUE(block.ready());
    block.solve(net.bodies, net.rows);
    for (const Real r : residuals(net))
        EXPECT_NEAR(r, 0, 1e-9);
}

TEST(SpringBlock, AgreesWithADenseSolve) {
    Net net = smallNet(false);
    prepareSpringRows(net.bodies, net.rows, 1.0 / 60, false);
    const Net before = net;
    SpringBlockSolver block;
    block.prepare(net.bodies, net.rows);
    block.solve(net.bodies, net.rows);

    // K column by column: the velocity change of every row per unit impulse of one row.
    const int n = static_cast<int>(before.rows.size());
    Eigen::MatrixXd k(n, n);
    Eigen::VectorXd r(n);
    for (int j = 0; j < n; ++j) {
        Net probe = before;
        const SpringRow& row = probe.rows[j];
        const std::vector<Real> r0 = residuals(probe);
        applySpringImpulse(probe.bodies[row.bodyA], probe.bodies[row.bodyB], row, 1);
        probe.rows[j].impulse += 1;
        const std::vector<Real> r1 = residuals(probe);
        for (int i = 0; i < n; ++i)
            k(i, j) = r1[i] - r0[i];
        r(j) = r0[j];
    }
    const Eigen::VectorXd lambda = k.ldlt().solve(-r);
    for (int i = 0; i < n; ++i)
        EXPECT_NEAR(net.rows[i].impulse, lambda(i), 1e-9 * (1 + std::abs(lambda(i))));
}

TEST(SpringBlock, ThreadsPullButNeverPush) {
    Net net = smallNet(true);
    prepareSpringRows(net.bodies, net.rows, 1.0 / 60, false);
    SpringBlockSolver block;
    block.prepare(net.bodies, net.rows);
    block.solve(net.bodies, net.rows);
    const std::vector<Real> r = residuals(net);
    int taut = 0;
    int slack = 0;
    for (std::size_t i = 0; i < net.rows.size(); ++i) {
        // Complementarity: a pulling thread meets its equation; a slack one has no impulse and
        // would not be stretched by the step.
        EXPECT_LE(net.rows[i].impulse, 0);
        if (net.rows[i].impulse < 0) {
            EXPECT_NEAR(r[i], 0, 1e-9);
            ++taut;
        } else {
            EXPECT_LE(r[i], 1e-9);
            ++slack;
        }
    }
    EXPECT_GT(taut, 0);
    EXPECT_GT(slack, 0);
}

// Through the contact solver: a stiff chain of 64 point masses falling at g h hanging from the
// world, omega_e h = 10^4. One direct solve stops it whole -- the top link takes the momentum
// of all 64 masses, to the chain's compliance (N^2 / (omega_e h)^2 ~ 4e-5 relative) -- where 20
// Gauss-Seidel sweeps pass less than half of it up the chain.
TEST(SpringBlock, ContactSolverSolvesALongStiffChainInOneStep) {
    for (const SpringSolve mode : {SpringSolve::Direct, SpringSolve::Iterative}) {
        std::vector<SolverBody> bodies{SolverBody{}};
        std::vector<SpringRow> rows;
        const Real h = 1.0 / 60;
        const Real m = 0.01;
        const Real k = 1e4 * 1e4 * m / (h * h);
        for (int j = 0; j < 64; ++j) {
            bodies.push_back(pointMass(m, Vec3(0, 0, -9.81 * h)));
            const Vec3 top(0, 0, -0.1 * j);
            rows.push_back(link(j, j + 1, top, top - Vec3(0, 0, 0.1), 0.1, k, 0));
            rows.back().direction = Vec3(0, 0, -1);
        }
        std::vector<ContactConstraint> none;
        std::vector<PseudoVelocity> pseudo;
        SolverSettings settings;
        settings.springSolve = mode;
        ConstraintSolver solver;
        solver.solve(bodies, none, pseudo, h, settings, rows);
        // The top link carries the weight of all 64 masses for the step.
        const Real topImpulse = -rows[0].impulse;
        if (mode == SpringSolve::Direct)
            EXPECT_NEAR(topImpulse, 64 * m * 9.81 * h, 1e-4 * topImpulse);
        else
            EXPECT_LT(topImpulse, 0.5 * 64 * m * 9.81 * h);
    }
}

// Resolved undamped threads (the three-level form), some slack at both levels before the step:
// those prepared in part and finished later are, bit for bit, the rows prepared at once, and the
// bodies' velocities the same.
TEST(PrepareSpringRows, DeferredSlackThreadsFinishAsPreparedAtOnce) {
    const Real h = 1.0 / 240;
    Net net = smallNet(true);
    for (std::size_t i = 0; i < net.rows.size(); ++i) {
        SpringRow& row = net.rows[i];
        row.damping = 0;
        row.stiffness = 200;  // (omega h)^2 ~ 0.02: resolved
        row.spectralRadius = 1;
        row.discreteGradient = true;  // an undamped thread (buildSpringRows)
        row.startVelocity = Vec3(0.1 * static_cast<Real>(i % 3) - 0.1, 0.05, -0.02);
        row.impulse = i % 4 == 0 ? Real(-0.01) : Real(0);  // warm-started: prepared at once
    }
    Net deferred = net;
    prepareSpringRows(net.bodies, net.rows, h, true);
    prepareSpringRows(deferred.bodies, deferred.rows, h, true, true);
    int count = 0;
    for (const SpringRow& row : deferred.rows)
        count += row.deferred ? 1 : 0;
    EXPECT_GT(count, 0);
    finishSpringRows(deferred.bodies, deferred.rows, h);
    const auto same = [](const Vec3& x, const Vec3& y) {
        return std::memcmp(x.data(), y.data(), sizeof(Real) * 3) == 0;
    };
    for (std::size_t i = 0; i < net.rows.size(); ++i) {
        const SpringRow& p = net.rows[i];
        const SpringRow& q = deferred.rows[i];
        EXPECT_TRUE(p.levelGradient && q.levelGradient && !q.deferred) << i;
        EXPECT_TRUE(same(p.direction, q.direction) && same(p.angularA, q.angularA) &&
                    same(p.angularB, q.angularB) && same(p.angularImpulseA, q.angularImpulseA) &&
                    same(p.angularImpulseB, q.angularImpulseB))
            << i;
        const Real left[] = {p.mass, p.softness, p.bias, p.linearisedAt, p.impulse};
        const Real right[] = {q.mass, q.softness, q.bias, q.linearisedAt, q.impulse};
        EXPECT_EQ(std::memcmp(left, right, sizeof(left)), 0) << i;
    }
    for (std::size_t k = 0; k < net.bodies.size(); ++k) {
        EXPECT_TRUE(same(net.bodies[k].linearVelocity, deferred.bodies[k].linearVelocity) &&
                    same(net.bodies[k].angularVelocity, deferred.bodies[k].angularVelocity))
            << k;
    }
}

}  // namespace
}  // namespace tumble
