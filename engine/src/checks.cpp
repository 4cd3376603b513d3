#include "checks.h"

#include <Eigen/Eigenvalues>
#include <cmath>
#include <sstream>
#include <string>

#include "tumble/core/error.h"
#include "tumble/solver/contact_solver.h"

namespace tumble::checks {
namespace {

std::string format(const Vec3& v) {
    std::ostringstream out;
    out << '(' << v.x() << ", " << v.y() << ", " << v.z() << ')';
    return out.str();
}

std::string format(const Quat& q) {
    std::ostringstream out;
    out << "(w " << q.w() << ", x " << q.x() << ", y " << q.y() << ", z " << q.z() << ')';
    return out.str();
}

// Unit length to this tolerance: loose enough for quaternions typed with a few digits, tight
// enough that renormalising cannot hide a real mistake.
constexpr Real kUnitTolerance = 1e-6;
// Relative tolerance for symmetry and the triangle inequality of an inertia tensor.
constexpr Real kInertiaTolerance = 1e-9;

}  // namespace

void finiteVector(const Vec3& v, std::string_view what) {
    if (!v.allFinite())
        fail(what, " = ", format(v), " must be finite");
}

void unitQuaternion(const Quat& q, std::string_view what) {
    if (!q.coeffs().allFinite())
        fail(what, " = ", format(q), " must be finite");
    const Real norm = q.norm();
    if (std::abs(norm - 1) > kUnitTolerance) {
        fail(what, " = ", format(q), " has norm ", norm,
             "; it must be a unit quaternion (|q| = 1 to 1e-6). Note Quat(w, x, y, z) takes w "
             "first");
    }
}

void nonNegative(Real value, std::string_view what) {
    if (!(std::isfinite(value) && value >= 0))
        fail(what, " = ", value, " must be finite and >= 0");
}

void massProperties(const MassProperties& mass, std::string_view what) {
    if (!(std::isfinite(mass.mass) && mass.mass > 0)) {
        fail(what, ".mass = ", mass.mass, " must be finite and > 0 for a dynamic body");
    }
    finiteVector(mass.localCenter, std::string(what) + ".localCenter");
    const Mat3& inertia = mass.inertia;
    if (!inertia.allFinite())
        fail(what, ".inertia must be finite");
    const Real scale = inertia.cwiseAbs().maxCoeff();
    if ((inertia - inertia.transpose()).cwiseAbs().maxCoeff() > kInertiaTolerance * scale) {
        fail(what, ".inertia must be symmetric");
    }
    const Eigen::SelfAdjointEigenSolver<Mat3> solver(inertia, Eigen::EigenvaluesOnly);
    const Vec3 moments = solver.eigenvalues();  // ascending
    if (!(moments.x() > 0)) {
        fail(what, ".inertia has principal moment ", moments.x(),
             " (kg m^2); all principal moments must be > 0");
    }
    if (moments.z() > (moments.x() + moments.y()) * (1 + kInertiaTolerance)) {
        fail(what, ".inertia has principal moments ", format(moments),
             " (kg m^2); the largest exceeds the sum of the other two, which no rigid body can "
             "have");
    }
}

void bodyDef(const BodyDef& def) {
    finiteVector(def.position, "BodyDef.position");
    unitQuaternion(def.orientation, "BodyDef.orientation");
    finiteVector(def.linearVelocity, "BodyDef.linearVelocity");
    finiteVector(def.angularVelocity, "BodyDef.angularVelocity");
    nonNegative(def.linearDamping, "BodyDef.linearDamping");
    nonNegative(def.angularDamping, "BodyDef.angularDamping");
    if (!std::isfinite(def.gravityScale))
        fail("BodyDef.gravityScale = ", def.gravityScale, " must be finite");
    if (def.type == BodyType::Dynamic)
        massProperties(def.mass, "BodyDef.mass");
    if (def.type == BodyType::Static) {
        // As World::setLinearVelocity refuses it: the velocity would be dropped unseen.
        if (!def.linearVelocity.isZero(0)) {
            fail("BodyDef.linearVelocity = ", format(def.linearVelocity),
                 ": a static body never moves, it must be zero (a kinematic body moves)");
        }
        if (!def.angularVelocity.isZero(0)) {
            fail("BodyDef.angularVelocity = ", format(def.angularVelocity),
                 ": a static body never moves, it must be zero (a kinematic body moves)");
        }
    }
    if (def.fixedRotation) {
        if (def.type != BodyType::Dynamic)
            fail("BodyDef.fixedRotation: only a dynamic body can be translation-only");
        if (!def.angularVelocity.isZero(0)) {
            fail("BodyDef.fixedRotation with angularVelocity = ", format(def.angularVelocity),
                 ": a translation-only body never rotates, it must be zero");
        }
    }
    if (!def.awake) {
        if (def.type != BodyType::Dynamic)
            fail("BodyDef.awake = false: only a dynamic body can be created asleep");
        if (!def.allowSleep)
            fail("BodyDef.awake = false contradicts BodyDef.allowSleep = false");
        if (!def.linearVelocity.isZero(0) || !def.angularVelocity.isZero(0)) {
            fail("BodyDef.awake = false with linearVelocity = ", format(def.linearVelocity),
                 " and angularVelocity = ", format(def.angularVelocity),
                 ": a body created asleep is at rest, both must be zero");
        }
    }
}

void surface(const Material& m, std::string_view what) {
    nonNegative(m.friction, std::string(what) + ".friction");
    nonNegative(m.spinningFriction, std::string(what) + ".spinningFriction");
    nonNegative(m.rollingFriction, std::string(what) + ".rollingFriction");
    if (!(m.restitution >= 0 && m.restitution <= 1)) {
        fail(what, ".restitution = ", m.restitution, " must be in [0, 1]");
    }
}

void material(const Material& m, std::string_view what) {
    surface(m, what);
    if (!(std::isfinite(m.density) && m.density > 0)) {
        fail(what, ".density = ", m.density, " (kg/m^3) must be finite and > 0");
    }
}

void shapeDef(const ShapeDef& def, BodyType bodyType) {
    checkShape(def.geometry, "ShapeDef.geometry");
    finiteVector(def.localPose.position, "ShapeDef.localPose.position");
    unitQuaternion(def.localPose.rotation, "ShapeDef.localPose.rotation");
    material(def.material, "ShapeDef.material");
    if (typeOf(def.geometry) == ShapeType::HalfSpace && bodyType != BodyType::Static) {
        fail("ShapeDef.geometry is a half-space, which only a static body may carry");
    }
    if (isTriangleSurface(def.geometry) && bodyType == BodyType::Dynamic) {
        fail(
            "ShapeDef.geometry is a triangle mesh or height field, which only a static or "
            "kinematic body may carry");
    }
}

void timeStep(Real h, std::string_view what) {
    if (!(std::isfinite(h) && h > 0))
        fail(what, " = ", h, " (s) must be finite and > 0");
}

// Both counts would compound (each of the step's substeps a soft step of its own substeps, so
// h / (substeps softSubsteps) where either field asked for its own), so a world takes one.
void substepCounts(int substeps, int softSubsteps, std::string_view where) {
    if (twoSubstepCounts(substeps, softSubsteps)) {
        fail(where, ": WorldDef.substeps = ", substeps,
             " with WorldDef.solver.softSubsteps = ", softSubsteps,
             ": one count of substeps per step; the soft step's is softSubsteps (set substeps = 1) "
             "and the default step's substeps (set softSubsteps = 0)");
    }
}

void worldDef(const WorldDef& def) {
    finiteVector(def.gravity, "WorldDef.gravity");
    timeStep(def.timeStep, "WorldDef.timeStep");
    nonNegative(def.contactMargin, "WorldDef.contactMargin");
    checkSolverSettings(def.solver);
    nonNegative(def.aabbMargin, "WorldDef.aabbMargin");
    if (def.maxStepsPerAdvance < 1) {
        fail("WorldDef.maxStepsPerAdvance = ", def.maxStepsPerAdvance, " must be >= 1");
    }
    if (def.substeps < 1)
        fail("WorldDef.substeps = ", def.substeps, " must be >= 1");
    substepCounts(def.substeps, def.solver.softSubsteps, "World");
    if (!(std::isfinite(def.linearSleepVelocity) && def.linearSleepVelocity >= 0)) {
        fail("WorldDef.linearSleepVelocity = ", def.linearSleepVelocity,
             " (m/s) must be finite and >= 0");
    }
    if (!(std::isfinite(def.angularSleepVelocity) && def.angularSleepVelocity >= 0)) {
        fail("WorldDef.angularSleepVelocity = ", def.angularSleepVelocity,
             " (rad/s) must be finite and >= 0");
    }
    if (!(std::isfinite(def.timeToSleep) && def.timeToSleep > 0))
        fail("WorldDef.timeToSleep = ", def.timeToSleep, " (s) must be finite and > 0");
    if (!(def.impactSpeedThreshold > 0)) {
        fail("WorldDef.impactSpeedThreshold = ", def.impactSpeedThreshold,
             " (m/s) must be > 0 (infinity: no impact events)");
    }
}

}  // namespace tumble::checks
