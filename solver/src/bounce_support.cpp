#include "bounce_support.h"

namespace tumble {
namespace {

// The constraint's cached impulses (normal, friction, torsion and rolling) on zero-velocity
// copies of A and B.
void applyCached(SolverBody& a, SolverBody& b, const ContactConstraint& c) {
    for (int i = 0; i < c.pointCount; ++i) {
        const ContactConstraintPoint& p = c.points[i];
        const std::array<Vec3, 2> tangents = frictionBasis(c.normal);
        const Vec3 impulse = p.normalImpulse * c.normal + p.tangentImpulse[0] * tangents[0] +
                             p.tangentImpulse[1] * tangents[1];
        applyImpulse(a, -impulse, p.rA);
        applyImpulse(b, impulse, p.rB);
    }
    a.angularVelocity -= a.inverseInertia * c.angularImpulse;
    b.angularVelocity += b.inverseInertia * c.angularImpulse;
}

Real normalVelocity(const SolverBody& a, const SolverBody& b, const ContactConstraint& c,
                    const ContactConstraintPoint& p) {
    return c.normal.dot(b.velocityAt(p.rB) - a.velocityAt(p.rA));
}

SolverBody atRest(const SolverBody& body) {
    SolverBody rest = body;
    rest.linearVelocity.setZero();
    rest.angularVelocity.setZero();
    return rest;
}

}  // namespace

void addSupportAcceleration(std::span<const SolverBody> bodies,
                            std::span<ContactConstraint> constraints, Real h,
                            std::vector<SolverBody>& scratch) {
    scratch.resize(bodies.size());
    for (std::size_t i = 0; i < bodies.size(); ++i)
        scratch[i] = atRest(bodies[i]);
    for (const ContactConstraint& c : constraints)
        applyCached(scratch[c.bodyA], scratch[c.bodyB], c);
    for (ContactConstraint& c : constraints) {
        if (c.restitution == 0) {
            for (int i = 0; i < c.pointCount; ++i)
                c.points[i].supportSpeed = 0;
            continue;
        }
        SolverBody ownA = atRest(bodies[c.bodyA]);
        SolverBody ownB = atRest(bodies[c.bodyB]);
        applyCached(ownA, ownB, c);
        for (int i = 0; i < c.pointCount; ++i) {
            ContactConstraintPoint& p = c.points[i];
            const Real others = normalVelocity(scratch[c.bodyA], scratch[c.bodyB], c, p) -
                                normalVelocity(ownA, ownB, c, p);
            p.supportSpeed = others;
            p.normalAcceleration += others / h;
        }
    }
}

}  // namespace tumble
