#include "spring_store.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace tumble {

SpringId SpringStore::add(const SpringDef& def) {
    const SpringId id = pool_.add();
    defs.push_back(def);
    state.push_back({});
    previousState.push_back({});
    if (def.formulation != SpringFormulation::Explicit)
        implicitCount += 1;
    if (def.contactRadius > 0)
        contactCount += 1;
    forgetStiffest();
    return id;
}

void SpringStore::remove(SpringId id) {
    if (defs[indexOf(id)].formulation != SpringFormulation::Explicit)
        implicitCount -= 1;
    if (defs[indexOf(id)].contactRadius > 0)
        contactCount -= 1;
    moveLastInto(pool_.remove(id), defs, state, previousState);
    forgetStiffest();
}

Real SpringStore::stiffestThread() const {
    if (stiffestThread_ < 0) {
        Real stiffest = 0;
        for (const SpringDef& def : defs) {
            if (isUndampedThread(def))
                stiffest = std::max(stiffest, def.stiffness);
        }
        stiffestThread_ = stiffest;
    }
    return stiffestThread_;
}

void SpringStore::reserve(std::size_t n) {
    defs.reserve(n);
    state.reserve(n);
    previousState.reserve(n);
    pool_.reserve(n);
}

void SpringStore::removeAttachedTo(BodyId body) {
    // Backwards, so the element moved into a freed index has already been looked at.
    for (std::uint32_t i = count(); i-- > 0;) {
        if (defs[i].bodyA == body || defs[i].bodyB == body)
            remove(idAt(i));
    }
}

SpringId SpringStore::strongestOn(BodyId body) const {
    // By the largest |tension|; when several overflowed together (a body gone to infinity
    // stretches every spring on it), by the largest stiffness: the stiffest is the first to pass
    // its stability limit h < 2 / omega.
    SpringId best;
    Real largest = -1;
    Real stiffest = -1;
    for (std::uint32_t i = 0; i < count(); ++i) {
        if (!(defs[i].bodyA == body || defs[i].bodyB == body))
            continue;
        const Real t = state[i].tension;
        const Real size = std::isfinite(t) ? std::abs(t) : std::numeric_limits<Real>::infinity();
        if (size > largest || (size == largest && defs[i].stiffness > stiffest)) {
            largest = size;
            stiffest = defs[i].stiffness;
            best = idAt(i);
        }
    }
    return best;
}

std::uint32_t DragStore::find(BodyId body) const {
    if (body.index >= denseOfSlot_.size())
        return kNone;
    const std::uint32_t dense = denseOfSlot_[body.index];
    return dense != kNone && bodies[dense] == body ? dense : kNone;
}

void DragStore::set(BodyId body, const Drag& drag) {
    const std::uint32_t dense = find(body);
    const bool none = drag.linear == 0 && drag.quadratic == 0;
    if (dense != kNone) {
        if (none) {
            remove(body);
        } else {
            drags[dense] = drag;
        }
        return;
    }
    if (none)
        return;
    if (body.index >= denseOfSlot_.size())
        denseOfSlot_.resize(body.index + 1, kNone);
    denseOfSlot_[body.index] = static_cast<std::uint32_t>(bodies.size());
    bodies.push_back(body);
    drags.push_back(drag);
}

Drag DragStore::get(BodyId body) const {
    const std::uint32_t dense = find(body);
    return dense == kNone ? Drag{} : drags[dense];
}

void DragStore::remove(BodyId body) {
    const std::uint32_t dense = find(body);
    if (dense == kNone)
        return;
    // Erase in place (not swap with the last) so the order of application stays the order in
    // which drag was set; removals are rare.
    bodies.erase(bodies.begin() + dense);
    drags.erase(drags.begin() + dense);
    denseOfSlot_[body.index] = kNone;
    for (std::uint32_t i = dense; i < bodies.size(); ++i)
        denseOfSlot_[bodies[i].index] = i;
}

}  // namespace tumble
