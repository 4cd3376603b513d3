#pragma once
/// World queries: ray casts and overlaps, answered through the broadphase.

#include <optional>

#include "tumble/body.h"
#include "tumble/shape.h"

namespace tumble {

/// Which shapes a query sees: those whose category has a bit in `mask`.
struct QueryFilter {
    std::uint32_t mask = 0xFFFFFFFF;
};

struct RayCastHit {
    ShapeId shape;
    BodyId body;
    Real fraction = 0;            ///< along the cast: point = origin + fraction * translation
    Vec3 point = Vec3::Zero();    ///< world (m)
    Vec3 normal = Vec3::UnitZ();  ///< outward surface normal at the point, unit
};

}  // namespace tumble
