// Narrowphase dispatch: one table entry per ordered pair of shape types. Only the upper triangle
// (A's type <= B's type) names routines; the lower triangle is served by swapping the arguments
// and flipping the normal, so each routine is written once, for one order.

#include "tumble/collision/narrowphase.h"

#include <algorithm>
#include <array>
#include <cstddef>

#include "pair_routines.h"

namespace tumble {
namespace {

using detail::CollideFn;

constexpr std::size_t kTypeCount = static_cast<std::size_t>(ShapeType::Count);

/// [typeA][typeB] for typeA <= typeB; nullptr = no contact (between half-spaces, meshes and
/// height fields).
/// Pairs without a closed form go through libccd and clipping (detail::collideConvex).
constexpr std::array<std::array<CollideFn, kTypeCount>, kTypeCount> makeTable() {
    using enum ShapeType;
    std::array<std::array<CollideFn, kTypeCount>, kTypeCount> table{};
    for (std::size_t i = 0; i < kTypeCount; ++i)
        for (std::size_t j = i; j < kTypeCount; ++j)
            table[i][j] = &detail::collideConvex;
    auto set = [&](ShapeType a, ShapeType b, CollideFn fn) {
        table[static_cast<std::size_t>(a)][static_cast<std::size_t>(b)] = fn;
    };
    set(Sphere, Sphere, &detail::collideSpheres);
    set(Sphere, Capsule, &detail::collideSphereCapsule);
    set(Sphere, Box, &detail::collideSphereBox);
    set(Capsule, Capsule, &detail::collideCapsules);
    set(Box, Box, &detail::collideBoxes);
    for (ShapeType convex : {Sphere, Capsule, Box, Cylinder, ConvexHull}) {
        set(convex, HalfSpace, &detail::collideConvexHalfSpace);
        set(convex, TriangleMesh, &detail::collideConvexMeshDeepest);
        set(convex, HeightField, &detail::collideConvexMeshDeepest);
    }
    // Static geometry never meets static geometry.
    for (ShapeType a : {HalfSpace, TriangleMesh, HeightField})
        for (ShapeType b : {HalfSpace, TriangleMesh, HeightField})
            if (a <= b)
                set(a, b, nullptr);
    return table;
}

constexpr auto kTable = makeTable();

bool isSurface(ShapeType type) {
    return type == ShapeType::TriangleMesh || type == ShapeType::HeightField;
}

bool isConvex(ShapeType type) {
    return type != ShapeType::HalfSpace && !isSurface(type);
}

}  // namespace

void collide(const Shape& a, const Transform& poseA, const Shape& b, const Transform& poseB,
             Real margin, Manifold& out) {
    out.clear();
    const auto typeA = static_cast<std::size_t>(typeOf(a));
    const auto typeB = static_cast<std::size_t>(typeOf(b));
    if (typeA <= typeB) {
        if (const CollideFn fn = kTable[typeA][typeB])
            fn(a, poseA, b, poseB, margin, out);
        return;
    }
    if (const CollideFn fn = kTable[typeB][typeA]) {
        fn(b, poseB, a, poseA, margin, out);
        out.normal = -out.normal;
    }
}

void collide(const Shape& a, const Transform& poseA, const Shape& b, const Transform& poseB,
             Real margin, ManifoldSet& out) {
    const ShapeType typeA = typeOf(a);
    const ShapeType typeB = typeOf(b);
    if (isConvex(typeA) && isSurface(typeB)) {
        detail::collideConvexMesh(a, poseA, b, poseB, margin, out);
    } else if (isSurface(typeA) && isConvex(typeB)) {
        detail::collideConvexMesh(b, poseB, a, poseA, margin, out);
        for (int k = 0; k < std::max(out.count, 1); ++k)
            out.manifolds[static_cast<std::size_t>(k)].normal *= -1;
    } else {
        // As a fresh manifold: the pair's record copies all of it, unused points included.
        out.manifolds[0] = Manifold{};
        collide(a, poseA, b, poseB, margin, out.manifolds[0]);
        out.count = out.manifolds[0].pointCount > 0 ? 1 : 0;
    }
}

}  // namespace tumble
