#include "joints.h"

#include <cmath>
#include <limits>

#include "springs.h"
#include "tumble/solver/contact_solver.h"

namespace tumble {
namespace {

Quat orientationOf(const BodyStore& bodies, std::uint32_t index, bool world) {
    return world ? Quat::Identity() : bodies.motion[index].orientation;
}

// Solver body 0 is every static body (and stands in for a sleeping one); awake body k is solver
// body 1 + k, as in the solve stage.
std::uint32_t solverIndex(const BodyStore& bodies, std::uint32_t index) {
    return bodies.isAwake(index) && bodies.info[index].type != BodyType::Static
               ? 1 + bodies.info[index].awakeIndex
               : 0;
}

}  // namespace

JointRecord makeJointRecord(const JointDef& def, const BodyStore& bodies) {
    JointRecord record;
    record.def = def;
    const bool world = def.bodyB.isNull();
    const std::uint32_t a = bodies.indexOf(def.bodyA);
    const std::uint32_t b = world ? 0 : bodies.indexOf(def.bodyB);
    const Quat qA = orientationOf(bodies, a, false);
    const Quat qB = orientationOf(bodies, b, world);
    const auto local = [&](std::uint32_t index, const Quat& q, const Vec3& point) -> Vec3 {
        const BodyMotion& m = bodies.motion[index];
        const Vec3 origin = m.center - m.orientation * bodies.inertia[index].localCenter;
        return q.conjugate() * (point - origin);
    };
    const Vec3 anchorB = def.type == JointType::Distance ? def.anchorB : def.anchor;
    record.localAnchorA = local(a, qA, def.anchor);
    record.localAnchorB = world ? anchorB : local(b, qB, anchorB);
    const Vec3 axis = def.axis.normalized();
    record.localAxisA = qA.conjugate() * axis;
    record.localAxisB = qB.conjugate() * axis;
    const Vec3 reference = frictionBasis(axis)[0];
    record.localReferenceA = qA.conjugate() * reference;
    record.localReferenceB = qB.conjugate() * reference;
    record.relativeOrientation = qA.conjugate() * qB;
    record.length = def.length >= 0 ? def.length : (anchorB - def.anchor).norm();
    return record;
}

JointFrame jointFrame(const JointRecord& record, const BodyStore& bodies) {
    const JointDef& def = record.def;
    JointFrame f;
    f.world = def.bodyB.isNull();
    f.a = bodies.indexOf(def.bodyA);
    f.b = f.world ? 0 : bodies.indexOf(def.bodyB);
    const BodyMotion& mA = bodies.motion[f.a];
    const Quat qA = mA.orientation;
    const Quat qB = orientationOf(bodies, f.b, f.world);
    const Vec3 pA = anchorPosition(bodies, def.bodyA, record.localAnchorA);
    const Vec3 pB = anchorPosition(bodies, def.bodyB, record.localAnchorB);
    f.rA = pA - mA.center;
    f.rB = f.world ? Vec3::Zero() : Vec3(pB - bodies.motion[f.b].center);
    f.separation = pB - pA;
    f.axis = qA * record.localAxisA;
    const Vec3 vA = mA.linearVelocity + mA.angularVelocity.cross(f.rA);
    const Vec3 wA = mA.angularVelocity;
    Vec3 vB = Vec3::Zero();
    Vec3 wB = Vec3::Zero();
    if (!f.world) {
        const BodyMotion& mB = bodies.motion[f.b];
        vB = mB.linearVelocity + mB.angularVelocity.cross(f.rB);
        wB = mB.angularVelocity;
    }
    switch (def.type) {
        case JointType::Hinge: {
            f.angularError = f.axis.cross(qB * record.localAxisB);
            const Vec3 referenceA = qA * record.localReferenceA;
            const Vec3 referenceB = qB * record.localReferenceB;
            f.position =
                std::atan2(f.axis.dot(referenceA.cross(referenceB)), referenceA.dot(referenceB));
            f.speed = f.axis.dot(wB - wA);
            break;
        }
        case JointType::Fixed:
        case JointType::Slider: {
            Quat error = qB * (qA * record.relativeOrientation).conjugate();
            if (error.w() < 0)
                error.coeffs() = -error.coeffs();
            f.angularError = 2 * error.vec();
            if (def.type == JointType::Slider) {
                f.position = f.axis.dot(f.separation);
                // A's point under B's anchor moves with A: its velocity, not the anchor's.
                f.speed = f.axis.dot(vB - (vA + wA.cross(f.separation)));
            }
            break;
        }
        case JointType::Distance:
            f.position = f.separation.norm();
            f.speed = f.position > 0 ? f.separation.dot(vB - vA) / f.position : 0;
            break;
        case JointType::Ball:
            break;
    }
    return f;
}

void buildJointRows(const JointStore& joints, const BodyStore& bodies, Real h,
                    std::vector<JointRow>& rows, std::vector<std::uint32_t>& rowJoint) {
    rows.clear();
    rowJoint.clear();
    for (std::uint32_t i = 0; i < joints.count(); ++i) {
        const JointRecord& record = joints.records[i];
        const JointStepState& state = joints.state[i];
        const JointDef& def = record.def;
        if (state.broken)
            continue;
        const std::uint32_t a = bodies.indexOf(def.bodyA);
        const bool world = def.bodyB.isNull();
        const std::uint32_t b = world ? 0 : bodies.indexOf(def.bodyB);
        if (!bodies.isAwakeDynamic(a) && (world || !bodies.isAwakeDynamic(b)))
            continue;
        const JointFrame f = jointFrame(record, bodies);
        JointRow row;
        row.type = def.type;
        row.bodyA = solverIndex(bodies, a);
        row.bodyB = world ? 0 : solverIndex(bodies, b);
        row.rA = f.rA;
        row.rB = f.rB;
        row.separation = f.separation;
        row.axis = f.axis;
        row.angularError = f.angularError;
        row.position = f.position;
        if (def.type == JointType::Distance) {
            row.lower = def.rope ? -std::numeric_limits<Real>::infinity() : record.length;
            row.upper = record.length;
        } else if (def.enableLimit &&
                   (def.type == JointType::Hinge || def.type == JointType::Slider)) {
            row.lower = def.lower;
            row.upper = def.upper;
        }
        row.motor =
            def.enableMotor && (def.type == JointType::Hinge || def.type == JointType::Slider);
        row.motorSpeed = def.motorSpeed;
        row.maxMotorForce = def.maxMotorForce;
        row.linearImpulse = h * state.linearForce;
        row.previousLinearImpulse = h * state.previousLinearForce;
        row.angularImpulse = h * state.angularTorque;
        row.motorImpulse = h * state.motorForce;
        row.lowerImpulse = h * state.lowerForce;
        row.upperImpulse = h * state.upperForce;
        rows.push_back(row);
        rowJoint.push_back(i);
    }
}

void storeJointResults(JointStore& joints, std::span<const JointRow> rows,
                       std::span<const std::uint32_t> rowJoint, Real h,
                       std::vector<std::uint32_t>& broken) {
    const Real inverseH = 1 / h;
    for (std::size_t j = 0; j < rows.size(); ++j) {
        const JointRow& row = rows[j];
        const std::uint32_t i = rowJoint[j];
        JointStepState& s = joints.state[i];
        s.previousLinearForce = s.linearForce;
        s.linearForce = inverseH * row.linearImpulse;
        s.angularTorque = inverseH * row.angularImpulse;
        s.motorForce = inverseH * row.motorImpulse;
        s.lowerForce = inverseH * row.lowerImpulse;
        s.upperForce = inverseH * row.upperImpulse;
        s.force = jointReactionForce(row, h);
        s.torque = jointReactionTorque(row, h);
        const JointDef& def = joints.records[i].def;
        if (s.force.norm() > def.breakForce || s.torque.norm() > def.breakTorque) {
            s.broken = true;
            broken.push_back(i);
        }
    }
}

void wakeJointLinked(const JointStore& joints, BodyStore& bodies, ContactManager& contacts,
                     Islands& islands, const StepContext* midStep) {
    const auto drives = [&](std::uint32_t i) {
        return bodies.isAwakeDynamic(i) || bodies.isMovingKinematic(i);
    };
    for (bool woke = true; woke;) {
        woke = false;
        for (std::uint32_t i = 0; i < joints.count(); ++i) {
            const JointDef& def = joints.records[i].def;
            if (def.bodyB.isNull() || joints.state[i].broken)
                continue;
            const std::uint32_t a = bodies.indexOf(def.bodyA);
            const std::uint32_t b = bodies.indexOf(def.bodyB);
            if (bodies.isSleeping(a) && drives(b)) {
                islands.wake(bodies, contacts, a, midStep);
                woke = true;
            } else if (bodies.isSleeping(b) && drives(a)) {
                islands.wake(bodies, contacts, b, midStep);
                woke = true;
            }
        }
    }
}

}  // namespace tumble

