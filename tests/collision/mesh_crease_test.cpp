// Several manifolds per shape-mesh pair: a convex shape in a V-shaped crease of a mesh gets one
// manifold per face, each the manifold of the half-space in that face's plane.

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <random>
#include <vector>

#include "collision/crease_fixtures.h"
#include "tumble/collision/mesh_shape.h"
#include "tumble/collision/narrowphase.h"

namespace tumble {
namespace {

using testing::Crease;

Real deepest(const Manifold& m) {
    Real d = INFINITY;
    for (int k = 0; k < m.pointCount; ++k)
        d = std::min(d, m.points[static_cast<std::size_t>(k)].separation);
    return d;
}

Shape convexOfKind(std::mt19937& rng, int kind) {
    std::uniform_real_distribution<Real> size(0.1, 0.25);
    const Real a = size(rng), b = size(rng), c = size(rng);
    const std::array<Shape, 4> kinds{Sphere{a}, Capsule{a, b}, Box{Vec3(a, b, c)}, Cylinder{a, b}};
    return kinds[static_cast<std::size_t>(kind)];
}

/// Whether every point of the face's manifold lies over that face, `clear` (m) from the crease
/// and from the mesh's border (|x|, |y| < `extent`).
bool awayFromEdges(const Manifold& m, int side, Real clear, Real extent) {
    for (int k = 0; k < m.pointCount; ++k) {
        const Vec3& p = m.points[static_cast<std::size_t>(k)].position;
        const Real x = side == 0 ? -p.x() : p.x();
        if (x < clear || x > extent - clear || std::abs(p.y()) > extent - clear)
            return false;
    }
    return true;
}

// Random shapes pressed into creases of 60 to 170 degrees, each face touched from 0.03 m deep to
// 0.015 m apart (within the speculative margin). Away from the crease and the border, the mesh's
// manifolds are the half-spaces' manifolds: as many, with equal normals and deepest depths.
TEST(MeshCrease, EveryConvexShapeInACreaseGetsEachFacesHalfSpaceManifold) {
    const Real margin = 0.02, cell = 0.25, extent = 2.0;
    std::mt19937 rng(2626);
    std::uniform_real_distribution<Real> unit(0, 1);
    std::normal_distribution<Real> gauss;
    int compared = 0, both = 0;
    Real worstDepth = 0, worstNormal = 0;
    for (const Real degrees : {60.0, 90.0, 120.0, 150.0, 170.0}) {
        const Crease crease{degrees};
        const Shape mesh = TriangleMesh::fromData(crease.mesh(8, cell));
        for (int trial = 0; trial < 400; ++trial) {
            const Shape shape = convexOfKind(rng, trial % 4);
            Transform pose{Vec3(0, 1.5 * (2 * unit(rng) - 1), 1),
                           Quat(gauss(rng), gauss(rng), gauss(rng), gauss(rng)).normalized()};
            crease.place(shape, pose, -0.03 + 0.045 * unit(rng), -0.03 + 0.045 * unit(rng));
            ManifoldSet onMesh;
            collide(shape, pose, mesh, Transform{}, margin, onMesh);
            std::array<Manifold, 2> onFace;
            bool clear = true;
            for (int side = 0; side < 2; ++side) {
                collide(shape, pose, crease.face(side), Transform{}, margin,
                        onFace[static_cast<std::size_t>(side)]);
                clear = clear &&
                        awayFromEdges(onFace[static_cast<std::size_t>(side)], side, 0.01, extent);
            }
            if (!clear)
                continue;
            ++compared;
            const int touched = (onFace[0].pointCount > 0) + (onFace[1].pointCount > 0);
            both += touched == 2;
            ASSERT_EQ(onMesh.count, touched) << degrees << " degrees, trial " << trial;
            for (const Manifold& face : onFace) {
                if (face.pointCount == 0)
                    continue;
                const Manifold* match = &onMesh.manifolds[0];
                for (int k = 1; k < onMesh.count; ++k) {
                    const Manifold& m = onMesh.manifolds[static_cast<std::size_t>(k)];
                    if (m.normal.dot(face.normal) > match->normal.dot(face.normal))
                        match = &m;
                }
                worstDepth = std::max(worstDepth, std::abs(deepest(*match) - deepest(face)));
                worstNormal = std::max(worstNormal, (match->normal - face.normal).norm());
            }
        }
    }
    std::printf(
        "crease mesh vs two half-spaces: %d poses compared (%d touching both faces), "
        "worst depth difference %.3g m, normal %.3g\n",
        compared, both, worstDepth, worstNormal);
    EXPECT_GE(compared, 1000);
    EXPECT_GE(both, 500);
    EXPECT_LT(worstDepth, 1e-9);
    EXPECT_LT(worstNormal, 1e-9);
}

// The single-manifold call keeps the deepest of the set: what a caller that takes one manifold
// per pair got before (a mesh pair's first manifold).
TEST(MeshCrease, SingleManifoldCallGivesTheDeepestOfTheSet) {
    const Crease crease{120};
    const Shape mesh = TriangleMesh::fromData(crease.mesh(8, 0.25));
    const Shape box = Box{Vec3(0.3, 0.2, 0.1)};
    Transform pose{Vec3(0.05, 0, 1), Quat::Identity()};
    crease.place(box, pose, -0.004, -0.002);
    ManifoldSet set;
    collide(box, pose, mesh, Transform{}, 0.02, set);
    ASSERT_EQ(set.count, 2);
    EXPECT_LT(deepest(set.manifolds[0]), deepest(set.manifolds[1]));
    Manifold one;
    collide(box, pose, mesh, Transform{}, 0.02, one);
    EXPECT_EQ(one.pointCount, set.manifolds[0].pointCount);
    EXPECT_EQ(one.normal, set.manifolds[0].normal);
    EXPECT_EQ(deepest(one), deepest(set.manifolds[0]));
    // The mesh as shape A: the same manifolds, normals reversed.
    ManifoldSet reversed;
    collide(mesh, Transform{}, box, pose, 0.02, reversed);
    ASSERT_EQ(reversed.count, 2);
    for (int k = 0; k < 2; ++k)
        EXPECT_EQ(reversed.manifolds[static_cast<std::size_t>(k)].normal,
                  -set.manifolds[static_cast<std::size_t>(k)].normal);
}

}  // namespace
}  // namespace tumble
