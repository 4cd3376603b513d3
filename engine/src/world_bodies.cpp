// World: listing bodies and what is attached to them; changing bodies and shapes after creation
// (type, damping, user data, a shape's material and filter).

#include <algorithm>
#include <variant>

#include "checks.h"
#include "joints.h"
#include "tumble/core/error.h"
#include "world_impl.h"

namespace tumble {
namespace {

template <typename Visit>
void forEachShape(const BodyStore& bodies, const ShapeStore& shapes, std::uint32_t bodyIndex,
                  Visit&& visit) {
    for (std::uint32_t slot = bodies.info[bodyIndex].firstShape; slot != BodyInfo::kNoShape;
         slot = shapes.records[slot].nextInBody)
        visit(slot);
}

struct NewMass {
    MassProperties mass;
    bool fromShapes = false;
};

// What setBodyType refuses, checked before anything changes; returns the mass the body will
// have (used by a dynamic body only).
NewMass checkTypeChange(const BodyStore& bodies, const ShapeStore& shapes, const JointStore& joints,
                        BodyId id, BodyType type) {
    const std::uint32_t index = bodies.indexOf(id);
    const BodyInfo& info = bodies.info[index];
    bool shapesGiveMass = false;
    forEachShape(bodies, shapes, index, [&](std::uint32_t slot) {
        const ShapeDef& def = shapes.records[slot].def;
        if (type != BodyType::Static && std::holds_alternative<HalfSpace>(def.geometry)) {
            fail(
                "setBodyType: the body carries a half-space shape, which only a static body "
                "may carry");
        }
        if (type == BodyType::Dynamic && isTriangleSurface(def.geometry)) {
            fail(
                "setBodyType: the body carries a triangle mesh or height field, which only a "
                "static or kinematic body may carry");
        }
        shapesGiveMass = shapesGiveMass || def.updateBodyMass;
    });
    if (type != BodyType::Dynamic) {
        for (std::uint32_t i = 0; i < joints.count(); ++i) {
            const JointDef& def = joints.records[i].def;
            if (!(def.bodyA == id || def.bodyB == id))
                continue;
            const BodyId other = def.bodyA == id ? def.bodyB : def.bodyA;
            if (other.isNull() || bodies.info[bodies.indexOf(other)].type != BodyType::Dynamic) {
                const JointId joint = joints.idAt(i);
                fail("setBodyType: JointId {index ", joint.index, ", generation ", joint.generation,
                     "} of the body would join no dynamic body");
            }
        }
        return {info.mass, false};
    }
    const MassProperties mass = shapesGiveMass ? compoundMass(shapes, info.firstShape) : info.mass;
    checks::massProperties(mass, "setBodyType: the body's mass");
    return {mass, shapesGiveMass};
}

}  // namespace

// The calls are those of destroyShape and createShape, in the body's shape order: deterministic.
void World::Impl::detachShape(std::uint32_t slot) {
    contacts.removeShape(shapes, slot, bodies);
}
void World::Impl::attachShape(std::uint32_t slot) {
    contacts.addShape(shapes, slot, bodies, settings.timeStep);
    if (joints.count() > 0)
        excludeJointedPairs(joints, shapes, bodies, contacts, slot);
}

std::vector<BodyId> World::bodies() const {
    std::vector<BodyId> ids(impl_->bodies.count());
    for (std::uint32_t i = 0; i < ids.size(); ++i)
        ids[i] = impl_->bodies.idAt(i);
    return ids;
}

DenseState World::denseState() const {
    const std::vector<BodyMotion>& motion = impl_->bodies.motion;
    if (motion.empty())
        return {};
    const BodyMotion& first = motion.front();
    return {first.center.data(),
            first.orientation.coeffs().data(),
            first.linearVelocity.data(),
            first.angularVelocity.data(),
            motion.size(),
            sizeof(BodyMotion)};
}

std::vector<ShapeId> World::bodyShapes(BodyId id) const {
    const Impl& w = *impl_;
    std::vector<ShapeId> ids;
    forEachShape(w.bodies, w.shapes, w.bodies.indexOf(id),
                 [&](std::uint32_t slot) { ids.push_back(w.shapes.idAt(slot)); });
    std::reverse(ids.begin(), ids.end());  // the body's list is newest first
    return ids;
}

std::vector<JointId> World::bodyJoints(BodyId id) const {
    impl_->bodies.indexOf(id);  // refuses a bad id
    std::vector<JointId> ids;
    for (std::uint32_t i = 0; i < impl_->joints.count(); ++i) {
        const JointDef& def = impl_->joints.records[i].def;
        if (def.bodyA == id || def.bodyB == id)
            ids.push_back(impl_->joints.idAt(i));
    }
    return ids;
}

std::vector<SpringId> World::bodySprings(BodyId id) const {
    impl_->bodies.indexOf(id);  // refuses a bad id
    std::vector<SpringId> ids;
    for (std::uint32_t i = 0; i < impl_->springs.count(); ++i) {
        const SpringDef& def = impl_->springs.defs[i];
        if (def.bodyA == id || def.bodyB == id)
            ids.push_back(impl_->springs.idAt(i));
    }
    return ids;
}

Real World::linearDamping(BodyId id) const {
    return impl_->bodies.info[impl_->bodies.indexOf(id)].linearDamping;
}
Real World::angularDamping(BodyId id) const {
    return impl_->bodies.info[impl_->bodies.indexOf(id)].angularDamping;
}

void World::setLinearDamping(BodyId id, Real damping) {
    const std::uint32_t index = impl_->bodies.indexOf(id);
    checks::nonNegative(damping, "setLinearDamping damping (1/s)");
    impl_->bodies.info[index].linearDamping = damping;
}

void World::setAngularDamping(BodyId id, Real damping) {
    const std::uint32_t index = impl_->bodies.indexOf(id);
    checks::nonNegative(damping, "setAngularDamping damping (1/s)");
    impl_->bodies.info[index].angularDamping = damping;
}

void World::setUserData(BodyId id, std::uint64_t userData) {
    impl_->bodies.info[impl_->bodies.indexOf(id)].userData = userData;
}

void World::setBodyType(BodyId id, BodyType type) {
    Impl& w = *impl_;
    const std::uint32_t index = w.bodies.indexOf(id);
    if (w.bodies.info[index].type == type)
        return;
    const NewMass mass = checkTypeChange(w.bodies, w.shapes, w.joints, id, type);
    // What it touched wakes, as when a body is moved: all it has contacts with, for a static
    // or kinematic body (a parked pair may touch once the body moves).
    w.wakeChanged(index, true);
    forEachShape(w.bodies, w.shapes, index, [&](std::uint32_t slot) { w.detachShape(slot); });
    BodyInfo& info = w.bodies.info[index];
    info.type = type;
    info.sleepTime = 0;
    info.builtAsleep = false;
    info.massFromShapes = type == BodyType::Dynamic && mass.fromShapes;
    w.bodies.setMass(index, mass.mass);
    if (type != BodyType::Dynamic)
        w.bodies.forces[index] = {};
    if (type == BodyType::Static) {
        for (BodyMotion* m : {&w.bodies.motion[index], &w.bodies.previousMotion[index]}) {
            m->linearVelocity.setZero();
            m->angularVelocity.setZero();
        }
        if (w.bodies.isAwake(index))
            w.bodies.markNotAwake(index);
    } else if (type == BodyType::Kinematic && !w.bodies.isAwake(index)) {
        w.bodies.markAwake(index);
    }
    forEachShape(w.bodies, w.shapes, index, [&](std::uint32_t slot) { w.attachShape(slot); });
    w.refreshExtent(index);
    w.islands.push(w.bodies, w.contacts, index);  // a dynamic body wakes; others: nothing
}

void World::setShapeMaterial(ShapeId id, const Material& material) {
    Impl& w = *impl_;
    const std::uint32_t slot = w.shapes.slotOf(id);
    checks::material(material, "setShapeMaterial material");
    ShapeRecord& record = w.shapes.records[slot];
    const std::uint32_t bodyIndex = w.bodies.indexOf(record.body);
    BodyInfo& info = w.bodies.info[bodyIndex];
    const bool updateMass = info.type == BodyType::Dynamic && info.massFromShapes &&
                            record.def.updateBodyMass &&
                            material.density != record.def.material.density;
    const Material previous = record.def.material;
    record.def.material = material;
    if (updateMass) {
        const MassProperties mass = compoundMass(w.shapes, info.firstShape);
        try {
            checks::massProperties(mass, "setShapeMaterial: the body's mass from its shapes");
        } catch (...) {
            record.def.material = previous;  // a refusal changes nothing
            throw;
        }
        w.bodies.setMass(bodyIndex, mass);
        w.refreshExtent(bodyIndex);
    }
    w.islands.push(w.bodies, w.contacts, bodyIndex);
}

void World::setShapeFilter(ShapeId id, const CollisionFilter& filter) {
    Impl& w = *impl_;
    const std::uint32_t slot = w.shapes.slotOf(id);
    const std::uint32_t bodyIndex = w.bodies.indexOf(w.shapes.records[slot].body);
    w.wakeChanged(bodyIndex, true);  // what rested on the shape may now fall through
    w.detachShape(slot);
    w.shapes.records[slot].def.filter = filter;
    w.attachShape(slot);
}

}  // namespace tumble
