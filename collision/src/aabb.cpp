#include "tumble/collision/aabb.h"

namespace tumble {

Aabb Aabb::ofOrientedBox(const Transform& pose, const Vec3& halfExtents) {
    // Half extent of the rotated box along world axis i is sum_j |R_ij| e_j.
    const Mat3 rotation = pose.rotation.toRotationMatrix();
    const Vec3 extent = rotation.cwiseAbs() * halfExtents;
    return {pose.position - extent, pose.position + extent};
}

Real Aabb::surfaceArea() const {
    const Vec3 d = upper - lower;
    return 2 * (d.x() * d.y() + d.y() * d.z() + d.z() * d.x());
}

}  // namespace tumble
