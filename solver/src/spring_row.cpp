#include "tumble/solver/spring_row.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>

namespace tumble {
namespace {

// Anchors closer than this have no line to pull along (m).
constexpr Real kMinimumLength = 1e-12;

// (omega h)^2 of an element up to which the symmetric weights hold the phase to fourth order
// (Fox-Goodwin, beta = 1/12): stable to (omega h)^2 = 6, and a node's highest mode is about
// twice its element's (omega h)^2.
constexpr Real kFourthOrderUpTo = 1.5;
// Fox-Goodwin's beta: the symmetric weights there.
constexpr Real kFoxGoodwin = Real(1) / 12;
// (omega h)^2 from which the unresolved element is damped: rho = this / (omega h)^2.
constexpr Real kDampedFrom = 4;
// (omega h)^2 from which an undamped thread takes the discrete gradient, up to the second
// (spring_row.h): above Fox-Goodwin's range the trapezoidal catches lost a tumbling net's
// energy (`net-energy` at omega_e h = 1: 0.04 of it left).
constexpr Real kDiscreteGradientFrom = kFourthOrderUpTo;
constexpr Real kDiscreteGradientUpTo = 100;

struct SchemeWeights {
    Real next;      // w1
    Real last;      // w_1
    Real rateNext;  // a
};

// The three-level weights (spring_row.h) for an element with (omega h)^2 = squared.
SchemeWeights schemeWeights(Real spectralRadius, Real squared) {
    if (spectralRadius >= 1 && squared < kDampedFrom) {
        // Symmetric: no numerical damping. beta rises to keep the highest mode stable.
        const Real beta = squared <= kFourthOrderUpTo ? kFoxGoodwin : Real(0.25) - 0.25 / squared;
        return {beta, beta, 0.5};
    }
    const Real rho =
        spectralRadius * std::min<Real>(1, kDampedFrom / std::max(squared, kDampedFrom));
    const Real next = 1 / ((1 + rho) * (1 + rho));
    return {next, rho * rho * next, 1 / (1 + rho)};
}

// The weights of a thread's catching step: the trapezoidal rule (beta = 1/4: stable at every
// omega h, no numerical damping of a linear mode) where the element is resolved and the scheme
// undamped, implicit Euler otherwise (see spring_row.h).
SchemeWeights catchWeights(Real spectralRadius, Real squared) {
    if (spectralRadius >= 1 && squared < kDampedFrom)
        return {0.25, 0.25, 0.5};
    return schemeWeights(0, squared);
}

// A thread's stretch at the step's end is linearised at no less than this share of its rest
// length when it is slack at the start (the discrete gradient's slope is 0 below it: such a row
// could never take load).
constexpr Real kCatchFloor = 1e-3;
// A discrete-gradient row whose linear model misses the gradient at the solved stretch by more
// than this share of it is linearised there again and the block solved again. 3e-4, not 1e-3:
// the misses at 1e-3 took ~0.5 % of a tumbling net's energy in 10 s with one solve a step, ~1 %
// with two (`net-energy` at omega_e h = 3, two substeps: 0.9895; now 0.9976). 1e-4 on both
// tolerances gained 1.35 % at omega_e h = 2 (not diagnosed).
constexpr Real kGradientTolerance = 3e-4;
// ... or whose direction (d0 + d1) / |d0 + d1| moved by more than this (rad).
constexpr Real kDirectionTolerance = 3e-4;
// A turn row's stiffness where its thread does not pull, per unit of the thread's (N/m): it
// then holds almost nothing, and its row stays in the factorisation's pattern.
constexpr Real kInertTurn = 1e-6;
// Newton (or bisection) steps of a thread's first guess alone (stretchAlone).
constexpr int kLocalIterations = 12;

// The discrete gradient (V(c1) - V(c0)) / (c1 - c0) of a thread's energy V = k max(C, 0)^2 / 2
// between the stretches c0 and c1 (N), and its derivative in c1 (N/m).
struct Gradient {
    Real value;
    Real slope;
};

Gradient threadGradient(Real k, Real c0, Real c1) {
    if (c0 >= 0 && c1 >= 0)
        return {0.5 * k * (c0 + c1), 0.5 * k};
    if (c0 >= 0) {  // released within the step
        const Real q = c0 / (c0 - c1);
        return {0.5 * k * c0 * q, 0.5 * k * q * q};
    }
    if (c1 <= 0)
        return {0, 0};
    const Real q = c1 / (c1 - c0);  // caught within the step: the share of it spent taut
    return {0.5 * k * c1 * q, 0.5 * k * q * (2 - q)};
}

// The three-level form's pull per unit k, G = (Phi(x0, x1) - Phi(xm, x0)) / (x1 - xm) (m), and its
// slope in x1, by the levels' signs (spring_row.h): Phi(x0, x1) - Phi(xm, x0) = (x1+ - xm+)
// (beta (x1+ + xm+) + (1 - 2 beta) x0+). The slope's divided difference is written out: at
// x1 ~ xm it cancels to rounding.
// Inlined: called ~4 times per row and per round; the call was a share of the net-10 step.
[[gnu::always_inline]] inline Gradient levelGradient(Real xm, Real x0, Real x1) {
    constexpr Real beta = kFoxGoodwin;
    const Real p0 = std::max<Real>(x0, 0);
    if (xm >= 0 && x1 >= 0)  // taut at both ends: Fox-Goodwin's weights
        return {beta * (x1 + xm) + (1 - 2 * beta) * p0, beta};
    if (x1 <= 0 && xm <= 0)
        return {0, 0};
    if (xm >= 0) {  // released: G = xm (beta xm + (1 - 2 beta) x0+) / (xm - x1)
        const Real value = xm * (beta * xm + (1 - 2 * beta) * p0) / (xm - x1);
        return {value, value / (xm - x1)};
    }
    const Real run = x1 - xm;  // caught: > x1 > 0
    const Real tangent = 2 * beta * x1 + (1 - 2 * beta) * p0;
    return {x1 * (beta * x1 + (1 - 2 * beta) * p0) / run,
            (beta * x1 * x1 - xm * tangent) / (run * run)};
}

// The root x1 of x1 + weight G(x1) = free for a gradient G nondecreasing in x1 (>= 0), from
// lo, where the left side is <= free: a thread's end stretch alone between its bodies, its
// first guess (the block's rounds only correct it). Newton, kept inside the bracket by
// bisection: on a stiff catch Newton from the constant-velocity guess halves its distance per
// step. It stops early where the residual is within `tolerance` (m).
template <class GradientAt>
Real stretchAlone(const GradientAt& gradientAt, Real lo, Real free, Real weight,
                  Real tolerance = -1) {
    Real hi = free;
    Real c1 = free;
    for (int i = 0; i < kLocalIterations; ++i) {
        const Gradient g = gradientAt(c1);
        const Real residual = c1 + weight * g.value - free;
        if (std::abs(residual) <= tolerance)
            break;
        if (residual > 0)
            hi = c1;
        else
            lo = c1;
        const Real newton = c1 - residual / (1 + weight * g.slope);
        c1 = newton > lo && newton < hi ? newton : 0.5 * (lo + hi);
    }
    return c1;
}

// The row's Jacobians along its direction, and J M^-1 J'.
[[gnu::always_inline]] inline Real setJacobians(const SolverBody& a, const SolverBody& b,
                                                SpringRow& row) {
    row.angularA = row.rA.cross(row.direction);
    row.angularB = row.rB.cross(row.direction);
    row.angularImpulseA = a.inverseInertia * row.angularA;
    row.angularImpulseB = b.inverseInertia * row.angularB;
    return a.inverseMass + b.inverseMass + row.angularA.dot(row.angularImpulseA) +
           row.angularB.dot(row.angularImpulseB);
}

// The end-of-step stretch c1 of a thread alone between its bodies: the root of c1 + (h^2 / 2)
// J M^-1 J' D(c0, c1) = free, free its end stretch without this step's half (D' >= 0).
Real threadStretchAlone(Real k, Real c0, Real free, Real weight) {
    const auto gradientAt = [&](Real c1) { return threadGradient(k, c0, c1); };
    return stretchAlone(gradientAt, std::min<Real>(free, 0) - std::abs(c0), free, weight);
}

// A discrete-gradient row's half impulse from the last step, along last step's line.
void applyCarriedImpulse(SolverBody& a, SolverBody& b, const SpringRow& row) {
    a.linearVelocity -= a.inverseMass * row.carried;
    a.angularVelocity -= a.inverseInertia * row.rA.cross(row.carried);
    b.linearVelocity += b.inverseMass * row.carried;
    b.angularVelocity += b.inverseInertia * row.rB.cross(row.carried);
}

}  // namespace

void implicitEulerThreadRow(const SolverBody& a, const SolverBody& b, SpringRow& row, Real h) {
    row.discreteGradient = false;
    row.levelGradient = false;
    row.direction = row.span / row.length;
    const Real inverseMass = setJacobians(a, b, row);
    const Real resistance = row.damping + h * row.stiffness;  // spring_row.h, rho = 0
    if (!(resistance > 0) || !(inverseMass > 0)) {
        row.mass = 0;
        return;
    }
    row.softness = 1 / (h * resistance);
    row.mass = 1 / (inverseMass + row.softness);
    row.bias = row.stiffness * (row.length - row.restLength) / resistance;
}

namespace {

// A direction with the components it owes to rounding alone set to zero. x_-1 = x0 - h v0 picks up
// the velocities' rounding (~1e-17 m/s) that the positions never resolved, so Gonzalez's m of a
// flat net's thread leaks ~1e-15 across it; two crossing threads then couple in the block where
// their start lines (exactly perpendicular) did not, and the factorisation fills in (net-40-soft
// 1.45x main's cost, 1.15x with the start lines).
Vec3 snapRounding(const Vec3& direction) {
    constexpr Real kRounding = 1e-12;
    Vec3 snapped = direction;
    for (int i = 0; i < 3; ++i)
        snapped[i] = std::abs(snapped[i]) < kRounding ? Real(0) : snapped[i];
    return snapped;
}

// The three-level form's row (spring_row.h) linearised at the end span d1*, along Gonzalez's
// m = (d_-1 + d1*) / (L_-1 + L1*) = s n: r = h k s^2 G', bias = k s (G + G' (x_-1 + h s w0 -
// x1*)) / r.
void lineariseLevelRow(const SolverBody& a, const SolverBody& b, SpringRow& row, Real h,
                       const Vec3& endSpan) {
    const Real xm = row.lastStretch;
    const Real x0 = row.length - row.restLength;
    Vec3 end = endSpan;
    const Real endLength = end.norm();
    Real x1 = endLength - row.restLength;
    const Real floor = kCatchFloor * row.restLength;
    Gradient g = levelGradient(xm, x0, x1);
    if (x1 < floor && !(g.slope > 0)) {
        // Just past the rest length, along the span's line: the slope is 0 below it.
        end = (endLength > kMinimumLength ? Vec3(end / endLength) : row.direction) *
              (row.restLength + floor);
        x1 = floor;
        g = levelGradient(xm, x0, x1);
    }
    const Vec3 mid = row.span - h * row.startVelocity + end;
    const Real midLength = mid.norm();
    if (midLength > kMinimumLength)
        row.direction = snapRounding(mid / midLength);
    const Real scale =
        midLength > kMinimumLength ? midLength / (2 * row.restLength + xm + x1) : Real(1);
    row.linearisedAt = x1;
    row.knownImpulse = 0;
    const Real inverseMass = setJacobians(a, b, row);
    const Real resistance = h * row.stiffness * scale * scale * g.slope;
    if (!(resistance > 0) || !(inverseMass > 0)) {
        row.mass = 0;
        return;
    }
    const Real startRate = row.direction.dot(row.startVelocity);
    row.softness = 1 / (h * resistance);
    row.mass = 1 / (inverseMass + row.softness);
    row.bias = row.stiffness * scale * (g.value + g.slope * (xm + h * scale * startRate - x1)) /
               resistance;
}

// A resolved undamped thread's levels (spring_row.h): its start span and its stretch at the
// level before the step.
void startResolvedThread(SpringRow& row, Real h) {
    row.levelGradient = true;
    row.span = row.length * row.direction;
    row.lastStretch = (row.span - h * row.startVelocity).norm() - row.restLength;
}

// A resolved undamped thread (spring_row.h), after startResolvedThread(): the form's row by the
// true lengths, linearised at its end stretch alone (the root of x1 + (omega h)^2 G(x1) = its
// stretch at constant velocity; linear, Fox-Goodwin's, where the three levels are taut).
void lineariseResolvedThread(const SolverBody& a, const SolverBody& b, SpringRow& row, Real h,
                             Real squared) {
    const Real x0 = row.length - row.restLength;
    const Real xm = row.lastStretch;
    const Vec3 free = row.span + h * row.startVelocity;
    const Real freeLength = free.norm();
    const Real freeStretch = freeLength - row.restLength;
    // Taut at all three (most threads of a net): the root is Fox-Goodwin's, linear.
    const Real taut = (freeStretch - squared * (kFoxGoodwin * xm + (1 - 2 * kFoxGoodwin) * x0)) /
                      (1 + squared * kFoxGoodwin);
    Real x1 = taut;
    if (!(xm > 0 && x0 > 0 && taut > 0)) {
        const auto gradientAt = [&](Real c1) { return levelGradient(xm, x0, c1); };
        const Real lo = freeStretch - squared * levelGradient(xm, x0, freeStretch).value;
        x1 = stretchAlone(gradientAt, lo, freeStretch, squared,
                          kGradientTolerance * kCatchFloor * row.restLength);
    }
    const Real toEnd = freeLength > kMinimumLength ? (row.restLength + x1) / freeLength : 1;
    lineariseLevelRow(a, b, row, h, free * toEnd);
}

}  // namespace

bool threadRowStale(const SolverBody& a, const SolverBody& b, const SpringRow& row, Real h,
                    Vec3& endSpan) {
    threadRowEndStretch(a, b, row, h, endSpan);
    // The direction over the scheme's two levels: d0 and d1, or a three-level form's d_-1 and d1.
    const Vec3 mid =
        (row.levelGradient ? Vec3(row.span - h * row.startVelocity) : row.span) + endSpan;
    const Real midLength = mid.norm();
    if (!(midLength > kMinimumLength))
        return false;
    if ((mid / midLength - row.direction).norm() > kDirectionTolerance)
        return true;
    const Real c0 = row.length - row.restLength;
    const Real c1 = endSpan.norm() - row.restLength;
    const Real floor = kCatchFloor * row.restLength;
    const Real before = row.levelGradient ? row.lastStretch : c0;  // slack: a catch
    if (before < 0 && c1 <= floor && row.linearisedAt <= floor)
        return false;  // linearised at the floor already (lineariseThreadRow)
    const auto gradientAt = [&](Real c) {
        return row.levelGradient ? levelGradient(row.lastStretch, c0, c)
                                 : threadGradient(row.stiffness, c0, c);
    };
    const Gradient at = gradientAt(row.linearisedAt);
    const Real model = at.value + at.slope * (c1 - row.linearisedAt);
    const Real exact = gradientAt(c1).value;
    return std::abs(model - exact) >
           kGradientTolerance * std::max(std::abs(exact), std::abs(model));
}

// Gonzalez's discrete gradient: along m = (d0 + d1) / (L0 + L1), for which m . (d1 - d0) =
// L1 - L0 exactly. With n = m / s, s = |m| <= 1, and the rate w = J v1 along n, the new half is
// -2 lambda / (h s) = D(c0, c1*) + D' (c0 + h s w - c1*) + c s w (spring_row.h).
void lineariseThreadRow(const SolverBody& a, const SolverBody& b, SpringRow& row, Real h,
                        const Vec3& endSpan) {
    if (row.levelGradient) {
        lineariseLevelRow(a, b, row, h, endSpan);
        return;
    }
    const Real k = row.stiffness;
    const Real c0 = row.length - row.restLength;
    Vec3 end = endSpan;
    Real c1 = end.norm() - row.restLength;
    const Real floor = kCatchFloor * row.restLength;
    if (c1 < floor && (c0 < 0 || !(threadGradient(k, c0, c1).slope > 0))) {
        // Linearise just past the rest length, along the span's line: below it the gradient's
        // slope is 0 and the row could never take load.
        const Real endLength = end.norm();
        end = (endLength > kMinimumLength ? Vec3(end / endLength) : row.direction) *
              (row.restLength + floor);
        c1 = floor;
    }
    const Gradient g = threadGradient(k, c0, c1);
    const Vec3 mid = row.span + end;
    const Real midLength = mid.norm();
    if (midLength > kMinimumLength)
        row.direction = mid / midLength;
    const Real scale =
        midLength > kMinimumLength ? midLength / (row.length + c1 + row.restLength) : Real(1);
    row.linearisedAt = c1;
    const Real inverseMass = setJacobians(a, b, row);
    const Real resistance = scale * scale * (h * g.slope + row.damping);
    if (!(resistance > 0) || !(inverseMass > 0)) {
        row.mass = 0;
        return;
    }
    row.softness = 2 / (h * resistance);
    row.mass = 1 / (inverseMass + row.softness);
    row.bias = scale * (g.value + g.slope * (c0 - c1)) / resistance;
}

// The turn of m with the end span, -D (d1 - d1*)_t / (L0 + L1) along t, t . m* = 0: with
// t . d1* = -t . d0, the half impulse is lambda = -(h / 2) K_t (2 t . d0 + h w_t), w_t = J_t v1.
void lineariseThreadTurn(const SolverBody& a, const SolverBody& b, const SpringRow& thread,
                         SpringRow& turn, Real h) {
    const Real inverseMass = setJacobians(a, b, turn);
    const Real c0 = thread.length - thread.restLength;
    const Real c1 = thread.linearisedAt;
    const Real pull =
        thread.discreteGradient ? threadGradient(thread.stiffness, c0, c1).value : Real(0);
    turn.stiffness = std::max<Real>(pull / (thread.length + c1 + thread.restLength),
                                    kInertTurn * thread.stiffness);
    turn.knownImpulse = 0;
    if (!(inverseMass > 0) || !(h > 0)) {
        turn.mass = 0;
        return;
    }
    turn.softness = 2 / (h * h * turn.stiffness);
    turn.mass = 1 / (inverseMass + turn.softness);
    turn.bias = 2 * turn.direction.dot(thread.span) / h;
}

namespace {

// J M^-1 J' along the row's Jacobians as they stand.
[[gnu::always_inline]] inline Real jacobianInverseMass(const SolverBody& a, const SolverBody& b,
                                                       const SpringRow& row) {
    return a.inverseMass + b.inverseMass + row.angularA.dot(row.angularImpulseA) +
           row.angularB.dot(row.angularImpulseB);
}

// Whether the row's warm start comes out +0 whatever its mass (prepareSpringRows).
bool noWarmStart(const SpringRow& row, bool warmStart) {
    return !warmStart || row.impulse > 0 || (row.impulse == 0 && !std::signbit(row.impulse));
}

// prepareRow()'s deferral of an undamped thread between its bodies' centres (a net's), decided
// without its Jacobians, which a deferred row does not keep (finishSpringRow() sets them): with
// rA = rB = 0 their angular terms of J M^-1 J' are +-0 (the inverse inertias are finite: mass
// properties are checked finite and positive definite), which leave the inverse masses' sum
// unchanged, so (omega h)^2 is the one prepareRow() finds, bit for bit. Most of a net in
// flight is deferred: its Jacobians were a fifth of preparing the 10 x 10 net's rows.
bool deferCentred(const SolverBody& a, const SolverBody& b, SpringRow& row, Real h,
                  bool warmStart) {
    // A centred row's arms are +0 (buildSpringRows): its flag answers without six compares.
    if (!(row.centred || ((row.rA.array() == 0).all() && (row.rB.array() == 0).all())))
        return false;
    const Real inverseMass = a.inverseMass + b.inverseMass;
    const Real squared = h * h * row.stiffness * inverseMass;  // (omega h)^2
    if (!(squared < kDiscreteGradientFrom && row.length >= kMinimumLength && inverseMass > 0 &&
          row.length < row.restLength && noWarmStart(row, warmStart)))
        return false;
    startResolvedThread(row, h);
    if (row.lastStretch > 0)
        return false;
    row.discreteGradient = false;  // squared is below its band
    row.deferred = true;
    return true;
}

// prepareSpringRow(); mayDefer: a resolved thread slack at both levels and without a warm start
// is left `deferred` after its levels (spring_row.h), its Jacobians those of its start line.
void prepareRow(const SolverBody& a, const SolverBody& b, SpringRow& row, Real h, bool mayDefer,
                bool warmStart) {
    row.knownImpulse = 0;
    row.deferred = false;
    // Only threads past Fox-Goodwin's range, and not the stiffest, take the discrete gradient;
    // undamped ones within it the three-level scheme's energy-conserving form.
    const bool undampedThread =
        row.discreteGradient && row.tensionOnly && row.damping == 0 && row.spectralRadius >= 1;
    if (mayDefer && undampedThread && deferCentred(a, b, row, h, warmStart))
        return;
    row.angularA = row.rA.cross(row.direction);
    row.angularB = row.rB.cross(row.direction);
    row.angularImpulseA = a.inverseInertia * row.angularA;
    row.angularImpulseB = b.inverseInertia * row.angularB;
    const Real inverseMass = jacobianInverseMass(a, b, row);
    const Real squared = h * h * row.stiffness * inverseMass;  // (omega h)^2
    row.discreteGradient = row.discreteGradient && squared >= kDiscreteGradientFrom &&
                           squared <= kDiscreteGradientUpTo;
    row.levelGradient = false;
    if (undampedThread && squared < kDiscreteGradientFrom && row.length >= kMinimumLength &&
        inverseMass > 0) {
        startResolvedThread(row, h);
        if (mayDefer && row.length < row.restLength && !(row.lastStretch > 0) &&
            noWarmStart(row, warmStart)) {
            row.deferred = true;
            return;
        }
        lineariseResolvedThread(a, b, row, h, squared);
        return;
    }
    if (row.discreteGradient) {
        // The last step's half comes again; this step's is linearised at constant velocity.
        row.knownImpulse = row.direction.dot(row.carried);
        row.span = row.length * row.direction;
        Vec3 endSpan =
            row.span + h * (row.startVelocity + (a.inverseMass + b.inverseMass) * row.carried);
        const Real endLength = endSpan.norm();
        if (!(row.length >= kMinimumLength && inverseMass > 0 && endLength > kMinimumLength)) {
            row.mass = 0;
            return;
        }
        const Real c0 = row.length - row.restLength;
        const Real c1 = threadStretchAlone(row.stiffness, c0, endLength - row.restLength,
                                           0.5 * h * h * inverseMass);
        lineariseThreadRow(a, b, row, h, endSpan * ((row.restLength + c1) / endLength));
        return;
    }
    const SchemeWeights w = row.catching ? catchWeights(row.spectralRadius, squared)
                                         : schemeWeights(row.spectralRadius, squared);
    const Real next = w.next, last = w.last, rateNext = w.rateNext;
    const Real resistance = h * row.stiffness * next + row.damping * rateNext;  // r (N s/m)
    const bool usable = row.length >= kMinimumLength && inverseMass > 0;
    const Real startRate = row.direction.dot(row.startVelocity);  // J v0
    const Real stretch = row.length - row.restLength;
    const bool split = row.tensionOnly && row.spectralRadius > 0;
    if (split && usable) {
        // The known levels with the thread's own law, k max(C, 0) (see above).
        const Real lastStretch = stretch - h * startRate;
        row.knownImpulse = -h * row.stiffness *
                           ((1 - next - last) * std::max<Real>(stretch, 0) +
                            last * std::max<Real>(lastStretch, 0));
    }
    if (resistance <= 0 || !usable) {
        row.mass = 0;
        return;
    }
    row.softness = 1 / (h * resistance);
    row.mass = 1 / (inverseMass + row.softness);
    if (split) {
        row.bias = (row.stiffness * next * stretch + row.damping * (1 - rateNext) * startRate) /
                   resistance;
        return;
    }
    const Real lastShare = h * row.stiffness * last - row.damping * (1 - rateNext);
    row.bias = (row.stiffness * stretch - lastShare * startRate) / resistance;
}

// Whether a zero impulse applied to the body leaves every bit of its velocity: v - (+-0) is v
// but for v = -0, which may become +0. -0 is the one value whose bits are the sign bit alone:
// one integer compare a component (comparing and testing the sign was a fifth of a net's
// preparation, two bodies a deferred row).
bool noNegativeZero(const SolverBody& body) {
    constexpr std::uint64_t kNegativeZero = std::uint64_t{1} << 63;
    const auto negativeZero = [](Real v) {
        return std::bit_cast<std::uint64_t>(v) == kNegativeZero;
    };
    bool none = true;
    for (int k = 0; k < 3; ++k) {
        none =
            none && !negativeZero(body.linearVelocity[k]) && !negativeZero(body.angularVelocity[k]);
    }
    return none;
}

}  // namespace

void prepareSpringRow(const SolverBody& a, const SolverBody& b, SpringRow& row, Real h) {
    prepareRow(a, b, row, h, false, false);
}

void finishSpringRow(const SolverBody& a, const SolverBody& b, SpringRow& row, Real h) {
    row.deferred = false;
    // The start line's Jacobians (deferCentred() left them out): the same (omega h)^2 as
    // prepareRow()'s, bit for bit.
    const Real squared = h * h * row.stiffness * setJacobians(a, b, row);
    lineariseResolvedThread(a, b, row, h, squared);
    // Its impulse is 0 whatever its mass (prepareSpringRows).
}

void finishSpringRows(std::span<const SolverBody> bodies, std::span<SpringRow> rows, Real h) {
    for (SpringRow& row : rows) {
        if (row.deferred)
            finishSpringRow(bodies[row.bodyA], bodies[row.bodyB], row, h);
    }
}

int discreteGradientSubsteps(Real squared) {
    if (!(squared >= kDiscreteGradientFrom && squared <= kDiscreteGradientUpTo))
        return 0;
    return std::max(1, static_cast<int>(std::sqrt(squared / kDampedFrom)));
}

Real discreteGradientBandStart() {
    return kDiscreteGradientFrom;
}

bool springRowUnresolved(const SpringRow& row, Real h) {
    if (row.mass <= 0)
        return false;
    const Real inverseMass = 1 / row.mass - row.softness;
    return h * h * row.stiffness * inverseMass >= kDampedFrom;
}

void prepareSpringRows(std::span<SolverBody> bodies, std::span<SpringRow> rows, Real h,
                       bool warmStart, bool deferSlackThreads) {
    for (SpringRow& row : rows) {
        SolverBody& a = bodies[row.bodyA];
        SolverBody& b = bodies[row.bodyB];
        prepareRow(a, b, row, h, deferSlackThreads, warmStart);
        // Deferred only where its warm start is +0 and applying it changes no bit: then skipping
        // it is the same step.
        if (row.deferred) {
            row.impulse = 0;
            if (noNegativeZero(a) && noNegativeZero(b))
                continue;
            finishSpringRow(a, b, row, h);
        }
        row.impulse -= row.knownImpulse;  // the warm start is the whole step's impulse
        if (row.mass == 0 || !warmStart || (row.tensionOnly && row.impulse > 0))
            row.impulse = 0;
        if (row.discreteGradient) {
            applySpringImpulse(a, b, row, row.impulse);
            applyCarriedImpulse(a, b, row);
        } else {
            applySpringImpulse(a, b, row, row.impulse + row.knownImpulse);
        }
    }
}

Real solveSpringRows(std::span<SolverBody> bodies, std::span<SpringRow> rows, Real relaxation) {
    Real largestChange = 0;
    for (SpringRow& row : rows) {
        if (row.mass == 0)
            continue;
        SolverBody& a = bodies[row.bodyA];
        SolverBody& b = bodies[row.bodyB];
        const Real residual = springRowSpeed(a, b, row) + row.bias + row.softness * row.impulse;
        Real next = row.impulse - relaxation * row.mass * residual;
        if (row.tensionOnly)
            next = std::min<Real>(next, 0);
        const Real delta = next - row.impulse;
        applySpringImpulse(a, b, row, delta);
        row.impulse = next;
        largestChange = std::max(largestChange, std::abs(delta) / row.mass);
    }
    return largestChange;
}

}  // namespace tumble
