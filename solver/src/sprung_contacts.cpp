// The contacts of sprung bodies (net nodes) and the thread contacts, solved together with the
// spring block after the relax sweeps.
//
// Why. runSweeps ends on the springs: ending on the contacts left the stiff rows acting on stale
// velocities and pumped a net resting across gaps into a vibration. But contacts and springs
// meet only by block Gauss-Seidel, which converges slowly where a node is held between a stiff
// net and a contact, so that last spring solve undoes part of the contacts' work: a pile under a
// net ended each step with nodes approaching their contacts at 1.5-27 mm/s (10 + 10 sweeps), the
// next step's push-out (on the pseudo-velocities, which the threads do not answer) took them back
// out, and the threads' elastic energy grew at rest: 62.9 -> 66.3 J over 6-10 s, the total
// energy with it (bench/README.md, "Energy created at rest under a net").
//
// How. With the active set of the step's spring solves kept, the block's response is linear: a
// normal impulse x_j at contact row j changes the bodies' velocities by M^-1 c_j x_j and the
// next spring solve answers that with -M^-1 J_s' K^-1 J_s M^-1 c_j x_j. So the rows' normal
// speeds after "impulses, then springs" are v_n + W x, W = C' (M^-1 - M^-1 J_s' K^-1 J_s M^-1) C,
// symmetric positive semidefinite: the contacts' Schur complement over the springs. Its columns
// take one solve with the block's factor each (SpringBlockSolver::respond). Projected
// Gauss-Seidel on this small dense LCP (lambda + x >= 0, v_n + W x >= target, complementary)
// converges the two blocks together; the impulses are applied and the springs solved once more,
// which lands on v_n + W x. The step still ends on the springs, and the change reaches the
// positions too (they advance with the relaxed velocity plus the pseudo-velocity): keeping the
// positions on the biased sweeps' velocity instead left 0.1-0.5 % growth.
//
// Friction is left as the sweeps left it; the other contacts (the rain's) see the change of the
// sprung rows' other bodies only.

#include <algorithm>
#include <cmath>

#include "normal_block.h"
#include "tumble/solver/constraint_solver.h"

