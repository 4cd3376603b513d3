// The contact rows' part of the soft step (docs/ARCHITECTURE.md, "The soft step").
#include <algorithm>
#include <cmath>
#include <numbers>

#include "bounce_support.h"
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

// The separation of a soft point where the bodies now stand (softTargets says how).
template <class SoftPoint>
Real separationNow(const SoftPoint& q, std::span<const BodyDisplacement> moved) {
    const BodyDisplacement& a = moved[q.bodyA];
    const BodyDisplacement& b = moved[q.bodyB];
    return q.start + q.normal.dot(b.translation - a.translation) + b.turn.dot(q.angularB) -
           a.turn.dot(q.angularA);
}

// The slip along the tangents that the kinematic bodies' velocity changes (`jumps`) made at the
// manifold's centroid: the slip of the step's start (`start`) along the change, up to the change.
std::array<Real, 2> kinematicSlip(const ContactConstraint& c, std::span<const PseudoVelocity> jumps,
                                  std::span<const SolverBody> start) {
    Vec3 rA = Vec3::Zero();
    Vec3 rB = Vec3::Zero();
    for (int i = 0; i < c.pointCount; ++i) {
        rA += c.points[i].rA;
        rB += c.points[i].rB;
    }
    rA /= c.pointCount;
    rB /= c.pointCount;
    const Vec3 change = (jumps[c.bodyB].linear + jumps[c.bodyB].angular.cross(rB)) -
                        (jumps[c.bodyA].linear + jumps[c.bodyA].angular.cross(rA));
    const Vec3 slip = start[c.bodyB].velocityAt(rB) - start[c.bodyA].velocityAt(rA);
    const Real change0 = c.tangents[0].dot(change);
    const Real change1 = c.tangents[1].dot(change);
    const Real size = change0 * change0 + change1 * change1;
    if (!(size > 0))
        return {0, 0};
    const Real along = c.tangents[0].dot(slip) * change0 + c.tangents[1].dot(slip) * change1;
    const Real made = std::clamp<Real>(along / size, 0, 1);
    return {made * change0, made * change1};
}

}  // namespace

// A gap (m) no step closes: -kUnreachable / hs is no target a body reaches.
constexpr Real kUnreachable = 1e3;

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

