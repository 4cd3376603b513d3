// When both cores are polytopes (a box, a hull, a sphere's centre or a capsule's segment) the
// Minkowski difference D = A - B is a polytope whose facets have, as outward normals, the face
// normals of A, the negated face normals of B and cross products of non-parallel edge pairs (a
// facet of a Minkowski sum is a sum of faces F_A + F_B of dimension 2: face + vertex, vertex +
// face or edge + edge). The penetration depth is the distance from the origin (inside D) to the
// nearest facet plane, h_D(n) for the facet normal n, and h_D(n) >= depth along any direction. So
// the least overlap over those axes is the exact depth, and the axis its exact normal.
//
// Not every edge pair spans a facet: eA - eB does only when the arc of A's edge on the Gauss map
// (from one adjacent face normal to the other) crosses the arc of B's edge negated (Gregorius,
// "The Separating Axis Test between Convex Polyhedra", GDC 2013). That test costs a few products,
// and a facet's overlap is then n . (a - b) for points a, b on the two edges, so the edge pairs
// cost O(edges A x edges B) small tests instead of as many support sweeps over all vertices.

#include "polytope_sat.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

namespace tumble::detail {

bool isPolytopeCore(const Shape& shape) {
    const ShapeType type = typeOf(shape);
    return type == ShapeType::Sphere || type == ShapeType::Capsule || type == ShapeType::Box ||
           type == ShapeType::ConvexHull;
}

namespace {

/// Cross products shorter than this (squared, of unit directions) mark parallel edges: they span
/// no facet, and their cross product would be noise.
constexpr Real kParallelCross2 = 1e-20;
/// An edge-pair axis replaces a face axis only when shallower by more than this (m): on ties the
/// face normal is kept, which collideConvex clips against.
constexpr Real kEdgeAxisMargin = 1e-12;
/// Edges whose Gauss-map arcs are gathered per shape and query (a 64-vertex hull has at most 186
/// edges). A hull with more takes the brute-force path: every edge pair by support sweeps.
constexpr int kMaxArcEdges = 192;

/// The flat faces of a core: a box's and a hull's, and a cylinder's two caps.
int faceCount(const Shape& shape) {
    if (typeOf(shape) == ShapeType::Box)
        return 6;
    if (typeOf(shape) == ShapeType::Cylinder)
        return 2;
    if (const auto* hull = std::get_if<ConvexHull>(&shape))
        return static_cast<int>(hull->data->faces.size());
    return 0;
}

/// Outward normal (local, unit) and plane offset (m) of face `k`: normal . x <= offset inside.
void faceAt(const Shape& shape, int k, Vec3& normal, Real& offset) {
    if (const auto* box = std::get_if<Box>(&shape)) {
        normal = (k % 2 == 0 ? 1.0 : -1.0) * Vec3::Unit(k / 2);
        offset = box->halfExtents[k / 2];
        return;
    }
    if (const auto* cylinder = std::get_if<Cylinder>(&shape)) {
        normal = (k == 0 ? 1.0 : -1.0) * Vec3::UnitZ();
        offset = cylinder->halfLength;
        return;
    }
    const HullFace& face = std::get<ConvexHull>(shape).data->faces[static_cast<std::size_t>(k)];
    normal = face.normal;
    offset = face.offset;
}

/// The interval a posed polytope or cylinder core covers along a world axis (m).
struct Extent {
    Real low, high;
};

Extent extentAlong(const PosedCore& core, const Vec3& axis) {
    const Vec3 local = core.rotation.transpose() * axis;
    const Real centre = axis.dot(core.position);
    Real radius = 0;
    switch (typeOf(*core.shape)) {
        case ShapeType::Box:
            radius = local.cwiseAbs().dot(std::get<Box>(*core.shape).halfExtents);
            break;
        case ShapeType::Capsule:
            radius = std::abs(local.z()) * std::get<Capsule>(*core.shape).halfLength;
            break;
        case ShapeType::Cylinder: {
            const auto& cylinder = std::get<Cylinder>(*core.shape);
            radius = std::abs(local.z()) * cylinder.halfLength +
                     cylinder.radius * std::hypot(local.x(), local.y());
            break;
        }
        case ShapeType::ConvexHull: {
            Real low = std::numeric_limits<Real>::infinity(), high = -low;
            for (const Vec3& vertex : std::get<ConvexHull>(*core.shape).data->vertices) {
                const Real dot = local.dot(vertex);
                low = std::min(low, dot);
                high = std::max(high, dot);
            }
            return {centre + low, centre + high};
        }
        default:
            break;  // a sphere's core is its centre
    }
    return {centre - radius, centre + radius};
}

/// An edge with its Gauss-map arc: the outward normals of its two faces (world).
struct ArcEdge {
    Vec3 point, direction;  ///< a point on the edge (m) and its unit direction
    Vec3 normal1, normal2;
    Vec3 arcPlane;  ///< normal2 x normal1: the normal of the plane through the arc
};

/// The edges of a posed core with their arcs. A segment (capsule core) is one edge whose normals
/// span the whole circle around it (`segment`); a sphere's point has none. `complete` is false
/// for a hull of more than kMaxArcEdges edges, which then lists none.
struct ArcEdges {
    std::array<ArcEdge, kMaxArcEdges> edges;
    int count = 0;
    bool segment = false;
    bool complete = true;
};

void boxArcEdges(const Box& box, const PosedCore& core, ArcEdges& out) {
    const Mat3& r = core.rotation;
    for (int i = 0; i < 3; ++i) {
        const int j = (i + 1) % 3, k = (i + 2) % 3;
        for (const Real signJ : {-1.0, 1.0}) {
            for (const Real signK : {-1.0, 1.0}) {
                Vec3 corner;
                corner[i] = -box.halfExtents[i];
                corner[j] = signJ * box.halfExtents[j];
                corner[k] = signK * box.halfExtents[k];
                const Vec3 normal1 = signJ * r.col(j), normal2 = signK * r.col(k);
                out.edges[static_cast<std::size_t>(out.count++)] = {
                    r * corner + core.position, r.col(i), normal1, normal2, normal2.cross(normal1)};
            }
        }
    }
}

/// Each hull edge lies on two faces, running counter-clockwise (u -> v) on one and v -> u on the
/// other; HullData::edges is sorted, so a binary search finds the edge of each face side.
void hullArcEdges(const HullData& hull, const PosedCore& core, ArcEdges& out) {
    if (hull.edges.size() > static_cast<std::size_t>(kMaxArcEdges)) {
        out.complete = false;
        return;
    }
    out.count = static_cast<int>(hull.edges.size());
    for (const HullFace& face : hull.faces) {
        const Vec3 normal = core.rotation * face.normal;
        for (std::uint32_t k = 0; k < face.count; ++k) {
            const std::uint32_t u = hull.faceVertices[face.first + k];
            const std::uint32_t v = hull.faceVertices[face.first + (k + 1) % face.count];
            const std::array<std::uint32_t, 2> key{std::min(u, v), std::max(u, v)};
            const auto found = std::lower_bound(hull.edges.begin(), hull.edges.end(), key);
            ArcEdge& edge = out.edges[static_cast<std::size_t>(found - hull.edges.begin())];
            if (u < v) {
                edge.point = core.rotation * hull.vertices[u] + core.position;
                edge.direction = core.rotation * (hull.vertices[v] - hull.vertices[u]).normalized();
                edge.normal1 = normal;
            } else {
                edge.normal2 = normal;
            }
        }
    }
    for (int k = 0; k < out.count; ++k) {
        ArcEdge& edge = out.edges[static_cast<std::size_t>(k)];
        edge.arcPlane = edge.normal2.cross(edge.normal1);
    }
}

void gatherArcEdges(const PosedCore& core, ArcEdges& out) {
    if (const auto* box = std::get_if<Box>(core.shape)) {
        boxArcEdges(*box, core, out);
    } else if (const auto* hull = std::get_if<ConvexHull>(core.shape)) {
        hullArcEdges(*hull->data, core, out);
    } else if (const auto* capsule = std::get_if<Capsule>(core.shape)) {
        out.edges[0].point = core.rotation * Vec3(0, 0, -capsule->halfLength) + core.position;
        out.edges[0].direction = core.rotation.col(2);
        out.count = 1;
        out.segment = true;
    }
}

/// Whether the arc of A's edge (a to b) crosses the arc of B's edge negated (c = -normal1 of B to
/// d = -normal2) on the unit sphere: c and d lie on opposite sides of the plane through a and b,
/// a and b on opposite sides of the plane through c and d, and the crossing is on the arcs, not
/// at their antipodes (cba and bdc of one sign). d x c = normal2 x normal1 of B, as the signs
/// cancel. Branch-free: the outcome is a coin toss that a branch predictor cannot learn.
bool arcsCross(const ArcEdge& edgeA, const ArcEdge& edgeB) {
    const Real cba = -edgeB.normal1.dot(edgeA.arcPlane), dba = -edgeB.normal2.dot(edgeA.arcPlane);
    const Real adc = edgeA.normal1.dot(edgeB.arcPlane), bdc = edgeA.normal2.dot(edgeB.arcPlane);
    return (cba * dba < 0) & (adc * bdc < 0) & (cba * bdc > 0);
}

enum class AxisKind : std::uint8_t { FaceA, FaceB, Edges };

/// The least-overlap axis of two polytope cores.
struct SeparatingAxis {
    Vec3 normal = Vec3::UnitZ();                         ///< world, unit, from A to B
    Real depth = std::numeric_limits<Real>::infinity();  ///< core overlap along it (m)
    AxisKind kind = AxisKind::FaceA;
    ArcEdge edgeA, edgeB;  ///< the edge pair (point and direction), for Edges
};

/// The overlap along A's face normals (B moves out along n) and B's (along -m): only the other
/// shape's extent is needed, the face plane gives the own one.
void faceAxes(const PosedCore& a, const PosedCore& b, SeparatingAxis& best) {
    for (const PosedCore* owner : {&a, &b}) {
        const PosedCore& other = owner == &a ? b : a;
        const int faces = faceCount(*owner->shape);
        for (int k = 0; k < faces; ++k) {
            Vec3 local;
            Real offset = 0;
            faceAt(*owner->shape, k, local, offset);
            const Vec3 normal = owner->rotation * local;
            const Real plane = offset + normal.dot(owner->position);
            const Real overlap = plane - extentAlong(other, normal).low;
            if (overlap < best.depth) {
                best.depth = overlap;
                best.normal = owner == &a ? normal : Vec3(-normal);
                best.kind = owner == &a ? AxisKind::FaceA : AxisKind::FaceB;
            }
        }
    }
}

/// Offers the axis edgeA x edgeB with the smaller of its two overlaps, measured by support
/// sweeps: for a segment (whose arc is a whole circle) and for the brute-force path.
void sweptEdgeAxis(const PosedCore& a, const PosedCore& b, const ArcEdge& edgeA,
                   const ArcEdge& edgeB, SeparatingAxis& best) {
    Vec3 axis = edgeA.direction.cross(edgeB.direction);
    const Real length2 = axis.squaredNorm();
    if (length2 <= kParallelCross2)
        return;
    axis /= std::sqrt(length2);
    const Extent extentA = extentAlong(a, axis), extentB = extentAlong(b, axis);
    // B moves out along +axis by high A - low B, along -axis by high B - low A.
    const Real along = extentA.high - extentB.low, against = extentB.high - extentA.low;
    const Real overlap = std::min(along, against);
    if (overlap < best.depth - kEdgeAxisMargin) {
        const Vec3 normal = along <= against ? axis : Vec3(-axis);
        ArcEdge supportA = edgeA, supportB = edgeB;  // the edges through the supporting points
        supportA.point = a.support(normal);
        supportB.point = b.support(-normal);
        best = {normal, overlap, AxisKind::Edges, supportA, supportB};
    }
}

/// Offers the axes of the edge pairs that span facets of the Minkowski difference.
void edgeAxes(const PosedCore& a, const PosedCore& b, const ArcEdges& edgesA,
              const ArcEdges& edgesB, SeparatingAxis& best) {
    for (int i = 0; i < edgesA.count; ++i) {
        const ArcEdge& edgeA = edgesA.edges[static_cast<std::size_t>(i)];
        for (int j = 0; j < edgesB.count; ++j) {
            const ArcEdge& edgeB = edgesB.edges[static_cast<std::size_t>(j)];
            if (edgesA.segment || edgesB.segment) {
                sweptEdgeAxis(a, b, edgeA, edgeB, best);
                continue;
            }
            if (!arcsCross(edgeA, edgeB))
                continue;
            Vec3 axis = edgeA.direction.cross(edgeB.direction);
            const Real length2 = axis.squaredNorm();
            if (length2 <= kParallelCross2)
                continue;
            axis /= std::sqrt(length2);
            if (axis.dot(edgeA.normal1 + edgeA.normal2) < 0)
                axis = -axis;  // the crossing lies on A's arc, within the cone of its normals
            const Real overlap = axis.dot(edgeA.point - edgeB.point);
            if (overlap < best.depth - kEdgeAxisMargin)
                best = {axis, overlap, AxisKind::Edges, edgeA, edgeB};
        }
    }
}

/// The direction of edge `k` of a posed core, with no arc: the brute-force path's view of a hull
/// past kMaxArcEdges.
ArcEdge sweptEdge(const PosedCore& core, const ArcEdges& arcs, int k) {
    if (arcs.complete)
        return arcs.edges[static_cast<std::size_t>(k)];
    const HullData& hull = *std::get<ConvexHull>(*core.shape).data;
    const auto& pair = hull.edges[static_cast<std::size_t>(k)];
    const Vec3 local = (hull.vertices[pair[1]] - hull.vertices[pair[0]]).normalized();
    return {Vec3::Zero(), core.rotation * local, Vec3::Zero(), Vec3::Zero(), Vec3::Zero()};
}

/// Every edge pair by support sweeps, for hulls past kMaxArcEdges.
void bruteForceEdgeAxes(const PosedCore& a, const PosedCore& b, const ArcEdges& edgesA,
                        const ArcEdges& edgesB, SeparatingAxis& best) {
    const auto countOf = [](const PosedCore& core, const ArcEdges& arcs) {
        return arcs.complete
                   ? arcs.count
                   : static_cast<int>(std::get<ConvexHull>(*core.shape).data->edges.size());
    };
    const int countA = countOf(a, edgesA), countB = countOf(b, edgesB);
    for (int i = 0; i < countA; ++i) {
        const ArcEdge edgeA = sweptEdge(a, edgesA, i);
        for (int j = 0; j < countB; ++j)
            sweptEdgeAxis(a, b, edgeA, sweptEdge(b, edgesB, j), best);
    }
}

/// The minimum-overlap axis over face normals and edge pairs; depth stays infinite when there is
/// no axis at all (two point cores).
SeparatingAxis minimumOverlapAxis(const PosedCore& a, const PosedCore& b) {
    SeparatingAxis best;
    faceAxes(a, b, best);
    ArcEdges edgesA, edgesB;
    gatherArcEdges(a, edgesA);
    gatherArcEdges(b, edgesB);
    if (edgesA.complete && edgesB.complete)
        edgeAxes(a, b, edgesA, edgesB, best);
    else
        bruteForceEdgeAxes(a, b, edgesA, edgesB, best);
    return best;
}

/// Fills `out` from the least-overlap axis: the witness points are the deepest point of the
/// shape opposite the face and its projection onto the face plane, or for an edge pair the
/// closest points of the two edge lines.
void axisContact(const PosedCore& a, const PosedCore& b, const SeparatingAxis& axis,
                 ConvexContact& out) {
    const Vec3& n = axis.normal;
    Vec3 pointA, pointB;
    if (axis.kind == AxisKind::FaceA) {
        pointB = b.support(-n);
        pointA = pointB + axis.depth * n;
    } else if (axis.kind == AxisKind::FaceB) {
        pointA = a.support(n);
        pointB = pointA - axis.depth * n;
    } else {
        // Lines pA + s eA and pB + t eB: the closest pair solves eA.(r + s eA - t eB) = 0 and
        // eB.(r + s eA - t eB) = 0 with r = pA - pB (unit e, 1 - b^2 > 0 as they are not parallel).
        const Vec3& edgeA = axis.edgeA.direction;
        const Vec3& edgeB = axis.edgeB.direction;
        const Vec3 r = axis.edgeA.point - axis.edgeB.point;
        const Real cosine = edgeA.dot(edgeB);
        const Real c = edgeA.dot(r), f = edgeB.dot(r);
        const Real s = (cosine * f - c) / (1 - cosine * cosine);
        pointA = axis.edgeA.point + s * edgeA;
        pointB = axis.edgeB.point + (f + s * cosine) * edgeB;
    }
    out.normal = n;
    out.separation = -(axis.depth + a.radius + b.radius);
    out.pointA = pointA + a.radius * n;
    out.pointB = pointB - b.radius * n;
}
}  // namespace

bool leastFaceOverlap(const PosedCore& a, const PosedCore& b, Vec3& normal, Real& depth) {
    SeparatingAxis best;
    faceAxes(a, b, best);
    if (!(best.depth < std::numeric_limits<Real>::infinity()))
        return false;
    normal = best.normal;
    depth = best.depth + a.radius + b.radius;
    return true;
}

bool polytopePenetration(const PosedCore& a, const PosedCore& b, ConvexContact& out) {
    const SeparatingAxis axis = minimumOverlapAxis(a, b);
    if (!(axis.depth < std::numeric_limits<Real>::infinity()))
        return false;
    axisContact(a, b, axis, out);
    return true;
}

}  // namespace tumble::detail
