// A segment through a thin sheet of a triangle mesh (a thread between nodes on either side of
// an open bin's wall): the contact over the sheet's nearest border edge.
//
// The capsule's own manifold against such a sheet (collide_mesh.cpp) takes the least
// penetrating axis, often the face normal when the segment's ends lie near the wall: it pushes
// the thread sideways through the wall, which its nodes, held on both sides, cannot follow.
// The way out for a segment through a sheet is over an edge the sheet ends at: along the axis
// normal to both the segment and that edge, pointing out past the edge, as the closest features
// of the segment and the edge give it.

#include <cmath>

#include "mesh_triangles.h"
#include "pair_routines.h"
#include "tumble/collision/narrowphase.h"

namespace tumble {
namespace {

// Whether the segment from a to b crosses triangle t's plane inside the triangle.
bool pierces(const MeshTriangle& t, const Vec3& a, const Vec3& b) {
    const Real sa = (a - t.vertices[0]).dot(t.normal);
    const Real sb = (b - t.vertices[0]).dot(t.normal);
    if (!(sa * sb < 0))
        return false;
    const Vec3 x = a + sa / (sa - sb) * (b - a);
    for (std::size_t k = 0; k < 3; ++k) {
        const Vec3 edge = t.vertices[(k + 1) % 3] - t.vertices[k];
        if (edge.cross(x - t.vertices[k]).dot(t.normal) < 0)
            return false;
    }
    return true;
}

struct BorderEdge {
    Vec3 onSegment = Vec3::Zero();
    Vec3 onEdge = Vec3::Zero();
    Vec3 edge = Vec3::Zero();     ///< from its first vertex to its second
    Vec3 outward = Vec3::Zero();  ///< in the triangle's plane, away from it
    Real squaredGap = INFINITY;
};

}  // namespace

bool crossingOverBorder(const Shape& surface, const Transform& pose, const Vec3& a, const Vec3& b,
                        Real radius, SheetCrossing& out) {
    const auto* mesh = std::get_if<TriangleMesh>(&surface);
    if (mesh == nullptr)
        return false;  // a height field has no sheet to pass through but at its border
    const detail::Segment segment{pose.applyInverse(a), pose.applyInverse(b)};
    const Real length = segment.direction().norm();
    if (!(length > 0))
        return false;
    // A border edge the segment passes under lies within its length of it.
    const Vec3 reach = Vec3::Constant(length + radius);
    const Aabb box{Vec3(segment.start.cwiseMin(segment.end) - reach),
                   Vec3(segment.start.cwiseMax(segment.end) + reach)};
    bool pierced = false;
    // Only an edge within reach: a closed mesh's far border (a wall's foot) is no way out.
    BorderEdge best{.squaredGap = (length + radius) * (length + radius)};
    detail::forEachTriangle(*mesh->data, box, [&](const MeshTriangle& t) {
        pierced = pierced || pierces(t, segment.start, segment.end);
        for (std::size_t k = 0; k < 3; ++k) {
            if (mesh->data->across[t.index][k] != kNoNeighbour)
                continue;
            const detail::Segment edge{t.vertices[k], t.vertices[(k + 1) % 3]};
            const auto [s, u] = detail::closestParameters(segment, edge);
            const Vec3 onSegment = segment.start + s * segment.direction();
            const Vec3 onEdge = edge.start + u * edge.direction();
            const Real squaredGap = (onSegment - onEdge).squaredNorm();
            if (squaredGap < best.squaredGap)
                best = {onSegment, onEdge, edge.direction(), edge.direction().cross(t.normal),
                        squaredGap};
        }
    });
    if (!pierced || best.edge.squaredNorm() == 0)
        return false;
    Vec3 normal = segment.direction().cross(best.edge);
    if (!(normal.squaredNorm() >
          1e-12 * segment.direction().squaredNorm() * best.edge.squaredNorm()))
        normal = best.outward;  // along the edge: out in the sheet's plane
    normal.normalize();
    if (normal.dot(best.outward) < 0)
        normal = -normal;
    out.normal = pose.rotation * normal;
    out.point = pose.apply(best.onEdge);
    out.separation = (best.onSegment - best.onEdge).dot(normal) - radius;
    return true;
}

}  // namespace tumble
