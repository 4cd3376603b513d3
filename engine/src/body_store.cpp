#include "body_store.h"

#include "tumble/core/error.h"

namespace tumble {

BodyId BodyStore::add(const BodyDef& def) {
    std::uint32_t slotIndex;
    if (freeSlots_.empty()) {
        slotIndex = static_cast<std::uint32_t>(slots_.size());
        slots_.push_back({});
    } else {
        slotIndex = freeSlots_.back();
        freeSlots_.pop_back();
    }
    Slot& slot = slots_[slotIndex];
    slot.generation += 1;
    slot.dense = count();
    slot.alive = true;

    BodyMotion m;
    m.orientation = def.orientation.normalized();
    m.center = def.position;  // the origin until setMass moves it to the centre of mass
    if (def.type != BodyType::Static) {
        m.linearVelocity = def.linearVelocity;
        m.angularVelocity = def.angularVelocity;
    }
    motion.push_back(m);
    previousMotion.push_back(m);
    inertia.push_back({});
    forces.push_back({});
    BodyInfo bodyInfo;
    bodyInfo.type = def.type;
    bodyInfo.linearDamping = def.linearDamping;
    bodyInfo.angularDamping = def.angularDamping;
    bodyInfo.gravityScale = def.gravityScale;
    bodyInfo.userData = def.userData;
    bodyInfo.slot = slotIndex;
    bodyInfo.allowSleep = def.allowSleep;
    bodyInfo.builtAsleep = def.type == BodyType::Dynamic && !def.awake;
    bodyInfo.fixedRotation = def.fixedRotation;
    info.push_back(bodyInfo);
    setMass(slot.dense, def.mass);
    previousMotion.back() = motion.back();
    if (def.type == BodyType::Kinematic || (def.type == BodyType::Dynamic && def.awake))
        markAwake(slot.dense);
    return BodyId{slotIndex, slot.generation};
}

void BodyStore::remove(BodyId id) {
    const std::uint32_t index = indexOf(id);
    if (isAwake(index))
        markNotAwake(index);
    const std::uint32_t last = count() - 1;
    if (index != last) {
        motion[index] = motion[last];
        previousMotion[index] = previousMotion[last];
        inertia[index] = inertia[last];
        forces[index] = forces[last];
        info[index] = info[last];
        slots_[info[index].slot].dense = index;
        if (isAwake(index))
            awake[info[index].awakeIndex] = index;
    }
    motion.pop_back();
    previousMotion.pop_back();
    inertia.pop_back();
    forces.pop_back();
    info.pop_back();
    slots_[id.index].alive = false;
    freeSlots_.push_back(id.index);
}

bool BodyStore::isValid(BodyId id) const {
    return id.generation != 0 && id.index < slots_.size() && slots_[id.index].alive &&
           slots_[id.index].generation == id.generation;
}

std::uint32_t BodyStore::indexOf(BodyId id) const {
    if (!isValid(id)) {
        if (id.isNull())
            fail("body id is null");
        fail("body id {index ", id.index, ", generation ", id.generation,
             "} does not name a live body (destroyed, or from another world)");
    }
    return slots_[id.index].dense;
}

BodyId BodyStore::idAt(std::uint32_t index) const {
    const std::uint32_t slot = info[index].slot;
    return BodyId{slot, slots_[slot].generation};
}

void BodyStore::markAwake(std::uint32_t index) {
    info[index].builtAsleep = false;
    info[index].awakeIndex = static_cast<std::uint32_t>(awake.size());
    awake.push_back(index);
}

void BodyStore::markNotAwake(std::uint32_t index) {
    const std::uint32_t position = info[index].awakeIndex;
    const std::uint32_t moved = awake.back();
    awake[position] = moved;
    info[moved].awakeIndex = position;
    awake.pop_back();
    info[index].awakeIndex = BodyInfo::kNone;
}

void BodyStore::savePreviousMotion() {
    for (const std::uint32_t i : awake)
        previousMotion[i] = motion[i];
}

void BodyStore::restorePreviousMotion() {
    for (const std::uint32_t i : awake)
        motion[i] = previousMotion[i];
}

void BodyStore::setMass(std::uint32_t index, const MassProperties& mass) {
    BodyInertia& bodyInertia = inertia[index];
    const bool dynamic = info[index].type == BodyType::Dynamic;
    const Vec3 newLocalCenter = dynamic ? mass.localCenter : Vec3::Zero();
    // The origin stays where it is; the centre of mass moves with the new local centre.
    for (BodyMotion* m : {&motion[index], &previousMotion[index]}) {
        m->center += m->orientation * (newLocalCenter - bodyInertia.localCenter);
    }
    info[index].mass = mass;
    if (!dynamic) {
        bodyInertia = {};
        return;
    }
    bodyInertia.inverseMass = 1 / mass.mass;
    bodyInertia.localCenter = mass.localCenter;
    bodyInertia.inertiaLocal = mass.inertia;
    // A translation-only body keeps its inertia for reporting but never turns.
    bodyInertia.inverseInertiaLocal =
        info[index].fixedRotation ? Mat3::Zero() : Mat3(mass.inertia.inverse());
}

}  // namespace tumble