namespace tumble {
namespace {

// Does a live, unbroken joint other than `skip` keep bodies x and y from colliding?
bool excludedByJoint(const JointStore& joints, BodyId x, BodyId y, std::uint32_t skip) {
    for (std::uint32_t i = 0; i < joints.count(); ++i) {
        const JointDef& def = joints.records[i].def;
        if (i == skip || joints.state[i].broken || def.collideConnected)
            continue;
        if ((def.bodyA == x && def.bodyB == y) || (def.bodyA == y && def.bodyB == x))
            return true;
    }
    return false;
}

template <typename Visit>
void forEachShape(const ShapeStore& shapes, const BodyStore& bodies, BodyId body, Visit&& visit) {
    for (std::uint32_t slot = bodies.info[bodies.indexOf(body)].firstShape;
         slot != BodyInfo::kNoShape; slot = shapes.records[slot].nextInBody)
        visit(shapes.records[slot]);
}

}  // namespace

void setJointedPairsExcluded(const JointStore& joints, const ShapeStore& shapes,
                             const BodyStore& bodies, ContactManager& contacts, std::uint32_t index,
                             bool excluded) {
    const JointDef& def = joints.records[index].def;
    if (def.bodyB.isNull() || def.collideConnected)
        return;
    if (!excluded && excludedByJoint(joints, def.bodyA, def.bodyB, index))
        return;
    forEachShape(shapes, bodies, def.bodyA, [&](const ShapeRecord& shapeA) {
        forEachShape(shapes, bodies, def.bodyB, [&](const ShapeRecord& shapeB) {
            contacts.setPairExcluded(shapeA.proxy, shapeB.proxy, excluded);
        });
    });
}

void excludeJointedPairs(const JointStore& joints, const ShapeStore& shapes,
                         const BodyStore& bodies, ContactManager& contacts,
                         std::uint32_t shapeSlot) {
    const ShapeRecord& shape = shapes.records[shapeSlot];
    for (std::uint32_t i = 0; i < joints.count(); ++i) {
        const JointDef& def = joints.records[i].def;
        if (def.bodyB.isNull() || def.collideConnected || joints.state[i].broken)
            continue;
        const BodyId other = def.bodyA == shape.body   ? def.bodyB
                             : def.bodyB == shape.body ? def.bodyA
                                                       : BodyId{};
        if (other.isNull())
            continue;
        forEachShape(shapes, bodies, other, [&](const ShapeRecord& otherShape) {
            contacts.setPairExcluded(shape.proxy, otherShape.proxy, true);
        });
    }
}

}  // namespace tumble
