// Scene-file meshes and height fields (docs/scene-format.md): the JSON forms read into checked
// data, files found beside the scene, every refusal at the JSON path (and so the line) of what
// it refuses; scenes holding them load and collide.

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "refusal.h"
#include "scene/src/scene_parts.h"
#include "tumble/scene/mesh_io.h"

namespace tumble::cli {
namespace {

using test::contains;
using test::refusal;

const std::string kData = TUMBLE_TEST_DATA_DIR "/mesh";

TriangleMeshData mesh(const std::string& text, std::vector<std::string>* warnings = nullptr,
                      const std::string& directory = kData) {
    const Json value = Json::parse(text);
    JsonObject o(value, "bodies[0].shapes[0]");
    o.has("type");
    return parseMeshData(o, ShapeSource{directory, warnings});
}

HeightFieldData field(const std::string& text) {
    const Json value = Json::parse(text);
    JsonObject o(value, "bodies[0].shapes[0]");
    return parseHeightFieldData(o, ShapeSource{kData, nullptr});
}

TEST(MeshSceneSyntax, InlineMeshWithWarningNamingTheShape) {
    std::vector<std::string> warnings;
    const TriangleMeshData m = mesh(
        R"({"vertices": [[0,0,0],[1,0,0],[0,1,0]], "triangles": [[0,1,2],[0,0,1]]})", &warnings);
    EXPECT_EQ(m.vertices.size(), 3u);
    EXPECT_EQ(m.triangles.size(), 1u);
    ASSERT_EQ(warnings.size(), 1u);
    EXPECT_TRUE(contains(warnings[0], "bodies[0].shapes[0]: mesh: dropped 1 degenerate triangle"));
}

TEST(MeshSceneSyntax, MeshFileRelativeToTheScene) {
    if (!haveObjLoader())
        GTEST_SKIP() << "built without libtinyobjloader-dev";
    EXPECT_EQ(mesh(R"({"file": "open_box.obj"})").triangles.size(), 10u);
    EXPECT_EQ(mesh(R"({"file": "two_triangles.stl"})").triangles.size(), 2u);
}

TEST(MeshSceneSyntax, RefusesBadMeshesAtTheirPath) {
    const std::string at = "bodies[0].shapes[0].";
    const std::string corners = R"("vertices": [[0,0,0],[1,0,0],[0,1,0]])";
    EXPECT_TRUE(contains(refusal([&] { mesh("{" + corners + R"(, "triangles": [[0,1,3]]})"); }),
                         at + "triangles[0]: vertex index 3 is out of range"));
    EXPECT_TRUE(contains(refusal([&] { mesh("{" + corners + R"(, "triangles": [[0,1,-1]]})"); }),
                         at + "triangles[0][2]: expected a vertex index"));
    EXPECT_TRUE(contains(refusal([&] { mesh("{" + corners + R"(, "triangles": [[0,1]]})"); }),
                         at + "triangles[0]: expected an array of 3 vertex indices"));
    EXPECT_TRUE(contains(refusal([&] { mesh(R"({"vertices": [[0,0]], "triangles": []})"); }),
                         at + "vertices[0]: expected an array of 3 numbers"));
    EXPECT_TRUE(
        contains(refusal([&] { mesh("{" + corners + "}"); }),
                 at + "triangles: expected an array of [i, j, k] vertex indices, got nothing"));
    EXPECT_TRUE(contains(refusal([&] { mesh("{" + corners + R"(, "triangles": []})"); }),
                         at + "triangles: a mesh needs at least one triangle"));
    EXPECT_TRUE(contains(refusal([&] { mesh(R"({"file": "open_box.obj", "vertices": []})"); }),
                         at + "vertices: give either \"file\" or \"vertices\" and \"triangles\""));
    EXPECT_TRUE(contains(refusal([&] { mesh(R"({"file": "nowhere.obj"})"); }),
                         at + "file: " + kData + "/nowhere.obj: cannot open the file"));
    EXPECT_TRUE(contains(refusal([&] { mesh(R"({"file": "grey8_3x2.png"})"); }),
                         at + "file: " + kData + "/grey8_3x2.png: a mesh file must end in"));
}

TEST(MeshSceneSyntax, InlineHeightField) {
    const HeightFieldData f =
        field(R"({"heights": [[0, 1, 2], [3, 4, 5]], "spacing": [0.5, 2], "holes": [[0, 1]]})");
    EXPECT_EQ(f.columns, 3u);
    EXPECT_EQ(f.rows, 2u);
    EXPECT_EQ(f.spacingX, 0.5);
    EXPECT_EQ(f.spacingY, 2);
    EXPECT_EQ(f.heights, (std::vector<Real>{0, 1, 2, 3, 4, 5}));
    EXPECT_EQ(f.holes, (std::vector<std::uint8_t>{0, 1}));
}

TEST(MeshSceneSyntax, PngHeightFieldRelativeToTheScene) {
    if (!havePngLoader())
        GTEST_SKIP() << "built without libpng-dev";
    const HeightFieldData f = field(
        R"({"file": "grey8_3x2.png", "spacing": [1, 1], "heightScale": 255, "heightOffset": 1})");
    EXPECT_EQ(f.columns, 3u);
    EXPECT_EQ(f.heights[1], 1);    // pixel (1, 1), black
    EXPECT_EQ(f.heights[4], 256);  // pixel (1, 0), white
}

TEST(MeshSceneSyntax, RefusesBadHeightFieldsAtTheirPath) {
    const std::string at = "bodies[0].shapes[0].";
    EXPECT_TRUE(
        contains(refusal([&] { field(R"({"heights": [[0, 1], [2]], "spacing": [1, 1]})"); }),
                 at + "heights[1]: expected a row of 2 heights (as row 0), got 1 values"));
    EXPECT_TRUE(contains(refusal([&] { field(R"({"heights": [[0, 1]], "spacing": [1, 1]})"); }),
                         at + "heights: a height field needs at least 2 x 2 samples"));
    EXPECT_TRUE(contains(refusal([&] { field(R"({"heights": [[0, 1], [2, 3]]})"); }),
                         at + "spacing: expected [dx, dy]"));
    EXPECT_TRUE(
        contains(refusal([&] { field(R"({"heights": [[0, 1], [2, 3]], "spacing": [0, 1]})"); }),
                 at + "spacing: spacingX = 0 must be finite and > 0"));
    EXPECT_TRUE(
        contains(refusal([&] { field(R"({"heights": [[0, 1], [2, "x"]], "spacing": [1, 1]})"); }),
                 at + "heights[1][1]: expected a height (m), got a string"));
    EXPECT_TRUE(
        contains(refusal([&] {
                     field(R"({"heights": [[0, 1], [2, 3]], "spacing": [1, 1], "heightScale": 2})");
                 }),
                 at + "heightScale: only with \"file\""));
    EXPECT_TRUE(
        contains(refusal([&] {
                     field(R"({"heights": [[0, 1], [2, 3]], "spacing": [1, 1], "holes": [[2]]})");
                 }),
                 at + "holes[0][0]: expected 0 or 1"));
    EXPECT_TRUE(
        contains(refusal([&] { field(R"({"file": "rgb_2x2.png", "spacing": [1, 1]})"); }),
                 at + "file: " + kData + "/rgb_2x2.png: a height field is an 8- or 16-bit"));
}

/// A scene file with one static body carrying `shape`, written beside the fixtures' copies.
std::string sceneWith(const std::string& shape) {
    const auto dir = std::filesystem::path(::testing::TempDir()) / "tumble_mesh_scene";
    std::filesystem::create_directories(dir);
    std::filesystem::copy_file(kData + "/two_triangles.stl", dir / "level.stl",
                               std::filesystem::copy_options::overwrite_existing);
    const std::string path = (dir / "level.json").string();
    std::ofstream(path) << "{\n  \"bodies\": [\n    {\"type\": \"static\",\n     \"shapes\": [\n"
                        << "       " << shape << "\n     ]}\n  ]\n}\n";
    return path;
}

TEST(MeshSceneSyntax, SceneWithAMeshLoadsAndMissingFilesAreRefusedAtTheKey) {
    // The file is found beside the scene, read, checked and made a shape.
    const std::string path = sceneWith(R"({"type": "mesh", "file": "level.stl"})");
    const Scene scene = loadScene(path, {}, ".");
    ASSERT_EQ(scene.bodies.size(), 1u);
    ASSERT_EQ(scene.bodies[0].shapes.size(), 1u);
    EXPECT_EQ(typeOf(scene.bodies[0].shapes[0].geometry), ShapeType::TriangleMesh);
    const std::string missing = sceneWith(R"({"type": "mesh", "file": "gone.obj"})");
    EXPECT_TRUE(
        contains(refusal([&] { loadScene(missing, {}, "."); }), ":5: bodies[0].shapes[0].file: "));
    EXPECT_TRUE(contains(refusal([&] { loadScene(missing, {}, "."); }), "gone.obj: cannot open"));
    const std::string terrain =
        sceneWith(R"({"type": "heightField", "heights": [[0, 0], [0, 1]], "spacing": [1, 1]})");
    EXPECT_EQ(typeOf(loadScene(terrain, {}, ".").bodies[0].shapes[0].geometry),
              ShapeType::HeightField);
}

/// A sphere of radius 0.1 m dropped from 0.5 m above `surface` (a static body's shape whose
/// top is z = `height` under the sphere at x = y = 0.3) after 2 s of simulated time.
Real restingHeight(const std::string& surface) {
    const Json document = Json::parse(R"({"duration": 2, "bodies": [
        {"type": "static", "shapes": [)" +
                                      surface + R"(]},
        {"name": "ball", "position": [0.3, 0.3, 0.6],
         "shapes": [{"type": "sphere", "radius": 0.1}]}]})");
    const Scene scene = parseScene(document, "drop");
    EXPECT_TRUE(scene.warnings.empty());
    BuiltScene built = buildScene(scene);
    const auto steps = static_cast<int>(scene.duration / scene.world.timeStep + 0.5);
    for (int i = 0; i < steps; ++i)
        EXPECT_TRUE(built.world.step().ok());
    return built.world.position(built.bodies[1]).z();
}

// Tolerance set before measuring: at rest the sphere sits on the surface at h + r, less at most
// the contact slop (0.005 m, left unresolved by design), plus 1 mm for what 2 s of settling
// leaves of the bounce.
constexpr Real kRestTolerance = 0.005 + 0.001;

TEST(MeshSceneSyntax, SphereComesToRestOnAnInlineMesh) {
    // A flat 2 m x 2 m square at z = 0.1, two triangles.
    const Real z = restingHeight(R"({"type": "mesh",
        "vertices": [[-1, -1, 0.1], [1, -1, 0.1], [1, 1, 0.1], [-1, 1, 0.1]],
        "triangles": [[0, 1, 2], [0, 2, 3]]})");
    EXPECT_NEAR(z, 0.1 + 0.1, kRestTolerance);
}

TEST(MeshSceneSyntax, SphereComesToRestOnAnInlineHeightField) {
    // 3 x 3 samples 1 m apart, all 0.2 m high: a flat field from (0, 0) to (2, 2).
    const Real z = restingHeight(R"({"type": "heightField", "spacing": [1, 1],
        "heights": [[0.2, 0.2, 0.2], [0.2, 0.2, 0.2], [0.2, 0.2, 0.2]]})");
    EXPECT_NEAR(z, 0.2 + 0.1, kRestTolerance);
}

}  // namespace
}  // namespace tumble::cli
