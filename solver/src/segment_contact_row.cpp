#include "tumble/solver/segment_contact_row.h"

#include <algorithm>
#include <cmath>

#include "tumble/solver/contact_solver.h"

namespace tumble {
namespace {

// Velocity of the segment's point relative to S's (m/s).
Vec3 relativeVelocity(std::span<const SolverBody> bodies, const SegmentContactRow& row) {
    return (1 - row.t) * bodies[row.bodyA].velocityAt(row.rA) +
           row.t * bodies[row.bodyB].velocityAt(row.rB) - bodies[row.bodyS].velocityAt(row.rS);
}

// The same for a row whose S is fixed (SegmentContactRow::fixedS): S's velocity at the point
// is +0, and x - (+0) = x bitwise, so leaving it out changes no result (a third of the sweeps'
// reads and writes on a net over static shapes).
Vec3 nodesVelocity(std::span<const SolverBody> bodies, const SegmentContactRow& row) {
    return (1 - row.t) * bodies[row.bodyA].velocityAt(row.rA) +
           row.t * bodies[row.bodyB].velocityAt(row.rB);
}

// +0 exactly (not -0): what an untouched fixed body's velocity stays under any impulse.
bool positiveZero(const Vec3& v) {
    return (v.array() == 0).all() && !std::signbit(v.x()) && !std::signbit(v.y()) &&
           !std::signbit(v.z());
}

// Nothing moves S: no inverse mass or inertia, at rest. An impulse p adds 0 p = +-0 to its +0
// velocity components, which leaves them +0, so it stays at rest through every sweep.
bool fixedBody(const SolverBody& body) {
    return body.inverseMass == 0 && body.inverseInertia.isZero(0) &&
           positiveZero(body.linearVelocity) && positiveZero(body.angularVelocity);
}

// Velocity change along d of a body's point at r per unit impulse there along d (1/kg).
Real compliance(const SolverBody& body, const Vec3& r, const Vec3& d) {
    const Vec3 arm = r.cross(d);
    return body.inverseMass + arm.dot(body.inverseInertia * arm);
}

// K of the row along unit d: wA^2 kA + wB^2 kB + kS; its inverse, 0 if nothing can move.
Real rowMass(std::span<const SolverBody> bodies, const SegmentContactRow& row, const Vec3& d) {
    const Real k = (1 - row.t) * (1 - row.t) * compliance(bodies[row.bodyA], row.rA, d) +
                   row.t * row.t * compliance(bodies[row.bodyB], row.rB, d) +
                   compliance(bodies[row.bodyS], row.rS, d);
    return k > 0 ? 1 / k : 0;
}

// The impulse p (N s) on the segment's point, split between its nodes; -p on S.
void applySegmentImpulse(std::span<SolverBody> bodies, const SegmentContactRow& row,
                         const Vec3& p) {
    applyImpulse(bodies[row.bodyA], (1 - row.t) * p, row.rA);
    applyImpulse(bodies[row.bodyB], row.t * p, row.rB);
    applyImpulse(bodies[row.bodyS], -p, row.rS);
}

// relativeVelocity and applySegmentImpulse on the velocity sweeps' bodies, for which
// prepareSegmentContacts set fixedS: a fixed S is left out (its velocity stays +0 either way).
Vec3 sweepVelocity(std::span<const SolverBody> bodies, const SegmentContactRow& row) {
    return row.fixedS ? nodesVelocity(bodies, row) : relativeVelocity(bodies, row);
}

void sweepImpulse(std::span<SolverBody> bodies, const SegmentContactRow& row, const Vec3& p) {
    applyImpulse(bodies[row.bodyA], (1 - row.t) * p, row.rA);
    applyImpulse(bodies[row.bodyB], row.t * p, row.rB);
    if (!row.fixedS)
        applyImpulse(bodies[row.bodyS], -p, row.rS);
}

// (a, b) clamped to the disc of radius `limit` (+0 or above: mu >= 0 times a max(0, ...)
// impulse), bitwise as by std::hypot, which was 4 % of a dustbin-mesh step and is now asked only
// where in doubt. Strictly inside when the squares say so with room to spare: their rounding (a
// few ulp) is far inside the 1e-9 margin, and limit^2 above 1e-290 keeps them off the
// subnormals. On a zero disc (most rows hold no normal impulse) hypot's size only decides
// whether to scale, by 0 / size = +0: when it is > 0, i.e. either is infinite or neither is NaN
// and one is non-zero.
void clampToDisc(std::array<Real, 2>& next, Real limit) {
    const Real a = next[0], b = next[1];
    if (limit == 0) {
        if (std::isinf(a) || std::isinf(b) ||
            (!std::isnan(a) && !std::isnan(b) && (a != 0 || b != 0)))
            next = {a * Real(0), b * Real(0)};
        return;
    }
    const Real squared = limit * limit;
    if (squared > 1e-290 && a * a + b * b < squared * (1 - 1e-9))
        return;
    const Real size = std::hypot(a, b);
    if (size > limit) {
        const Real scale = size > 0 ? limit / size : 0;
        next = {a * scale, b * scale};
    }
}

// The fastest push-out of a row's depth (m/s). The position pass moved the row's nodes without
// their threads (no spring row was in it; now they pull in it): each step's push stretched the
// threads by up to its h x speed, which the next spring solve turned into velocity. At factor / h,
// a thread 5 - 7 cm deep in dustbin-mesh's rim was pushed 1 - 2 cm in a step (1 J in one thread)
// and the rim's rows at a few mm kept the skirt on the wall moving: median node speed 18.6 mm/s
// after 2 s, 1.0 at 0.1 m/s (0.9 at 0.02, 4.9 at 0.15, 18 at 0.6). The rows' velocity sweeps
// still stop any deeper approach.
constexpr Real kMaxPushOutSpeed = 0.1;

}  // namespace

void prepareSegmentContacts(std::span<SolverBody> bodies, std::span<SegmentContactRow> rows,
                            bool warmStart) {
    for (SegmentContactRow& row : rows) {
        row.fixedS = fixedBody(bodies[row.bodyS]);
        row.tangents = frictionBasis(row.normal);
        row.normalMass = rowMass(bodies, row, row.normal);
        row.tangentMass = {rowMass(bodies, row, row.tangents[0]),
                           rowMass(bodies, row, row.tangents[1])};
        if (!warmStart) {
            row.normalImpulse = 0;
            row.tangentImpulse = {0, 0};
            continue;
        }
        applySegmentImpulse(bodies, row,
                            row.normalImpulse * row.normal +
                                row.tangentImpulse[0] * row.tangents[0] +
                                row.tangentImpulse[1] * row.tangents[1]);
    }
}

void solveSegmentPositions(std::span<SolverBody> bodies, std::span<SegmentContactRow> rows,
                           std::span<const SpringRow> springs, std::vector<ThreadPull>& pulls,
                           Real factor, Real inverseH, Real slop, int iterations) {
    bool pushing = false;
    for (SegmentContactRow& row : rows) {
        row.positionImpulse = 0;
        pushing = pushing || (row.pushOut && row.separation < -slop);
    }
    if (!pushing)
        return;
    // The threads' rows: the pass may add no stretching to a taut thread and take a slack one
    // only up to its rest length, (L0 - L) / h over the pass's speed on entry. Without them a
    // push lifted a thin wall's nodes 0.8 mm off the taut threads hanging below them, +12 - 42 mJ
    // of spring energy in one step (ThreadRestThinWall). On the pass's own addition only: the
    // nodes' contacts' push-out (SprungPushOut, before) carried by the threads put a pile's
    // spheres under a net in motion (SprungPushOut.SpheresInAPileUnderANetComeToRest).
    pulls.clear();
    for (std::size_t i = 0; i < springs.size(); ++i) {
        const SpringRow& spring = springs[i];
        if (!spring.tensionOnly)
            continue;
        const SolverBody& a = bodies[spring.bodyA];
        const SolverBody& b = bodies[spring.bodyB];
        const Real inverseMass = a.inverseMass + b.inverseMass +
                                 spring.angularA.dot(spring.angularImpulseA) +
                                 spring.angularB.dot(spring.angularImpulseB);
        if (inverseMass <= 0)
            continue;
        pulls.push_back({static_cast<std::uint32_t>(i),
                         springRowSpeed(a, b, spring) +
                             std::max<Real>(0, spring.restLength - spring.length) * inverseH,
                         1 / inverseMass, 0});
    }
    for (int sweep = 0; sweep < iterations; ++sweep) {
        for (SegmentContactRow& row : rows) {
            if (!row.pushOut || row.separation >= -slop)
                continue;
            const Real target =
                std::min(factor * inverseH * (-row.separation - slop), kMaxPushOutSpeed);
            const Real speed = relativeVelocity(bodies, row).dot(row.normal);
            const Real old = row.positionImpulse;
            row.positionImpulse = std::max<Real>(0, old - row.normalMass * (speed - target));
            applySegmentImpulse(bodies, row, (row.positionImpulse - old) * row.normal);
        }
        // Forwards and backwards in turn: a pull reaches down a hanging chain of threads in
        // either order of its nodes (at (0 cm, 8 rows) 0.35 mJ against 6.7 forwards only).
        for (std::size_t k = 0; k < pulls.size(); ++k) {
            ThreadPull& pull = pulls[sweep % 2 == 1 ? pulls.size() - 1 - k : k];
            const SpringRow& spring = springs[pull.spring];
            SolverBody& a = bodies[spring.bodyA];
            SolverBody& b = bodies[spring.bodyB];
            const Real old = pull.impulse;
            pull.impulse =
                std::min<Real>(0, old - pull.mass * (springRowSpeed(a, b, spring) - pull.target));
            applySpringImpulse(a, b, spring, pull.impulse - old);
        }
    }
}

Real solveSegmentContacts(std::span<SolverBody> bodies, std::span<SegmentContactRow> rows,
                          Real inverseH, Real bias, Real slop) {
    Real largestChange = 0;
    for (SegmentContactRow& row : rows) {
        // The normal first, so friction is clamped by this sweep's support.
        const Real push = row.separation > 0 || !row.pushOut
                              ? 0
                              : bias * inverseH * std::max<Real>(0, -row.separation - slop);
        const Real target = row.separation > 0 ? -row.separation * inverseH : push;
        const Real speed = sweepVelocity(bodies, row).dot(row.normal);
        const Real old = row.normalImpulse;
        row.normalImpulse = std::max<Real>(0, old - row.normalMass * (speed - target));
        sweepImpulse(bodies, row, (row.normalImpulse - old) * row.normal);
        if (row.normalMass > 0)
            largestChange =
                std::max(largestChange, std::abs(row.normalImpulse - old) / row.normalMass);
        if (row.friction == 0)
            continue;
        const Vec3 slip = sweepVelocity(bodies, row);
        std::array<Real, 2> next{};
        for (int k = 0; k < 2; ++k)
            next[k] = row.tangentImpulse[k] - row.tangentMass[k] * slip.dot(row.tangents[k]);
        const Real limit = row.friction * row.normalImpulse;
        clampToDisc(next, limit);
        sweepImpulse(bodies, row,
                     (next[0] - row.tangentImpulse[0]) * row.tangents[0] +
                         (next[1] - row.tangentImpulse[1]) * row.tangents[1]);
        for (int k = 0; k < 2; ++k) {
            if (row.tangentMass[k] > 0)
                largestChange = std::max(
                    largestChange, std::abs(next[k] - row.tangentImpulse[k]) / row.tangentMass[k]);
        }
        row.tangentImpulse = next;
    }
    return largestChange;
}

}  // namespace tumble
