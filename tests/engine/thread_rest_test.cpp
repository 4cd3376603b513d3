// A net whose threads collide (ThreadDef::collide) comes to rest where it is draped: over a box's
// edge, over a faceted cylinder of triangles (its skirt on the curved wall, as dustbin-mesh's),
// across the opening of an open bin of thin triangle walls (dustbin-mesh's rim) and flat on a
// half-space. Dropped across the top edge of a single thin wall, it hangs on it, its threads
// through the wall below the edge leaving over the edge, not sideways.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <vector>

#include "tumble/collision/mesh_data.h"
#include "tumble/lumped.h"
#include "tumble/world.h"

namespace tumble {
namespace {

enum class Support { BoxEdge, MeshCylinder, OpenBin, ThinWall, HalfSpace };

constexpr Real kCylinderRadius = 0.15;
constexpr Real kTop = 0.5;  // of the box and the cylinder (m)

// A cylinder of `sides` facets about z, from the ground to kTop: closed by a lid, or open (the
// wall alone, of no thickness, as dustbin-mesh's bin).
TriangleMeshData cylinder(int sides, bool lid = true) {
    TriangleMeshData mesh;
    mesh.vertices.push_back(Vec3(0, 0, kTop));
    for (int k = 0; k < sides; ++k) {
        const Real a = 2 * std::numbers::pi * k / sides;
        const Vec3 rim(kCylinderRadius * std::cos(a), kCylinderRadius * std::sin(a), 0);
        mesh.vertices.push_back(rim);
        mesh.vertices.push_back(rim + Vec3(0, 0, kTop));
    }
    const auto bottom = [&](int k) { return std::uint32_t(1 + 2 * (k % sides)); };
    for (int k = 0; k < sides; ++k) {
        const std::uint32_t b0 = bottom(k), b1 = bottom(k + 1);
        mesh.triangles.push_back({b0, b1, b1 + 1});
        mesh.triangles.push_back({b0, b1 + 1, b0 + 1});
        if (lid)
            mesh.triangles.push_back({0, b0 + 1, b1 + 1});
    }
    return mesh;
}

// A wall of no thickness in the plane x = 0, 1 m long, from the ground to kTop, of 10 panels.
TriangleMeshData thinWall() {
    TriangleMeshData mesh;
    constexpr int kPanels = 10;
    for (int k = 0; k <= kPanels; ++k) {
        const Real y = -0.5 + Real(k) / kPanels;
        mesh.vertices.push_back(Vec3(0, y, 0));
        mesh.vertices.push_back(Vec3(0, y, kTop));
    }
    for (std::uint32_t k = 0; k < kPanels; ++k) {
        const std::uint32_t b0 = 2 * k, b1 = 2 * k + 2;
        mesh.triangles.push_back({b0, b1, b1 + 1});
        mesh.triangles.push_back({b0, b1 + 1, b0 + 1});
    }
    return mesh;
}

// Where a net lands across the thin wall: its middle `offset` off the wall's plane (x), of `rows`
// rows along x, 0.1 m apart (0: n).
struct WallDrop {
    Real offset;
    int rows;
};

// The support, and a net of n x n nodes (dustbin-mesh's: 10 g, 1 cm, threads of 1e3 N over
// 0.1 m, colliding) dropped onto it from 5 cm above.
Lumped build(World& world, Support support, int n, WallDrop drop = {0.01, 0}) {
    const BodyDef ground{.type = BodyType::Static};
    const Material bin{.friction = 0.4};
    world.createShape(world.createBody(ground), ShapeDef{.geometry = HalfSpace{}, .material = bin});
    Vec3 center(0, 0, 0.06);
    if (support == Support::BoxEdge) {
        // The net's middle row of nodes over the box's edge at x = 0: half of it hangs down.
        const BodyId box = world.createBody(ground);
        ShapeDef def{.geometry = Box{Vec3(0.5, 0.5, kTop / 2)}, .material = bin};
        def.localPose.position = Vec3(-0.5, 0, kTop / 2);
        world.createShape(box, def);
        center = Vec3(0.03, 0, kTop + 0.05);
    } else if (support == Support::MeshCylinder || support == Support::OpenBin) {
        const BodyId body = world.createBody(ground);
        const bool lid = support == Support::MeshCylinder;
        world.createShape(body, ShapeDef{.geometry = TriangleMesh::fromData(cylinder(24, lid)),
                                         .material = Material{.friction = 0.4}});
        center = Vec3(0, 0, kTop + 0.05);
    } else if (support == Support::ThinWall) {
        // By default no node over the wall: the threads of the middle cells land on its edge.
        world.createShape(world.createBody(ground),
                          ShapeDef{.geometry = TriangleMesh::fromData(thinWall()),
                                   .material = Material{.friction = 0.4}});
        center = Vec3(drop.offset, 0, kTop + 0.05);
    }
    NetDef net;
    net.rows = drop.rows > 0 ? drop.rows : n;
    net.columns = n;
    net.center = center;
    net.node = NodeDef{.mass = 0.01, .radius = 0.01, .collide = true};
    net.node.material.friction = 0.4;
    net.thread.axialRigidity = 1e3;
    net.thread.damping = 0.05;
    net.thread.collide = true;
    return createNet(world, net);
}

Real medianSpeed(const World& world, const Lumped& net) {
    std::vector<Real> speeds;
    for (const BodyId node : net.nodes)
        speeds.push_back(world.linearVelocity(node).norm());
    std::nth_element(speeds.begin(), speeds.begin() + speeds.size() / 2, speeds.end());
    return speeds[speeds.size() / 2];
}

// Kinetic, gravitational and elastic energy of the net (J).
Real netEnergy(const World& world, const Lumped& net) {
    Real gravity = 0;
    for (const BodyId node : net.nodes)
        gravity += 0.01 * 9.81 * world.position(node).z();
    return world.kineticEnergy() + gravity + world.springPotentialEnergy();
}

class ThreadRest : public ::testing::TestWithParam<Support> {};

// A net dropped across a single thin wall's edge (5 cm above it), its middle `offset` off the
// wall's plane, of `rows` rows: the rows nearest the wall land on the edge, the halves fold
// down either side. Rest is not asked of this support, unlike the others: the row on the edge
// props its threads over the corner, so the halves hang 3 - 4 cm clear of the wall and swing as
// free pendulums, a mode the threads' axial damping does not touch and no contact reaches (8
// rows, 1 cm off: kinetic energy 10 mJ at 1 s, 2.7 mJ at 2 s, 0.5 - 2 mJ from 3 s to 5 s;
// with a node drag of 0.01 N s/m, 0.04 mJ at 5 s).
struct WallRun {
    Real largestGain = 0;  ///< in one step, after landing (0.5 s) (J)
    int crossed = 0;       ///< node-steps below the edge on the other side from their drop
    Real lowestNear = 1;   ///< lowest node of the rows dropped within a mesh size of the wall
};

WallRun dropOnWall(const WallDrop& drop) {
    WorldDef def;
    def.timeStep = 1.0 / 120;
    def.enableSleep = false;
    World world(def);
    const Real firstRow = drop.offset - 0.05 * (drop.rows - 1);  // build()'s row 0 (x)
    const Lumped net = build(world, Support::ThinWall, 8, drop);
    WallRun run;
    Real before = netEnergy(world, net);
    for (int step = 0; step < 480; ++step) {
        if (!world.step().ok())
            return WallRun{1, 1, 0};
        const Real now = netEnergy(world, net);
        if (step >= 60)
            run.largestGain = std::max(run.largestGain, now - before);
        before = now;
        for (int row = 0; row < drop.rows; ++row) {
            const Real x0 = firstRow + 0.1 * row;
            if (std::abs(x0) <= 0.01)  // dropped onto the edge: on neither side
                continue;
            for (int column = 0; column < 8; ++column) {
                const Vec3 p = world.position(net.nodes[row * 8 + column]);
                if (p.z() < kTop && p.x() * x0 < 0)
                    ++run.crossed;
            }
        }
    }
    for (int row = 0; row < drop.rows; ++row) {
        if (std::abs(firstRow + 0.1 * row) < 0.1) {
            for (int column = 0; column < 8; ++column)
                run.lowestNear =
                    std::min(run.lowestNear, world.position(net.nodes[row * 8 + column]).z());
        }
    }
    return run;
}

const WallDrop kWallDrops[] = {{0, 8},    {0, 9},    {0.01, 8}, {0.01, 9}, {0.02, 8},
                               {0.02, 9}, {0.03, 8}, {0.03, 9}, {0.05, 8}, {0.05, 9}};

TEST(ThreadRestThinWall, ThreadsThroughTheWallLeaveOverItsEdge) {
    // Tolerance, written before measuring: no node below the edge is ever on the other side of
    // the wall from where it was dropped, and the threads hold the net on the wall: the rows
    // dropped within a mesh size of it end no lower than a mesh size below the edge.
    for (const WallDrop& drop : kWallDrops) {
        const WallRun run = dropOnWall(drop);
        EXPECT_EQ(run.crossed, 0) << "offset " << drop.offset << ", " << drop.rows << " rows";
        EXPECT_GT(run.lowestNear, kTop - 0.1)
            << "offset " << drop.offset << ", " << drop.rows << " rows";
    }
}

// Largest gain in one step after 0.5 s, by (offset m, rows): (0, 8) 0.35 mJ, (0, 9) 0.085,
// (0.01, 8) 0.29, (0.01, 9) 0.16, (0.02, 8) 0.099, (0.02, 9) 0.64, (0.03, 8) 0.00003, (0.03, 9)
// 0.13, (0.05, 8) 0.028, (0.05, 9) 0.16 (1.9 before a thread leaving a node on the edge over it
// counted no depth: its 5 - 7 mm, pushed at the cap, lifted the nodes with their threads).
TEST(ThreadRestThinWall, LandsWithoutKicks) {
    // Tolerance, written before measuring: once the net has landed (0.5 s), no step gains more
    // than 1 mJ of energy (dustbin-mesh's kicks pushing threads sideways through its thin wall
    // were 0.3 J in one step).
    for (const WallDrop& drop : kWallDrops)
        EXPECT_LT(dropOnWall(drop).largestGain, 1e-3)
            << "offset " << drop.offset << ", " << drop.rows << " rows";
}

TEST_P(ThreadRest, ADrapedNetComesToRest) {
    // Tolerance, written before measuring: after 2 s the median node speed is below 1 mm/s (no
    // sleeping: the net must settle by itself). Held at every step of the second after, not
    // only at 2 s: on the box edge the net slides in stick-slip jerks until ~1.9 s (median
    // 4.7 mm/s at 1.917 s), so one sample could pass or fail by a jerk's phase; from 2 s to
    // 3 s the worst step is 8.5e-7 (box edge), 1.7e-5 (cylinder), 1.3e-5 (bin), 6e-26 (ground).
    WorldDef def;
    def.timeStep = 1.0 / 120;
    def.enableSleep = false;
    World world(def);
    const Lumped net = build(world, GetParam(), 8);
    Real worst = 0;
    for (int step = 1; step <= 360; ++step) {
        ASSERT_TRUE(world.step().ok());
        if (step >= 240)
            worst = std::max(worst, medianSpeed(world, net));
    }
    EXPECT_LT(worst, 1e-3);
    if (GetParam() == Support::OpenBin) {
        // Held across the opening by the threads on the rim: the middle node no lower than the
        // net's own mesh size below the rim, not on the ground inside.
        const Vec3 middle = world.position(net.nodes[4 * 8 + 4]);
        EXPECT_GT(middle.z(), kTop - 0.1);
        EXPECT_LT(std::hypot(middle.x(), middle.y()), kCylinderRadius);
    }
}

INSTANTIATE_TEST_SUITE_P(Supports, ThreadRest,
                         ::testing::Values(Support::BoxEdge, Support::MeshCylinder,
                                           Support::OpenBin, Support::HalfSpace),
                         [](const auto& param) {
                             switch (param.param) {
                                 case Support::BoxEdge:
                                     return std::string("BoxEdge");
                                 case Support::MeshCylinder:
                                     return std::string("MeshCylinder");
                                 case Support::OpenBin:
                                     return std::string("OpenBin");
                                 default:
                                     return std::string("HalfSpace");
                             }
                         });

}  // namespace
}  // namespace tumble
