// Mesh and height-field loading (scene/mesh_io.h): good files give the right counts and values,
// every bad input is refused naming the file (or list) and what is wrong, degenerate triangles
// are dropped with a warning.

#include "tumble/scene/mesh_io.h"

#include <gtest/gtest.h>

#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>

#include "refusal.h"

namespace tumble {
namespace {

using test::contains;
using test::refusal;

const std::string kData = TUMBLE_TEST_DATA_DIR "/mesh/";

/// Writes `text` to a file of its own under the test's scratch directory; returns its path.
std::string scratch(const std::string& name, const std::string& text) {
    const auto dir = std::filesystem::path(::testing::TempDir()) / "tumble_mesh_io";
    std::filesystem::create_directories(dir);
    const std::string path = (dir / name).string();
    std::ofstream(path, std::ios::binary) << text;
    return path;
}

#define SKIP_WITHOUT(have, package) \
    if (!(have))                    \
    GTEST_SKIP() << "built without " package << " (apt install it and configure again)"

TEST(MeshArrays, KeepsGoodTrianglesAndDropsDegenerateOnesWithAWarning) {
    std::vector<std::string> warnings;
    const TriangleMeshData mesh =
        meshFromArrays({Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0), Vec3(2, 0, 0)},
                       {{0, 1, 2}, {0, 0, 1}, {0, 1, 3}, {2, 1, 0}}, &warnings);
    ASSERT_EQ(mesh.vertices.size(), 4u);
    // {0, 0, 1} repeats an index; {0, 1, 3} is three points on the x axis (zero area).
    ASSERT_EQ(mesh.triangles.size(), 2u);
    EXPECT_EQ(mesh.triangles[0], (std::array<std::uint32_t, 3>{0, 1, 2}));
    EXPECT_EQ(mesh.triangles[1], (std::array<std::uint32_t, 3>{2, 1, 0}));
    ASSERT_EQ(warnings.size(), 1u);
    EXPECT_TRUE(contains(warnings[0], "dropped 2 degenerate triangles"));
    EXPECT_TRUE(contains(warnings[0], "the first triangles[1]"));
}

TEST(MeshArrays, RefusesBadElementsNamingThem) {
    const Real nan = std::numeric_limits<Real>::quiet_NaN();
    const Real inf = std::numeric_limits<Real>::infinity();
    const std::vector<Vec3> corners{Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0)};
    EXPECT_TRUE(contains(refusal([&] {
                             meshFromArrays(corners, {{0, 1, 3}});
                         }),
                         "triangles[0]: vertex index 3 is out of range (the mesh has 3 vertices)"));
    EXPECT_TRUE(
        contains(refusal([&] {
                     meshFromArrays({Vec3(0, 0, 0), Vec3(1, nan, 0), Vec3(0, 1, 0)}, {{0, 1, 2}});
                 }),
                 "vertices[1]: coordinates must be finite"));
    EXPECT_TRUE(
        contains(refusal([&] {
                     meshFromArrays({Vec3(0, 0, inf), Vec3(1, 0, 0), Vec3(0, 1, 0)}, {{0, 1, 2}});
                 }),
                 "vertices[0]: coordinates must be finite"));
    EXPECT_TRUE(contains(refusal([&] { meshFromArrays(corners, {}); }),
                         "a mesh needs at least one triangle"));
    EXPECT_TRUE(contains(refusal([&] {
                             meshFromArrays(corners, {{0, 0, 1}});
                         }),
                         "every triangle is degenerate"));
}

TEST(MeshArrays, RefusalChangesNothing) {
    TriangleMeshData mesh{{Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0)}, {{0, 0, 1}, {0, 1, 9}}};
    EXPECT_FALSE(refusal([&] { checkTriangleMesh(mesh); }).empty());
    EXPECT_EQ(mesh.triangles.size(), 2u);  // the degenerate one was not dropped either
}

TEST(HeightFieldArray, KeepsTheGrid) {
    const HeightFieldData field = heightFieldFromArray(3, 2, 0.5, 0.25, {0, 1, 2, 3, 4, 5}, {0, 1});
    EXPECT_EQ(field.columns, 3u);
    EXPECT_EQ(field.rows, 2u);
    EXPECT_EQ(field.spacingX, 0.5);
    EXPECT_EQ(field.spacingY, 0.25);
    EXPECT_EQ(field.heights[4], 4);
    EXPECT_EQ(field.holes[1], 1);
}