namespace tumble {
namespace {

// The sprung rows' complementarity residual (m/s) above which they are settled. A step ending
// with a node approaching its contact at v moves it h v in, which the next push-out takes back
// against the threads: at 1 mm/s (the rest tests' speed) the pile under a net gains 0.011 % of
// its threads' energy over 6 s (anchors on; 0.003 % at 1e-4 m/s and at 1e-9) for 5-9 % more
// time than without the settle (40 % at 1e-4, 80 % at 1e-9): W's columns cost a spring solve
// each, and the pile's nodes hold ~120 contact points at rest.
constexpr Real kTrigger = 1e-3;
// PGS sweeps over W at most, and the change of v_n (m/s) at which they stop: W is small and
// dense; 10 sweeps stopped the growth as well as 100.
constexpr int kSweeps = 100;
constexpr Real kStop = 1e-9;
// The most rows settled in one step: W is m x m and costs m spring solves, so a large net
// lying on the ground (1,600 node contacts for a 40 x 40 net) would take 1,600 solves and 20 MB
// a step. Beyond it the rows furthest from complementarity are settled, the rest held at the
// sweeps' impulses; the next step takes the next worst.
constexpr std::size_t kMostRows = 128;

// A segment row's point velocity relative to S along its normal (segment_contact_row.h).
Real segmentSpeed(std::span<const SolverBody> bodies, const SegmentContactRow& row) {
    const Vec3 v = (1 - row.t) * bodies[row.bodyA].velocityAt(row.rA) +
                   row.t * bodies[row.bodyB].velocityAt(row.rB) -
                   bodies[row.bodyS].velocityAt(row.rS);
    return v.dot(row.normal);
}

void applySegmentNormal(std::span<SolverBody> bodies, const SegmentContactRow& row, Real lambda) {
    const Vec3 p = lambda * row.normal;
    applyImpulse(bodies[row.bodyA], (1 - row.t) * p, row.rA);
    applyImpulse(bodies[row.bodyB], row.t * p, row.rB);
    applyImpulse(bodies[row.bodyS], -p, row.rS);
}

void atRest(SolverBody& body) {
    body.linearVelocity = Vec3::Zero();
    body.angularVelocity = Vec3::Zero();
}

}  // namespace

template <class F>
void ConstraintSolver::forEachSprungBody(std::span<const ContactConstraint> constraints,
                                         const SprungPoint& point, F&& f) const {
    if (point.segment) {
        const SegmentContactRow& row = segments_[point.index];
        f(row.bodyA);
        f(row.bodyB);
        f(row.bodyS);
        return;
    }
    f(constraints[point.index].bodyA);
    f(constraints[point.index].bodyB);
}

void ConstraintSolver::keepWorstSprung() {
    // The kMostRows largest residuals, ties to the earlier row, then back in row order: the same
    // rows in the same order on every machine.
    sprungOrder_.resize(sprungPoints_.size());
    for (std::size_t k = 0; k < sprungOrder_.size(); ++k)
        sprungOrder_[k] = static_cast<std::uint32_t>(k);
    const auto worse = [&](std::uint32_t i, std::uint32_t j) {
        return sprungResidual_[i] > sprungResidual_[j] ||
               (sprungResidual_[i] == sprungResidual_[j] && i < j);
    };
    std::nth_element(sprungOrder_.begin(), sprungOrder_.begin() + kMostRows, sprungOrder_.end(),
                     worse);
    sprungOrder_.resize(kMostRows);
    std::sort(sprungOrder_.begin(), sprungOrder_.end());
    for (std::size_t k = 0; k < kMostRows; ++k) {
        sprungPoints_[k] = sprungPoints_[sprungOrder_[k]];
        sprungGap_[k] = sprungGap_[sprungOrder_[k]];
    }
    sprungPoints_.resize(kMostRows);
    sprungGap_.resize(kMostRows);
}

Real ConstraintSolver::sprungSpeed(std::span<const SolverBody> bodies,
                                   std::span<const ContactConstraint> constraints,
                                   const SprungPoint& point) const {
    if (point.segment)
        return segmentSpeed(bodies, segments_[point.index]);
    const ContactConstraint& c = constraints[point.index];
    return normalSpeed(bodies[c.bodyA], bodies[c.bodyB], c.normal, c.points[point.point]);
}

void ConstraintSolver::applySprung(std::span<SolverBody> bodies,
                                   std::span<const ContactConstraint> constraints,
                                   const SprungPoint& point, Real lambda) const {
    if (point.segment) {
        applySegmentNormal(bodies, segments_[point.index], lambda);
        return;
    }
    const ContactConstraint& c = constraints[point.index];
    applyNormal(bodies[c.bodyA], bodies[c.bodyB], c.normal, c.points[point.point], lambda);
}

void ConstraintSolver::settleSprungContacts(std::span<SolverBody> bodies,
                                            std::span<ContactConstraint> constraints,
                                            std::span<SpringRow> springs,
                                            const SolverSettings& settings, Real inverseH) {
    sprungPoints_.clear();
    sprungGap_.clear();
    // Only rows that push or would be violated can change.
    // Complementarity of each in velocity units, min(lambda / mass, gap), as the contacts'
    // residual.
    sprungResidual_.clear();
    Real worst = 0;
    auto take = [&](const SprungPoint& point, Real impulse, Real mass, Real target) {
        const Real gap = sprungSpeed(bodies, constraints, point) - target;
        if (impulse > 0 || gap < 0) {
            sprungPoints_.push_back(point);
            sprungGap_.push_back(gap);
            const Real residual = std::abs(std::min(impulse / mass, gap));
            sprungResidual_.push_back(residual);
            worst = std::max(worst, residual);
        }
    };
    for (std::size_t j = 0; j < constraints.size(); ++j) {
        const ContactConstraint& c = constraints[j];
        if (c.pushOut)
            continue;
        for (int i = 0; i < c.pointCount; ++i) {
            const ContactConstraintPoint& p = c.points[i];
            if (p.normalMass > 0)
                take({static_cast<std::uint32_t>(j), i, false}, p.normalImpulse, p.normalMass,
                     normalTarget(p, 0, settings.slop, inverseH));
        }
    }
    // The thread contacts hold the net as its nodes' do (their push-out is in the position pass
    // too, segmentPositions_): left out, correcting the nodes' contacts alone let a net hanging
    // over a thin wall's edge slip down and be pushed back up by its threads' push-out (a 5.6
    // mJ kick, ThreadRestThinWall).
    if (segmentPositions_) {
        for (std::size_t j = 0; j < segments_.size(); ++j) {
            const SegmentContactRow& row = segments_[j];
            if (row.normalMass > 0)
                take({static_cast<std::uint32_t>(j), 0, true}, row.normalImpulse, row.normalMass,
                     row.separation > 0 ? -row.separation * inverseH : 0);
        }
    }
    // Nothing to do where the rows are complementary already.
    if (sprungPoints_.empty() || worst <= kTrigger)
        return;
    if (sprungPoints_.size() > kMostRows)
        keepWorstSprung();
    const std::size_t m = sprungPoints_.size();
    auto impulse = [&](const SprungPoint& point) -> Real& {
        return point.segment ? segments_[point.index].normalImpulse
                             : constraints[point.index].points[point.point].normalImpulse;
    };

    // W column by column: a unit impulse on a copy of the bodies at rest, the springs' answer.
    // Only the column's bodies and the springs' are set to rest again, not the whole scene.
    response_.assign(bodies.begin(), bodies.end());
    for (SolverBody& b : response_)
        atRest(b);
    sprungMatrix_.assign(m * m, 0);
    for (std::size_t j = 0; j < m; ++j) {
        applySprung(response_, constraints, sprungPoints_[j], 1);
        springBlock_.respond(response_);
        for (std::size_t k = 0; k < m; ++k)
            sprungMatrix_[j * m + k] = sprungSpeed(response_, constraints, sprungPoints_[k]);
        forEachSprungBody(constraints, sprungPoints_[j],
                          [&](std::uint32_t body) { atRest(response_[body]); });
        for (const SpringRow& row : springs) {
            atRest(response_[row.bodyA]);
            atRest(response_[row.bodyB]);
        }
    }

    // Projected Gauss-Seidel on the dense LCP; sprungGap_ follows v_n + W x - target.
    sprungDelta_.assign(m, 0);
    for (int sweep = 0; sweep < kSweeps; ++sweep) {
        Real largest = 0;
        for (std::size_t k = 0; k < m; ++k) {
            const Real diagonal = sprungMatrix_[k * m + k];
            if (!(diagonal > 0))
                continue;
            const Real old = sprungDelta_[k];
            const Real next = std::max(-impulse(sprungPoints_[k]), old - sprungGap_[k] / diagonal);
            const Real change = next - old;
            if (change == 0)
                continue;
            sprungDelta_[k] = next;
            const Real* column = &sprungMatrix_[k * m];  // W is symmetric: column k is row k
            for (std::size_t i = 0; i < m; ++i)
                sprungGap_[i] += column[i] * change;
            largest = std::max(largest, std::abs(change) * diagonal);
        }
        if (largest <= kStop)
            break;
    }

    for (std::size_t k = 0; k < m; ++k) {
        applySprung(bodies, constraints, sprungPoints_[k], sprungDelta_[k]);
        impulse(sprungPoints_[k]) += sprungDelta_[k];
    }
    // The springs' answer, without the slack threads' Gauss-Seidel, which W leaves out: a thread
    // the impulses stretch enters the active set next step.
    springBlock_.solveActive(bodies, springs);
}

}  // namespace tumble
