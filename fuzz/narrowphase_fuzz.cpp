// libFuzzer target: the narrowphase (tumble::collide) on two shapes at poses decoded from the
// input bytes. Findings: a crash, undefined behaviour, an exception, or a manifold that breaks its
// contract (more than 4 points, a non-finite point or separation, a normal that is not unit
// length, a point separated by more than the margin).
//
// Input layout (bytes missing at the end read as zero), each value from a little-endian uint16
// mapped linearly onto its range unless said otherwise:
//   margin in [0, 0.1] m
//   shape A, shape B, each:
//     kind (1 byte, mod 8: sphere, capsule, box, cylinder, convex hull, half-space, triangle mesh,
//       height field)
//     three sizes, each log-uniform in [1e-3, 10] m (radius, half length / half extents)
//     hull only: point count (1 byte, 4 + n mod 9) and points, each coordinate in [-1, 1] x size
//     mesh and height field only: 3 x 3 sample heights, each in [-1, 1] x size 3, over a grid of
//       spacing size 1 by size 2; a mesh folds each cell along a diagonal picked by one byte's
//       bits, a height field takes one byte whose low 4 bits mark holes in its 2 x 2 cells
//     orientation: four components in [-1, 1], normalised (identity when the norm is < 1e-3)
//   position of A: each coordinate in [-1e3, 1e3] m
//   offset of B from A: each coordinate in [-1.5, 1.5] x (extent A + extent B), where the
//     extent of a half-space is 1 m
// Legal shapes only (the sizes every ShapeDef accepts), so any finding is the narrowphase's.

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <vector>

#include "tumble/collision/mesh_data.h"
#include "tumble/collision/narrowphase.h"
#include "tumble/core/error.h"