TEST(HeightFieldArray, RefusesBadGrids) {
    const Real nan = std::numeric_limits<Real>::quiet_NaN();
    const std::vector<Real> six{0, 1, 2, 3, 4, 5};
    EXPECT_TRUE(contains(refusal([&] {
                             heightFieldFromArray(3, 2, 1, 1, {0, 1, 2, 3, 4});
                         }),
                         "heights has 5 samples; columns * rows = 3 * 2 = 6"));
    EXPECT_TRUE(contains(refusal([&] { heightFieldFromArray(1, 6, 1, 1, six); }),
                         "at least 2 x 2 samples (got columns = 1, rows = 6)"));
    EXPECT_TRUE(contains(refusal([&] { heightFieldFromArray(3, 2, 0, 1, six); }),
                         "spacingX = 0 must be finite and > 0"));
    EXPECT_TRUE(contains(refusal([&] { heightFieldFromArray(3, 2, 1, -2, six); }),
                         "spacingY = -2 must be finite and > 0"));
    EXPECT_TRUE(contains(refusal([&] { heightFieldFromArray(3, 2, 1, nan, six); }),
                         "spacingY = nan must be finite"));
    EXPECT_TRUE(contains(refusal([&] {
                             heightFieldFromArray(3, 2, 1, 1, {0, 1, nan, 3, 4, 5});
                         }),
                         "heights[2]: must be finite (got nan)"));
    EXPECT_TRUE(contains(refusal([&] { heightFieldFromArray(3, 2, 1, 1, six, {0}); }),
                         "holes has 1 flags; a 3 x 2 height field has 2 cells"));
    EXPECT_TRUE(contains(refusal([&] {
                             heightFieldFromArray(3, 2, 1, 1, six, {0, 7});
                         }),
                         "holes[1] = 7 must be 0 or 1"));
}

TEST(ObjLoader, ReadsAnOpenBoxSplittingQuadsIntoFans) {
    SKIP_WITHOUT(haveObjLoader(), "libtinyobjloader-dev");
    std::vector<std::string> warnings;
    const TriangleMeshData mesh = loadObj(kData + "open_box.obj", &warnings);
    ASSERT_EQ(mesh.vertices.size(), 8u);
    EXPECT_EQ(mesh.vertices[6], Vec3(1, 1, 1));
    ASSERT_EQ(mesh.triangles.size(), 10u);
    // The bottom quad 1 4 3 2 (1-based) as the fan (0, 3, 2), (0, 2, 1).
    EXPECT_EQ(mesh.triangles[0], (std::array<std::uint32_t, 3>{0, 3, 2}));
    EXPECT_EQ(mesh.triangles[1], (std::array<std::uint32_t, 3>{0, 2, 1}));
    // The last face's relative indices -8 -4 -1 -5 are vertices 0, 4, 7, 3.
    EXPECT_EQ(mesh.triangles[8], (std::array<std::uint32_t, 3>{0, 4, 7}));
    EXPECT_EQ(mesh.triangles[9], (std::array<std::uint32_t, 3>{0, 7, 3}));
    EXPECT_TRUE(warnings.empty());
    EXPECT_EQ(loadMeshFile(kData + "open_box.obj").triangles.size(), 10u);
}

TEST(ObjLoader, DropsDegenerateFacesNamingTheFirstLine) {
    SKIP_WITHOUT(haveObjLoader(), "libtinyobjloader-dev");
    const std::string path = scratch("degenerate.obj",
                                     "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 2 0 0\n"
                                     "f 1 2 3\n# a sliver\nf 1 2 4\nf 1 1 2\n");
    std::vector<std::string> warnings;
    const TriangleMeshData mesh = loadObj(path, &warnings);
    EXPECT_EQ(mesh.triangles.size(), 1u);
    ASSERT_EQ(warnings.size(), 1u);
    EXPECT_TRUE(contains(warnings[0], "dropped 2 degenerate triangles"));
    EXPECT_TRUE(contains(warnings[0], "the first at " + path + ":7"));
}

