#include "body_store.h"

namespace tumble {

BodyId BodyStore::add(const BodyDef& def) {
    const BodyId id = pool_.add();
    const std::uint32_t index = count() - 1;

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
    bodyInfo.allowSleep = def.allowSleep;
    bodyInfo.builtAsleep = def.type == BodyType::Dynamic && !def.awake;
    bodyInfo.fixedRotation = def.fixedRotation;
    info.push_back(bodyInfo);
    setMass(index, def.mass);
    previousMotion.back() = motion.back();
    if (def.type == BodyType::Kinematic || (def.type == BodyType::Dynamic && def.awake))
        markAwake(index);
    return id;
}

void BodyStore::remove(BodyId id) {
    if (isAwake(indexOf(id)))
        markNotAwake(indexOf(id));
    const std::uint32_t index = pool_.remove(id);
    moveLastInto(index, motion, previousMotion, inertia, forces, info);
    if (index < count() && isAwake(index))
        awake[info[index].awakeIndex] = index;  // the body moved into the freed index
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
