#include "tumble/solver/spring_row.h"

#include <algorithm>
#include <cmath>

namespace tumble {
namespace {

// Anchors closer than this have no line to pull along (m).
constexpr Real kMinimumLength = 1e-12;

}  // namespace

void prepareSpringRow(const SolverBody& a, const SolverBody& b, SpringRow& row, Real h) {
    row.angularA = row.rA.cross(row.direction);
    row.angularB = row.rB.cross(row.direction);
    row.angularImpulseA = a.inverseInertia * row.angularA;
    row.angularImpulseB = b.inverseInertia * row.angularB;
    const Real inverseMass = a.inverseMass + b.inverseMass + row.angularA.dot(row.angularImpulseA) +
                             row.angularB.dot(row.angularImpulseB);
    // The weights of the three-level scheme (spring_row.h). rho falls as 1 / (omega h)^2 once
    // the step does not resolve the element: undamped, its unresolved mode would swing the
    // positions by ~omega h / 2 times its amplitude.
    const Real squared = h * h * row.stiffness * inverseMass;  // (omega h)^2 of the element
    const Real rho = row.spectralRadius / std::max<Real>(squared, 1);
    const Real next = 1 / ((1 + rho) * (1 + rho));                              // w1
    const Real last = rho * rho * next;                                         // w_1
    const Real rateNext = 1 / (1 + rho);                                        // a
    const Real resistance = h * row.stiffness * next + row.damping * rateNext;  // r (N s/m)
    if (resistance <= 0 || row.length < kMinimumLength || inverseMass <= 0) {
        row.mass = 0;
        return;
    }
    row.softness = 1 / (h * resistance);
    row.mass = 1 / (inverseMass + row.softness);
    const Real startRate = rho > 0 ? row.direction.dot(row.startVelocity) : Real(0);  // J v0
    const Real lastShare = h * row.stiffness * last - row.damping * (1 - rateNext);
    row.bias = (row.stiffness * (row.length - row.restLength) - lastShare * startRate) / resistance;
}

void prepareSpringRows(std::span<SolverBody> bodies, std::span<SpringRow> rows, Real h,
                       bool warmStart) {
    for (SpringRow& row : rows) {
        SolverBody& a = bodies[row.bodyA];
        SolverBody& b = bodies[row.bodyB];
        prepareSpringRow(a, b, row, h);
        if (row.mass == 0 || !warmStart || (row.tensionOnly && row.impulse > 0))
            row.impulse = 0;
        applySpringImpulse(a, b, row, row.impulse);
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