TEST(ObjLoader, RefusesBadFilesNamingTheLine) {
    SKIP_WITHOUT(haveObjLoader(), "libtinyobjloader-dev");
    const std::string v3 = "v 0 0 0\nv 1 0 0\nv 0 1 0\n";
    const auto refused = [&](const std::string& name, const std::string& text) {
        const std::string path = scratch(name, text);
        return refusal([&] { loadObj(path); });
    };
    const std::string dir = std::filesystem::path(scratch("x", "")).parent_path().string() + "/";
    EXPECT_TRUE(contains(refusal([&] { loadObj(dir + "missing.obj"); }),
                         dir + "missing.obj: cannot open the file"));
    EXPECT_TRUE(contains(refused("range.obj", v3 + "f 1 2 4\n"),
                         "range.obj:4: corner 3 is outside the file's 3 vertices"));
    EXPECT_TRUE(contains(refused("relative.obj", v3 + "f -1 -2 -4\n"),
                         "relative.obj:4: corner 3 is outside the file's 3 vertices"));
    EXPECT_TRUE(contains(refused("zero.obj", v3 + "f 0 1 2\n"), "zero.obj: OBJ parse error"));
    EXPECT_TRUE(contains(refused("zero.obj", v3 + "f 0 1 2\n"), "line 4"));
    EXPECT_TRUE(contains(refused("nan.obj", "v 0 0 0\nv nan 0 0\nv 0 1 0\nf 1 2 3\n"),
                         "nan.obj:2: coordinate \"nan\" is not finite"));
    EXPECT_TRUE(contains(refused("inf.obj", "v 0 0 0\nv 1 -inf 0\nv 0 1 0\nf 1 2 3\n"),
                         "inf.obj:2: coordinate \"-inf\" is not finite"));
    EXPECT_TRUE(contains(refused("huge.obj", "v 0 0 1e999\nv 1 0 0\nv 0 1 0\nf 1 2 3\n"),
                         "huge.obj:1: coordinate \"1e999\" is out of a double's range"));
    EXPECT_TRUE(contains(refused("word.obj", "v 0 0 0\nv 1 0 0\nv 0 one 0\nf 1 2 3\n"),
                         "word.obj:3: coordinate \"one\" is not a number"));
    EXPECT_TRUE(contains(refused("short.obj", "v 0 0\n"),
                         "short.obj:1: a vertex needs three coordinates (got 2)"));
    EXPECT_TRUE(contains(refused("edge.obj", v3 + "\n\nf 1 2\n"),
                         "edge.obj:6: a face needs at least three vertices (got 2)"));
    EXPECT_TRUE(
        contains(refused("empty.obj", v3), "empty.obj: a mesh needs at least one triangle"));
    EXPECT_TRUE(
        contains(refused("flat.obj", v3 + "f 1 1 2\n"), "flat.obj: every triangle is degenerate"));
    EXPECT_TRUE(contains(refusal([&] { loadObj(dir); }), dir + ": not a regular file"));
    EXPECT_TRUE(contains(refusal([&] { loadObj("/dev/zero"); }), "/dev/zero: not a regular file"));
    EXPECT_TRUE(contains(refusal([&] { loadMeshFile(kData + "grey8_3x2.png"); }),
                         "a mesh file must end in .obj or .stl"));
}

TEST(StlLoader, ReadsAsciiAndMergesSharedVertices) {
    const TriangleMeshData mesh = loadStl(kData + "two_triangles.stl");
    EXPECT_EQ(mesh.vertices.size(), 4u);
    ASSERT_EQ(mesh.triangles.size(), 2u);
    EXPECT_EQ(mesh.triangles[1], (std::array<std::uint32_t, 3>{0, 2, 3}));
    EXPECT_EQ(mesh.vertices[2], Vec3(1, 1, 0));
}

/// A binary STL of the given triangles (corner coordinates), with a header that starts with
/// "solid" as some writers make it.
std::string binaryStl(const std::vector<std::array<float, 9>>& triangles) {
    std::string bytes(80, ' ');
    bytes.replace(0, 5, "solid");
    const auto count = static_cast<std::uint32_t>(triangles.size());
    bytes.append(reinterpret_cast<const char*>(&count), 4);
    for (const auto& t : triangles) {
        const float normal[3] = {0, 0, 1};
        bytes.append(reinterpret_cast<const char*>(normal), 12);
        bytes.append(reinterpret_cast<const char*>(t.data()), 36);
        bytes.append(2, '\0');
    }
    return bytes;
}

TEST(StlLoader, ReadsBinary) {
    const std::string path = scratch(
        "square.stl", binaryStl({{0, 0, 0, 1, 0, 0, 1, 1, 0}, {0, 0, 0, 1, 1, 0, 0, 1, 0}}));
    const TriangleMeshData mesh = loadMeshFile(path);
    EXPECT_EQ(mesh.vertices.size(), 4u);
    EXPECT_EQ(mesh.triangles.size(), 2u);
    EXPECT_EQ(mesh.vertices[1], Vec3(1, 0, 0));
}

