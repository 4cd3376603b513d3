#pragma once
/// Contact manifolds: what the narrowphase tells the solver about one touching pair.

#include <array>
#include <cstdint>

#include "tumble/core/math.h"

namespace tumble {

/// One contact point. `featureId` names the pair of features (face, edge, vertex of each shape)
/// that made the point, and stays the same while the contact persists, so the solver can warm
/// start it from the last step's impulses.
struct ContactPoint {
    Vec3 position = Vec3::Zero();  ///< world; midway between the two surfaces (m)
    Real separation = 0;           ///< along the normal (m); negative when penetrating
    std::uint32_t featureId = 0;
};

/// Up to four points sharing one normal. The normal points from shape A to shape B (world).
/// Points with separation up to the speculative margin are included.
struct Manifold {
    static constexpr int kMaxPoints = 4;
    Vec3 normal = Vec3::UnitZ();
    int pointCount = 0;
    std::array<ContactPoint, kMaxPoints> points;

    void clear() { pointCount = 0; }
    void add(const Vec3& position, Real separation, std::uint32_t featureId) {
        if (pointCount < kMaxPoints)
            points[pointCount++] = {position, separation, featureId};
    }
};

/// The manifolds of one shape pair: one for most pairs, several where a convex shape touches a
/// triangle mesh or height field along faces of different normals (a box in a V-shaped crease),
/// one per normal. Listed deepest first; each listed manifold has points.
struct ManifoldSet {
    static constexpr int kMaxManifolds = 4;
    int count = 0;
    std::array<Manifold, kMaxManifolds> manifolds;
};

}  // namespace tumble
