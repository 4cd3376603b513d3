#include "impacts.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace tumble {
namespace {

// Velocity of a body point at the start of the step (m/s): before this step's forces, so a
// body resting on the ground approaches it at 0, not at the g h its weight adds each step.
Vec3 startVelocityAt(const BodyStore& bodies, std::uint32_t index, const Vec3& point) {
    const BodyMotion& m = bodies.previousMotion[index];
    return m.linearVelocity + m.angularVelocity.cross(point - m.center);
}

Real totalNormalImpulse(const Contact& contact) {
    Real sum = 0;
    for (int i = 0; i < contact.manifold.pointCount; ++i)
        sum += contact.normalImpulse[i];
    return sum;
}

// The contact was solved this step (as the solve stage decides: active, touching, no
// sleeping body). A live contact's bodies are live: they are looked up unchecked.
bool wasSolved(const ContactManager& contacts, const BodyStore& bodies, std::uint32_t slot) {
    const Contact& contact = contacts.contact(slot);
    return contacts.isAlive(slot) && contacts.isActive(slot) && contact.manifold.pointCount > 0 &&
           !bodies.isSleeping(bodies.checkedIndexOf(contact.bodyA)) &&
           !bodies.isSleeping(bodies.checkedIndexOf(contact.bodyB));
}

}  // namespace

void ImpactTracker::update(const ContactManager& contacts, const BodyStore& bodies, Real threshold,
                           std::vector<ImpactEvent>& out) {
    if (bySlot_.size() < contacts.slotCount())
        bySlot_.resize(contacts.slotCount());
    next_.clear();
    if (std::isfinite(threshold)) {
        for (const std::uint32_t slot : contacts.touchingSlots()) {
            if (bySlot_[slot].open || !wasSolved(contacts, bodies, slot))
                continue;  // an open impact takes this step's impulse below
            const Contact& contact = contacts.contact(slot);
            const Real impulse = totalNormalImpulse(contact);
            if (!(impulse > 0))
                continue;
            const std::uint32_t a = bodies.checkedIndexOf(contact.bodyA);
            const std::uint32_t b = bodies.checkedIndexOf(contact.bodyB);
            const Vec3& normal = contact.manifold.normal;
            Real approach = -std::numeric_limits<Real>::infinity();
            for (int i = 0; i < contact.manifold.pointCount; ++i) {
                const Vec3& p = contact.manifold.points[i].position;
                approach = std::max<Real>(approach, -normal.dot(startVelocityAt(bodies, b, p) -
                                                                startVelocityAt(bodies, a, p)));
            }
            if (approach < threshold)
                continue;
            // The impact's point only for the few contacts that open one.
            Vec3 weighted = Vec3::Zero();
            for (int i = 0; i < contact.manifold.pointCount; ++i)
                weighted += contact.normalImpulse[i] * contact.manifold.points[i].position;
            Open& entry = bySlot_[slot];
            entry.open = true;
            entry.event = {contact.shapeA,     contact.shapeB, contact.bodyA, contact.bodyB,
                           weighted / impulse, normal,         approach,      impulse};
            next_.push_back(slot);
        }
    }
    // The impacts opened last step take this step's impulse (if their contact was solved) and
    // are reported. A destroyed contact's slot is not reused before the narrowphase after the
    // one that freed it, which comes after this; the shape ids are checked all the same.
    for (const std::uint32_t slot : opened_) {
        Open& entry = bySlot_[slot];
        const Contact& contact = contacts.contact(slot);
        if (wasSolved(contacts, bodies, slot) && contact.shapeA == entry.event.shapeA &&
            contact.shapeB == entry.event.shapeB)
            entry.event.normalImpulse += totalNormalImpulse(contact);
        out.push_back(entry.event);
        entry.open = false;
    }
    opened_.swap(next_);
}

}  // namespace tumble
