#pragma once
/// The internal-edge rules of the mesh narrowphase (collide_mesh_edges.cpp; internal to
/// collision/): which of a triangle's contacts keep the pair routine's normal, which are redone
/// along the face normal, and the points below concave corners that no face's projection
/// reaches. collide_mesh.cpp collides each triangle, files it here, and merges what is kept.

#include <cstdint>
#include <vector>

#include "tumble/collision/manifold.h"
#include "tumble/collision/mesh_shape.h"

namespace tumble::detail {

/// Points of one group closer than this (m) are one contact point.
constexpr Real kSamePoint = 1e-6;
/// Depths this close (m) are equal but for rounding: far below what the solver or a caller sees.
constexpr Real kDepthNoise = 1e-10;

struct TriangleManifold {
    Manifold manifold;
    std::uint32_t triangle;
    std::uint8_t group = 0;  ///< which of the pair's manifolds takes its points
};

/// A point below a triangle's plane that the redo along its face normal dropped as lying over a
/// neighbour, while it may lie where no triangle's projection reaches (collide_mesh_edges.cpp).
struct GapPoint {
    ContactPoint point;
    Vec3 normal;      ///< the triangle's face normal, from the shape into it
    Vec3 shapePoint;  ///< the point on the shape it stands for
    Vec3 core;        ///< the centre of the shape's rounding there (shapePoint if none)
    bool inside;      ///< whether `core` lies below the triangle's plane
    std::uint32_t triangle;
};

/// What the edge rules keep of a pair's triangles; cleared for each pair, grown and kept (no
/// allocation in a warm step).
struct EdgeContacts {
    std::vector<TriangleManifold> manifolds;    ///< kept, each with its normal
    std::vector<TriangleManifold> unclaimed;    ///< the fallback when nothing else is kept
    std::vector<TriangleManifold> speculative;  ///< ahead of the shape on internal features
    std::vector<GapPoint> gaps;
    std::vector<MeshTriangle> triangles;  ///< all under the shape's box, in walk order

    void clear() {
        manifolds.clear();
        unclaimed.clear();
        speculative.clear();
        gaps.clear();
        triangles.clear();
    }
};

/// Files triangle t of `surface` (one of out.triangles, filled first) and its contact `tm` (the
/// pair routine's, shape against the triangle's prism; the shape at `pose` in the surface's frame)
/// under the internal-edge rules: kept with its own normal on an active edge or vertex when the
/// normal lies in that feature's normal cone, else redone along the face normal, from the side
/// the shape lies on.
void fileTriangleContact(const Shape& shape, const Transform& pose, const Shape& surface,
                         const MeshTriangle& t, Real margin, TriangleManifold tm,
                         EdgeContacts& out);

/// After every triangle is filed: adds the gap points no triangle holds, and falls back on the
/// unclaimed contacts when nothing else was kept. `rounding` is the shape's (m).
void finishEdgeContacts(Real rounding, EdgeContacts& out);

}  // namespace tumble::detail
