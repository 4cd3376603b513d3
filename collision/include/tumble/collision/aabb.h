#pragma once
/// Axis-aligned bounding boxes: the currency of the broadphase.

#include "tumble/core/math.h"

namespace tumble {

struct Aabb {
    Vec3 lower = Vec3::Zero();  ///< (m)
    Vec3 upper = Vec3::Zero();  ///< (m), componentwise >= lower

    /// The box around a transformed box of half extents `halfExtents` (m).
    static Aabb ofOrientedBox(const Transform& pose, const Vec3& halfExtents);

    bool overlaps(const Aabb& other) const {
        return (lower.array() <= other.upper.array()).all() &&
               (other.lower.array() <= upper.array()).all();
    }
    bool contains(const Aabb& other) const {
        return (lower.array() <= other.lower.array()).all() &&
               (other.upper.array() <= upper.array()).all();
    }
    Aabb merged(const Aabb& other) const {
        return {lower.cwiseMin(other.lower), upper.cwiseMax(other.upper)};
    }
    /// Grown by `margin` (m) on every side: a "fat" box that stays valid while the body moves less
    /// than the margin, so the broadphase need not touch it.
    Aabb fattened(Real margin) const { return {lower.array() - margin, upper.array() + margin}; }
    Vec3 center() const { return (lower + upper) / 2; }
    bool allFinite() const { return lower.allFinite() && upper.allFinite(); }
    Real surfaceArea() const;
};

}  // namespace tumble
