// Convex hulls from point clouds (Qhull behind ConvexHull::fromPoints): topology, orientation,
// containment, and refusal of degenerate input.

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <map>
#include <random>
#include <string>
#include <vector>

#include "refusal.h"
#include "tumble/collision/shape.h"
#include "tumble/core/error.h"

namespace tumble {
namespace {

using test::contains;

/// The message of the InvalidArgument that fromPoints throws; fails the test if Qhull wrote
/// anything to stderr on the way.
std::string refusal(std::span<const Vec3> points) {
    ::testing::internal::CaptureStderr();
    std::string message;
    try {
        ConvexHull::fromPoints(points);
    } catch (const InvalidArgument& e) {
        message = e.what();
    }
    EXPECT_EQ(::testing::internal::GetCapturedStderr(), "");
    return message;
}

std::vector<Vec3> unitCubeCorners() {
    std::vector<Vec3> corners;
    for (int i = 0; i < 8; ++i)
        corners.emplace_back((i & 1) ? 1 : -1, (i & 2) ? 1 : -1, (i & 4) ? 1 : -1);
    return corners;
}

/// Every structural property a hull must have, with `points` its input. `tolerance` (m) bounds
/// how far outside a face plane an input point may lie (Qhull's merged facets are planar to
/// rounding).
void expectValidHull(const HullData& hull, std::span<const Vec3> points, Real tolerance) {
    const auto v = static_cast<long>(hull.vertices.size());
    const auto e = static_cast<long>(hull.edges.size());
    const auto f = static_cast<long>(hull.faces.size());
    EXPECT_EQ(v - e + f, 2) << "Euler: V " << v << ", E " << e << ", F " << f;

    for (const Vec3& vertex : hull.vertices)  // vertices are input points
        EXPECT_NE(std::find(points.begin(), points.end(), vertex), points.end());

    std::map<std::array<std::uint32_t, 2>, int> edgeUses;
    for (const HullFace& face : hull.faces) {
        EXPECT_NEAR(face.normal.norm(), 1, 1e-14);
        EXPECT_LT(face.normal.dot(hull.centroid), face.offset) << "normal points outward";
        for (std::uint32_t k = 0; k < face.count; ++k) {
            const std::uint32_t a = hull.faceVertices[face.first + k];
            const std::uint32_t b = hull.faceVertices[face.first + (k + 1) % face.count];
            const std::uint32_t c = hull.faceVertices[face.first + (k + 2) % face.count];
            EXPECT_NEAR(face.normal.dot(hull.vertices[a]), face.offset, tolerance) << "on plane";
            // Counter-clockwise seen from outside: each turn is left about the normal.
            const Vec3 turn =
                (hull.vertices[b] - hull.vertices[a]).cross(hull.vertices[c] - hull.vertices[b]);
            EXPECT_GT(turn.dot(face.normal), 0);
            ++edgeUses[{std::min(a, b), std::max(a, b)}];
        }
        for (const Vec3& p : points)
            EXPECT_LE(face.normal.dot(p), face.offset + tolerance) << "input point outside";
    }
    EXPECT_EQ(edgeUses.size(), hull.edges.size());
    for (const std::array<std::uint32_t, 2>& edge : hull.edges) {
        EXPECT_LT(edge[0], edge[1]);
        EXPECT_EQ(edgeUses[edge], 2) << "each edge borders exactly two faces";
    }
    EXPECT_TRUE(std::is_sorted(hull.edges.begin(), hull.edges.end()));
}

TEST(ConvexHull, BoxCornersGiveSixQuadrilaterals) {
    const std::vector<Vec3> corners = unitCubeCorners();
    const ConvexHull hull = ConvexHull::fromPoints(corners);
    const HullData& data = *hull.data;
    ASSERT_EQ(data.vertices.size(), 8u);
    ASSERT_EQ(data.faces.size(), 6u);
    EXPECT_EQ(data.edges.size(), 12u);
    EXPECT_EQ(data.vertices, corners) << "vertices keep their input order";
    for (const HullFace& face : data.faces) {
        EXPECT_EQ(face.count, 4u);
        EXPECT_EQ(face.offset, 1);
    }
    for (int i = 0; i < 6; ++i) {  // one face per signed axis, with exactly that normal
        const Vec3 axis = Vec3::Unit(i / 2) * (i % 2 == 0 ? 1 : -1);
        EXPECT_EQ(std::count_if(data.faces.begin(), data.faces.end(),
                                [&](const HullFace& face) { return face.normal == axis; }),
                  1)
            << axis.transpose();
    }
    expectValidHull(data, corners, 1e-15);
    EXPECT_EQ(data.centroid, Vec3::Zero());
}

TEST(ConvexHull, DropsInteriorEdgeAndFacePoints) {
    std::vector<Vec3> points = unitCubeCorners();
    std::mt19937 rng(5);
    std::uniform_real_distribution<Real> inside(-0.99, 0.99);
    for (int i = 0; i < 200; ++i)
        points.emplace_back(inside(rng), inside(rng), inside(rng));
    points.emplace_back(0, 0, 1);     // face centre
    points.emplace_back(1, 1, 0.3);   // on an edge
    points.emplace_back(0.2, -1, 0);  // on a face
    const ConvexHull hull = ConvexHull::fromPoints(points);
    EXPECT_EQ(hull.data->vertices, unitCubeCorners());
    EXPECT_EQ(hull.data->faces.size(), 6u);
    expectValidHull(*hull.data, points, 1e-15);
}

TEST(ConvexHull, RandomCloudsGiveValidHulls) {
    std::mt19937 rng(6);
    std::uniform_real_distribution<Real> uniform(-1, 1);
    for (int trial = 0; trial < 30; ++trial) {
        const int count = 4 + trial * 7;
        std::vector<Vec3> points;
        for (int i = 0; i < count; ++i)
            points.emplace_back(3 * uniform(rng) + 10, uniform(rng), 0.5 * uniform(rng) - 4);
        const ConvexHull hull = ConvexHull::fromPoints(points);
        SCOPED_TRACE(count);
        EXPECT_LE(hull.data->vertices.size(), points.size());
        expectValidHull(*hull.data, points, 1e-12);
    }
}

TEST(ConvexHull, ThinSlabIsStillASolid) {
    // 1e-6 thick, well above the flatness tolerance of 1e-9 of the diameter.
    std::vector<Vec3> points;
    for (int i = 0; i < 8; ++i)
        points.emplace_back((i & 1) ? 1 : -1, (i & 2) ? 1 : -1, (i & 4) ? 1e-6 : 0);
    const ConvexHull hull = ConvexHull::fromPoints(points);
    EXPECT_EQ(hull.data->faces.size(), 6u);
    EXPECT_NEAR(massOf(hull, 1).mass, 4e-6, 4e-6 * 1e-9);
    expectValidHull(*hull.data, points, 1e-15);
}

TEST(ConvexHull, SmallHullFarFromTheOriginKeepsItsShape) {
    // A 0.2 mm cube at 1 km: Qhull works on the cloud moved to the origin and scaled to unit size.
    std::vector<Vec3> points = unitCubeCorners();
    for (Vec3& p : points)
        p = Vec3(1000, -1000, 500) + 1e-4 * p;
    const ConvexHull hull = ConvexHull::fromPoints(points);
    EXPECT_EQ(hull.data->faces.size(), 6u);
    EXPECT_EQ(hull.data->vertices, points);
    expectValidHull(*hull.data, points, 1e-12);
    // The volume of the box the rounded corners actually span (they moved by ~1e-13 at 1 km).
    const Vec3 sides = points[7] - points[0];
    EXPECT_NEAR(massOf(hull, 1).mass, sides.prod(), sides.prod() * 1e-12);
}

TEST(ConvexHull, OutputIsDeterministic) {
    std::mt19937 rng(7);
    std::normal_distribution<Real> normal;
    std::vector<Vec3> points;
    for (int i = 0; i < 300; ++i)
        points.emplace_back(normal(rng), normal(rng), normal(rng));
    const ConvexHull a = ConvexHull::fromPoints(points);
    const ConvexHull b = ConvexHull::fromPoints(points);
    EXPECT_EQ(a.data->vertices, b.data->vertices);
    EXPECT_EQ(a.data->faceVertices, b.data->faceVertices);
    EXPECT_EQ(a.data->edges, b.data->edges);
    ASSERT_EQ(a.data->faces.size(), b.data->faces.size());
    for (std::size_t i = 0; i < a.data->faces.size(); ++i) {
        EXPECT_EQ(a.data->faces[i].normal, b.data->faces[i].normal);
        EXPECT_EQ(a.data->faces[i].offset, b.data->faces[i].offset);
    }
}

TEST(ConvexHull, RefusesTooFewPoints) {
    const std::array<Vec3, 3> points = {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0)};
    EXPECT_TRUE(contains(refusal(points), "points.size() = 3 must be >= 4"));
}

TEST(ConvexHull, RefusesNonFiniteCoordinatesNamingTheIndex) {
    std::vector<Vec3> points = unitCubeCorners();
    points[5].y() = std::numeric_limits<Real>::quiet_NaN();
    const std::string message = refusal(points);
    EXPECT_TRUE(contains(message, "points[5] = (1, nan, 1)"));
    EXPECT_TRUE(contains(message, "must be finite"));
}

TEST(ConvexHull, RefusesFlatInput) {
    std::vector<Vec3> coplanar;
    for (int i = 0; i < 20; ++i)  // a tilted plane
        coplanar.emplace_back(i % 5, i / 5, 0.5 * (i % 5) - 0.25 * (i / 5));
    EXPECT_TRUE(contains(refusal(coplanar), "the 20 points are coplanar"));

    std::vector<Vec3> collinear;
    for (int i = 0; i < 6; ++i)
        collinear.push_back(Vec3(1, 2, 3) * i);
    EXPECT_TRUE(contains(refusal(collinear), "the 6 points are collinear"));

    const std::vector<Vec3> coincident(5, Vec3(1, 1, 1));
    EXPECT_TRUE(contains(refusal(coincident), "all 5 points coincide"));

    // A cube of 2e-200 m: its volume underflows.
    std::vector<Vec3> tiny = unitCubeCorners();
    for (Vec3& p : tiny)
        p *= 1e-200;
    EXPECT_TRUE(contains(refusal(tiny), "is not representable"));

    // Almost flat: 1e-12 of the size off the plane.
    std::vector<Vec3> nearlyFlat = coplanar;
    nearlyFlat[7].z() += 1e-12;
    EXPECT_TRUE(contains(refusal(nearlyFlat), "coplanar"));
}

}  // namespace
}  // namespace tumble
