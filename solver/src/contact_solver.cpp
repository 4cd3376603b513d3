#include "tumble/solver/contact_solver.h"

#include <algorithm>
#include <cmath>

#include "bounce_support.h"
#include "contact_kernels.h"
#include "normal_block.h"
#include "tumble/core/error.h"
#include "tumble/core/lane_kernel.h"

namespace tumble {
namespace {

using Mat2 = Eigen::Matrix<Real, 2, 2>;
using Vec2 = Eigen::Matrix<Real, 2, 1>;

Vec3 relativeVelocity(const SolverBody& a, const SolverBody& b, const ContactConstraintPoint& p) {
    return b.velocityAt(p.rB) - a.velocityAt(p.rA);
}

// The impulse P acts on B at rB and -P on A at rA.
void applyPair(SolverBody& a, SolverBody& b, const ContactConstraintPoint& p, const Vec3& impulse) {
    applyImpulse(a, -impulse, p.rA);
    applyImpulse(b, impulse, p.rB);
}

// A pure angular impulse L (N m s) on B, -L on A.
void applyAngular(SolverBody& a, SolverBody& b, const Vec3& impulse) {
    a.angularVelocity -= a.inverseInertia * impulse;
    b.angularVelocity += b.inverseInertia * impulse;
}

// The angular rows' effective masses. K = T'(IA^-1 + IB^-1) T for the relative spin about the
// axes T per unit angular impulse; bodies that cannot turn (static, translation-only) give none.
void prepareAngularFriction(const SolverBody& a, const SolverBody& b, ContactConstraint& c,
                            bool warmStart) {
    if (c.spinningFriction == 0 && c.rollingFriction == 0) {
        // No rows (most manifolds): what the general path gives them, without the effective
        // masses and the norms of every point (angularReach is only read with angular rows).
        c.spinMass = 0;
        c.rollingActive = false;
        c.angularReach = 0;
        c.angularImpulse = Vec3::Zero();
        return;
    }
    const Mat3 inverseInertia = a.inverseInertia + b.inverseInertia;
    const Real kSpin = c.normal.dot(inverseInertia * c.normal);
    c.spinMass = c.spinningFriction > 0 && kSpin > 0 ? 1 / kSpin : 0;
    c.rollingActive = false;
    if (c.rollingFriction > 0) {
        Mat2 kRolling;
        for (int r = 0; r < 2; ++r) {
            for (int col = 0; col < 2; ++col)
                kRolling(r, col) = c.tangents[r].dot(inverseInertia * c.tangents[col]);
        }
        c.rollingActive = c.rolling.set(kRolling);
    }
    // Keep only the cached parts that have rows this step, within this step's limits (from the
    // warm-start normal impulses): a patch whose load has gone keeps no torque.
    Real normalImpulse = 0;
    c.angularReach = 0;
    for (int i = 0; i < c.pointCount; ++i) {
        normalImpulse += c.points[i].normalImpulse;
        c.angularReach = std::max({c.angularReach, c.points[i].rA.norm(), c.points[i].rB.norm()});
    }
    const Real spinLimit = c.spinningFriction * normalImpulse;
    const Real spinPart =
        c.spinMass > 0 ? std::clamp(c.normal.dot(c.angularImpulse), -spinLimit, spinLimit) : 0;
    Vec3 rollingPart = Vec3::Zero();
    if (c.rollingActive) {
        rollingPart = c.angularImpulse - c.normal.dot(c.angularImpulse) * c.normal;
        const Real rollingLimit = c.rollingFriction * normalImpulse;
        if (rollingPart.norm() > rollingLimit)
            rollingPart *= rollingLimit / rollingPart.norm();
    }
    c.angularImpulse = warmStart ? Vec3(spinPart * c.normal + rollingPart) : Vec3::Zero();
}

// The angular part of d' K e for a point's mass matrix K = (1/mA + 1/mB) 1 - [rA]x IA^-1 [rA]x
// - [rB]x IB^-1 [rB]x (velocity change at the point per unit impulse): with [r]x d = r x d and
// [r]x skew, -d' [r]x I^-1 [r]x e = (r x d)' I^-1 (r x e), the rows' angular parts. Its tangent
// block is the coupled friction's.
inline Real pointMass(const Vec3& angularA, const Vec3& impulseA, const Vec3& angularB,
                      const Vec3& impulseB) {
    return angularA.dot(impulseA) + angularB.dot(impulseB);
}

}  // namespace

// When and how fast a point at separation s hits, under a constant normal acceleration a, given
// its normal velocity vEnd at the end of the step before contact (so vEnd - a h at its start).
//
// Semi-implicit Euler (v += a h, then x += h v) under constant a puts its positions exactly on a
// parabola whose velocity runs half a step ahead: x_n = X(n h) for X(t) = x_0 + w t + a t^2 / 2
// with w = v_0 + a h / 2. The impact is where that parabola meets the surface, and the bounce
// restarts it there with -e times its speed (see reboundSpeed). So the discrete flight after a
// bounce samples the continuous one and bounce heights are right to O(h^2). Taking vEnd as the
// impact speed instead, as a plain Newton's law does, put +0.7 % into the first bounce's height at
// h = 1/240, and the continuous speed at the impact -1.9 %.
namespace {

// impactWithinStep, inline so that prepareManifold's AVX2 copy takes it in (as setDisc).
inline Impact impactAt(Real s, Real vEnd, Real a, Real h) {
    const Real w = vEnd - 0.5 * a * h;
    if (s <= 0)
        return {0, w < 0 ? w : vEnd};
    // Roots of (a/2) t^2 + w t + s; the q form avoids cancellation.
    const Real discriminant = w * w - 2 * a * s;
    if (w < 0 && discriminant >= 0) {
        const Real q = -0.5 * (w - std::sqrt(discriminant));  // > 0
        Real t = s / q;
        if (a != 0) {
            const Real other = q / (0.5 * a);
            if (other > 0 && other < t)
                t = other;
        }
        if (t <= h)
            return {t, w + a * t};
    }
    // Stopped although it would not have arrived (pushed by other contacts): the linear guess.
    return {vEnd < 0 ? std::clamp(-s / vEnd, Real(0), h) : h, vEnd};
}

}  // namespace

Impact impactWithinStep(Real s, Real vEnd, Real a, Real h) {
    return impactAt(s, vEnd, a, h);
}

// The coupled friction update of one point, solved exactly: the impulse lambda in the disc
// |lambda| <= r that minimises  1/2 (lambda - old)' K (lambda - old) + vt' (lambda - old),
// i.e. the best friction this point alone can apply. At its solution the slip velocity after the
// impulse, vt + K (lambda - old), is either zero (sticking) or anti-parallel to lambda on the rim
// (sliding): Coulomb's law with maximal dissipation, the same in every direction.
//
// Projecting the unconstrained answer old - K^-1 vt onto the disc instead would be cheaper but
// wrong when K is not a multiple of the identity (contacts off the centre line): friction would
// then oppose K^-1 vt, not vt, and a sliding box would veer.
//
// Sliding case: a trust-region problem; lambda(nu) = (K + nu 1)^-1 b with b = K old - vt, and the
// multiplier nu >= 0 solves |lambda(nu)| = r. Newton on 1/|lambda(nu)| - 1/r, which is concave
// and increasing in nu, converges monotonically from any nu left of the root (More & Sorensen).
// (solveDisc, inline in contact_kernels.h, returns the free answer when it is in the disc.)
Vec2 solveDiscRim(const DiscBlock& k, const Vec2& b, Real radius) {
    const Vec2& moments = k.moments;  // moments(0) <= moments(1)
    const Vec2 c = k.axes.transpose() * b;
    // |lambda(nu)| >= |c| / (moments(1) + nu) and >= |c0| / (moments(0) + nu), so at this nu
    // lambda is still outside the disc: Newton starts left of the root, where it stays
    // monotone, and for a nearly isotropic K (contacts near the centre line) it is the root.
    const Real bound0 = std::sqrt(c(0) * c(0) + c(1) * c(1)) / radius - moments(1);
    const Real bound1 = std::abs(c(0)) / radius - moments(0);
    Real nu = std::max<Real>(0, std::max(bound0, bound1));
    for (int iteration = 0; iteration < 20; ++iteration) {
        const Real s0 = 1 / (moments(0) + nu);
        const Real s1 = 1 / (moments(1) + nu);
        const Real q0 = c(0) * s0;  // lambda in the eigenbasis
        const Real q1 = c(1) * s1;
        const Real squared = q0 * q0 + q1 * q1;
        const Real length = std::sqrt(squared);
        // (1/|q| - 1/r) / (d/dnu 1/|q|), with d/dnu 1/|q| = (q0^2 s0 + q1^2 s1) / |q|^3.
        const Real step = squared * (1 - length / radius) / (q0 * q0 * s0 + q1 * q1 * s1);
        nu = std::max<Real>(0, nu - step);
        // Quadratic convergence: the step after this one would be ~1e-10 of nu's scale (the
        // rims of pile-1000 contract as e' ~ 0.02 e^2), far below what a sweep resolves.
        if (std::abs(step) <= 1e-5 * (nu + moments(1)))
            break;
    }
    const Vec2 lambda = k.axes * c.cwiseQuotient(moments + Vec2::Constant(nu));
    return lambda * (radius / lambda.norm());  // on the rim to rounding
}

namespace {

// The eigen-decomposition in closed form: k = axes diag(moments) axes'. Inline, so that
// prepareManifold's AVX2 copy (lane_kernel.h) takes it in: flatten left the member function a
// call to its baseline code.
inline bool setDisc(DiscBlock& disc, const Mat2& k) {
    const Real mean = 0.5 * (k(0, 0) + k(1, 1));
    const Real half = 0.5 * (k(0, 0) - k(1, 1));
    const Real radius = std::sqrt(half * half + k(0, 1) * k(0, 1));
    // Singular (a body that cannot turn about these axes): no rows.
    if (!(mean - radius > 1e-12 * mean)) {
        disc = DiscBlock{};
        return false;
    }
    // The larger moment's axis, (half + radius, k01) or, parallel to it, (k01, radius - half):
    // each step takes the form whose terms do not cancel, so no trigonometry is needed. Its sign
    // is free (the solve uses axes and axes' together).
    const Vec2 major = half >= 0 ? Vec2(half + radius, k(0, 1)) : Vec2(k(0, 1), radius - half);
    const Vec2 unit = radius > 0 ? Vec2(major / major.norm()) : Vec2::UnitX();  // any, if isotropic
    const Real cs = unit.x();
    const Real sn = unit.y();
    disc.block = k;
    disc.inverse = k.inverse();
    disc.moments = Vec2(mean - radius, mean + radius);
    disc.axes << -sn, cs, cs, sn;
    return true;
}

}  // namespace

bool DiscBlock::set(const Mat2& k) {
    return setDisc(*this, k);
}

void checkSolverSettings(const SolverSettings& s) {
    if (s.iterations < 1)
        fail("SolverSettings.iterations = ", s.iterations, " must be >= 1");
    if (s.relaxIterations < 0)
        fail("SolverSettings.relaxIterations = ", s.relaxIterations, " must be >= 0");
    if (s.linkIterations < 1)
        fail("SolverSettings.linkIterations = ", s.linkIterations, " must be >= 1");
    if (s.linkRelaxIterations < 0)
        fail("SolverSettings.linkRelaxIterations = ", s.linkRelaxIterations, " must be >= 0");
    if (!(std::isfinite(s.tolerance) && s.tolerance >= 0)) {
        fail("SolverSettings.tolerance = ", s.tolerance, " (m/s) must be finite and >= 0");
    }
    if (!(s.relaxation > 0 && s.relaxation < 2)) {
        fail("SolverSettings.relaxation = ", s.relaxation, " must be in (0, 2)");
    }
    if (!(s.baumgarte >= 0 && s.baumgarte <= 1))
        fail("SolverSettings.baumgarte = ", s.baumgarte, " must be in [0, 1]");
    if (!(s.splitImpulseFactor > 0 && s.splitImpulseFactor <= 1)) {
        fail("SolverSettings.splitImpulseFactor = ", s.splitImpulseFactor, " must be in (0, 1]");
    }
    if (!(std::isfinite(s.slop) && s.slop >= 0))
        fail("SolverSettings.slop = ", s.slop, " (m) must be finite and >= 0");
    if (!(std::isfinite(s.restitutionThreshold) && s.restitutionThreshold >= 0)) {
        fail("SolverSettings.restitutionThreshold = ", s.restitutionThreshold,
             " (m/s) must be finite and >= 0");
    }
    if (s.softSubsteps < 0)
        fail("SolverSettings.softSubsteps = ", s.softSubsteps, " must be >= 0");
    if (!(std::isfinite(s.contactHertz) && s.contactHertz > 0))
        fail("SolverSettings.contactHertz = ", s.contactHertz, " (Hz) must be finite and > 0");
    if (!(std::isfinite(s.contactDampingRatio) && s.contactDampingRatio >= 0)) {
        fail("SolverSettings.contactDampingRatio = ", s.contactDampingRatio,
             " must be finite and >= 0");
    }
    if (!(std::isfinite(s.maxPushOutSpeed) && s.maxPushOutSpeed > 0)) {
        fail("SolverSettings.maxPushOutSpeed = ", s.maxPushOutSpeed,
             " (m/s) must be finite and > 0");
    }
}

namespace {

// K_ij = 1/mA + 1/mB + (rA_i x n)' IA^-1 (rA_j x n) + (rB_i x n)' IB^-1 (rB_j x n): the normal
// block of a manifold of N points. N is a template argument so that its loops unroll (the same
// operations; their counters were a tenth of prepareManifold's instructions on pyramid-20).
template <int N>
void fillNormalBlock(const SolverBody& a, const SolverBody& b, ContactConstraint& c) {
#pragma GCC unroll 4
    for (int i = 0; i < N; ++i) {
        const ContactConstraintPoint& p = c.points[i];
#pragma GCC unroll 4
        for (int j = 0; j < N; ++j) {
            const ContactConstraintPoint& q = c.points[j];
            c.normalBlock(i, j) = a.inverseMass + b.inverseMass +
                                  p.angularA.dot(q.angularImpulseA) +
                                  p.angularB.dot(q.angularImpulseB);
        }
    }
}

// prepare's pass over one manifold: its basis, each point's masses, Jacobians, tangent block,
// approach and impact, its normal block and angular rows. Compiled for AVX2 and the baseline
// like the lane kernels (lane_kernel.h, the same bits): the baseline's two-operand SSE2 moved
// every Eigen temporary through extra register copies, and this pass took 11.6 % of
// pyramid-20's instructions.
TUMBLE_LANE_KERNEL void prepareManifold(const SolverBody& a, const SolverBody& b,
                                        ContactConstraint& c, Real h,
                                        const SolverSettings& settings, bool split, bool support,
                                        Real& deepestPenetration, bool& bounceCorrections) {
    if (!c.tangentsSet)
        c.tangents = frictionBasis(c.normal);
    for (int i = 0; i < c.pointCount; ++i) {
        ContactConstraintPoint& p = c.points[i];
        deepestPenetration = std::max(deepestPenetration, -p.separation);
        if (!support)
            p.supportSpeed = 0;
        p.angularA = p.rA.cross(c.normal);
        p.angularB = p.rB.cross(c.normal);
        p.angularImpulseA = a.inverseInertia * p.angularA;
        p.angularImpulseB = b.inverseInertia * p.angularB;
        for (int r = 0; r < 2; ++r) {
            p.tangentAngularA[r] = p.rA.cross(c.tangents[r]);
            p.tangentAngularB[r] = p.rB.cross(c.tangents[r]);
            p.tangentImpulseA[r] = a.inverseInertia * p.tangentAngularA[r];
            p.tangentImpulseB[r] = b.inverseInertia * p.tangentAngularB[r];
        }
        // d' K e for the point's mass matrix K (pointMass says why this is K), from the rows
        // just formed: the 3 x 3 K itself, two triple products a point, was a third of this
        // pass's instructions on pyramid-20 (callgrind: 145 -> 97 M over 2 s).
        const Real inverseMass = a.inverseMass + b.inverseMass;
        const Real kNormal =
            inverseMass + pointMass(p.angularA, p.angularImpulseA, p.angularB, p.angularImpulseB);
        p.normalMass = kNormal > 0 ? 1 / kNormal : 0;
        Mat2 kTangent;
        for (int r = 0; r < 2; ++r) {
            kTangent(r, r) = inverseMass + pointMass(p.tangentAngularA[r], p.tangentImpulseA[r],
                                                     p.tangentAngularB[r], p.tangentImpulseB[r]);
        }
        kTangent(0, 1) = pointMass(p.tangentAngularA[0], p.tangentImpulseA[1], p.tangentAngularB[0],
                                   p.tangentImpulseB[1]);
        kTangent(1, 0) = kTangent(0, 1);  // symmetric to the bit
        setDisc(p.tangent, kTangent);
        p.tangentMass = {1 / kTangent(0, 0), 1 / kTangent(1, 1)};
        p.approachSpeed = relativeVelocity(a, b, p).dot(c.normal);
        const Impact impact =
            impactAt(p.separation, p.approachSpeed + p.supportSpeed, p.normalAcceleration, h);
        p.impactTime = impact.time;
        p.impactSpeed = impact.speed;
        // Newton's law at the impact, then the parabola for the rest of the step; the
        // step's velocity runs half a step behind it (impactWithinStep).
        p.reboundSpeed =
            -c.restitution * impact.speed + p.normalAcceleration * (0.5 * h - impact.time);
        // Only points that approach fast and reach the surface within the step bounce.
        p.bounces = c.restitution > 0 && impact.speed < -settings.restitutionThreshold &&
                    (p.separation <= 0 || p.approachSpeed < -p.separation / h);
        // Integrated with the rebound speed from where it stands, a speculative point would
        // end s + h v+ above the surface; the bounce at the impact puts it at `rebound`.
        const Real rest = h - impact.time;
        const Real rebound =
            -c.restitution * impact.speed * rest + 0.5 * p.normalAcceleration * rest * rest;
        p.bounceCorrection = split && p.bounces && p.separation > 0
                                 ? p.separation + h * p.reboundSpeed - rebound
                                 : 0;
        bounceCorrections = bounceCorrections || p.bounceCorrection != 0;
        if (!settings.warmStart || c.friction == 0)
            p.tangentImpulse = {0, 0};
        if (!settings.warmStart)
            p.normalImpulse = 0;
    }
    // Zeros only where no point writes (a rep stos of 16 quadwords for every manifold before).
    if (c.pointCount < 4)
        c.normalBlock.setZero();
    withPointCount(c.pointCount, [&]<int N>() { fillNormalBlock<N>(a, b, c); });
    prepareAngularFriction(a, b, c, settings.warmStart);
}

// The warm start of one manifold: its cached impulses applied to its bodies (a kernel like
// prepareManifold, for the same reason).
TUMBLE_LANE_KERNEL void warmStart(SolverBody& a, SolverBody& b, const ContactConstraint& c) {
    for (int i = 0; i < c.pointCount; ++i) {
        const ContactConstraintPoint& p = c.points[i];
        applyPair(a, b, p,
                  p.normalImpulse * c.normal + p.tangentImpulse[0] * c.tangents[0] +
                      p.tangentImpulse[1] * c.tangents[1]);
    }
    applyAngular(a, b, c.angularImpulse);
}

}  // namespace

Real ContactSolver::prepare(std::span<SolverBody> bodies, std::span<ContactConstraint> constraints,
                            Real h, const SolverSettings& settings) {
    const bool split = settings.stabilisation == Stabilisation::SplitImpulse;
    // The support pass only matters when something can bounce; a scene without restitution
    // (every benchmark pile) reads one header line per manifold here, not its points.
    const bool support = settings.warmStart &&
                         std::any_of(constraints.begin(), constraints.end(),
                                     [](const ContactConstraint& c) { return c.restitution > 0; });
    if (support)
        addSupportAcceleration(bodies, constraints, h, supportBodies_);
    Real deepestPenetration = 0;
    bounceCorrections_ = false;
    std::size_t points = 0;
    for (ContactConstraint& c : constraints) {
        SolverBody& a = bodies[c.bodyA];
        SolverBody& b = bodies[c.bodyB];
        points += static_cast<std::size_t>(c.pointCount);
        prepareManifold(a, b, c, h, settings, split, support, deepestPenetration,
                        bounceCorrections_);
    }
    islands_.prepare(bodies, constraints);
    factors_.resize(constraints.size());
    for (NormalFactor& factor : factors_)
        factor.set = NormalFactor::kNone;
    // Warm start only once every approach speed is measured: applied point by point above, the
    // cached impulses of earlier contacts leaked into the approach speeds of later ones, and a
    // row of touching elastic balls (Newton's cradle) gained energy with every collision.
    // The scalar sweep's compact rows are copied here, while each constraint is in cache; a
    // pile's step (too few points for the rows) is known to take them before this loop.
    wide_ = settings.colouredContacts && ContactRows::enoughPoints(points, constraints.size());
    narrow_.clear();
    for (ContactConstraint& c : constraints) {
        warmStart(bodies[c.bodyA], bodies[c.bodyB], c);
        if (!wide_)
            narrow_.add(c, static_cast<std::uint32_t>(&c - constraints.data()), settings);
    }
    // Rows too sparse to fill the lanes (a lone column) fall back to the scalar sweep, which
    // gives the same bits.
    if (wide_ && !rows_.build(bodies, constraints, settings, 1 / h)) {
        wide_ = false;
        for (ContactConstraint& c : constraints)
            narrow_.add(c, static_cast<std::uint32_t>(&c - constraints.data()), settings);
    }
    return deepestPenetration;
}

void ContactSolver::dropBounceCorrections(std::span<ContactConstraint> constraints) {
    if (!bounceCorrections_)
        return;  // all zero already: no pass over the constraints
    for (ContactConstraint& c : constraints) {
        for (int i = 0; i < c.pointCount; ++i)
            c.points[i].bounceCorrection = 0;
    }
    if (wide_)
        rows_.dropBounceCorrections();
    else
        narrow_.dropBounceCorrections();
}

void ContactSolver::finish(std::span<ContactConstraint> constraints) const {
    if (wide_)
        rows_.store(constraints);
    else
        narrow_.store(constraints);
}

Real ContactSolver::solveVelocitySweep(std::span<SolverBody> bodies,
                                       std::span<ContactConstraint> constraints,
                                       const SolverSettings& settings, Real inverseH, Real bias,
                                       bool resident) {
    if (wide_) {
        // The exact groups' solve after each sweep changes the bodies behind the rows' copy.
        Real largestChange = rows_.sweep(bodies, constraints, factors_, settings, bias, inverseH,
                                         false, resident && islands_.empty());
        if (!islands_.empty()) {
            largestChange =
                std::max(largestChange, islands_.solve(bodies, constraints, settings.relaxation,
                                                       bias, settings.slop, inverseH));
            rows_.readGroupImpulses(constraints);
        }
        return largestChange;
    }
    Real largestChange = narrow_.sweep(bodies, constraints, factors_, settings, inverseH, bias);
    if (!islands_.empty()) {
        largestChange =
            std::max(largestChange, islands_.solve(bodies, constraints, settings.relaxation, bias,
                                                   settings.slop, inverseH));
        narrow_.readGroupImpulses(constraints);
    }
    return largestChange;
}

// Torsion and rolling resistance, with the normal impulses of the last sweep like the linear
// friction: the spin about the normal driven to zero within +-spinningFriction x sum(lambda_n),
// the relative spin about the tangents within the disc of radius rollingFriction x
// sum(lambda_n), solved exactly as the point friction is (solveDisc), relaxed by the SOR factor
// like it. The disc is used under the box friction model too: the study's box model is about
// linear friction. Returns the change as a speed at the manifold's farthest point (m/s).
Real solveAngularFriction(SolverBody& a, SolverBody& b, ContactConstraint& c, Real omega) {
    Real normalImpulse = 0;
    for (int i = 0; i < c.pointCount; ++i)
        normalImpulse += c.points[i].normalImpulse;
    Vec3 change = Vec3::Zero();
    Real spinChange = 0;
    if (c.spinMass > 0) {
        const Real spin = c.normal.dot(b.angularVelocity - a.angularVelocity);
        const Real old = c.normal.dot(c.angularImpulse);
        const Real limit = c.spinningFriction * normalImpulse;
        const Real solved = std::clamp(old - c.spinMass * spin, -limit, limit);
        const Real next = old + omega * (solved - old);
        change += (next - old) * c.normal;
        applyAngular(a, b, (next - old) * c.normal);
        spinChange = std::abs(next - old) / c.spinMass;
    }
    Real rollingChange = 0;
    if (c.rollingActive) {
        const Vec3 relative = b.angularVelocity - a.angularVelocity;
        const Vec2 roll(c.tangents[0].dot(relative), c.tangents[1].dot(relative));
        const Vec2 old(c.tangents[0].dot(c.angularImpulse), c.tangents[1].dot(c.angularImpulse));
        const Vec2 solved = solveDisc(c.rolling, old, roll, c.rollingFriction * normalImpulse);
        const Vec2 delta = omega * (solved - old);
        const Vec3 impulse = delta.x() * c.tangents[0] + delta.y() * c.tangents[1];
        change += impulse;
        applyAngular(a, b, impulse);
        rollingChange = (c.rolling.block * delta).norm();
    }
    c.angularImpulse += change;
    // The change of relative spin (rad/s), as a speed at the farthest contact point (m/s), so
    // the tolerance, in m/s, sees it.
    return std::max(spinChange, rollingChange) * c.angularReach;
}

// Compiled like the kernels (lane_kernel.h): the same bits, 1 % of pyramid-20's instructions.
TUMBLE_LANE_KERNEL Real ContactSolver::residual(std::span<const SolverBody> bodies,
                                                std::span<const ContactConstraint> constraints,
                                                const SolverSettings& settings, Real inverseH,
                                                Real bias) const {
    Real worst = 0;
    for (const ContactConstraint& c : constraints) {
        const SolverBody& a = bodies[c.bodyA];
        const SolverBody& b = bodies[c.bodyB];
        for (int i = 0; i < c.pointCount; ++i) {
            const ContactConstraintPoint& p = c.points[i];
            if (p.normalMass == 0)
                continue;
            const Vec3 v = relativeVelocity(a, b, p);
            // Complementarity of the normal row, in velocity units: min(lambda / m, v_n - target)
            // is zero at a solution (either no impulse or the target velocity met).
            const Real gap = v.dot(c.normal) - normalTarget(p, bias, settings.slop, inverseH);
            worst = std::max(worst, std::abs(std::min(p.normalImpulse / p.normalMass, gap)));
        }
    }
    return worst;
}

}  // namespace tumble
