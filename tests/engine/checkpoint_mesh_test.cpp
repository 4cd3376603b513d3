// Checkpoints of worlds holding triangle meshes and height fields: the geometry travels in the
// checkpoint's mesh section (each surface once, however many shapes share it) and is built again
// on load, so a resumed world continues bitwise-identically with no scene file; a mesh section
// that is corrupt, truncated or of another version is refused naming what is wrong, with the
// world left as it was.

#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <string>
#include <vector>

#include "collision/mesh_fixtures.h"
#include "engine/checkpoint_resume.h"
#include "refusal.h"
#include "testkit/same_ids.h"
#include "tumble/checkpoint.h"
#include "tumble/collision/mesh_shape.h"
#include "tumble/world.h"

namespace tumble {
namespace {

using test::addBody;
using test::contains;
using test::readU64;
using test::refusal;
using test::Scene;
using test::writeU64;
using testing::flatGrid;
using testing::heightGrid;

/// A vertex coordinate found nowhere else in the payload, to locate the mesh section (m).
constexpr Real kMarkerX = -2.718281828459045;
/// Likewise for the first height sample (m).
constexpr Real kMarkerHeight = 0.314159265358979;

/// A bumpy mesh (a grid with raised vertices, one marked, and one degenerate triangle that the
/// builder drops), a rolling height field with a hole, and a kinematic platform that shares the
/// mesh; boxes, spheres, capsules and a hull land and slide on all three.
Scene surfaceScene() {
    Scene s;
    TriangleMeshData bumps = flatGrid(12, 0.5);
    for (std::size_t v = 0; v < bumps.vertices.size(); ++v)
        bumps.vertices[v].z() = 0.08 * std::sin(1.7 * static_cast<Real>(v));
    bumps.vertices[0].x() = kMarkerX;
    bumps.triangles.insert(bumps.triangles.begin() + 5, {3, 3, 4});  // dropped as degenerate
    const TriangleMesh mesh = TriangleMesh::fromData(bumps);
    EXPECT_EQ(mesh.data->droppedTriangles, 1u);
    HeightFieldData grid = heightGrid(25, 21, 0.3, 0.35, [](std::uint32_t i, std::uint32_t j) {
        return 0.3 * std::sin(0.4 * i) * std::cos(0.3 * j) - 0.02 * i;
    });
    grid.heights[0] = kMarkerHeight;
    grid.holes.assign(24 * 20, 0);
    grid.holes[3 * 24 + 20] = 1;

    const BodyId ground = addBody(s, Vec3::Zero(), BodyType::Static);
    s.world.createShape(ground, ShapeDef{.geometry = mesh, .material = {.friction = 0.4}});
    const BodyId terrain = addBody(s, Vec3(5, -3, 0), BodyType::Static);
    s.world.createShape(terrain, ShapeDef{.geometry = HeightField::fromData(grid)});
    const BodyId platform = addBody(s, Vec3(0, 9, 0), BodyType::Kinematic);
    s.world.createShape(platform, ShapeDef{.geometry = mesh});
    s.world.setLinearVelocity(platform, Vec3(0.3, 0, 0));
    s.world.setAngularVelocity(platform, Vec3(0, 0, 0.2));

    const std::vector<Shape> shapes = {
        Box{Vec3(0.2, 0.15, 0.1)}, Sphere{0.15}, Capsule{0.1, 0.15},
        ConvexHull::fromPoints(std::vector<Vec3>{Vec3(0.2, 0, -0.06), Vec3(-0.1, 0.17, -0.06),
                                                 Vec3(-0.1, -0.17, -0.06), Vec3(0, 0, 0.19)})};
    const std::vector<Vec3> centres = {Vec3(0, 0, 0.5), Vec3(8.5, 0.5, 0.9), Vec3(0, 9, 0.5)};
    int k = 0;
    for (const Vec3& centre : centres) {
        for (int i = 0; i < 8; ++i, ++k) {
            const Vec3 at =
                centre + Vec3(0.45 * (i % 4) - 0.7, 0.5 * (i / 4) - 0.25, 0.3 * (i % 3));
            const BodyId b = addBody(s, at);
            s.world.createShape(b, ShapeDef{.geometry = shapes[static_cast<std::size_t>(k) % 4]});
            s.world.setLinearVelocity(b, Vec3(0.6 * std::cos(k), 0.6 * std::sin(k), 0));
        }
    }
    return s;
}

TEST(CheckpointMesh, MeshHeightFieldAndKinematicMeshResumeBitwise) {
    Scene s = surfaceScene();
    test::expectBitwiseResume(s, 45, 150);
    // The bodies stay on the surfaces (the lowest at -0.78 m), none fell through or off.
    for (std::size_t b = 3; b < s.bodies.size(); ++b)
        EXPECT_GT(s.world.position(s.bodies[b]).z(), -1) << "body " << b;
}

TEST(CheckpointMesh, SharedGeometryIsSavedOnceAndSharedAfterLoading) {
    Scene s = surfaceScene();
    const std::vector<std::uint8_t> saved = checkpointBytes(s.world);
    // The mesh's 169 vertices are in the file once, though two shapes carry it.
    std::vector<std::uint8_t> marker(8);
    const auto bits = std::bit_cast<std::uint64_t>(kMarkerX);
    std::memcpy(marker.data(), &bits, 8);
    int copies = 0;
    for (std::size_t at = 0; at + 8 <= saved.size(); ++at)
        copies += std::equal(marker.begin(), marker.end(), saved.begin() + static_cast<long>(at));
    EXPECT_EQ(copies, 1);
    World loaded;
    restoreCheckpoint(loaded, saved);
    const std::vector<BodyId> bodies = test::sameBodies(loaded, s.bodies);
    const auto meshOf = [&](BodyId body) {
        return std::get<TriangleMesh>(loaded.shapeDef(loaded.bodyShapes(body)[0]).geometry).data;
    };
    EXPECT_EQ(meshOf(bodies[0]), meshOf(bodies[2])) << "one geometry for both shapes";
    const MeshGeometry& before =
        *std::get<TriangleMesh>(s.world.shapeDef(s.world.bodyShapes(s.bodies[0])[0]).geometry).data;
    const MeshGeometry& after = *meshOf(bodies[0]);
    EXPECT_EQ(after.droppedTriangles, 1u);
    EXPECT_EQ(after.triangles, before.triangles);
    EXPECT_EQ(after.sourceIndex, before.sourceIndex);
    EXPECT_EQ(after.activeEdges, before.activeEdges);
    EXPECT_EQ(after.across, before.across);
    ASSERT_EQ(after.nodes.size(), before.nodes.size());
    for (std::size_t n = 0; n < after.nodes.size(); ++n) {
        EXPECT_EQ(after.nodes[n].index, before.nodes[n].index);
        EXPECT_EQ(after.nodes[n].box.lower, before.nodes[n].box.lower);
        EXPECT_EQ(after.nodes[n].box.upper, before.nodes[n].box.upper);
    }
}

class CheckpointMeshRefusal : public test::CheckpointRefusalBase {
protected:
    void SetUp() override { prepare(surfaceScene(), 3, surfaceScene(), 7); }
    /// Where the 8 bytes of `value` first sit in the good checkpoint.
    std::size_t offsetOf(Real value) const {
        const auto bits = std::bit_cast<std::uint64_t>(value);
        for (std::size_t at = 32; at + 8 <= good.size(); ++at) {
            if (readU64(good, at) == bits)
                return at;
        }
        ADD_FAILURE() << "marker not found";
        return 0;
    }
    /// `bytes` with a header that agrees with its payload, refused: the message.
    std::string refuse(std::vector<std::uint8_t> bytes) {
        test::sealPayload(bytes);
        const std::string message = CheckpointRefusalBase::refuse(bytes, "terrain.ckpt");
        EXPECT_TRUE(contains(message, "checkpoint terrain.ckpt: corrupt payload at byte"));
        return message;
    }
};

TEST_F(CheckpointMeshRefusal, NonFiniteVertexOrHeightNamesTheBuildersReason) {
    std::vector<std::uint8_t> vertex = good;
    writeU64(vertex, offsetOf(kMarkerX), std::bit_cast<std::uint64_t>(std::nan("")));
    const std::string mesh = refuse(vertex);
    EXPECT_TRUE(contains(mesh, "mesh section: surface 0 does not build: TriangleMesh: vertex 0"));
    EXPECT_TRUE(contains(mesh, "must be finite"));
    std::vector<std::uint8_t> height = good;
    writeU64(height, offsetOf(kMarkerHeight),
             std::bit_cast<std::uint64_t>(std::numeric_limits<Real>::infinity()));
    EXPECT_TRUE(contains(refuse(height), "surface 1 does not build: HeightField: heights[0]"));
}

// The mesh section starts with its version (u32) and surface count (u64), then the first
// surface's type (u8) and vertex count (u64) just before the marked vertex's x.
TEST_F(CheckpointMeshRefusal, OtherSectionVersionOrSurfaceTypeIsRefused) {
    const std::size_t type = offsetOf(kMarkerX) - 8 - 1;
    const std::size_t version = type - 8 - 4;
    ASSERT_EQ(good[version], 1);
    ASSERT_EQ(readU64(good, version + 4), 2u) << "two surfaces";
    std::vector<std::uint8_t> newer = good;
    newer[version] = 2;
    EXPECT_TRUE(contains(refuse(newer), "mesh section version 2, this build reads version 1"));
    std::vector<std::uint8_t> box = good;
    box[type] = static_cast<std::uint8_t>(ShapeType::Box);
    EXPECT_TRUE(contains(refuse(box), "surface 0 has shape type 2"));
}

TEST_F(CheckpointMeshRefusal, TruncatedInsideTheSectionIsRefused) {
    for (const std::size_t end : {offsetOf(kMarkerX) + 3, offsetOf(kMarkerHeight) + 100}) {
        const std::vector<std::uint8_t> cut(good.begin(), good.begin() + static_cast<long>(end));
        const std::string message = refuse(cut);
        EXPECT_TRUE(contains(message, "ends early") || contains(message, "exceeds the bytes left"))
            << message;
    }
    // And a file cut short whose header still says the full length.
    const std::vector<std::uint8_t> cut(good.begin(), good.begin() + offsetOf(kMarkerHeight));
    EXPECT_TRUE(
        contains(refusal([&] { restoreCheckpoint(target, cut, "terrain.ckpt"); }), "truncated"));
    EXPECT_EQ(checkpointBytes(target), before);
}

TEST_F(CheckpointMeshRefusal, ShapeReferringPastTheSectionIsRefused) {
    // Crafted: the surface count says one, so the height field's shape refers past the end
    // and the height field's bytes are read as shape records; whatever breaks first, the
    // load is refused and the world unchanged.
    const std::size_t version = offsetOf(kMarkerX) - 8 - 1 - 8 - 4;
    std::vector<std::uint8_t> one = good;
    writeU64(one, version + 4, 1);
    refuse(one);
}

}  // namespace
}  // namespace tumble
