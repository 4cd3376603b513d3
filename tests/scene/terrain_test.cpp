// The terrain scenes' ground (bench/harness/terrain.h): one surface as a height field and as
// triangles, so every engine and Tumble's two shapes meet the same geometry.

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "bench/harness/terrain.h"

#include "tumble/scene/mesh_io.h"

namespace tumble::bench {
namespace {

TEST(Terrain, HeightFieldAndMeshAreTheSameSurface) {
    const HeightFieldData field = rollingTerrain();
    checkHeightField(field);
    TriangleMeshData mesh = terrainMesh(field);
    ASSERT_EQ(mesh.vertices.size(), 65u * 65u);
    ASSERT_EQ(mesh.triangles.size(), 2u * 64u * 64u);
    EXPECT_EQ(checkTriangleMesh(mesh).count, 0u);  // nothing degenerate
    for (const auto& t : mesh.triangles) {
        const Vec3& a = mesh.vertices[t[0]];
        const Vec3& b = mesh.vertices[t[1]];
        const Vec3& c = mesh.vertices[t[2]];
        ASSERT_GT((b - a).cross(c - a).z(), 0);  // counter-clockwise seen from above
        // Each triangle is the plane terrainHeight interpolates over it: check its centroid and
        // a point near each corner.
        for (const Vec3& p :
             std::initializer_list<Vec3>{(a + b + c) / 3, 0.9 * a + 0.05 * (b + c),
                                         0.9 * b + 0.05 * (a + c), 0.9 * c + 0.05 * (a + b)})
            ASSERT_NEAR(terrainHeight(field, p.x(), p.y()), p.z(), 1e-12);
    }
    // Samples sit where HeightFieldData says: (i dx, j dy, heights[j * columns + i]).
    EXPECT_DOUBLE_EQ(terrainHeight(field, 3 * 0.25, 7 * 0.25), field.heights[7 * 65 + 3]);
    EXPECT_EQ(mesh.vertices[7 * 65 + 3], Vec3(0.75, 1.75, field.heights[7 * 65 + 3]));
}

TEST(Terrain, IsABowlThatHoldsThePile) {
    const HeightFieldData field = rollingTerrain();
    const Real middle = 8;
    // The rim is higher than anywhere the pile is dropped (the middle 5.4 m), bumps included.
    EXPECT_GT(terrainHeight(field, 0.5, middle), terrainHeight(field, middle + 2.7, middle) + 1);
    EXPECT_NEAR(
        terrainHeight(field, middle, middle),
        0.3 * std::sin(2 * std::numbers::pi * 8 / 3) * std::sin(2 * std::numbers::pi * 8 / 3),
        1e-12);
}

}  // namespace
}  // namespace tumble::bench
