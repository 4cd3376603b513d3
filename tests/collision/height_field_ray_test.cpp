// Ray casts on a height field walk the grid (a 2D DDA over the cells the ray crosses): the walk
// gives the same hit as testing every cell under the box of the ray's stretch (the reference,
// raycastCellsUnderBox), for rays of every kind -- long and short, steep and grazing, axis-
// parallel, vertical, through holes, from inside the field's box and from outside. Its cost (the
// cells crossed, not the cells under the box) is measured in bench/mesh_query_bench.cpp.

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <limits>
#include <random>
#include <vector>

#include "collision/mesh_fixtures.h"
#include "mesh_queries.h"
#include "tumble/collision/mesh_shape.h"
#include "tumble/collision/raycast.h"

namespace tumble {
namespace {

using testing::heightGrid;

/// 129 x 97 samples, 0.25 x 0.3 m apart, rolling hills up to ~1.5 m, and a band of holes.
HeightField rollingField() {
    HeightFieldData grid = heightGrid(129, 97, 0.25, 0.3, [](std::uint32_t i, std::uint32_t j) {
        return 0.8 * std::sin(0.11 * i) * std::cos(0.07 * j) + 0.4 * std::sin(0.23 * (i + j));
    });
    grid.holes.assign(std::size_t{128} * 96, 0);
    for (std::uint32_t i = 40; i < 60; ++i)
        grid.holes[50 * 128 + i] = 1;
    return HeightField::fromData(grid);
}

struct Rays {
    std::vector<Ray> rays;
    Transform pose;
};

/// Rays of every kind over the field (32 m x 28.8 m) at a tilted pose.
Rays randomRays(int count) {
    Rays r;
    r.pose = Transform{Vec3(-3, 2, 0.5),
                       Quat(Eigen::AngleAxis<Real>(0.3, Vec3(1, 2, 0.5).normalized()))};
    std::mt19937 rng(2601);
    std::uniform_real_distribution<Real> u(0, 1);
    for (int k = 0; k < count; ++k) {
        const Vec3 from(-4 + 40 * u(rng), -4 + 37 * u(rng), -2 + 6 * u(rng));
        Vec3 to(-4 + 40 * u(rng), -4 + 37 * u(rng), -2 + 4 * u(rng));
        switch (k % 5) {
            case 0:  // vertical
                to.head<2>() = from.head<2>();
                break;
            case 1:  // along x or y in the field's frame
                to[k % 2] = from[k % 2];
                break;
            case 2:  // grazing: nearly level
                to.z() = from.z() - 0.05 * u(rng);
                break;
            default:
                break;
        }
        const Real reach = k % 7 == 0 ? std::numeric_limits<Real>::infinity() : 0.2 + 1.5 * u(rng);
        r.rays.push_back(Ray{r.pose.apply(from), r.pose.rotation * (to - from), reach});
    }
    return r;
}

std::optional<RayHit> reference(const HeightField& field, const Transform& pose, const Ray& ray) {
    const Vec3 o = pose.applyInverse(ray.origin);
    const Vec3 d = pose.rotation.conjugate() * ray.direction;
    return detail::raycastCellsUnderBox(*field.data, pose, o, d, ray);
}

TEST(HeightFieldRay, GridWalkMatchesTheCellsUnderTheBoxAtRandomRays) {
    const HeightField field = rollingField();
    const Rays r = randomRays(4000);
    int hits = 0, misses = 0;
    Real worstFraction = 0, worstNormal = 0;
    for (std::size_t k = 0; k < r.rays.size(); ++k) {
        const auto walked = raycast(field, r.pose, r.rays[k]);
        const auto scanned = reference(field, r.pose, r.rays[k]);
        ASSERT_EQ(walked.has_value(), scanned.has_value()) << "ray " << k;
        if (!scanned) {
            ++misses;
            continue;
        }
        ++hits;
        worstFraction = std::max(worstFraction, std::abs(walked->fraction - scanned->fraction));
        worstNormal = std::max(worstNormal, (walked->normal - scanned->normal).norm());
    }
    std::printf(
        "height-field rays: %d hits, %d misses, worst fraction difference %.3g, normal %.3g\n",
        hits, misses, worstFraction, worstNormal);
    EXPECT_GE(hits, 1000);
    EXPECT_GE(misses, 200);
    EXPECT_LE(worstFraction, 1e-12);
    EXPECT_LE(worstNormal, 1e-12);
}

// Long rays across the field, where the walk visits ~the cells crossed and the reference ~the
// cells under the box (their square): the same hits. Their costs are BM_HeightFieldRay* in
// tumble-microbench (bench/mesh_query_bench.cpp).
TEST(HeightFieldRay, GridWalkMatchesTheScanOnLongRays) {
    const HeightField field = rollingField();
    std::mt19937 rng(7);
    std::uniform_real_distribution<Real> u(0, 1);
    const Transform pose;
    int walkHits = 0, scanHits = 0;
    Real worstFraction = 0;
    for (int k = 0; k < 2000; ++k) {
        // From above one side, descending gently across the field.
        const Vec3 from(32 * u(rng), -1, 3), to(32 * u(rng), 30, -u(rng));
        const Ray ray{from, to - from, 1};
        const auto walked = raycast(field, pose, ray);
        const auto scanned = reference(field, pose, ray);
        ASSERT_EQ(walked.has_value(), scanned.has_value()) << "ray " << k;
        walkHits += walked ? 1 : 0;
        scanHits += scanned ? 1 : 0;
        if (walked)
            worstFraction = std::max(worstFraction, std::abs(walked->fraction - scanned->fraction));
    }
    EXPECT_EQ(walkHits, scanHits);
    EXPECT_GT(walkHits, 1000);
    EXPECT_LE(worstFraction, 1e-12);
}

}  // namespace
}  // namespace tumble