namespace {

using namespace tumble;

class Reader {
public:
    Reader(const std::uint8_t* data, std::size_t size) : data_(data), size_(size) {}
    std::uint8_t byte() { return at_ < size_ ? data_[at_++] : 0; }
    /// A uint16 mapped onto [lo, hi].
    Real linear(Real lo, Real hi) {
        const unsigned u = byte() | (unsigned{byte()} << 8);
        return lo + (hi - lo) * u / 65535.0;
    }
    Real logUniform(Real lo, Real hi) { return lo * std::pow(hi / lo, linear(0, 1)); }

private:
    const std::uint8_t* data_;
    std::size_t size_;
    std::size_t at_ = 0;
};

struct Posed {
    Shape shape;
    Quat orientation = Quat::Identity();
    Real extent = 1;  ///< a bounding radius (m)
};

Quat readOrientation(Reader& in) {
    Eigen::Vector4d q;
    for (int k = 0; k < 4; ++k)
        q[k] = in.linear(-1, 1);
    if (q.norm() < 1e-3)
        return Quat::Identity();
    q.normalize();
    return Quat(q[0], q[1], q[2], q[3]);
}

/// A 3 x 3 grid of samples as a triangle mesh (`mesh`) or a height field; see the file comment.
Shape readSurface(Reader& in, bool mesh, const Real* s) {
    HeightFieldData grid;
    grid.columns = grid.rows = 3;
    grid.spacingX = s[0];
    grid.spacingY = s[1];
    for (int k = 0; k < 9; ++k)
        grid.heights.push_back(in.linear(-1, 1) * s[2]);
    const std::uint8_t bits = in.byte();
    if (!mesh) {
        for (int k = 0; k < 4; ++k)
            grid.holes.push_back((bits >> k) & 1);
        return HeightField::fromData(grid);
    }
    TriangleMeshData data;
    for (std::uint32_t j = 0; j < 3; ++j)
        for (std::uint32_t i = 0; i < 3; ++i)
            data.vertices.emplace_back(i * s[0], j * s[1], grid.heights[j * 3 + i]);
    for (std::uint32_t j = 0; j < 2; ++j) {
        for (std::uint32_t i = 0; i < 2; ++i) {
            const std::uint32_t a = j * 3 + i, b = a + 1, c = a + 4, d = a + 3;
            if ((bits >> (j * 2 + i)) & 1) {
                data.triangles.push_back({a, b, c});
                data.triangles.push_back({a, c, d});
            } else {
                data.triangles.push_back({a, b, d});
                data.triangles.push_back({b, c, d});
            }
        }
    }
    return TriangleMesh::fromData(data);
}

/// Returns false when the bytes describe a hull that Qhull refuses (flat, too few points).
bool readShape(Reader& in, Posed& out) {
    const int kind = in.byte() % 8;
    Real s[3];
    for (Real& x : s)
        x = in.logUniform(1e-3, 10);
    bool ok = true;
    switch (kind) {
        case 0:
            out.shape = Sphere{s[0]};
            out.extent = s[0];
            break;
        case 1:
            out.shape = Capsule{s[0], s[1]};
            out.extent = s[0] + s[1];
            break;
        case 2:
            out.shape = Box{Vec3(s[0], s[1], s[2])};
            out.extent = Vec3(s[0], s[1], s[2]).norm();
            break;
        case 3:
            out.shape = Cylinder{s[0], s[1]};
            out.extent = std::hypot(s[0], s[1]);
            break;
        case 4: {
            std::vector<Vec3> points(4 + in.byte() % 9);
            for (Vec3& p : points)
                p = Vec3(in.linear(-1, 1) * s[0], in.linear(-1, 1) * s[1], in.linear(-1, 1) * s[2]);
            try {
                out.shape = ConvexHull::fromPoints(points);
            } catch (const InvalidArgument&) {
                ok = false;  // a refused cloud is the hull builder's business, not ours
            }
            out.extent = Vec3(s[0], s[1], s[2]).norm();
            break;
        }
        case 5:
            out.shape = HalfSpace{};  // the normal is set by the orientation
            out.extent = 1;
            break;
        default:
            out.shape = readSurface(in, kind == 6, s);
            out.extent = 2 * Vec3(s[0], s[1], s[2]).norm();
            break;
    }
    out.orientation = readOrientation(in);
    return ok;
}

[[noreturn]] void finding(const char* what, const Manifold& m) {
    std::fprintf(stderr, "narrowphase_fuzz: %s (points %d, normal %.17g %.17g %.17g)\n", what,
                 m.pointCount, m.normal.x(), m.normal.y(), m.normal.z());
    for (int i = 0; i < m.pointCount && i < Manifold::kMaxPoints; ++i)
        std::fprintf(stderr, "  point %d: %.17g %.17g %.17g separation %.17g\n", i,
                     m.points[i].position.x(), m.points[i].position.y(), m.points[i].position.z(),
                     m.points[i].separation);
    std::abort();
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    Reader in(data, size);
    const Real margin = in.linear(0, 0.1);
    Posed a, b;
    if (!readShape(in, a) || !readShape(in, b))
        return 0;
    Transform poseA, poseB;
    poseA.position = Vec3(in.linear(-1e3, 1e3), in.linear(-1e3, 1e3), in.linear(-1e3, 1e3));
    poseA.rotation = a.orientation;
    const Real reach = 1.5 * (a.extent + b.extent);
    poseB.position = poseA.position + Vec3(in.linear(-reach, reach), in.linear(-reach, reach),
                                           in.linear(-reach, reach));
    poseB.rotation = b.orientation;

    Manifold m;
    collide(a.shape, poseA, b.shape, poseB, margin, m);  // any exception escapes: a finding

    if (m.pointCount < 0 || m.pointCount > Manifold::kMaxPoints)
        finding("point count outside [0, 4]", m);
    if (m.pointCount == 0)
        return 0;
    if (!m.normal.allFinite() || std::abs(m.normal.norm() - 1) > 1e-9)
        finding("normal not finite and unit", m);
    for (int i = 0; i < m.pointCount; ++i) {
        const ContactPoint& p = m.points[i];
        if (!p.position.allFinite() || !std::isfinite(p.separation))
            finding("non-finite contact point", m);
        // Relative to the coordinates' size: positions up to 1e3 m carry 1e-13 m of rounding.
        if (p.separation > margin + 1e-9 * (1 + poseA.position.norm()))
            finding("point separated by more than the margin", m);
    }
    return 0;
}
