#include "tumble/solver/sprung_push_out.h"

#include <algorithm>

#include "normal_block.h"

namespace tumble {

void loadPseudoBodies(std::span<const SolverBody> bodies, std::span<const PseudoVelocity> pseudo,
                      std::vector<SolverBody>& out) {
    out.assign(bodies.begin(), bodies.end());
    for (std::size_t i = 0; i < out.size(); ++i) {
        out[i].linearVelocity = pseudo[i].linear;
        out[i].angularVelocity = pseudo[i].angular;
    }
}

void storePseudoBodies(std::span<const SolverBody> bodies, std::span<PseudoVelocity> pseudo) {
    for (std::size_t i = 0; i < bodies.size(); ++i) {
        pseudo[i].linear = bodies[i].linearVelocity;
        pseudo[i].angular = bodies[i].angularVelocity;
    }
}

Real SprungPushOut::hold(std::span<ContactConstraint> constraints, Real slop) {
    held_.clear();
    Real deepest = 0;
    for (std::size_t j = 0; j < constraints.size(); ++j) {
        ContactConstraint& c = constraints[j];
        if (c.pushOut)
            continue;
        for (int i = 0; i < c.pointCount; ++i) {
            ContactConstraintPoint& p = c.points[i];
            if (p.separation >= -slop)
                continue;
            held_.push_back({static_cast<std::uint32_t>(j), i, p.separation, 0});
            deepest = std::max(deepest, -p.separation);
            p.separation = -slop;
        }
    }
    return deepest;
}

void SprungPushOut::solve(std::span<SolverBody> bodies,
                          std::span<const ContactConstraint> constraints, Real factor,
                          Real inverseH, Real slop, int iterations) {
    for (Held& held : held_)
        held.impulse = 0;
    for (int sweep = 0; sweep < iterations; ++sweep) {
        for (Held& held : held_) {
            const ContactConstraint& c = constraints[held.constraint];
            const ContactConstraintPoint& p = c.points[held.point];
            SolverBody& a = bodies[c.bodyA];
            SolverBody& b = bodies[c.bodyB];
            const Real target = factor * inverseH * (-held.separation - slop);
            const Real old = held.impulse;
            held.impulse =
                std::max<Real>(0, old - p.normalMass * (normalSpeed(a, b, c.normal, p) - target));
            applyNormal(a, b, c.normal, p, held.impulse - old);
        }
    }
}

void SprungPushOut::restore(std::span<ContactConstraint> constraints) const {
    for (const Held& held : held_)
        constraints[held.constraint].points[held.point].separation = held.separation;
}

}  // namespace tumble
