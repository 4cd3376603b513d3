// Mass properties from geometry: closed forms for the primitives, polyhedral volume integration
// for convex hulls, and the parallel-axis theorem to combine and move them.
//
// Inertia from the second moment: with C = integral of x x^T dm about the centre of mass,
// I = trace(C) 1 - C. Moving mass m from its centre to an offset d adds m (|d|^2 1 - d d^T).

#include <cmath>
#include <numbers>
#include <variant>

#include "tumble/collision/shape.h"
#include "tumble/core/error.h"

namespace tumble {
namespace {

constexpr Real kPi = std::numbers::pi_v<Real>;

MassProperties diagonal(Real mass, const Vec3& moments) {
    MassProperties out;
    out.mass = mass;
    out.localCenter = Vec3::Zero();
    out.inertia = moments.asDiagonal();
    return out;
}

/// The inertia that mass `mass` at offset `d` from the reference point adds (parallel axis).
Mat3 pointInertia(Real mass, const Vec3& d) {
    return mass * (d.squaredNorm() * Mat3::Identity() - d * d.transpose());
}

/// Solid hemisphere of radius r with its flat face at the origin, bulging along +z. Its centroid
/// sits 3r/8 from the face. About the face centre, every axis through it gives 2/5 m r^2 (half a
/// sphere, by symmetry of the sphere through that plane); about the centroid the transverse
/// moment loses m (3r/8)^2.
struct Hemisphere {
    Real mass;
    Real centroidHeight;    ///< 3r/8 (m)
    Real axialMoment;       ///< about z through the centroid: 2/5 m r^2
    Real transverseMoment;  ///< about x (or y) through the centroid: (2/5 - 9/64) m r^2
};

Hemisphere hemisphere(Real radius, Real density) {
    const Real mass = density * 2 * kPi * radius * radius * radius / 3;
    const Real h = 3 * radius / 8;
    const Real faceMoment = 0.4 * mass * radius * radius;
    return {mass, h, faceMoment, faceMoment - mass * h * h};
}

MassProperties massOfCapsule(const Capsule& capsule, Real density) {
    const Real r = capsule.radius;
    const Real h = capsule.halfLength;
    // Cylinder of length 2h: I_z = m r^2 / 2, I_x = m (3 r^2 + (2h)^2) / 12.
    const Real cylinderMass = density * kPi * r * r * 2 * h;
    const Real cylinderAxial = cylinderMass * r * r / 2;
    const Real cylinderTransverse = cylinderMass * (3 * r * r + 4 * h * h) / 12;
    // Two hemispheres, centroids at z = +-(h + 3r/8): parallel axis for the transverse moment.
    const Hemisphere cap = hemisphere(r, density);
    const Real offset = h + cap.centroidHeight;
    const Real capTransverse = cap.transverseMoment + cap.mass * offset * offset;
    const Real transverse = cylinderTransverse + 2 * capTransverse;
    return diagonal(cylinderMass + 2 * cap.mass,
                    Vec3(transverse, transverse, cylinderAxial + 2 * cap.axialMoment));
}

/// Integrates volume, first and second moments over the solid as a fan of signed tetrahedra
/// from a reference point to each face's triangle fan. For a tetrahedron (0, a, b, c) with
/// D = det[a b c]: volume D/6, first moment D/24 (a + b + c), and second moment
/// integral x x^T dV = D/120 (a a^T + b b^T + c c^T + s s^T) with s = a + b + c (the standard
/// simplex result: mapping the unit simplex linearly, whose integral of x_i x_j is
/// (1 + [i = j]) / 120). Faces are counter-clockwise from outside, so D > 0 for a reference point
/// inside. The reference is the vertices' mean, to keep the products small for hulls far from the
/// origin.
MassProperties massOfHull(const HullData& hull, Real density) {
    Vec3 reference = Vec3::Zero();
    for (const Vec3& v : hull.vertices)
        reference += v;
    reference /= static_cast<Real>(hull.vertices.size());

    Real volume = 0;
    Vec3 firstMoment = Vec3::Zero();
    Mat3 secondMoment = Mat3::Zero();
    for (const HullFace& face : hull.faces) {
        const Vec3 a = hull.vertices[hull.faceVertices[face.first]] - reference;
        for (std::uint32_t k = 1; k + 1 < face.count; ++k) {
            const Vec3 b = hull.vertices[hull.faceVertices[face.first + k]] - reference;
            const Vec3 c = hull.vertices[hull.faceVertices[face.first + k + 1]] - reference;
            const Real det = a.dot(b.cross(c));
            const Vec3 s = a + b + c;
            volume += det / 6;
            firstMoment += det / 24 * s;
            secondMoment +=
                det / 120 *
                (a * a.transpose() + b * b.transpose() + c * c.transpose() + s * s.transpose());
        }
    }
    const Vec3 center = firstMoment / volume;  // relative to the reference
    const Mat3 centralMoment = secondMoment - volume * center * center.transpose();
    MassProperties out;
    out.mass = density * volume;
    out.localCenter = reference + center;
    out.inertia = density * (centralMoment.trace() * Mat3::Identity() - centralMoment);
    return out;
}

struct MassOfShape {
    Real density;

