// The contact rows' part of the soft step (docs/ARCHITECTURE.md, "The soft step").
#include <algorithm>
#include <numbers>

#include "contact_kernels.h"
#include "normal_block.h"
#include "tumble/solver/contact_solver.h"

namespace tumble {
namespace {

// A contact held by a spring k = m w^2 and a damper c = 2 m zeta w on its depth, integrated by
// implicit Euler over h, is a rigid row that keeps `massScale` of the rigid answer (m the row's
// effective mass), aims at pushing out `biasRate` x depth per second, and lets go of the rest
// of its accumulated impulse: lambda = massScale (lambda_old - m (v_n - biasRate d)). Its
// stiffness is relative to m, so a light body on a heavy one is as stiff as the reverse.
void setSoft(SoftContact& soft, int kind, Real hertz, Real dampingRatio, Real h) {
    const Real omega = 2 * std::numbers::pi * hertz;
    const Real a1 = 2 * dampingRatio + h * omega;
    const Real a2 = h * omega * a1;
    soft.massScale[kind] = a2 / (1 + a2);
    soft.biasRate[kind] = omega / a1;
}

}  // namespace

// A spring faster than a quarter of the substep rate is not resolved by one iteration a
// substep (Box2D's limit); against a static body, which takes none of the motion, twice as stiff.
SoftContact softContact(const SolverSettings& settings, Real h) {
    SoftContact soft;
    const Real hertz = std::min(settings.contactHertz, 0.25 / h);
    setSoft(soft, 1, hertz, settings.contactDampingRatio, h);
    setSoft(soft, 2, 2 * hertz, settings.contactDampingRatio, h);
    soft.maxPush = settings.maxPushOutSpeed;
    soft.slop = settings.slop;
    return soft;
}

void ContactSolver::beginSoft(std::span<ContactConstraint> constraints) {
    softSums_.assign(constraints.size(), SoftSum{});
    softBounces_.clear();
    softPoints_.clear();
    softFirst_.resize(constraints.size());
    for (std::size_t j = 0; j < constraints.size(); ++j) {
        ContactConstraint& c = constraints[j];
        softFirst_[j] = static_cast<std::uint32_t>(softPoints_.size());
        const bool grouped = c.normalGroup != NormalIslands::kNone;
        for (int i = 0; i < c.pointCount; ++i) {
            ContactConstraintPoint& p = c.points[i];
            softPoints_.push_back(
                {p.angularA, p.angularB, c.normal, p.separation, c.bodyA, c.bodyB,
                 grouped ? static_cast<std::uint32_t>(4 * j + i) : SoftPoint::kNotGrouped,
                 static_cast<std::uint8_t>(c.bodyA == 0 || c.bodyB == 0 ? 2 : 1)});
            if (p.bounces) {
                softBounces_.push_back(
                    {static_cast<std::uint32_t>(j), i, -c.restitution * p.approachSpeed});
            }
            p.bounces = false;  // the exactly solved groups read them from here
            p.bounceCorrection = 0;
        }
    }
    softSeparations_.resize(softPoints_.size());
    narrow_.dropBounces();
}

// s = s0 + n . (dB - dA), d the displacement of the body's material point at the contact to
// first order in the turn, t + theta x r, with the anchors and the normal of the step's start
// (the collision is not run again); n . (theta x r) = theta . (r x n), prepare's angular rows,
// so a point costs three dot products (two cross products were a tenth of the soft step). The exact
// rotation, t + (R - 1) r, lifts a rolling ball's point by r (1 - cos theta) (1.4 mm a step for r =
// 0.1 m at 1 m/s, h = 1/60): speculative, the ball lost its support for the step's last substeps,
// and the rolling-resistance case's roll-out fell 24 % short. The biased target is the spring's
// push-out, capped, from the whole depth: the spring has no dead zone, or a resting body would
// creep through the slop at the (1 - massScale) of its weight the soft row gives way each substep
// (1.2 mm/s on the ground at 60 Hz). The rows compute bias / h x (depth - slop), so with bias = h
// the depth written is slop + that push. The points are read from a compact copy in the rows' order
// (through the constraints, 3 KB each, this pass was a tenth of pyramid-20's soft step).
void ContactSolver::softTargets(std::span<ContactConstraint> constraints,
                                std::span<const BodyDisplacement> moved, const SoftContact& soft,
                                Real inverseH) {
    for (std::size_t k = 0; k < softPoints_.size(); ++k) {
        const SoftPoint& q = softPoints_[k];
        const BodyDisplacement& a = moved[q.bodyA];
        const BodyDisplacement& b = moved[q.bodyB];
        const Real s = q.start + q.normal.dot(b.translation - a.translation) +
                       b.turn.dot(q.angularB) - a.turn.dot(q.angularA);
        const Real separation =
            s > 0 ? s : -soft.slop - std::min(-soft.biasRate[q.kind] * s, soft.maxPush);
        softSeparations_[k] = separation;
        if (q.grouped != SoftPoint::kNotGrouped)
            constraints[q.grouped / 4].points[q.grouped % 4].separation = separation;
    }
    if (wide_)
        rows_.softTargets(softSeparations_, softFirst_, soft.massScale, soft.slop, inverseH);
    else
        narrow_.softTargets(softSeparations_);
}

// In constraint order, as the scalar rows': the coloured rows' impulses are in the constraints
// (endSoftSubstep), and every body meets its manifolds in the same order either way.
void ContactSolver::softWarmStart(std::span<SolverBody> bodies,
                                  std::span<const ContactConstraint> constraints) {
    if (!wide_) {
        narrow_.warmStart(bodies, constraints);
        return;
    }
    for (const ContactConstraint& c : constraints) {
        SolverBody& a = bodies[c.bodyA];
        SolverBody& b = bodies[c.bodyB];
        for (int i = 0; i < c.pointCount; ++i)
            warmStartPoint(a, b, c.normal, c.tangents, c.points[i]);
        if (c.spinMass > 0 || c.rollingActive) {
            a.angularVelocity -= a.inverseInertia * c.angularImpulse;
            b.angularVelocity += b.inverseInertia * c.angularImpulse;
        }
    }
}

void ContactSolver::softSweep(std::span<SolverBody> bodies,
                              std::span<ContactConstraint> constraints,
                              const SolverSettings& settings, Real inverseH,
                              const SoftContact* soft) {
    const Real bias = soft != nullptr ? 1 / inverseH : 0;
    if (wide_) {
        rows_.sweep(bodies, constraints, factors_, settings, bias, inverseH, soft != nullptr);
    } else {
        narrow_.sweep(bodies, constraints, factors_, settings, inverseH, bias,
                      soft != nullptr ? soft->massScale.data() : nullptr);
    }
    if (!islands_.empty()) {
        islands_.solve(bodies, constraints, settings.relaxation, bias, settings.slop, inverseH);
        if (wide_)
            rows_.readGroupImpulses(constraints);
        else
            narrow_.readGroupImpulses(constraints);
    }
}

void ContactSolver::endSoftSubstep(std::span<ContactConstraint> constraints) {
    finish(constraints);
    for (std::size_t j = 0; j < constraints.size(); ++j) {
        const ContactConstraint& c = constraints[j];
        SoftSum& sum = softSums_[j];
        for (int i = 0; i < c.pointCount; ++i) {
            sum.normal[i] += c.points[i].normalImpulse;
            sum.tangent[i][0] += c.points[i].tangentImpulse[0];
            sum.tangent[i][1] += c.points[i].tangentImpulse[1];
        }
        sum.angular += c.angularImpulse;
    }
}

// Newton's law once, on the velocities the substeps left, for the points that approached
// faster than the threshold and carried load within the step: v_n >= -e v_n-, the impulse
// added to the last substep's (which it may not make negative) and to the step's sum.
void ContactSolver::endSoft(std::span<SolverBody> bodies,
                            std::span<ContactConstraint> constraints) {
    for (const SoftBounce& bounce : softBounces_) {
        ContactConstraint& c = constraints[bounce.constraint];
        ContactConstraintPoint& p = c.points[bounce.point];
        Real& sum = softSums_[bounce.constraint].normal[bounce.point];
        if (!(sum > 0))
            continue;
        SolverBody& a = bodies[c.bodyA];
        SolverBody& b = bodies[c.bodyB];
        const Real vn = normalSpeed(a, b, c.normal, p);
        const Real next = std::max<Real>(0, p.normalImpulse + p.normalMass * (bounce.target - vn));
        applyNormal(a, b, c.normal, p, next - p.normalImpulse);
        sum += next - p.normalImpulse;
        p.normalImpulse = next;
    }
    for (std::size_t j = 0; j < constraints.size(); ++j) {
        ContactConstraint& c = constraints[j];
        const SoftSum& sum = softSums_[j];
        for (int i = 0; i < c.pointCount; ++i) {
            c.points[i].normalImpulse = sum.normal[i];
            c.points[i].tangentImpulse = sum.tangent[i];
        }
        c.angularImpulse = sum.angular;
    }
}

}  // namespace tumble
