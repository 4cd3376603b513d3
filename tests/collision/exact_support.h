#pragma once
/// Exact support points of curved shapes, for checking manifolds against the true geometry (the
/// narrowphase clips a cylinder's cap as an inscribed polygon).

#include <cmath>

#include "tumble/collision/shape.h"

namespace tumble::test {

/// The farthest point of a cylinder along `direction` (world), its true rim, not the polygon.
inline Vec3 cylinderSupport(const Cylinder& c, const Transform& t, const Vec3& direction) {
    const Vec3 d = t.rotation.conjugate() * direction;
    Vec3 s(0, 0, d.z() >= 0 ? c.halfLength : -c.halfLength);
    const Real radial = std::hypot(d.x(), d.y());
    if (radial > 0) {
        s.x() = c.radius * d.x() / radial;
        s.y() = c.radius * d.y() / radial;
    }
    return t.apply(s);
}

}  // namespace tumble::test
