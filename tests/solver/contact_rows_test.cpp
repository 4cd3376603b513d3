// The contact sweeps on coloured wide rows (contact_rows.h) against the narrow sweeps: the same
// rows updated in an order each body sees as constraint order, so the same bits.

#include "tumble/solver/contact_rows.h"

#include <gtest/gtest.h>

#include <vector>

#include "testkit/solver_scenes.h"
#include "tumble/solver/constraint_solver.h"

namespace tumble {
namespace {

constexpr Real kG = 9.81;
constexpr Real kH = 1.0 / 60;

// Body 0: static ground. Bodies 1..columns*height: unit cubes of 1 kg in `columns` columns of
// `height`, each resting on the one below (the first on the ground), with friction 0.5.
struct Stacks {
    std::vector<SolverBody> bodies;
    std::vector<ContactConstraint> constraints;
    std::vector<PseudoVelocity> pseudo;
    ConstraintSolver solver;
    SolverSettings settings;

    Stacks(int columns, int height, bool coloured) {
        bodies.resize(1 + columns * height);
        for (std::size_t i = 1; i < bodies.size(); ++i) {
            bodies[i].inverseMass = 1;
            bodies[i].inverseInertia = Mat3::Identity() * 6;
        }
        for (int level = 0; level < height; ++level) {
            for (int column = 0; column < columns; ++column) {
                const auto cube = static_cast<std::uint32_t>(1 + column * height + level);
                ContactConstraint c = testkit::cubeOnGround(cube, 0.5);
                if (level > 0) {
                    c.bodyA = cube - 1;
                    for (int i = 0; i < 4; ++i)
                        c.points[i].rA.z() = 0.5;
                }
                constraints.push_back(c);
            }
        }
        settings.iterations = 200;
        settings.relaxIterations = 200;
        settings.colouredContacts = coloured;
    }
    void step() {
        for (std::size_t i = 1; i < bodies.size(); ++i)
            bodies[i].linearVelocity.z() -= kG * kH;
        solver.solve(bodies, constraints, pseudo, kH, settings);
    }
    // Sum of the normal impulses under cube level `level` of column `column` (N s).
    Real load(int columns, int column, int level) const {
        Real sum = 0;
        for (const ContactConstraintPoint& p : constraints[level * columns + column].points)
            sum += p.normalImpulse;
        return sum;
    }
};

// Every body's velocity to the bit.
void expectSameVelocities(const Stacks& wide, const Stacks& narrow) {
    for (std::size_t i = 0; i < wide.bodies.size(); ++i) {
        for (int k = 0; k < 3; ++k) {
            EXPECT_EQ(wide.bodies[i].linearVelocity[k], narrow.bodies[i].linearVelocity[k]);
            EXPECT_EQ(wide.bodies[i].angularVelocity[k], narrow.bodies[i].angularVelocity[k]);
        }
    }
}

TEST(ContactRows, StacksCarryTheirWeightAsTheNarrowSweepsDo) {
    // 5 columns of 3: 15 manifolds, 3 colours (one per level), bundles of 4 with padding.
    constexpr int kColumns = 5;
    constexpr int kHeight = 3;
    Stacks wide(kColumns, kHeight, true);
    Stacks narrow(kColumns, kHeight, false);
    for (int s = 0; s < 30; ++s) {
        wide.step();
        narrow.step();
    }
    for (int column = 0; column < kColumns; ++column) {
        for (int level = 0; level < kHeight; ++level) {
            const Real weight = (kHeight - level) * kG * kH;
            EXPECT_NEAR(wide.load(kColumns, column, level), weight, 1e-9 * weight);
            EXPECT_NEAR(wide.load(kColumns, column, level), narrow.load(kColumns, column, level),
                        1e-9 * weight);
        }
    }
    for (std::size_t i = 1; i < wide.bodies.size(); ++i) {
        EXPECT_LT(wide.bodies[i].linearVelocity.norm(), 1e-9) << "cube " << i;
        EXPECT_LT(wide.bodies[i].angularVelocity.norm(), 1e-9) << "cube " << i;
    }
}

TEST(ContactRows, SlidingBoxLosesTheSameSpeedAsInTheNarrowSweeps) {
    for (const FrictionModel model : {FrictionModel::Coupled, FrictionModel::Box}) {
        Stacks wide(1, 1, true);
        Stacks narrow(1, 1, false);
        for (Stacks* s : {&wide, &narrow}) {
            s->settings.friction = model;
            s->bodies[1].linearVelocity = Vec3(1.2, 1.6, 0);
            s->step();
        }
        // One step of friction removes mu g h of speed (coupled) from 2 m/s.
        EXPECT_NEAR((wide.bodies[1].linearVelocity - narrow.bodies[1].linearVelocity).norm(), 0,
                    1e-12);
        if (model == FrictionModel::Coupled) {
            EXPECT_NEAR(wide.bodies[1].linearVelocity.norm(), 2 - 0.5 * kG * kH, 1e-9);
        }
    }
}

TEST(ContactRows, ToleranceStopsEarly) {
    Stacks wide(3, 2, true);
    wide.settings.iterations = 100;
    wide.settings.tolerance = 1e-9;
    for (int s = 0; s < 10; ++s)
        wide.step();
    const SolverStats stats =
        wide.solver.solve(wide.bodies, wide.constraints, wide.pseudo, kH, wide.settings);
    EXPECT_LT(stats.iterations, 100);
}

TEST(ContactRows, ChainColoursGiveTheNarrowSweepsBits) {
    // 4 columns of 4 with a spinning cube, 10 + 10 sweeps (far from converged): 4 colours of 4
    // manifolds, each column's chain kept bottom to top.
    Stacks wide(4, 4, true);
    Stacks narrow(4, 4, false);
    for (Stacks* s : {&wide, &narrow}) {
        s->settings.iterations = 10;
        s->settings.relaxIterations = 10;
        s->bodies[5].angularVelocity = Vec3(0.3, -0.2, 0.1);
    }
    for (int s = 0; s < 20; ++s) {
        wide.step();
        narrow.step();
    }
    ContactRows rows;
    ASSERT_TRUE(rows.build(wide.bodies, wide.constraints, wide.settings, 1 / kH));
    EXPECT_EQ(rows.colourCount(), 4);
    expectSameVelocities(wide, narrow);
    for (std::size_t m = 0; m < wide.constraints.size(); ++m) {
        for (int i = 0; i < 4; ++i)
            EXPECT_EQ(wide.constraints[m].points[i].normalImpulse,
                      narrow.constraints[m].points[i].normalImpulse);
    }
}

TEST(ContactRows, OnePointBundlesAndTheRimGiveTheNarrowSweepsBits) {
    // Each level: two manifolds of one point (as a pile's spheres) and two of four, so a colour
    // makes a one-slot and a four-slot bundle; every cube slides, so friction solves on the
    // disc's rim, in the lanes.
    Stacks wide(4, 3, true);
    Stacks narrow(4, 3, false);
    for (Stacks* s : {&wide, &narrow}) {
        s->settings.iterations = 10;
        s->settings.relaxIterations = 10;
        for (std::size_t m = 0; m < s->constraints.size(); ++m) {
            if (m % 4 < 2)
                s->constraints[m].pointCount = 1;
        }
        for (std::size_t i = 1; i < s->bodies.size(); ++i)
            s->bodies[i].linearVelocity = Vec3(1.2 + 0.1 * static_cast<Real>(i), -0.4, 0);
    }
    for (int s = 0; s < 5; ++s) {
        wide.step();
        narrow.step();
    }
    ContactRows rows;
    ASSERT_TRUE(rows.build(wide.bodies, wide.constraints, wide.settings, 1 / kH));
    expectSameVelocities(wide, narrow);
    // A column's bottom cube (2.2 m/s at first, its column pushing it on) still slides: its
    // points were on the rim to the end.
    EXPECT_GT(wide.bodies[10].linearVelocity.head<2>().norm(), 1.0);
}

TEST(ContactRows, ALoneColumnLeavesTheLanesToTheScalarSweep) {
    // One column of 8: a colour per level, one lane of four used; two columns half the lanes.
    const Stacks lone(1, 8, true);
    ContactRows rows;
    EXPECT_FALSE(rows.build(lone.bodies, lone.constraints, lone.settings, 1 / kH));
    EXPECT_EQ(rows.colourCount(), 8);
    const Stacks pair(2, 8, true);
    EXPECT_TRUE(rows.build(pair.bodies, pair.constraints, pair.settings, 1 / kH));
    EXPECT_EQ(rows.colourCount(), 8);
}

TEST(ContactRows, SameInputSameBits) {
    Stacks first(4, 4, true);
    Stacks second(4, 4, true);
    first.bodies[5].angularVelocity = Vec3(0.3, -0.2, 0.1);
    second.bodies[5].angularVelocity = Vec3(0.3, -0.2, 0.1);
    for (int s = 0; s < 20; ++s) {
        first.step();
        second.step();
    }
    for (std::size_t i = 0; i < first.bodies.size(); ++i) {
        for (int k = 0; k < 3; ++k) {
            EXPECT_EQ(first.bodies[i].linearVelocity[k], second.bodies[i].linearVelocity[k]);
            EXPECT_EQ(first.bodies[i].angularVelocity[k], second.bodies[i].angularVelocity[k]);
        }
    }
}

}  // namespace
}  // namespace tumble
