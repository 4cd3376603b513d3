// World: joints (ball, hinge, slider, fixed, distance), their checks, state and motors.

#include <cmath>
#include <numbers>
#include <sstream>
#include <string>

#include "checks.h"
#include "joints.h"
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

const char* typeName(JointType type) {
    switch (type) {
        case JointType::Ball:
            return "ball";
        case JointType::Hinge:
            return "hinge";
        case JointType::Slider:
            return "slider";
        case JointType::Fixed:
            return "fixed";
        case JointType::Distance:
            return "distance";
    }
    return "unknown";
}

void checkMotor(Real speed, Real maxForce, const char* where) {
    if (!std::isfinite(speed))
        fail(where, ".motorSpeed = ", speed, " must be finite");
    if (!(std::isfinite(maxForce) && maxForce >= 0)) {
        fail(where, ".maxMotorForce = ", maxForce,
             " (N m for a hinge, N for a slider) must be finite and >= 0");
    }
}

void checkJointDef(const JointDef& def, const BodyStore& bodies) {
    if (static_cast<int>(def.type) > static_cast<int>(JointType::Distance))
        fail("JointDef.type = ", static_cast<int>(def.type), " is not a joint type");
    const char* type = typeName(def.type);
    if (def.bodyA.isNull())
        fail("JointDef.bodyA is null; a ", type, " joint needs a body at end A");
    if (!bodies.isValid(def.bodyA)) {
        fail("JointDef.bodyA = ", describe(def.bodyA), " ", bodies.whyInvalid(def.bodyA),
             "; the anchor needs a body");
    }
    if (!def.bodyB.isNull() && !bodies.isValid(def.bodyB)) {
        fail("JointDef.bodyB = ", describe(def.bodyB), " ", bodies.whyInvalid(def.bodyB),
             "; use a null bodyB to join to the world");
    }
    if (def.bodyA == def.bodyB) {
        fail("JointDef: bodyA and bodyB are the same body ", describe(def.bodyA),
             "; a joint joins two bodies, or a body and the world (null bodyB)");
    }
    const auto movable = [&](BodyId id) {
        return !id.isNull() && bodies.info[bodies.indexOf(id)].type == BodyType::Dynamic;
    };
    if (!movable(def.bodyA) && !movable(def.bodyB))
        fail("JointDef: neither body of the ", type, " joint is dynamic; it would do nothing");
    checks::finiteVector(def.anchor, "JointDef.anchor");
    checks::finiteVector(def.anchorB, "JointDef.anchorB");
    checks::finiteVector(def.axis, "JointDef.axis");
    const bool axial = def.type == JointType::Hinge || def.type == JointType::Slider;
    if (axial && !(def.axis.norm() > 1e-9)) {
        fail("JointDef.axis = (", def.axis.x(), ", ", def.axis.y(), ", ", def.axis.z(), ") of a ",
             type, " joint must be non-zero");
    }
    if (def.type == JointType::Distance) {
        if (!std::isfinite(def.length))
            fail("JointDef.length = ", def.length, " (m) must be finite");
        const Real length = def.length >= 0 ? def.length : (def.anchorB - def.anchor).norm();
        if (!(length > 0)) {
            fail("JointDef: the distance joint's length is 0 (anchor and anchorB coincide, or ",
                 "length = 0); it must be > 0 (use a ball joint to join two points)");
        }
    }
    if (axial && def.enableLimit) {
        if (!(std::isfinite(def.lower) && std::isfinite(def.upper)))
            fail("JointDef limits lower = ", def.lower, ", upper = ", def.upper, " must be finite");
        if (def.lower > def.upper) {
            fail("JointDef limits lower = ", def.lower, " > upper = ", def.upper,
                 "; lower must be <= upper");
        }
        const Real pi = std::numbers::pi_v<Real>;
        if (def.type == JointType::Hinge && (def.lower < -pi || def.upper > pi)) {
            fail("JointDef hinge limits [", def.lower, ", ", def.upper,
                 "] (rad) must lie in [-pi, pi]");
        }
    }
    checkMotor(def.motorSpeed, def.maxMotorForce, "JointDef");
    if (!(def.breakForce > 0))
        fail("JointDef.breakForce = ", def.breakForce, " (N) must be > 0 (infinity: unbreakable)");
    if (!(def.breakTorque > 0)) {
        fail("JointDef.breakTorque = ", def.breakTorque,
             " (N m) must be > 0 (infinity: unbreakable)");
    }
}

}  // namespace

JointId World::createJoint(const JointDef& def) {
    Impl& w = *impl_;
    checkJointDef(def, w.bodies);
    const JointId id = w.joints.add(makeJointRecord(def, w.bodies));
    setJointedPairsExcluded(w.joints, w.shapes, w.bodies, w.contacts, w.joints.indexOf(id), true);
    if (!def.bodyB.isNull()) {
        w.warnings.checkMassRatio(
            def.bodyA, w.bodies.inertia[w.bodies.indexOf(def.bodyA)].inverseMass, def.bodyB,
            w.bodies.inertia[w.bodies.indexOf(def.bodyB)].inverseMass, id);
    }
    w.islands.push(w.bodies, w.contacts, w.bodies.indexOf(def.bodyA));
    if (!def.bodyB.isNull())
        w.islands.push(w.bodies, w.contacts, w.bodies.indexOf(def.bodyB));
    return id;
}

void World::destroyJoint(JointId id) {
    Impl& w = *impl_;
    const std::uint32_t index = w.joints.indexOf(id);
    const JointDef def = w.joints.records[index].def;
    if (!w.joints.state[index].broken)
        setJointedPairsExcluded(w.joints, w.shapes, w.bodies, w.contacts, index, false);
    w.joints.remove(id);
    w.islands.push(w.bodies, w.contacts, w.bodies.indexOf(def.bodyA));
    if (!def.bodyB.isNull())
        w.islands.push(w.bodies, w.contacts, w.bodies.indexOf(def.bodyB));
}

bool World::isValid(JointId id) const {
    return impl_->joints.isValid(id);
}

int World::jointCount() const {
    return static_cast<int>(impl_->joints.count());
}

const JointDef& World::jointDef(JointId id) const {
    return impl_->joints.records[impl_->joints.indexOf(id)].def;
}

JointState World::jointState(JointId id) const {
    const Impl& w = *impl_;
    const std::uint32_t index = w.joints.indexOf(id);
    const JointStepState& s = w.joints.state[index];
    const JointFrame f = jointFrame(w.joints.records[index], w.bodies);
    const Vec3 anchorA = w.bodies.motion[f.a].center + f.rA;
    return {s.force, s.torque, f.position, f.speed, s.broken, anchorA, anchorA + f.separation,
            f.axis};
}

void World::setJointMotor(JointId id, bool enable, Real speed, Real maxForce) {
    Impl& w = *impl_;
    const std::uint32_t index = w.joints.indexOf(id);
    checkMotor(speed, maxForce, "setJointMotor");
    JointDef& def = w.joints.records[index].def;
    if (enable && def.type != JointType::Hinge && def.type != JointType::Slider)
        fail("setJointMotor: a ", typeName(def.type), " joint has no motor (hinge and slider do)");
    def.enableMotor = enable;
    def.motorSpeed = speed;
    def.maxMotorForce = maxForce;
    w.islands.push(w.bodies, w.contacts, w.bodies.indexOf(def.bodyA));
    if (!def.bodyB.isNull())
        w.islands.push(w.bodies, w.contacts, w.bodies.indexOf(def.bodyB));
}

}  // namespace tumble