TEST(StlLoader, RefusesBadFiles) {
    const float nan = std::numeric_limits<float>::quiet_NaN();
    const std::string nanPath = scratch("nan.stl", binaryStl({{0, 0, 0, 1, nan, 0, 1, 1, 0}}));
    EXPECT_TRUE(contains(refusal([&] { loadStl(nanPath); }),
                         "nan.stl: triangle 1 of 1: vertex 2 has a coordinate that is not finite"));
    const std::string garbage = scratch("garbage.stl", "hello");
    EXPECT_TRUE(contains(refusal([&] { loadStl(garbage); }), "garbage.stl: not an STL file"));
    const std::string word =
        scratch("word.stl",
                "solid x\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\n"
                "vertex 1 one 0\nendloop\nendfacet\nendsolid x\n");
    EXPECT_TRUE(contains(refusal([&] { loadStl(word); }),
                         "word.stl:6: coordinate \"one\" is not a number"));
    const std::string shortFacet =
        scratch("short.stl",
                "solid x\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\n"
                "endloop\nendfacet\nendsolid x\n");
    EXPECT_TRUE(contains(refusal([&] { loadStl(shortFacet); }),
                         "short.stl:6: expected \"vertex\", got \"endloop\""));
    const std::string cut = scratch("cut.stl", "solid x\nfacet normal 0 0 1\n");
    EXPECT_TRUE(contains(refusal([&] { loadStl(cut); }),
                         "cut.stl:2: the file ends where \"outer\" was expected"));
    const std::string flat = scratch("flat.stl", binaryStl({{0, 0, 0, 1, 0, 0, 2, 0, 0}}));
    EXPECT_TRUE(
        contains(refusal([&] { loadStl(flat); }), "flat.stl: every triangle is degenerate"));
}

TEST(PngHeightField, Reads8BitWithTheTopRowFarthest) {
    SKIP_WITHOUT(havePngLoader(), "libpng-dev");
    const HeightFieldData field = loadHeightFieldPng(kData + "grey8_3x2.png", 0.5, 2, 10, -1);
    EXPECT_EQ(field.columns, 3u);
    EXPECT_EQ(field.rows, 2u);
    EXPECT_EQ(field.spacingX, 0.5);
    EXPECT_EQ(field.spacingY, 2);
    // Image rows, top first: 0 255 51 / 102 0 255. Row j = 0 is the image's bottom row.
    const std::vector<Real> expected{-1 + 10 * 102 / 255.0, -1, 9, -1, 9, -1 + 10 * 51 / 255.0};
    ASSERT_EQ(field.heights.size(), 6u);
    for (std::size_t k = 0; k < 6; ++k)
        EXPECT_DOUBLE_EQ(field.heights[k], expected[k]) << k;
    EXPECT_TRUE(field.holes.empty());
}

TEST(PngHeightField, Reads16Bit) {
    SKIP_WITHOUT(havePngLoader(), "libpng-dev");
    const HeightFieldData field = loadHeightFieldPng(kData + "grey16_2x2.png", 1, 1, 65535);
    // Image rows, top first: 0 65535 / 32768 1.
    EXPECT_EQ(field.heights, (std::vector<Real>{32768, 1, 0, 65535}));
}

TEST(PngHeightField, RefusesBadFiles) {
    SKIP_WITHOUT(havePngLoader(), "libpng-dev");
    const auto refused = [&](const std::string& name, Real spacing = 1, Real scale = 1) {
        return refusal([&] { loadHeightFieldPng(kData + name, spacing, 1, scale); });
    };
    EXPECT_TRUE(contains(refused("missing.png"), "missing.png: cannot open the file"));
    EXPECT_TRUE(contains(refused("not_png.png"), "not_png.png: not a PNG file"));
    EXPECT_TRUE(contains(refused("rgb_2x2.png"),
                         "rgb_2x2.png: a height field is an 8- or 16-bit greyscale image "
                         "(got colour type 2, 8 bits per sample)"));
    EXPECT_TRUE(contains(refused("grey8_1x5.png"),
                         "grey8_1x5.png: a height field needs at least 2 x 2 samples"));
    EXPECT_TRUE(contains(refused("truncated.png"), "truncated.png: "));
    EXPECT_TRUE(contains(refused("grey8_3x2.png", 0), "grey8_3x2.png: spacingX = 0 must be"));
    EXPECT_TRUE(contains(refused("grey8_3x2.png", 1, std::numeric_limits<Real>::infinity()),
                         "grey8_3x2.png: heightScale = inf"));
}

}  // namespace
}  // namespace tumble
