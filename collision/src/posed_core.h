#pragma once
/// A shape's core posed in the world, shared by GJK, the libccd adapter and the separating-axis
/// pass (internal to collision/).

#include "gjk.h"
#include "tumble/collision/shape.h"

namespace tumble::detail {

/// A shape's core at a pose held as a rotation matrix: a world support query then costs two 3x3
/// products instead of two quaternion rotations (which dominated the profile).
struct PosedCore {
    const Shape* shape;
    Mat3 rotation;
    Vec3 position;
    Real radius;

    PosedCore(const Shape& s, const Transform& pose)
        : shape(&s),
          rotation(pose.rotation.toRotationMatrix()),
          position(pose.position),
          radius(roundingRadius(s)) {}

    /// The core's farthest point along `direction` (world, need not be unit), world frame.
    Vec3 support(const Vec3& direction) const {
        const Vec3 local = rotation.transpose() * direction;
        return rotation * coreSupport(*shape, local) + position;
    }
};

}  // namespace tumble::detail
