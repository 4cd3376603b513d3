// World: shapes attached to bodies, body mass from shapes, contacts.

#include <vector>

#include "checks.h"
#include "tumble/core/error.h"
#include "world_impl.h"

namespace tumble {

MassProperties compoundMass(const ShapeStore& shapes, std::uint32_t firstShape) {
    std::vector<MassProperties> parts;
    for (std::uint32_t slot = firstShape; slot != BodyInfo::kNoShape;
         slot = shapes.records[slot].nextInBody) {
        const ShapeDef& def = shapes.records[slot].def;
        parts.push_back(transformed(massOf(def.geometry, def.material.density), def.localPose));
    }
    return combine(parts);
}

namespace {

// Contacts leave up to the slop of penetration; on a shape less than twice the slop across that
// is half its size or more (a 1 mm cube at the default 5 mm stays sunk on a corner). The size is
// the smallest side of the shape's box in its own frame.
void warnIfSmallerThanSlop(Real slop, BodyId body, const Shape& geometry, WarningLog& warnings) {
    if (std::holds_alternative<HalfSpace>(geometry) || isTriangleSurface(geometry))
        return;  // unbounded, or a surface whose flat box says nothing of its size
    const Aabb box = boundsOf(geometry, Transform{});
    const Real size = (box.upper - box.lower).minCoeff();
    const Real limit = 2 * slop;
    if (!(size < limit))
        return;
    Warning warning;
    warning.kind = Warning::Kind::SmallerThanSlop;
    warning.bodyA = body;
    warning.value = size;
    warning.limit = limit;
    warnings.raise(warning);
}

}  // namespace

ShapeId World::createShape(BodyId body, const ShapeDef& def) {
    Impl& w = *impl_;
    const std::uint32_t bodyIndex = w.bodies.indexOf(body);
    BodyInfo& info = w.bodies.info[bodyIndex];
    checks::shapeDef(def, info.type);
    // Compute the new mass before changing anything, so a refusal leaves the world as it was.
    const bool updateMass = def.updateBodyMass && info.type == BodyType::Dynamic;
    MassProperties mass;
    if (updateMass) {
        MassProperties parts[2] = {
            transformed(massOf(def.geometry, def.material.density), def.localPose), {}};
        const bool hasOthers = info.massFromShapes && info.firstShape != BodyInfo::kNoShape;
        if (hasOthers)
            parts[1] = compoundMass(w.shapes, info.firstShape);
        mass = hasOthers ? combine(parts) : parts[0];
        checks::massProperties(mass, "the body's mass from its shapes");
    }

    const BodyMotion& motion = w.bodies.motion[bodyIndex];
    const Transform bodyPose{w.origin(bodyIndex), motion.orientation};
    const Transform pose{bodyPose.apply(def.localPose.position),
                         motion.orientation * def.localPose.rotation};
    const Aabb box = w.contacts.proxyBounds(boundsOf(def.geometry, pose), motion.linearVelocity,
                                            w.settings.timeStep);
    if (!box.allFinite()) {
        fail(
            "createShape: the shape's bounding box at its body's pose, swept over a step at the "
            "body's velocity, must be finite (lower = (",
            box.lower.transpose(), "), upper = (", box.upper.transpose(), ") m)");
    }

    const ShapeId id = w.shapes.add(def, body);
    if (info.type == BodyType::Dynamic)
        warnIfSmallerThanSlop(w.settings.solver.slop, body, def.geometry, w.warnings);
    ShapeRecord& record = w.shapes.records[id.index];
    record.nextInBody = info.firstShape;
    info.firstShape = id.index;
    w.contacts.addShape(w.shapes, id.index, w.bodies, w.settings.timeStep);
    if (w.joints.count() > 0)
        excludeJointedPairs(w.joints, w.shapes, w.bodies, w.contacts, id.index);
    if (updateMass) {
        w.bodies.setMass(bodyIndex, mass);
        info.massFromShapes = true;
    }
    w.refreshExtent(bodyIndex);
    // A body built asleep stays asleep as its shapes are added; any other one wakes. A new
    // static shape wakes nothing: a scene is built ground first, then a pile created asleep.
    if (info.type == BodyType::Dynamic && !info.builtAsleep)
        w.islands.push(w.bodies, w.contacts, bodyIndex);
    return id;
}

void World::destroyShape(ShapeId id) {
    Impl& w = *impl_;
    const std::uint32_t slot = w.shapes.slotOf(id);
    const std::uint32_t bodyIndex = w.bodies.indexOf(w.shapes.records[slot].body);
    w.wakeChanged(bodyIndex);
    BodyInfo& info = w.bodies.info[bodyIndex];
    // Unlink from the body's list.
    if (info.firstShape == slot) {
        info.firstShape = w.shapes.records[slot].nextInBody;
    } else {
        std::uint32_t previous = info.firstShape;
        while (w.shapes.records[previous].nextInBody != slot)
            previous = w.shapes.records[previous].nextInBody;
        w.shapes.records[previous].nextInBody = w.shapes.records[slot].nextInBody;
    }
    w.contacts.removeShape(w.shapes, slot, w.bodies);
    w.shapes.remove(id);
    w.refreshExtent(bodyIndex);
}

bool World::isValid(ShapeId id) const {
    return impl_->shapes.isValid(id);
}

BodyId World::shapeBody(ShapeId id) const {
    return impl_->shapes.records[impl_->shapes.slotOf(id)].body;
}

const ShapeDef& World::shapeDef(ShapeId id) const {
    return impl_->shapes.records[impl_->shapes.slotOf(id)].def;
}

Transform World::shapeTransform(ShapeId id) const {
    return shapePose(impl_->shapes.records[impl_->shapes.slotOf(id)], impl_->bodies);
}

Aabb World::shapeBounds(ShapeId id) const {
    const ShapeRecord& record = impl_->shapes.records[impl_->shapes.slotOf(id)];
    return boundsOf(record.def.geometry, shapePose(record, impl_->bodies));
}

std::span<const Contact> World::contacts() const {
    return impl_->contacts.contacts();
}

}  // namespace tumble
