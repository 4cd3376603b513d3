#include "solve_stage.h"

#include <algorithm>
#include <cmath>

namespace tumble {

Real mixFriction(Real a, Real b) {
    return std::sqrt(a * b);
}
Real mixRestitution(Real a, Real b) {
    return std::max(a, b);
}

namespace {

// What this step's forces did to the velocity of a body point (m/s): the solver turns it into
// the time and speed of an impact within the step.
Vec3 velocityChangeAt(const BodyStore& bodies, std::uint32_t index, const Vec3& r) {
    const BodyMotion& now = bodies.motion[index];
    const BodyMotion& start = bodies.previousMotion[index];
    return (now.linearVelocity - start.linearVelocity) +
           (now.angularVelocity - start.angularVelocity).cross(r);
}

}  // namespace

SolverStats SolveStage::run(BodyStore& bodies, const ShapeStore& shapes,
                            std::span<Contact> contacts, const StepContext& context,
                            const SolverSettings& settings) {
    const std::uint32_t count = bodies.count();
    solverBodies_.resize(count);
    for (std::uint32_t i = 0; i < count; ++i) {
        const BodyMotion& m = bodies.motion[i];
        const BodyInertia& inertia = bodies.inertia[i];
        SolverBody& s = solverBodies_[i];
        s.linearVelocity = m.linearVelocity;
        s.angularVelocity = m.angularVelocity;
        s.inverseMass = inertia.inverseMass;
        const Mat3 rotation = m.orientation.toRotationMatrix();
        s.inverseInertia = rotation * inertia.inverseInertiaLocal * rotation.transpose();
    }

    constraints_.clear();
    constraintContact_.clear();
    for (std::uint32_t k = 0; k < contacts.size(); ++k) {
        const Contact& contact = contacts[k];
        if (contact.manifold.pointCount == 0)
            continue;
        const Material& materialA = shapes.records[contact.shapeA.index].def.material;
        const Material& materialB = shapes.records[contact.shapeB.index].def.material;
        ContactConstraint c;
        c.bodyA = bodies.indexOf(contact.bodyA);
        c.bodyB = bodies.indexOf(contact.bodyB);
        c.normal = contact.manifold.normal;
        c.friction = mixFriction(materialA.friction, materialB.friction);
        c.restitution = mixRestitution(materialA.restitution, materialB.restitution);
        c.pointCount = contact.manifold.pointCount;
        for (int i = 0; i < c.pointCount; ++i) {
            const ContactPoint& point = contact.manifold.points[i];
            ContactConstraintPoint& p = c.points[i];
            p.rA = point.position - bodies.motion[c.bodyA].center;
            p.rB = point.position - bodies.motion[c.bodyB].center;
            p.separation = point.separation;
            p.normalImpulse = contact.normalImpulse[i];
            p.normalAcceleration = c.normal.dot(velocityChangeAt(bodies, c.bodyB, p.rB) -
                                                velocityChangeAt(bodies, c.bodyA, p.rA)) *
                                   context.inverseH;
        }
        constraints_.push_back(c);
        constraintContact_.push_back(k);
    }
    // The solver builds its tangent basis from the normal; cached friction is kept in world
    // coordinates so a turning basis does not scramble it.
    for (std::size_t j = 0; j < constraints_.size(); ++j) {
        ContactConstraint& c = constraints_[j];
        const Contact& contact = contacts[constraintContact_[j]];
        c.tangents = frictionBasis(c.normal);
        for (int i = 0; i < c.pointCount; ++i) {
            c.points[i].tangentImpulse = {contact.tangentImpulse[i].dot(c.tangents[0]),
                                          contact.tangentImpulse[i].dot(c.tangents[1])};
        }
    }

    const SolverStats stats =
        solver_.solve(solverBodies_, constraints_, pseudo_, context.h, settings);

    for (std::size_t j = 0; j < constraints_.size(); ++j) {
        const ContactConstraint& c = constraints_[j];
        Contact& contact = contacts[constraintContact_[j]];
        for (int i = 0; i < c.pointCount; ++i) {
            contact.normalImpulse[i] = c.points[i].normalImpulse;
            contact.tangentImpulse[i] = c.points[i].tangentImpulse[0] * c.tangents[0] +
                                        c.points[i].tangentImpulse[1] * c.tangents[1];
        }
    }
    for (std::uint32_t i = 0; i < count; ++i) {
        if (bodies.info[i].type != BodyType::Dynamic)
            continue;
        bodies.motion[i].linearVelocity = solverBodies_[i].linearVelocity;
        bodies.motion[i].angularVelocity = solverBodies_[i].angularVelocity;
    }
    return stats;
}

}  // namespace tumble
