// Bodies on triangle meshes and height fields: no ghost bumps at internal edges (a sliding box
// stops where Coulomb friction says, a rolling ball keeps its speed), a ball rolls down a height
// field slope at (5/7) g sin(theta), and meshes are refused on dynamic bodies.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <random>
#include <set>
#include <string>
#include <vector>

#include "collision/mesh_fixtures.h"
#include "tumble/collision/mesh_shape.h"
#include "tumble/core/error.h"
#include "tumble/world.h"

namespace tumble {
namespace {

using testing::flatGrid;
using testing::heightGrid;

constexpr Real kGravity = 9.81;

struct Slide {
    Real travelled = 0;      ///< (m)
    Real worstVertical = 0;  ///< (m/s)
    Real finalSpeed = 0;     ///< (m/s)
};

/// A box launched at `speed` along a direction that crosses the cells' sides and diagonals.
Slide slideOn(const Shape& ground, Real mu, Real speed) {
    const Real half = 0.2;
    World world;
    const BodyId base = world.createBody(BodyDef{.type = BodyType::Static});
    ShapeDef groundDef{.geometry = ground};
    groundDef.material.friction = mu;
    world.createShape(base, groundDef);
    const Vec3 direction = Vec3(1, 0.3, 0).normalized();
    BodyDef def;
    def.position = Vec3(-3, -1, half) - 1.2 * direction;
    def.linearVelocity = speed * direction;
    const BodyId box = world.createBody(def);
    ShapeDef shape{.geometry = Box{Vec3::Constant(half)}};
    shape.material.friction = mu;
    world.createShape(box, shape);
    Slide slide;
    for (int step = 0; step < 240; ++step) {
        if (!world.step().ok())
            return slide;
        slide.worstVertical =
            std::max(slide.worstVertical, std::abs(world.linearVelocity(box).z()));
    }
    slide.travelled = (world.centerOfMass(box) - def.position).head<2>().norm();
    slide.finalSpeed = world.linearVelocity(box).norm();
    return slide;
}

TEST(MeshContact, BoxSlidingAcrossFlatMeshStopsAtCoulombDistanceWithoutBumps) {
    const Real mu = 0.5, speed = 5;
    const Slide mesh = slideOn(TriangleMesh::fromData(flatGrid(40, 0.25)), mu, speed);
    const Slide plane = slideOn(HalfSpace{}, mu, speed);
    const Real expected = speed * speed / (2 * mu * kGravity);
    std::printf(
        "box on mesh: stopped after %.5f m (Coulomb %.5f m, ratio %.5f; on a half-space "
        "%.5f m), worst |vz| %.3g m/s\n",
        mesh.travelled, expected, mesh.travelled / expected, plane.travelled, mesh.worstVertical);
    EXPECT_LT(mesh.finalSpeed, 1e-3) << "at rest";
    EXPECT_NEAR(mesh.travelled / expected, 1, 0.02);
    EXPECT_NEAR(mesh.travelled / plane.travelled, 1, 1e-3) << "the mesh slides like the plane";
    EXPECT_LT(mesh.worstVertical, 1e-3);
}

TEST(MeshContact, BallRollsAcrossFlatMeshAtConstantSpeed) {
    const Real r = 0.15, speed = 2;
    World world;
    const BodyId ground = world.createBody(BodyDef{.type = BodyType::Static});
    ShapeDef groundDef{.geometry = TriangleMesh::fromData(flatGrid(40, 0.25))};
    groundDef.material.friction = 0.6;
    world.createShape(ground, groundDef);
    const Vec3 direction = Vec3(1, 0.3, 0).normalized();
    BodyDef def;
    def.position = Vec3(-3, -1, r);
    def.linearVelocity = speed * direction;
    def.angularVelocity = (speed / r) * Vec3(-direction.y(), direction.x(), 0);  // v = w x (r z)
    const BodyId ball = world.createBody(def);
    ShapeDef shape{.geometry = Sphere{r}};
    shape.material.friction = 0.6;
    world.createShape(ball, shape);

    Real slowest = speed, fastest = speed, worstVertical = 0;
    for (int step = 0; step < 120; ++step) {  // 2 s: 4 m, across 16 cells and their diagonals
        ASSERT_TRUE(world.step().ok());
        const Real v = world.linearVelocity(ball).head<2>().norm();
        slowest = std::min(slowest, v);
        fastest = std::max(fastest, v);
        worstVertical = std::max(worstVertical, std::abs(world.linearVelocity(ball).z()));
    }
    std::printf("ball on mesh: speed %.6f .. %.6f m/s (start %.1f), worst |vz| %.3g m/s\n", slowest,
                fastest, speed, worstVertical);
    EXPECT_NEAR(slowest / speed, 1, 1e-3);
    EXPECT_NEAR(fastest / speed, 1, 1e-3);
    EXPECT_LT(worstVertical, 1e-3);
}

TEST(MeshContact, BallRollsDownHeightFieldSlopeAtFiveSeventhsGSinTheta) {
    const Real theta = 15 * std::numbers::pi / 180, r = 0.3;
    const HeightFieldData grid = heightGrid(81, 11, 0.5, 0.5, [&](std::uint32_t i, std::uint32_t) {
        return -std::tan(theta) * i * 0.5;
    });
    World world;
    const BodyId ground = world.createBody(BodyDef{.type = BodyType::Static});
    ShapeDef field{.geometry = HeightField::fromData(grid)};
    field.material.friction = 0.8;
    world.createShape(ground, field);
    const Vec3 normal(std::sin(theta), 0, std::cos(theta));
    const Vec3 downhill(std::cos(theta), 0, -std::sin(theta));
    BodyDef def;
    const Vec3 onSurface(2.0, 2.5, -std::tan(theta) * 2.0);
    def.position = onSurface + r * normal;
    const BodyId ball = world.createBody(def);
    ShapeDef shape{.geometry = Sphere{r}};
    shape.material.friction = 0.8;
    world.createShape(ball, shape);

    const int steps = 120;
    for (int step = 0; step < steps; ++step)
        ASSERT_TRUE(world.step().ok());
    const Real h = world.settings().timeStep;
    const Real measured = world.linearVelocity(ball).dot(downhill) / (steps * h);
    const Real expected = 5.0 / 7.0 * kGravity * std::sin(theta);
    std::printf("ball on height field: a / (5/7 g sin) = %.5f, off-slope speed %.3g m/s\n",
                measured / expected, std::abs(world.linearVelocity(ball).dot(normal)));
    EXPECT_NEAR(measured / expected, 1, 0.01);
    EXPECT_LT(std::abs(world.linearVelocity(ball).dot(normal)), 1e-3) << "stays on the surface";
}

TEST(MeshContact, DynamicBodiesRefuseMeshesAndHeightFieldsKinematicOnesTakeThem) {
    World world;
    const Shape mesh = TriangleMesh::fromData(flatGrid(2, 1));
    const BodyId dynamic = world.createBody(BodyDef{});
    EXPECT_THROW(world.createShape(dynamic, ShapeDef{.geometry = mesh}), InvalidArgument);
    const BodyId kinematic = world.createBody(BodyDef{.type = BodyType::Kinematic});
    const ShapeId shape = world.createShape(kinematic, ShapeDef{.geometry = mesh});
    EXPECT_TRUE(world.isValid(shape));
    EXPECT_THROW(world.setBodyType(kinematic, BodyType::Dynamic), InvalidArgument);
}

/// Every shape's candidates from the hierarchy against all triangles, for its current box.
void expectBvhMatchesBruteForce(const World& world, const std::vector<ShapeId>& shapes,
                                const MeshGeometry& mesh, int step) {
    for (const ShapeId id : shapes) {
        const Aabb box = boundsOf(world.shapeDef(id).geometry, world.shapeTransform(id));
        const testing::Candidates c = testing::candidatesFor(mesh, box);
        ASSERT_EQ(c.walked, c.brute) << "step " << step;
    }
}

/// 40 mixed bodies dropped from up to 16 m onto a 6 m square of 24 x 24 cells with random
/// heights up to 0.1 m (1,152 triangles), for 4 s at 60 Hz. Returns the lowest centre of mass seen
/// over the mesh's footprint.
Real dropPileOnRoughMesh(bool checkCandidates) {
    TriangleMeshData data = flatGrid(24, 0.25);
    std::mt19937 rng(26);
    std::uniform_real_distribution<Real> unit(0, 1);
    for (Vec3& v : data.vertices)
        v.z() = 0.1 * unit(rng);
    World world;
    const BodyId ground = world.createBody(BodyDef{.type = BodyType::Static});
    const TriangleMesh mesh = TriangleMesh::fromData(data);
    world.createShape(ground, ShapeDef{.geometry = mesh});
    std::vector<ShapeId> shapes;
    std::vector<BodyId> bodies;
    for (int k = 0; k < 40; ++k) {
        BodyDef def;
        def.position = Vec3(3 * unit(rng) - 1.5, 3 * unit(rng) - 1.5, 0.5 + 0.4 * k);
        def.orientation = Quat(unit(rng), unit(rng), unit(rng), unit(rng)).normalized();
        bodies.push_back(world.createBody(def));
        const Shape kinds[] = {Sphere{0.15}, Capsule{0.1, 0.15}, Box{Vec3(0.2, 0.15, 0.1)},
                               Cylinder{0.15, 0.1}};
        shapes.push_back(world.createShape(bodies.back(), ShapeDef{.geometry = kinds[k % 4]}));
    }
    Real lowest = INFINITY;
    for (int step = 0; step < 240; ++step) {
        EXPECT_TRUE(world.step().ok());
        if (checkCandidates)
            expectBvhMatchesBruteForce(world, shapes, *mesh.data, step);
        for (const BodyId body : bodies) {
            const Vec3 c = world.centerOfMass(body);
            if (std::abs(c.x()) < 3 && std::abs(c.y()) < 3)
                lowest = std::min(lowest, c.z());
        }
    }
    return lowest;
}

/// Lowest centre of mass, over 3 s at 60 Hz, of a tetrahedron dropped from 0.8 m onto a jagged
/// mesh (vertex v at z = 0.08 sin(1.7 v), 12 x 12 cells of 0.5 m), its body origin `lift` above its
/// base face.
struct HullDrop {
    Real lowest = INFINITY;  ///< (m)
};
HullDrop dropHullOnJaggedMesh(Real lift, const Vec3& spot, Real yaw) {
    TriangleMeshData data = flatGrid(12, 0.5);
    for (std::size_t v = 0; v < data.vertices.size(); ++v)
        data.vertices[v].z() = 0.08 * std::sin(1.7 * static_cast<Real>(v));
    World world;
    const BodyId ground = world.createBody(BodyDef{.type = BodyType::Static});
    world.createShape(ground, ShapeDef{.geometry = TriangleMesh::fromData(data)});
    const std::vector<Vec3> points{Vec3(0.2, 0, -lift), Vec3(-0.1, 0.17, -lift),
                                   Vec3(-0.1, -0.17, -lift), Vec3(0, 0, 0.25 - lift)};
    BodyDef def;
    def.position = spot + Vec3(0, 0, 0.8);
    def.orientation = Quat(Eigen::AngleAxis<Real>(yaw, Vec3::UnitZ()));
    def.allowSleep = false;
    const BodyId body = world.createBody(def);
    world.createShape(body, ShapeDef{.geometry = ConvexHull::fromPoints(points)});
    HullDrop drop;
    for (int step = 0; step < 180; ++step) {
        EXPECT_TRUE(world.step().ok());
        drop.lowest = std::min(drop.lowest, world.centerOfMass(body).z());
    }
    return drop;
}

// A hull whose body origin sits on its base (or anywhere off its middle) lands on a jagged mesh
// and stays on it. Reported on a branch before several manifolds per pair were merged: such a
// tetrahedron fell through at 3.9 m/s (the side a triangle is met from is judged from the shape's
// origin). Not reproduced since; this guards it. Resting is not asserted: on slopes up to 0.3
// one drop still moves at 0.05 m/s after 2 s (not yet explained).
TEST(MeshContact, HullsWithOffCentreOriginsRestOnAJaggedMesh) {
    std::mt19937 rng(2611);
    std::uniform_real_distribution<Real> unit(0, 1);
    for (const Real lift : {0.0, 0.06, 0.125, 0.25}) {
        for (int k = 0; k < 6; ++k) {
            const Vec3 spot(4 * unit(rng) - 2, 4 * unit(rng) - 2, 0);
            const HullDrop drop = dropHullOnJaggedMesh(lift, spot, 6.3 * unit(rng));
            SCOPED_TRACE("origin " + std::to_string(lift) + " m above the base, drop " +
                         std::to_string(k));
            // The centre of mass sits 0.0625 m above the base: never below the wave's trough.
            EXPECT_GT(drop.lowest, -0.08) << "fell through the mesh";
        }
    }
}

TEST(MeshContact, HierarchyCandidatesEqualBruteForceAtEveryStepOfAFallingPile) {
    dropPileOnRoughMesh(true);
}

// The tunnel check: no body's centre goes below the surface's lowest point (0 m) while over it.
// A capsule at 10 m/s once sank past its centre into this mesh and was pushed out of the back of
// the triangles: the side is now taken as the front unless the centre is well behind.
TEST(MeshContact, PileOnARoughMeshStaysOnIt) {
    const Real lowest = dropPileOnRoughMesh(false);
    std::printf(
        "pile on a rough mesh: lowest centre of mass over it at %.4f m (surface 0 .. 0.1 "
        "m)\n",
        lowest);
    EXPECT_GT(lowest, 0.0) << "a body fell through the mesh";
}

}  // namespace
}  // namespace tumble
