// World queries: candidates from the broadphase, answers from the per-shape routines.

#include <algorithm>

#include "checks.h"
#include "tumble/collision/narrowphase.h"
#include "tumble/collision/raycast.h"
#include "tumble/core/error.h"
#include "world_impl.h"

namespace tumble {
namespace {

bool passes(const ShapeRecord& shape, const QueryFilter& filter) {
    return (shape.def.filter.category & filter.mask) != 0;
}

bool byShapeId(ShapeId a, ShapeId b) {
    return a.index < b.index;
}

}  // namespace

// Casts the segment through the broadphase and calls onHit(hit, maxFraction) for every shape
// that passes the filter and is hit within the current maxFraction; onHit returns the new
// maxFraction (the hit's fraction to keep only nearer ones).
template <typename OnHit>
void World::castRay(const Impl& w, const Vec3& origin, const Vec3& translation,
                    const QueryFilter& filter, OnHit&& onHit) {
    w.contacts.broadphase().raycast(
        origin, translation, Real(1), [&](std::uint32_t proxy, Real maxFraction) {
            const std::uint32_t slot = w.contacts.shapeOfProxy(proxy);
            const ShapeRecord& shape = w.shapes.records[slot];
            if (!passes(shape, filter))
                return maxFraction;
            const std::optional<RayHit> hit =
                raycast(shape.def.geometry, shapePose(shape, w.bodies),
                        Ray{origin, translation, maxFraction});
            if (!hit)
                return maxFraction;
            return onHit(
                RayCastHit{w.shapes.idAt(slot), shape.body, hit->fraction, hit->point, hit->normal},
                maxFraction);
        });
}

std::optional<RayCastHit> World::castRayClosest(const Vec3& origin, const Vec3& translation,
                                                const QueryFilter& filter) const {
    checks::finiteVector(origin, "castRayClosest origin");
    checks::finiteVector(translation, "castRayClosest translation");
    std::optional<RayCastHit> best;
    castRay(*impl_, origin, translation, filter, [&](const RayCastHit& hit, Real maxFraction) {
        // Ties go to the lower shape id, so the answer does not depend on visiting order.
        if (best && hit.fraction == best->fraction && best->shape.index < hit.shape.index) {
            return maxFraction;
        }
        best = hit;
        return hit.fraction;
    });
    return best;
}

std::vector<RayCastHit> World::castRayAll(const Vec3& origin, const Vec3& translation,
                                          const QueryFilter& filter) const {
    checks::finiteVector(origin, "castRayAll origin");
    checks::finiteVector(translation, "castRayAll translation");
    std::vector<RayCastHit> hits;
    castRay(*impl_, origin, translation, filter, [&](const RayCastHit& hit, Real maxFraction) {
        hits.push_back(hit);
        return maxFraction;  // never clip: every hit is wanted
    });
    std::sort(hits.begin(), hits.end(), [](const RayCastHit& a, const RayCastHit& b) {
        return a.fraction != b.fraction ? a.fraction < b.fraction : a.shape.index < b.shape.index;
    });
    return hits;
}

std::vector<ShapeId> World::overlapAabb(const Aabb& box, const QueryFilter& filter) const {
    checks::finiteVector(box.lower, "overlapAabb box.lower");
    checks::finiteVector(box.upper, "overlapAabb box.upper");
    const Impl& w = *impl_;
    std::vector<ShapeId> found;
    w.contacts.broadphase().query(box, [&](std::uint32_t proxy) {
        const std::uint32_t slot = w.contacts.shapeOfProxy(proxy);
        const ShapeRecord& shape = w.shapes.records[slot];
        // The broadphase holds fat boxes: confirm against the tight one.
        if (passes(shape, filter) && shape.bounds.overlaps(box))
            found.push_back(w.shapes.idAt(slot));
    });
    std::sort(found.begin(), found.end(), byShapeId);
    return found;
}

std::vector<ShapeId> World::overlapShape(const Shape& shape, const Transform& pose,
                                         const QueryFilter& filter) const {
    checkShape(shape, "overlapShape shape");
    checks::finiteVector(pose.position, "overlapShape pose.position");
    checks::unitQuaternion(pose.rotation, "overlapShape pose.rotation");
    const Impl& w = *impl_;
    std::vector<ShapeId> found;
    Manifold manifold;
    for (ShapeId id : overlapAabb(boundsOf(shape, pose), filter)) {
        const ShapeRecord& other = w.shapes.records[id.index];
        collide(shape, pose, other.def.geometry, shapePose(other, w.bodies), 0, manifold);
        if (manifold.pointCount > 0)
            found.push_back(id);
    }
    return found;
}

Vec3 World::closestPoint(ShapeId id, const Vec3& point) const {
    checks::finiteVector(point, "closestPoint point");
    const ShapeRecord& shape = impl_->shapes.records[impl_->shapes.slotOf(id)];
    return tumble::closestPoint(shape.def.geometry, shapePose(shape, impl_->bodies), point);
}

std::span<const Warning> World::warnings() const {
    return impl_->warnings.items();
}

std::size_t World::droppedWarnings() const {
    return impl_->warnings.dropped();
}

void World::clearWarnings() {
    impl_->warnings.clear();
}

}  // namespace tumble
