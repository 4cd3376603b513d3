#include "tumble/solver/spring_row.h"

#include <algorithm>
#include <cmath>

namespace tumble {
namespace {

// Anchors closer than this have no line to pull along (m).
constexpr Real kMinimumLength = 1e-12;

// (omega h)^2 of an element up to which the symmetric weights hold the phase to fourth order
// (Fox-Goodwin, beta = 1/12): stable to (omega h)^2 = 6, and a node's highest mode is about
// twice its element's (omega h)^2.
constexpr Real kFourthOrderUpTo = 1.5;
// (omega h)^2 from which the unresolved element is damped: rho = this / (omega h)^2.
constexpr Real kDampedFrom = 4;

struct SchemeWeights {
    Real next;      // w1
    Real last;      // w_1
    Real rateNext;  // a
};

// The three-level weights (spring_row.h) for an element with (omega h)^2 = squared.
SchemeWeights schemeWeights(Real spectralRadius, Real squared) {
    if (spectralRadius >= 1 && squared < kDampedFrom) {
        // Symmetric: no numerical damping. beta rises to keep the highest mode stable.
        const Real beta = squared <= kFourthOrderUpTo ? Real(1) / 12 : Real(0.25) - 0.25 / squared;
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

}  // namespace

void prepareSpringRow(const SolverBody& a, const SolverBody& b, SpringRow& row, Real h) {
    row.knownImpulse = 0;
    row.angularA = row.rA.cross(row.direction);
    row.angularB = row.rB.cross(row.direction);
    row.angularImpulseA = a.inverseInertia * row.angularA;
    row.angularImpulseB = b.inverseInertia * row.angularB;
    const Real inverseMass = a.inverseMass + b.inverseMass + row.angularA.dot(row.angularImpulseA) +
                             row.angularB.dot(row.angularImpulseB);
    const Real squared = h * h * row.stiffness * inverseMass;  // (omega h)^2
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

bool springRowUnresolved(const SpringRow& row, Real h) {
    if (row.mass <= 0)
        return false;
    const Real inverseMass = 1 / row.mass - row.softness;
    return h * h * row.stiffness * inverseMass >= kDampedFrom;
}

void prepareSpringRows(std::span<SolverBody> bodies, std::span<SpringRow> rows, Real h,
                       bool warmStart) {
    for (SpringRow& row : rows) {
        SolverBody& a = bodies[row.bodyA];
        SolverBody& b = bodies[row.bodyB];
        prepareSpringRow(a, b, row, h);
        row.impulse -= row.knownImpulse;  // the warm start is the whole step's impulse
        if (row.mass == 0 || !warmStart || (row.tensionOnly && row.impulse > 0))
            row.impulse = 0;
        applySpringImpulse(a, b, row, row.impulse + row.knownImpulse);
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
