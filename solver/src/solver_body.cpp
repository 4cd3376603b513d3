#include "tumble/solver/solver_body.h"

namespace tumble {

Real effectiveMass(const SolverBody& a, const Vec3& rA, const SolverBody& b, const Vec3& rB,
                   const Vec3& n) {
    const Vec3 rnA = rA.cross(n);
    const Vec3 rnB = rB.cross(n);
    const Real inverse = a.inverseMass + b.inverseMass + rnA.dot(a.inverseInertia * rnA) +
                         rnB.dot(b.inverseInertia * rnB);
    return inverse > 0 ? 1 / inverse : 0;
}

}  // namespace tumble