    MassProperties operator()(const Sphere& sphere) const {
        const Real r = sphere.radius;
        const Real mass = density * 4 * kPi * r * r * r / 3;
        return diagonal(mass, Vec3::Constant(0.4 * mass * r * r));
    }
    MassProperties operator()(const Capsule& capsule) const {
        return massOfCapsule(capsule, density);
    }
    MassProperties operator()(const Box& box) const {
        const Vec3 e = box.halfExtents;
        const Real mass = density * 8 * e.prod();
        const Vec3 square = e.cwiseProduct(e);
        // I_x = m (b^2 + c^2) / 12 with full sides b = 2 e_y, c = 2 e_z.
        return diagonal(mass, mass / 3 *
                                  Vec3(square.y() + square.z(), square.z() + square.x(),
                                       square.x() + square.y()));
    }
    MassProperties operator()(const Cylinder& cylinder) const {
        const Real r = cylinder.radius;
        const Real h = cylinder.halfLength;
        const Real mass = density * kPi * r * r * 2 * h;
        const Real transverse = mass * (3 * r * r + 4 * h * h) / 12;
        return diagonal(mass, Vec3(transverse, transverse, mass * r * r / 2));
    }
    MassProperties operator()(const ConvexHull& hull) const {
        return massOfHull(*hull.data, density);
    }
    MassProperties operator()(const HalfSpace&) const {
        fail("massOf: a HalfSpace is unbounded and has no finite mass; put it on a static body");
    }
    MassProperties operator()(const TriangleMesh&) const {
        fail(
            "massOf: a TriangleMesh is a surface with no mass; put it on a static or kinematic "
            "body");
    }
    MassProperties operator()(const HeightField&) const {
        fail(
            "massOf: a HeightField is a surface with no mass; put it on a static or kinematic "
            "body");
    }
};

}  // namespace

MassProperties massOf(const Shape& shape, Real density) {
    if (!std::isfinite(density) || density <= 0)
        fail("massOf: density = ", density, " kg/m^3 must be finite and > 0");
    checkShape(shape, "massOf");
    return std::visit(MassOfShape{density}, shape);
}

MassProperties combine(std::span<const MassProperties> parts) {
    Real mass = 0;
    Vec3 weighted = Vec3::Zero();
    for (std::size_t i = 0; i < parts.size(); ++i) {
        const MassProperties& part = parts[i];
        if (!std::isfinite(part.mass) || !isFinite(part.localCenter) || !isFinite(part.inertia))
            fail("combine: parts[", i, "] (mass = ", part.mass, " kg) must be finite");
        mass += part.mass;
        weighted += part.mass * part.localCenter;
    }
    if (!(mass > 0))
        fail("combine: total mass = ", mass, " kg over ", parts.size(), " parts must be > 0");
    MassProperties out;
    out.mass = mass;
    out.localCenter = weighted / mass;
    out.inertia = Mat3::Zero();
    for (const MassProperties& part : parts)
        out.inertia += part.inertia + pointInertia(part.mass, part.localCenter - out.localCenter);
    return out;
}

MassProperties transformed(const MassProperties& mass, const Transform& pose) {
    // Inertia is a tensor: in the parent axes it reads R I R^T; the centre moves as a point.
    const Mat3 rotation = pose.rotation.toRotationMatrix();
    MassProperties out;
    out.mass = mass.mass;
    out.localCenter = pose.apply(mass.localCenter);
    const Mat3 rotated = rotation * mass.inertia * rotation.transpose();
    out.inertia = (rotated + rotated.transpose()) / 2;  // symmetric to the last bit
    return out;
}

}  // namespace tumble
