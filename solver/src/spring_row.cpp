#include "tumble/solver/spring_row.h"

#include <algorithm>
#include <cmath>

namespace tumble {
namespace {

// Anchors closer than this have no line to pull along (m).
constexpr Real kMinimumLength = 1e-12;

}  // namespace

void prepareSpringRows(std::span<SolverBody> bodies, std::span<SpringRow> rows, Real h,
                       bool warmStart) {
    for (SpringRow& row : rows) {
        SolverBody& a = bodies[row.bodyA];
        SolverBody& b = bodies[row.bodyB];
        const Real resistance = row.damping + h * row.stiffness;  // c + h k (N s/m)
        row.angularA = row.rA.cross(row.direction);
        row.angularB = row.rB.cross(row.direction);
        row.angularImpulseA = a.inverseInertia * row.angularA;
        row.angularImpulseB = b.inverseInertia * row.angularB;
        const Real inverseMass = a.inverseMass + b.inverseMass +
                                 row.angularA.dot(row.angularImpulseA) +
                                 row.angularB.dot(row.angularImpulseB);
        if (resistance <= 0 || row.length < kMinimumLength || inverseMass <= 0) {
            row.mass = 0;
            row.impulse = 0;
            continue;
        }
        row.softness = 1 / (h * resistance);
        row.mass = 1 / (inverseMass + row.softness);
        row.bias = (row.stiffness / resistance) * (row.length - row.restLength);
        if (!warmStart || (row.tensionOnly && row.impulse > 0))
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