// The velocity changes the application gave kinematic bodies since the last step (`jumps`)
// reach a body sticking on them over the step, as from a steady acceleration: the slip they made
// at the manifold's centroid (the step's slip along v_t's change, up to the change: none for a
// body already given the kinematic body's new velocity) is taken off at 1/n a substep, a steady
// need the warm start replays. Taken by the first substep, it was a catch-up that the later
// substeps' warm start replayed as a force (0.18 of a turning platform's alpha r h left in the
// cube's velocity at 3 x 45), and it met that substep's Coulomb limit, mu m g h / n, where the
// default step's one solve has the step's. The body's velocity at the step's end is the
// kinematic body's; its place lags by (n - 1) / 2n of the change times h, which the friction
// anchors take back.
void ContactSolver::beginSoft(std::span<ContactConstraint> constraints,
                              std::span<const PseudoVelocity> jumps,
                              std::span<const SolverBody> start) {
    softSums_.assign(constraints.size(), SoftSum{});
    softBounces_.clear();
    softLate_.clear();
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
            if (c.restitution > 0)  // softImpacts decides, with the substeps' acceleration
                softBounces_.push_back({static_cast<std::uint32_t>(j), i});
            p.bounces = false;  // the exactly solved groups read them from here
            p.bounceCorrection = 0;
        }
    }
    softSeparations_.resize(softPoints_.size());
    softSeparationsStale_ = true;
    softFriction_.clear();
    for (std::size_t j = 0; j < constraints.size(); ++j) {
        const ContactConstraint& c = constraints[j];
        if (!(c.friction > 0 && c.pointCount > 0))
            continue;
        const std::array<Real, 2> jump =
            jumps.empty() ? std::array<Real, 2>{0, 0} : kinematicSlip(c, jumps, start);
        softFriction_.push_back(
            {c.normal, c.tangents, jump, c.bodyA, c.bodyB, static_cast<std::uint32_t>(j)});
    }
    softTangentTargets_.assign(constraints.size(), {0, 0});
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
//
// The friction rows' targets turn with the pair. Their levers and basis are the step's start's,
// so a sticking pair turning about the normal (a cube on a turning platform) met its points'
// change of velocity, w x (w x r) h a step, as a jump at the step's start: the first substep
// caught it up, the later substeps' warm start replayed that catch-up as a force, and the cube's
// velocity ended 0.18 of the jump off the platform's (3 x 45; docs/ARCHITECTURE.md, "Why a
// sticking cube's velocity was off"). With both levers turned by a spin s about the normal that
// the pair shares, the relative velocity at the turned points is v_t + t . (s n x (dA - dB)), d
// the centres' displacements since the step's start, so the rows aim at v_t = t . (s n x (dB -
// dA)): a steady need of s^2 r hs a substep, which the warm start replays, and a sticking body
// ends the step with the platform's velocity at its end pose. The biased sweep aims where the
// substep's positions will take the bodies (d + hs v), as its relax sweep does after them: at d,
// the need arrived in the relax sweep, one sweep after the warm start that replays it, and
// 0.12 of it stayed. The shared spin is the smaller of the two when they have one sign, else 0:
// exact for a pair that turns together (sticking), nothing against a ground that does not turn;
// a ball rolling and spinning keeps its contact under its centre, not on a material point, and
// turned with its own spin its rows would ask a slip of r w_roll w_spin t. Per manifold: a cross
// and two dot products.
void ContactSolver::softTargets(std::span<ContactConstraint> constraints,
                                std::span<const SolverBody> bodies,
                                std::span<const BodyDisplacement> moved, const SoftContact& soft,
                                Real inverseH, Real remaining, bool biased, bool last) {
    const Real ahead = biased ? 1 / inverseH : 0;
    for (const SoftFriction& f : softFriction_) {
        const SolverBody& a = bodies[f.bodyA];
        const SolverBody& b = bodies[f.bodyB];
        const Real spinA = a.angularVelocity.dot(f.normal);
        const Real spinB = b.angularVelocity.dot(f.normal);
        const Real shared =
            spinA * spinB > 0 ? (std::abs(spinA) < std::abs(spinB) ? spinA : spinB) : 0;
        const Vec3 moves = (moved[f.bodyB].translation + ahead * b.linearVelocity) -
                           (moved[f.bodyA].translation + ahead * a.linearVelocity);
        const Vec3 turned = (shared * f.normal).cross(moves);
        softTangentTargets_[f.constraint] = {f.tangents[0].dot(turned) + remaining * f.jump[0],
                                             f.tangents[1].dot(turned) + remaining * f.jump[1]};
    }
    // A substep's biased sweep stands where the last substep's relax sweep stood (the
    // positions move after it), so its separations are those already written, the same bits
    // (the late gaps below are the step's last sweep's only): the pass over the points runs
    // n + 1 times a step, not 2n (it was 3 % of a soft pyramid-20's step).
    for (std::size_t k = 0; (!biased || softSeparationsStale_) && k < softPoints_.size(); ++k) {
        const SoftPoint& q = softPoints_[k];
        const Real s = separationNow(q, moved);
        const Real separation =
            s > 0 ? s : -soft.slop - std::min(-soft.biasRate[q.kind] * s, soft.maxPush);
        softSeparations_[k] = separation;
        if (q.grouped != SoftPoint::kNotGrouped)
            constraints[q.grouped / 4].points[q.grouped % 4].separation = separation;
    }
    softSeparationsStale_ = false;
    // The step's last relax sweep would slow a point that reaches the surface early in the next
    // step so that it lands at the end of the next substep, and the next step's bounce would
    // start from that speed (a ball at 4.2 m/s, h = 1/1000, rebounded 14 % low). The next step's
    // first sweeps, before anything moves, stop it; here its gap is made one no step closes.
    for (const std::uint32_t k : softLate_) {
        if (!last || !(softSeparations_[k] > 0))
            continue;
        softSeparations_[k] += kUnreachable;
        const SoftPoint& q = softPoints_[k];
        if (q.grouped != SoftPoint::kNotGrouped)
            constraints[q.grouped / 4].points[q.grouped % 4].separation = softSeparations_[k];
    }
    if (wide_)
        rows_.softTargets(softSeparations_, softFirst_, softTangentTargets_, soft.massScale,
                          soft.slop, inverseH);
    else
        narrow_.softTargets(softSeparations_, softTangentTargets_);
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

// The biased sweep leaves the friction rows of exactly solved groups (heavy on light) to the
// relax sweep: solved in both, they diverged, the light box spinning and sliding ever faster from
// rounding (x13 a step at 100,000:1, 3 x 45; at 10,000:1 4 mm/s after 5 s), as they did with
// the friction warm start dropped; solved in the relax sweep alone they stay at rounding up to
// 1,000,000:1 (measured; the mechanism is not analysed). The relax sweep's friction, after the
// substep's positions, still holds the groups' bodies, with the warm start of the last.
//
// The relax sweep solves the torsion and rolling rows after its normal rows, so their bounds
// are the substep's whole normal impulse: while a body sinks into its sag the biased sweep's
// spring carries less than its weight, and the rigid relax sweep the rest (it leaves the normal
// speed at zero, so the two carry m g hs together). Bounded by the biased sweep's part, a ball
// spinning on the ground from zero depth lost c m d / hs of torsion in all (d the sag, g / w^2):
// its spin stayed 0.0136 rad/s above c m g t / I from step 10 on (3 x 45, r = 0.1 m, c = 0.01).
// A body resting at its sag is unchanged: there the spring carries the weight. A lone point's
// linear friction is solved again after its normal row: bounded by the biased part, a
// translation-only ball kicked along the ground from zero depth took 0.98817 of mu m g h in step 1
// (3 x 45). Again, not only after: solved after the normal row alone (its lever moves the
// point's normal velocity, and no normal row is left in the substep), the thousand-body pile on a
// height field sank below the test's limit (TerrainTunnel: 0.0289 m against 0.0248). Faces of
// several points still read the biased load (their patch's sum is split again by the normals,
// not bounded again).
void ContactSolver::softSweep(std::span<SolverBody> bodies,
                              std::span<ContactConstraint> constraints,
                              const SolverSettings& settings, Real inverseH,
                              const SoftContact* soft) {
    const Real bias = soft != nullptr ? 1 / inverseH : 0;
    if (wide_) {
        rows_.sweep(bodies, constraints, factors_, settings, bias, inverseH, soft != nullptr, false,
                    true);
    } else {
        narrow_.sweep(bodies, constraints, factors_, settings, inverseH, bias,
                      soft != nullptr ? soft->massScale.data() : nullptr, true);
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

// The substeps (v += a hs, then x += hs v) put a free point on the parabola x0 + w t + a t^2 / 2
// with w = v0 + a hs / 2 (impactWithinStep, which reads w from vEnd = w + a h / 2). The bounce
// restarts that parabola at the impact with -e times its speed; by the step's end the point is
// `lift` above the surface, and the velocity that continues the parabola under the next step's
// substeps runs half a substep behind it. Box2D's -e v0 on the substeps' end state instead (the
// bounce one step late at the approach speed of the step's start, with the time after the
// impact lost) put the apexes 1.6-7.4 % low at h = 1/240 and 10-14 % at 1/1000.
void ContactSolver::softImpacts(std::span<const SolverBody> change,
                                std::span<const ContactConstraint> constraints, Real h, Real hs,
                                Real threshold) {
    std::size_t kept = 0;
    for (SoftBounce& bounce : softBounces_) {
        const ContactConstraint& c = constraints[bounce.constraint];
        const ContactConstraintPoint& p = c.points[bounce.point];
        const Vec3 dv = change[c.bodyB].velocityAt(p.rB) - change[c.bodyA].velocityAt(p.rA);
        // The support the other contacts give its bodies (bounce_support.h; prepare read the
        // warm start of a substep, so supportSpeed is a substep's): without it a ball on a box
        // resting on the ground saw the box fall with it (a = 0, not -g), and rebounded up to
        // 3 % high (e = 0.3, 100 kg box).
        const Real a = (c.normal.dot(dv) + p.supportSpeed) / hs;
        const Real w = p.approachSpeed + 0.5 * a * hs;
        const Real start = softPoints_[softFirst_[bounce.constraint] + bounce.point].start;
        // Only a point that reaches the surface within the step, fast, bounces: the test on the
        // speed at the step's start alone missed a ball that gravity brings down within it.
        if (!(start <= 0 || start + h * (w + 0.5 * a * h) < 0)) {
            softLate_.push_back(softFirst_[bounce.constraint] + bounce.point);
            continue;
        }
        const Impact impact = impactWithinStep(start, w + 0.5 * a * h, a, h);
        if (!(impact.speed < -threshold))
            continue;
        const Real rest = h - impact.time;
        bounce.target = -c.restitution * impact.speed + a * (rest - 0.5 * hs);
        bounce.lift = -c.restitution * impact.speed * rest + 0.5 * a * rest * rest;
        softBounces_[kept++] = bounce;
    }
    softBounces_.resize(kept);
}

// Newton's law once, on the velocities the substeps left, for the points that approached
// faster than the threshold and carried load within the step: v_n >= target. A bouncing point
// in an exactly solved group (normal_islands.h: a bounce or a mass ratio puts it in one) is
// solved with its whole group, rigidly at the last relax sweep's targets, and lifted with it
// (softGroupBounces): the box under a bouncing ball answers with its support on the ground, as
// in the default step. Alone, the bounce was a collision with a free box (the ball kept
// (M / (M + m))^2 of e^2: 0.01 on a 0.1 kg box, 0.26 on 1 kg), its support's soft contact
// taking the box's share later. Other points alone: the impulse added to the last substep's
// (which it may not make negative), and the point moved to its rebound's separation by a
// displacement along its normal row (its effective mass times the shortfall, as a split
// impulse's position correction). The changes go into the step's sums.
void ContactSolver::endSoft(std::span<SolverBody> bodies, std::span<ContactConstraint> constraints,
                            std::span<const BodyDisplacement> moved, std::span<PseudoVelocity> lift,
                            Real slop, Real inverseH) {
    std::fill(lift.begin(), lift.end(), PseudoVelocity{});
    bool grouped = false;
    std::size_t kept = 0;
    for (const SoftBounce& bounce : softBounces_) {
        if (!(softSums_[bounce.constraint].normal[bounce.point] > 0))
            continue;  // carried no load within the step
        softBounces_[kept++] = bounce;
        grouped = grouped || constraints[bounce.constraint].normalGroup != NormalIslands::kNone;
    }
    softBounces_.resize(kept);
    for (const SoftBounce& bounce : softBounces_) {
        ContactConstraint& c = constraints[bounce.constraint];
        if (c.normalGroup != NormalIslands::kNone)
            continue;
        ContactConstraintPoint& p = c.points[bounce.point];
        SolverBody& a = bodies[c.bodyA];
        SolverBody& b = bodies[c.bodyB];
        Real& sum = softSums_[bounce.constraint].normal[bounce.point];
        const Real vn = normalSpeed(a, b, c.normal, p);
        const Real next = std::max<Real>(0, p.normalImpulse + p.normalMass * (bounce.target - vn));
        applyNormal(a, b, c.normal, p, next - p.normalImpulse);
        sum += next - p.normalImpulse;
        p.normalImpulse = next;
        const SoftPoint& q = softPoints_[softFirst_[bounce.constraint] + bounce.point];
        const Real shortfall = bounce.lift - separationNow(q, moved);
        if (shortfall > 0) {
            const Real push = p.normalMass * shortfall;
            lift[c.bodyA].linear -= (a.inverseMass * push) * c.normal;
            lift[c.bodyA].angular -= push * p.angularImpulseA;
            lift[c.bodyB].linear += (b.inverseMass * push) * c.normal;
            lift[c.bodyB].angular += push * p.angularImpulseB;
        }
    }
    if (grouped)
        softGroupBounces(bodies, constraints, moved, lift, slop, inverseH);
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

// The grouped bounces of endSoft: every group solved once more, rigidly, with the bouncing
// points' targets (the others' are the last relax sweep's, which they meet already). Then the
// lift as the same problem on displacements: from rest, the bouncing points reach their
// rebound's separation (v_n >= shortfall over a unit time), the others do not close (v_n >= 0
// touching, >= -s speculative). Split by the pair's masses instead, the lift pushed a light
// box into the ground and raised the ball by m_box / (m_box + m_ball) of it (1 kg ball on a
// 0.1 kg box: 4 % of e^2 low at e = 0.3).
void ContactSolver::softGroupBounces(std::span<SolverBody> bodies,
                                     std::span<ContactConstraint> constraints,
                                     std::span<const BodyDisplacement> moved,
                                     std::span<PseudoVelocity> lift, Real slop, Real inverseH) {
    const auto forGrouped = [&](auto&& f) {
        for (std::size_t j = 0; j < constraints.size(); ++j) {
            for (int i = 0; constraints[j].normalGroup != NormalIslands::kNone &&
                            i < constraints[j].pointCount;
                 ++i)
                f(j, constraints[j].points[i], softSums_[j].normal[i]);
        }
    };
    const auto setBounces = [&](bool lifts) {
        for (const SoftBounce& bounce : softBounces_) {
            ContactConstraint& c = constraints[bounce.constraint];
            ContactConstraintPoint& p = c.points[bounce.point];
            if (c.normalGroup == NormalIslands::kNone)
                continue;
            const SoftPoint& q = softPoints_[softFirst_[bounce.constraint] + bounce.point];
            p.bounces = true;
            p.reboundSpeed =
                lifts ? std::max<Real>(0, bounce.lift - separationNow(q, moved)) : bounce.target;
        }
    };
    setBounces(false);
    forGrouped([](std::size_t, ContactConstraintPoint& p, Real& sum) { sum -= p.normalImpulse; });
    islands_.solve(bodies, constraints, 1, 0, slop, inverseH);
    forGrouped([](std::size_t, ContactConstraintPoint& p, Real& sum) {
        sum += p.normalImpulse;
        p.normalImpulse = 0;  // endSoft writes the sums over it
    });
    // The separations the rows hold are the relax sweep's targets: touching ones read as
    // depths (target 0 at no bias), speculative ones as gaps; over a unit time they bound the
    // displacement as they bound the velocity over the substep.
    softLifts_.assign(bodies.begin(), bodies.end());
    for (SolverBody& body : softLifts_) {
        body.linearVelocity.setZero();
        body.angularVelocity.setZero();
    }
    setBounces(true);
    islands_.solve(softLifts_, constraints, 1, 0, slop, 1);
    forGrouped([](std::size_t, ContactConstraintPoint& p, Real&) { p.bounces = false; });
    for (std::size_t b = 0; b < lift.size(); ++b) {
        lift[b].linear += softLifts_[b].linearVelocity;
        lift[b].angular += softLifts_[b].angularVelocity;
    }
}

}  // namespace tumble
