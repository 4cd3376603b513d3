#include "contact_manager.h"

#include <algorithm>

#include "tumble/collision/narrowphase.h"

namespace tumble {
namespace {

// A persisting point whose feature id changed (e.g. a clip vertex renamed) still inherits its
// impulse when it lies this close to a point of the last step (m).
constexpr Real kMatchDistance = 0.01;

Transform bodyTransform(const BodyStore& bodies, std::uint32_t index) {
    const BodyMotion& m = bodies.motion[index];
    return {m.center - m.orientation * bodies.inertia[index].localCenter, m.orientation};
}

// The tight box, grown along the motion expected over the next step so fast bodies find their
// pairs before they reach them.
Aabb sweptBounds(const Aabb& tight, const Vec3& velocity, Real h) {
    const Vec3 displacement = h * velocity;
    return {tight.lower + displacement.cwiseMin(Vec3::Zero()),
            tight.upper + displacement.cwiseMax(Vec3::Zero())};
}

void carryImpulses(const Contact& previous, Contact& next) {
    for (int i = 0; i < next.manifold.pointCount; ++i) {
        const ContactPoint& point = next.manifold.points[i];
        int match = -1;
        for (int j = 0; j < previous.manifold.pointCount && match < 0; ++j) {
            if (previous.manifold.points[j].featureId == point.featureId)
                match = j;
        }
        for (int j = 0; j < previous.manifold.pointCount && match < 0; ++j) {
            if ((previous.manifold.points[j].position - point.position).norm() < kMatchDistance)
                match = j;
        }
        next.normalImpulse[i] = match >= 0 ? previous.normalImpulse[match] : 0;
        next.tangentImpulse[i] = match >= 0 ? previous.tangentImpulse[match] : Vec3::Zero();
    }
}

}  // namespace

Transform shapePose(const ShapeRecord& shape, const BodyStore& bodies) {
    const Transform body = bodyTransform(bodies, bodies.indexOf(shape.body));
    const Transform& local = shape.def.localPose;
    return {body.apply(local.position), body.rotation * local.rotation};
}

void ContactManager::addShape(ShapeStore& shapes, std::uint32_t slot, const BodyStore& bodies,
                              Real h) {
    ShapeRecord& shape = shapes.records[slot];
    const std::uint32_t bodyIndex = bodies.indexOf(shape.body);
    shape.bounds = boundsOf(shape.def.geometry, shapePose(shape, bodies));
    shape.fatBounds =
        sweptBounds(shape.bounds, bodies.motion[bodyIndex].linearVelocity, h).fattened(aabbMargin);
    ProxyFilter filter;
    filter.category = shape.def.filter.category;
    filter.mask = shape.def.filter.mask;
    filter.isStatic = bodies.info[bodyIndex].type == BodyType::Static;
    shape.proxy = broadphase_.add(shape.fatBounds, filter);
    if (proxyToShape_.size() <= shape.proxy)
        proxyToShape_.resize(shape.proxy + 1);
    proxyToShape_[shape.proxy] = slot;
}

void ContactManager::removeShape(ShapeStore& shapes, std::uint32_t slot) {
    broadphase_.remove(shapes.records[slot].proxy);
}

void ContactManager::refreshShape(ShapeStore& shapes, std::uint32_t slot, const BodyStore& bodies,
                                  Real h) {
    ShapeRecord& shape = shapes.records[slot];
    const std::uint32_t bodyIndex = bodies.indexOf(shape.body);
    shape.bounds = boundsOf(shape.def.geometry, shapePose(shape, bodies));
    const Aabb swept = sweptBounds(shape.bounds, bodies.motion[bodyIndex].linearVelocity, h);
    if (!shape.fatBounds.contains(swept)) {
        shape.fatBounds = swept.fattened(aabbMargin);
        broadphase_.move(shape.proxy, shape.fatBounds);
    }
}

void ContactManager::refreshBounds(ShapeStore& shapes, const BodyStore& bodies,
                                   const StepContext& context) {
    const std::uint32_t count = static_cast<std::uint32_t>(shapes.records.size());
    for (std::uint32_t slot = 0; slot < count; ++slot) {
        const ShapeRecord& shape = shapes.records[slot];
        if (!shape.alive)
            continue;
        if (bodies.info[bodies.indexOf(shape.body)].type == BodyType::Static)
            continue;
        refreshShape(shapes, slot, bodies, context.h);
    }
}

void ContactManager::updateContacts(const ShapeStore& shapes, const BodyStore& bodies,
                                    const StepContext& context) {
    nextContacts_.clear();
    nextKeys_.clear();
    std::size_t old = 0;
    for (const ProxyPair& pair : broadphase_.pairs()) {
        const ShapeRecord& shapeA = shapes.records[proxyToShape_[pair.first]];
        const ShapeRecord& shapeB = shapes.records[proxyToShape_[pair.second]];
        if (shapeA.body == shapeB.body)
            continue;  // parts of one compound never collide
        const std::uint32_t indexA = bodies.indexOf(shapeA.body);
        const std::uint32_t indexB = bodies.indexOf(shapeB.body);
        if (bodies.info[indexA].type != BodyType::Dynamic &&
            bodies.info[indexB].type != BodyType::Dynamic)
            continue;

        Contact contact;
        contact.shapeA = shapes.idAt(proxyToShape_[pair.first]);
        contact.shapeB = shapes.idAt(proxyToShape_[pair.second]);
        contact.bodyA = shapeA.body;
        contact.bodyB = shapeB.body;
        const Vec3 relativeVelocity =
            bodies.motion[indexB].linearVelocity - bodies.motion[indexA].linearVelocity;
        const Real margin = contactMargin + context.h * relativeVelocity.norm();
        collide(shapeA.def.geometry, shapePose(shapeA, bodies), shapeB.def.geometry,
                shapePose(shapeB, bodies), margin, contact.manifold);

        // Both lists are sorted by pair: advance the old one to this pair to find its cache.
        while (old < contactKeys_.size() && contactKeys_[old] < pair)
            ++old;
        if (old < contactKeys_.size() && contactKeys_[old] == pair)
            carryImpulses(contacts_[old], contact);
        nextContacts_.push_back(contact);
        nextKeys_.push_back(pair);
    }
    contacts_.swap(nextContacts_);
    contactKeys_.swap(nextKeys_);
}

}  // namespace tumble
