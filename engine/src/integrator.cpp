#include "integrator.h"

#include <Eigen/LU>  // Matrix3::inverse
#include <cmath>

namespace tumble {
namespace {

constexpr int kMaxNewtonIterations = 8;
// Newton converges quadratically: once an update is below 1e-9 |w|, the error left after it is
// of order (1e-9)^2 |w|, below rounding. Waiting for the update itself to reach rounding would
// spend every iteration of the budget chasing noise.
constexpr Real kNewtonTolerance = 1e-9;

}  // namespace

Vec3 gyroscopicMidpoint(const Mat3& inertia, const Mat3& inverseInertia, const Vec3& w0, Real h) {
    const Vec3 momentum0 = inertia * w0;
    const Vec3 gyroscopic0 = w0.cross(momentum0);
    const Real scale = w0.norm();
    // Spinning about a principal axis (or isotropic inertia): no gyroscopic torque, nothing to do.
    if (gyroscopic0.norm() <= kNewtonTolerance * scale * momentum0.norm())
        return w0;
    // Explicit half step as the first guess: Newton then needs one or two corrections.
    Vec3 x = w0 - 0.5 * h * inverseInertia * gyroscopic0;
    for (int iteration = 0; iteration < kMaxNewtonIterations; ++iteration) {
        const Vec3 momentum = inertia * x;
        const Vec3 residual = 2 * inertia * (x - w0) + h * x.cross(momentum);
        const Mat3 jacobian = 2 * inertia + h * (skew(x) * inertia - skew(momentum));
        const Vec3 delta = jacobian.inverse() * residual;  // closed-form 3x3 inverse
        x -= delta;
        if (delta.norm() <= kNewtonTolerance * scale)
            break;
    }
    return 2 * x - w0;
}

void integrateVelocities(BodyStore& bodies, const StepContext& context, Real forceSteps) {
    for (const std::uint32_t index : bodies.awake) {
        if (bodies.info[index].type == BodyType::Dynamic)
            integrateVelocity(bodies, index, context, forceSteps);
    }
}

void integrateVelocity(BodyStore& bodies, std::uint32_t index, const StepContext& context,
                       Real forceSteps) {
    const Real h = context.h;
    const BodyInfo& info = bodies.info[index];
    BodyMotion& m = bodies.motion[index];
    const BodyInertia& inertia = bodies.inertia[index];
    const BodyForces& forces = bodies.forces[index];

    // forceSteps = 1 multiplies exactly: the default step's bits.
    m.linearVelocity += h * (info.gravityScale * context.gravity +
                             forceSteps * (inertia.inverseMass * forces.force));
    if (info.fixedRotation) {
        // Zero inverse inertia (every lumped node): the angular velocity stays zero, and the
        // rotation, gyroscopic test and damping below would only carry zeros (the same bits for
        // an unrotated body; a rotated one could get a zero's sign flipped).
        m.linearVelocity /= 1 + h * info.linearDamping;
        return;
    }

    // Angular part in body axes, where the inertia is constant.
    const Mat3 rotation = m.orientation.toRotationMatrix();
    Vec3 bodyOmega = rotation.transpose() * m.angularVelocity;
    bodyOmega += (forceSteps * h) * torqueAcceleration(inertia, rotation, forces.torque);
    bodyOmega = gyroscopicMidpoint(inertia.inertiaLocal, inertia.inverseInertiaLocal, bodyOmega, h);

    // Implicit damping dv/dt = -c v: unconditionally stable, never reverses the velocity.
    m.linearVelocity /= 1 + h * info.linearDamping;
    bodyOmega /= 1 + h * info.angularDamping;
    m.angularVelocity = rotation * bodyOmega;
}

namespace {

// x += h v; q = exp(h w / 2) q, renormalised against rounding.
void move(BodyMotion& m, const Vec3& linear, const Vec3& angular, Real h) {
    m.center += h * linear;
    const Vec3 rotationVector = h * angular;
    const Real angle = rotationVector.norm();
    if (angle > 0) {
        const Quat delta(Eigen::AngleAxis<Real>(angle, rotationVector / angle));
        m.orientation = (delta * m.orientation).normalized();
    }
}

}  // namespace

void integratePositions(BodyStore& bodies, std::span<const PseudoVelocity> pseudo,
                        const StepContext& context) {
    for (std::size_t k = 0; k < bodies.awake.size(); ++k) {
        BodyMotion& m = bodies.motion[bodies.awake[k]];
        if (pseudo.empty())
            move(m, m.linearVelocity, m.angularVelocity, context.h);
        else
            move(m, m.linearVelocity + pseudo[k].linear, m.angularVelocity + pseudo[k].angular,
                 context.h);
    }
}

void displaceBodies(BodyStore& bodies, std::span<const PseudoVelocity> velocities, Real h) {
    for (std::size_t k = 0; k < bodies.awake.size(); ++k) {
        if (bodies.info[bodies.awake[k]].type == BodyType::Dynamic)
            move(bodies.motion[bodies.awake[k]], velocities[k].linear, velocities[k].angular, h);
    }
}

}  // namespace tumble
