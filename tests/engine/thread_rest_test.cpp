// A net whose threads collide (ThreadDef::collide) comes to rest where it is draped: over a box's
// edge, over a faceted cylinder of triangles (its skirt on the curved wall, as dustbin-mesh's),
// across the opening of an open bin of thin triangle walls (dustbin-mesh's rim), over the top
// edge of a single thin wall (its threads through the wall below the rim leave over the edge, not
// sideways) and flat on a half-space.

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

// The support, and a net of n x n nodes (dustbin-mesh's: 10 g, 1 cm, threads of 1e3 N over
// 0.1 m, colliding) dropped onto it from 5 cm above.
Lumped build(World& world, Support support, int n) {
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
        // No node over the wall: the threads of the middle column of cells land on its edge.
        world.createShape(world.createBody(ground),
                          ShapeDef{.geometry = TriangleMesh::fromData(thinWall()),
                                   .material = Material{.friction = 0.4}});
        center = Vec3(0.01, 0, kTop + 0.05);
    }
    NetDef net;
    net.rows = n;
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

// Disabled: not met yet (a known limit, docs/ARCHITECTURE.md, thread contacts). Measured with
// the mesh narrowphase's gap points past a sheet's border dropped and its side taken by the
// shape's reach along the face normal: the largest gain after 0.5 s is 0.30 mJ (at 0.73 s) and
// the net no longer slides over the edge (row 3's middle node on it, 0.1 mm past the wall's
// plane, row 4's 8 cm below it), but it hangs clear of the wall and swings: median node speed
// 49 mm/s at 2 s. Before: gain 2.1 mJ, the net slid 1.5 rows over the edge (middle nodes 0.18 /
// 0.28 m below it on the far side), 2.3 mm/s at 2 s. Why it swings (probed step by step): no
// kick feeds it. Row 3 sits on the edge, 1.4 cm above it, its threads' capsules (1 cm) resting
// on the edge at the slop, so rows 2 and 4 hang 3.5 - 4 cm out from the wall and the rows below
// them, clear of it, swing as free pendulums in x (row 1 at 0.2 m/s); the threads' axial
// damping does not touch that mode. From 2.5 s to 4 s the net's energy stays within 0.7 mJ
// (kinetic 0.5 - 2 mJ), no thread contact ends, and with a node drag of 0.01 N s/m the median
// is still 74 mm/s at 2 s. Row 3's middle node ends 0.08 mm past the plane on the edge (the
// side check fails by that too).
TEST(ThreadRestThinWall, DISABLED_ThreadsThroughTheWallLeaveOverItsEdgeWithoutKicks) {
    // Tolerance, written before measuring: once the net has landed (0.5 s), no step gains more
    // than 1 mJ of energy (dustbin-mesh's kicks pushing threads sideways through its thin wall
    // were 0.3 J in one step), the threads hold the net on the wall: its middle nodes no lower
    // than a mesh size below the edge, on the side they fell; and it comes to rest as on the
    // other supports (ThreadRest: median below 1 mm/s after 2 s).
    WorldDef def;
    def.timeStep = 1.0 / 120;
    def.enableSleep = false;
    World world(def);
    const Lumped net = build(world, Support::ThinWall, 8);
    Real before = netEnergy(world, net);
    Real largestGain = 0;
    for (int step = 0; step < 240; ++step) {
        ASSERT_TRUE(world.step().ok());
        const Real now = netEnergy(world, net);
        if (step >= 60)
            largestGain = std::max(largestGain, now - before);
        before = now;
    }
    EXPECT_LT(largestGain, 1e-3);
    EXPECT_LT(medianSpeed(world, net), 1e-3);
    for (const int row : {3, 4}) {  // at x = -0.04 and 0.06 when dropped
        const Vec3 p = world.position(net.nodes[row * 8 + 4]);
        EXPECT_GT(p.z(), kTop - 0.1) << "row " << row;
        EXPECT_GT(p.x() * (row == 3 ? -1 : 1), 0) << "row " << row;
    }
}

TEST_P(ThreadRest, ADrapedNetComesToRest) {
    // Tolerance, written before measuring: after 2 s the median node speed is below 1 mm/s (no
    // sleeping: the net must settle by itself).
    WorldDef def;
    def.timeStep = 1.0 / 120;
    def.enableSleep = false;
    World world(def);
    const Lumped net = build(world, GetParam(), 8);
    for (int step = 0; step < 240; ++step)
        ASSERT_TRUE(world.step().ok());
    EXPECT_LT(medianSpeed(world, net), 1e-3);
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
