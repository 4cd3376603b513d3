// World: spring-dampers and drag (the force elements of strings and nets).

#include <cmath>
#include <sstream>
#include <string>

#include "checks.h"
#include "tumble/core/error.h"
#include "tumble/world.h"
#include "world_impl.h"

namespace tumble {
namespace {

std::string describe(BodyId id) {
    std::ostringstream out;
    out << "{index " << id.index << ", generation " << id.generation << '}';
    return out.str();
}

void checkSpringDef(const SpringDef& def, const BodyStore& bodies) {
    if (def.bodyA.isNull())
        fail("SpringDef.bodyA is null; a spring needs a body at end A");
    if (!bodies.isValid(def.bodyA)) {
        fail("SpringDef.bodyA = ", describe(def.bodyA), " ", bodies.whyInvalid(def.bodyA));
    }
    if (!def.bodyB.isNull() && !bodies.isValid(def.bodyB)) {
        fail("SpringDef.bodyB = ", describe(def.bodyB), " ", bodies.whyInvalid(def.bodyB),
             "; use a null bodyB for a world anchor");
    }
    if (def.bodyA == def.bodyB) {
        fail("SpringDef: bodyA and bodyB are the same body ", describe(def.bodyA),
             "; a spring must join two bodies, or a body and a world point (null bodyB)");
    }
    checks::finiteVector(def.localAnchorA, "SpringDef.localAnchorA");
    checks::finiteVector(def.localAnchorB, "SpringDef.localAnchorB");
    if (!(std::isfinite(def.restLength) && def.restLength > 0))
        fail("SpringDef.restLength = ", def.restLength, " (m) must be finite and > 0");
    if (!(std::isfinite(def.stiffness) && def.stiffness >= 0))
        fail("SpringDef.stiffness = ", def.stiffness, " (N/m) must be finite and >= 0");
    if (!(std::isfinite(def.damping) && def.damping >= 0))
        fail("SpringDef.damping = ", def.damping, " (N s/m) must be finite and >= 0");
    if (def.formulation != SpringFormulation::Explicit &&
        def.formulation != SpringFormulation::Implicit &&
        def.formulation != SpringFormulation::BackwardEuler) {
        fail("SpringDef.formulation = ", static_cast<int>(def.formulation),
             " is not a formulation");
    }
    if (!(def.numericalDamping >= 0 && def.numericalDamping <= 1))
        fail("SpringDef.numericalDamping = ", def.numericalDamping, " must be in [0, 1]");
    if (!(std::isfinite(def.contactRadius) && def.contactRadius >= 0))
        fail("SpringDef.contactRadius = ", def.contactRadius, " (m) must be finite and >= 0");
    if (!(std::isfinite(def.contactFriction) && def.contactFriction >= 0))
        fail("SpringDef.contactFriction = ", def.contactFriction, " must be finite and >= 0");
}

// An explicit spring's step is stable only for omega h < 2 (omega^2 = k (1/m_A + 1/m_B), undamped;
// damping lowers the limit further). Checked when the spring is made, at the current step.
void warnIfUnstable(const BodyStore& bodies, Real h, SpringId id, const SpringDef& def,
                    WarningLog& warnings) {
    const Real inverseMassA = bodies.inertia[bodies.indexOf(def.bodyA)].inverseMass;
    const Real inverseMassB =
        def.bodyB.isNull() ? 0 : bodies.inertia[bodies.indexOf(def.bodyB)].inverseMass;
    const Real omegaH = std::sqrt(def.stiffness * (inverseMassA + inverseMassB)) * h;
    if (!(omegaH >= 2))
        return;
    Warning warning;
    warning.kind = Warning::Kind::ExplicitSpringUnstable;
    warning.bodyA = def.bodyA;
    warning.bodyB = def.bodyB;
    warning.spring = id;
    warning.value = omegaH;
    warning.limit = 2;
    warnings.raise(warning);
}

}  // namespace

Real axialStiffness(Real youngsModulus, Real area, Real restLength) {
    if (!(std::isfinite(youngsModulus) && youngsModulus > 0))
        fail("axialStiffness youngsModulus = ", youngsModulus, " (Pa) must be finite and > 0");
    if (!(std::isfinite(area) && area > 0))
        fail("axialStiffness area = ", area, " (m^2) must be finite and > 0");
    if (!(std::isfinite(restLength) && restLength > 0))
        fail("axialStiffness restLength = ", restLength, " (m) must be finite and > 0");
    return youngsModulus * area / restLength;
}

SpringId World::createSpring(const SpringDef& def) {
    Impl& w = *impl_;
    checkSpringDef(def, w.bodies);
    const SpringId id = w.springs.add(def);
    if (def.formulation == SpringFormulation::Explicit)
        warnIfUnstable(w.bodies, w.settings.timeStep, id, def, w.warnings);
    w.islands.push(w.bodies, w.contacts, w.bodies.indexOf(def.bodyA));
    if (!def.bodyB.isNull())
        w.islands.push(w.bodies, w.contacts, w.bodies.indexOf(def.bodyB));
    return id;
}

void World::destroySpring(SpringId id) {
    Impl& w = *impl_;
    const SpringDef def = w.springs.defs[w.springs.indexOf(id)];
    w.springs.remove(id);
    w.islands.push(w.bodies, w.contacts, w.bodies.indexOf(def.bodyA));
    if (!def.bodyB.isNull())
        w.islands.push(w.bodies, w.contacts, w.bodies.indexOf(def.bodyB));
}

bool World::isValid(SpringId id) const {
    return impl_->springs.isValid(id);
}

int World::springCount() const {
    return static_cast<int>(impl_->springs.count());
}

void World::reserveSprings(int count) {
    if (count < 0)
        fail("reserveSprings count = ", count, " must be >= 0");
    impl_->springs.reserve(static_cast<std::size_t>(count));
}

const SpringDef& World::springDef(SpringId id) const {
    return impl_->springs.defs[impl_->springs.indexOf(id)];
}

SpringState World::springState(SpringId id) const {
    const Impl& w = *impl_;
    const std::uint32_t index = w.springs.indexOf(id);
    const SpringStepState& s = w.springs.state[index];
    return {springLength(w.springs, w.bodies, index), s.tension, s.slack, s.carried};
}

Real World::springPotentialEnergy() const {
    return tumble::springPotentialEnergy(impl_->springs, impl_->bodies);
}

void World::setDrag(BodyId id, const Drag& drag) {
    Impl& w = *impl_;
    const std::uint32_t index = w.bodies.indexOf(id);
    checks::nonNegative(drag.linear, "Drag.linear (N s/m)");
    checks::nonNegative(drag.quadratic, "Drag.quadratic (N s^2/m^2)");
    if (!drag.projection.allFinite())
        fail("Drag.projection must be finite");
    w.drag.set(id, drag);
    w.islands.push(w.bodies, w.contacts, index);
}

Drag World::drag(BodyId id) const {
    impl_->bodies.indexOf(id);  // refuses a bad id
    return impl_->drag.get(id);
}

}  // namespace tumble
