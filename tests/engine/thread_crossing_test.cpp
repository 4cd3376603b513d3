// The depth rule of a thread's rows (setRowDepth, thread_contacts.h) on a thin box wall: a
// thread crossing over the wall's top edge -- its nodes touching the wall's two sides, the edge
// between them -- keeps its real depth and pushes it out; a thread lying along the rim, its
// nodes on one side, keeps the rule it had (no push-out while both nodes touch the wall); a
// thread leaving a node on the edge over it counts no depth, one cutting through the wall does. The
// nodes' contacts and the capsule's points come from the ordinary narrowphase, the capsule
// trimmed a radius from each node as ThreadContacts::build does.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <random>
#include <vector>

#include "thread_contacts.h"
#include "tumble/collision/narrowphase.h"

namespace tumble {
namespace {

constexpr Real kHalfWidth = 0.002;  // of the wall (m): a 4 mm sheet
constexpr Real kTop = 0.5;          // of the wall (m)
constexpr Real kRadius = 0.01;      // of the nodes and the thread (m)
constexpr Real kMargin = 0.005;     // speculative (m)
constexpr std::uint32_t kWall = 7;  // the wall's body (dense index)

const Shape kWallShape = Box{Vec3(kHalfWidth, 0.5, kTop / 2)};
const Transform kWallPose{Vec3(0, 0, kTop / 2), Quat::Identity()};

// A node's contacts with the wall, as ThreadContacts gathers them (normal from the wall out).
std::vector<ThreadContacts::NodeContact> nodeContacts(const Vec3& p) {
    ManifoldSet set;
    collide(Sphere{kRadius}, Transform{p, Quat::Identity()}, kWallShape, kWallPose, kMargin, set);
    std::vector<ThreadContacts::NodeContact> contacts;
    for (int m = 0; m < set.count; ++m) {
        if (set.manifolds[m].pointCount > 0)
            contacts.push_back({kWall, Vec3(-set.manifolds[m].normal)});
    }
    return contacts;
}

Real boxDistance(const Vec3& p) {
    const Vec3 local = p - kWallPose.position;
    const Vec3 half = std::get<Box>(kWallShape).halfExtents;
    return (local.cwiseAbs() - half).cwiseMax(0).norm();
}

// Distance from the segment a-b to the wall: the point-to-box distance is convex along it.
Real segmentDistance(const Vec3& a, const Vec3& b) {
    Real lo = 0, hi = 1;
    for (int k = 0; k < 200; ++k) {
        const Real m1 = lo + (hi - lo) / 3, m2 = hi - (hi - lo) / 3;
        if (boxDistance(a + m1 * (b - a)) < boxDistance(a + m2 * (b - a)))
            hi = m2;
        else
            lo = m1;
    }
    return boxDistance(a + (lo + hi) / 2 * (b - a));
}

struct Rows {
    std::vector<SegmentContactRow> rows;
    std::vector<Real> separations;  ///< the capsule's, before the rule
    Vec3 coreA, coreB;              ///< the capsule's segment
};

// The thread's rows against the wall, as ThreadContacts::collideThread makes them.
Rows threadRows(const Vec3& pA, const Vec3& pB) {
    const Vec3 d = pB - pA;
    const Real length = d.norm();
    const Vec3 axis = d / length;
    Rows out{{}, {}, Vec3(pA + kRadius * axis), Vec3(pB - kRadius * axis)};
    const Vec3 core = out.coreB - out.coreA;
    const Transform pose{Vec3((out.coreA + out.coreB) / 2),
                         Quat::FromTwoVectors(Vec3::UnitZ(), core).normalized()};
    ManifoldSet set;
    collide(Capsule{kRadius, core.norm() / 2}, pose, kWallShape, kWallPose, kMargin, set);
    const std::vector<ThreadContacts::NodeContact> contactsA = nodeContacts(pA);
    const std::vector<ThreadContacts::NodeContact> contactsB = nodeContacts(pB);
    for (int m = 0; m < set.count; ++m) {
        for (int k = 0; k < set.manifolds[m].pointCount; ++k) {
            const ContactPoint& point = set.manifolds[m].points[k];
            SegmentContactRow& row = out.rows.emplace_back();
            row.t = std::clamp((point.position - pA).dot(d) / (length * length), Real(0), Real(1));
            row.normal = -set.manifolds[m].normal;
            out.separations.push_back(point.separation);
            const Vec3 onS = point.position + point.separation / 2 * set.manifolds[m].normal;
            setRowDepth(row, point.separation, kRadius, axis, contactsA, contactsB, kWall, onS - pA,
                        onS - pB);
        }
    }
    return out;
}

// A node touching the wall's top edge on the side `side` (+1: x > 0), `gap` from the edge line
// (<= kRadius: touching), at `angle` above the horizontal, at `y`.
Vec3 onEdge(int side, Real gap, Real angle, Real y) {
    return Vec3(side * (kHalfWidth + gap * std::cos(angle)), y, kTop + gap * std::sin(angle));
}

TEST(ThreadCrossing, AThreadCrossingOverAThinWallsEdgeKeepsItsDepthAndPushes) {
    // Tolerance, written before measuring: the deepest row's separation equals the capsule
    // segment's distance to the wall less the radius within 1e-5 m (a hundredth of the 1 mm
    // slop), and every row pushes out.
    std::mt19937 random(26);
    std::uniform_real_distribution<Real> gap(kRadius - 0.003, kRadius);
    std::uniform_real_distribution<Real> rise(5 * std::numbers::pi / 180, std::numbers::pi / 6);
    std::uniform_real_distribution<Real> turn(-2 * std::numbers::pi / 9, 2 * std::numbers::pi / 9);
    std::uniform_real_distribution<Real> along(-0.3, 0.3);
    int crossings = 0;
    for (int trial = 0; trial < 1000; ++trial) {
        const Vec3 pA = onEdge(-1, gap(random), rise(random), along(random));
        Vec3 pB = onEdge(+1, gap(random), rise(random), 0);
        pB.y() = pA.y() + (pB.x() - pA.x()) * std::tan(turn(random));  // across at that angle
        const Rows rows = threadRows(pA, pB);
        ASSERT_FALSE(nodeContacts(pA).empty());
        ASSERT_FALSE(nodeContacts(pB).empty());
        if (rows.rows.empty())
            continue;  // the capsule is clear of the wall beyond the margin
        ++crossings;
        Real deepest = rows.rows[0].separation;
        for (const SegmentContactRow& row : rows.rows) {
            deepest = std::min(deepest, row.separation);
            EXPECT_TRUE(row.pushOut) << "trial " << trial;
        }
        EXPECT_NEAR(deepest, segmentDistance(rows.coreA, rows.coreB) - kRadius, 1e-5)
            << "trial " << trial;
    }
    EXPECT_GT(crossings, 900);  // the cases asked are the ones tested
}

TEST(ThreadCrossing, AThreadAlongARimKeepsTheRimsRule) {
    // Exact (the same rule): a thread along the top edge (within 20 degrees), both nodes on it
    // on one side, pushes out nothing while both nodes touch the wall, and takes the sag
    // allowance only where both rest on the row's side.
    std::mt19937 random(27);
    std::uniform_real_distribution<Real> gap(kRadius - 0.003, kRadius);
    std::uniform_real_distribution<Real> around(0, std::numbers::pi / 2);
    std::uniform_real_distribution<Real> slant(-std::numbers::pi / 9, std::numbers::pi / 9);
    std::uniform_real_distribution<Real> along(-0.3, 0.3);
    int rows = 0;
    for (int trial = 0; trial < 1000; ++trial) {
        const Vec3 pA = onEdge(+1, gap(random), around(random), along(random));
        Vec3 pB = onEdge(+1, gap(random), around(random), 0);
        pB.y() = pA.y() + 0.1;
        pB.z() += 0.1 * std::tan(slant(random));  // still touching: the edge ends at y = 0.5
        const bool touchesB = !nodeContacts(pB).empty();
        const Rows thread = threadRows(pA, pB);
        for (std::size_t k = 0; k < thread.rows.size(); ++k) {
            const SegmentContactRow& row = thread.rows[k];
            ++rows;
            const auto restsOnSide = [&](const Vec3& p) {
                for (const ThreadContacts::NodeContact& contact : nodeContacts(p)) {
                    if (contact.out.dot(row.normal) > 0.75)
                        return true;
                }
                return false;
            };
            const bool resting = touchesB && restsOnSide(pA) && restsOnSide(pB);
            EXPECT_EQ(row.pushOut, !touchesB) << "trial " << trial;
            EXPECT_EQ(row.separation,
                      thread.separations[k] + (resting ? 4 * kRadius * row.t * (1 - row.t) : 0))
                << "trial " << trial;
        }
    }
    EXPECT_GT(rows, 500);
}

// A node resting on the wall's top edge on the +x side: on the edge line (`onEdge`, between the
// top face and the side face) or on the top face within 3 mm of the edge.
Vec3 restingOnEdge(std::mt19937& random) {
    std::uniform_real_distribution<Real> gap(kRadius - 0.001, kRadius);
    std::uniform_real_distribution<Real> around(std::numbers::pi / 4, std::numbers::pi / 2);
    std::uniform_real_distribution<Real> inset(0, 0.003);
    std::uniform_real_distribution<Real> along(-0.3, 0.3);
    if (std::bernoulli_distribution(0.5)(random))
        return onEdge(+1, gap(random), around(random), along(random));
    return Vec3(kHalfWidth - inset(random), along(random), kTop + gap(random));
}

TEST(ThreadCrossing, AThreadLeavingANodeOnTheEdgeOverItCountsNoDepth) {
    // Tolerance, written before measuring: a thread from a node resting on the edge down the
    // wall's far side of it (slope 0 - 80 degrees, turned up to 30 degrees, its other node clear
    // of the wall) reports no row deeper than 1e-5 m (a hundredth of the 1 mm slop).
    std::mt19937 random(28);
    std::uniform_real_distribution<Real> slope(0, 4 * std::numbers::pi / 9);
    std::uniform_real_distribution<Real> turn(-std::numbers::pi / 6, std::numbers::pi / 6);
    int overlapping = 0;  // trials whose capsule overlaps the wall
    for (int trial = 0; trial < 1000; ++trial) {
        const Vec3 pA = restingOnEdge(random);
        const Real phi = slope(random), psi = turn(random);
        const Vec3 away(std::cos(phi) * std::cos(psi), std::cos(phi) * std::sin(psi),
                        -std::sin(phi));
        const Vec3 pB = pA + 0.1 * away;
        ASSERT_FALSE(nodeContacts(pA).empty());
        if (!nodeContacts(pB).empty() || segmentDistance(pA, pB) < 1e-6)
            continue;  // not clear of the wall, or cutting through it (the next test)
        const Rows rows = threadRows(pA, pB);
        for (std::size_t k = 0; k < rows.rows.size(); ++k) {
            overlapping += rows.separations[k] < -1e-5 ? 1 : 0;
            EXPECT_GE(rows.rows[k].separation, -1e-5)
                << "trial " << trial << " phi " << phi << " psi " << psi << " A " << pA.transpose()
                << " t " << rows.rows[k].t << " n " << rows.rows[k].normal.transpose();
        }
    }
    EXPECT_GT(overlapping, 100);  // the capsule does reach over the edge
}

TEST(ThreadCrossing, AThreadCuttingThroughTheWallFromANodeOnItsEdgeKeepsItsDepth) {
    // Tolerance, written before measuring: a thread from a node resting on the edge through the
    // wall to a node clear of its other side has a row at least a radius deep (its segment meets
    // the wall) within 1e-5 m, and that row pushes out.
    std::mt19937 random(29);
    std::uniform_real_distribution<Real> slope(std::numbers::pi / 18, 4 * std::numbers::pi / 9);
    std::uniform_real_distribution<Real> turn(-std::numbers::pi / 6, std::numbers::pi / 6);
    int cutting = 0;
    for (int trial = 0; trial < 1000; ++trial) {
        const Vec3 pA = restingOnEdge(random);
        const Real phi = slope(random), psi = turn(random);
        const Vec3 away(-std::cos(phi) * std::cos(psi), std::cos(phi) * std::sin(psi),
                        -std::sin(phi));
        const Vec3 pB = pA + 0.1 * away;
        if (!nodeContacts(pB).empty() || segmentDistance(pA, pB) >= 1e-6)
            continue;  // not clear of the wall, or not through it
        ++cutting;
        const Rows rows = threadRows(pA, pB);
        bool deep = false;
        for (const SegmentContactRow& row : rows.rows)
            deep = deep || (row.separation <= -kRadius + 1e-5 && row.pushOut);
        EXPECT_TRUE(deep) << "trial " << trial;
    }
    EXPECT_GT(cutting, 200);
}

}  // namespace
}  // namespace tumble
