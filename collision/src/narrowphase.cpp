// Narrowphase dispatch: one table entry per ordered pair of shape types. Only the upper triangle
// (A's type <= B's type) names routines; the lower triangle is served by swapping the arguments
// and flipping the normal, so each routine is written once, for one order.

#include "tumble/collision/narrowphase.h"

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
        set(convex, TriangleMesh, &detail::collideConvexMesh);
        set(convex, HeightField, &detail::collideConvexMesh);
    }
    // Static geometry never meets static geometry.
    for (ShapeType a : {HalfSpace, TriangleMesh, HeightField})
        for (ShapeType b : {HalfSpace, TriangleMesh, HeightField})
            if (a <= b)
                set(a, b, nullptr);
    return table;
}

constexpr auto kTable = makeTable();

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

}  // namespace tumble
