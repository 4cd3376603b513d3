#pragma once
/// The per-manifold pieces of the contact sweep that ContactSolver, SweepRows and ContactRows
/// share (contact_solver.cpp holds their derivations).

#include <Eigen/Core>
#include <algorithm>
#include <cmath>

#include "normal_block.h"
#include "tumble/solver/contact_solver.h"

namespace tumble {

/// solveDisc's sliding case (contact_solver.cpp): the answer on the rim, from b = K old - vt.
Eigen::Matrix<Real, 2, 1> solveDiscRim(const DiscBlock& k, const Eigen::Matrix<Real, 2, 1>& b,
                                       Real radius);

/// The coupled friction update of one point: the impulse in the disc |lambda| <= radius that
/// removes as much of the slip vt as the block k allows, from the impulse `old`. Inline: the
/// sticking case, most points of a resting stack, is a few operations on the sweep's critical
/// path, which a call (its arguments through memory) lengthened.
inline Eigen::Matrix<Real, 2, 1> solveDisc(const DiscBlock& k, const Eigen::Matrix<Real, 2, 1>& old,
                                           const Eigen::Matrix<Real, 2, 1>& vt, Real radius) {
    using Vec2 = Eigen::Matrix<Real, 2, 1>;
    if (radius <= 0)
        return Vec2::Zero();
    const Vec2 b = k.block * old - vt;
    const Vec2 free = k.inverse * b;
    if (free.squaredNorm() <= radius * radius)
        return free;
    return solveDiscRim(k, b, radius);
}

/// One point's coupled friction update relaxed by omega: the new impulse `next` and its change
/// `delta` from `old`. When the free answer old - K^-1 vt is inside the disc (sticking: most
/// points of a resting stack), the change -omega K^-1 vt is formed directly, four dependent
/// operations on the sweep's critical path where old + omega (K^-1 (K old - vt) - old) - old
/// took eight; the two differ by roundings. ContactRows::solveFriction does the same per lane.
inline void solveRelaxedDisc(const DiscBlock& k, const Eigen::Matrix<Real, 2, 1>& old,
                             const Eigen::Matrix<Real, 2, 1>& vt, Real radius, Real omega,
                             Eigen::Matrix<Real, 2, 1>& next, Eigen::Matrix<Real, 2, 1>& delta) {
    using Vec2 = Eigen::Matrix<Real, 2, 1>;
    const Real step0 = k.inverse(0, 0) * vt(0) + k.inverse(0, 1) * vt(1);  // K^-1 vt
    const Real step1 = k.inverse(1, 0) * vt(0) + k.inverse(1, 1) * vt(1);
    const Real free0 = old(0) - step0;
    const Real free1 = old(1) - step1;
    if (radius > 0 && free0 * free0 + free1 * free1 <= radius * radius) {
        delta = Vec2(-(omega * step0), -(omega * step1));
        next = Vec2(old(0) + delta(0), old(1) + delta(1));
        return;
    }
    // On the rim (sliding), or no load: the exact disc's answer, relaxed.
    const Vec2 solved =
        radius > 0 ? solveDiscRim(k, Vec2(k.block * old - vt), radius) : Vec2(Vec2::Zero());
    next = Vec2(old(0) + omega * (solved(0) - old(0)), old(1) + omega * (solved(1) - old(1)));
    delta = Vec2(next(0) - old(0), next(1) - old(1));
}

/// Torsion and rolling resistance of one manifold, with its current normal impulses; returns the
/// change as a speed at the farthest point (m/s).
Real solveAngularFriction(SolverBody& a, SolverBody& b, ContactConstraint& c, Real omega);

/// A point's normalTarget, or the one it keeps (SweepPoint::target, computed with the same
/// bias, slop and 1/h: SweepRows::sweep).
template <class Point>
inline Real pointTarget(const Point& p, Real bias, Real slop, Real inverseH) {
    if constexpr (requires { p.target; })
        return p.target;
    else
        return normalTarget(p, bias, slop, inverseH);
}

/// The normal rows of one manifold of n points (Point: ContactConstraintPoint or SweepPoint):
/// its block K solved exactly (normal_block.h) with the cached factor, or point by point when it
/// has one point or the block is degenerate. K is read only when n > 1 or when measuring. Raises
/// largestChange to the velocity change when settings.tolerance > 0. Body: as normalSpeed's.
/// `softScale` (the soft step's biased sweep, or null): the rigid answer of each point that
/// touches (separation <= 0) is scaled by it, which makes the row a spring-damper
/// (docs/ARCHITECTURE.md, the soft step); speculative points stay rigid. kMovesA: as
/// applyNormal's.
template <bool kMovesA = true, class Body, class Point>
void solveNormals(Body& a, Body& b, const Vec3& normal, const Mat4* k, Point* points, int n,
                  NormalFactor& factor, const SolverSettings& settings, Real inverseH, Real bias,
                  Real& largestChange, const Real* softScale = nullptr) {
    const Real omega = settings.relaxation;
    if (n == 1 && !(settings.tolerance > 0)) {
        // One point (most of a pile's manifolds): the loop below for i = 0, without the 4-vectors
        // (their zeroing, copies and store back: ~40 instructions a one-point manifold).
        Point& p = points[0];
        const Real old = p.normalImpulse;
        const Real vn =
            normalSpeed(a, b, normal, p) - pointTarget(p, bias, settings.slop, inverseH);
        Real next;
        if (softScale == nullptr) {
            next = std::max<Real>(0, old - omega * p.normalMass * vn);
        } else {
            const Real scale = p.separation > 0 ? 1 : *softScale;
            const Real soft = scale * (old - p.normalMass * vn);
            next = std::max<Real>(0, old + omega * (soft - old));
        }
        applyNormal<kMovesA>(a, b, normal, p, next - old);
        p.normalImpulse = next;
        return;
    }
    Vec4 old = Vec4::Zero();
    Vec4 next = Vec4::Zero();
    Vec4 gap = Vec4::Zero();  // v_n - target with the current impulses (m/s)
    for (int i = 0; i < n; ++i) {
        const Point& p = points[i];
        old(i) = p.normalImpulse;
        gap(i) = normalSpeed(a, b, normal, p) - pointTarget(p, bias, settings.slop, inverseH);
    }
    Vec4 exact = old;
    bool solved = false;
    if (n > 1) {
        const Vec4 c = gap - *k * old;
        solved = solveNormalBlockCached(*k, n, c, exact, factor) ||
                 solveNormalBlock(*k, n, c, exact, factor);
    }
    if (solved) {
        if (softScale != nullptr) {
            for (int i = 0; i < n; ++i)
                exact(i) *= points[i].separation > 0 ? 1 : *softScale;
        }
        next = (old + omega * (exact - old)).cwiseMax(0);
        for (int i = 0; i < n; ++i)
            applyNormal<kMovesA>(a, b, normal, points[i], next(i) - old(i));
    } else {
        // One point, or a degenerate block: the points one by one. The first sees the
        // velocities its gap was measured at (nothing has moved them since): its vn is gap(0),
        // bit for bit, measured once (a pile's one-point manifolds measured it twice).
        for (int i = 0; i < n; ++i) {
            Point& p = points[i];
            const Real vn = i == 0 ? gap(0)
                                   : normalSpeed(a, b, normal, p) -
                                         pointTarget(p, bias, settings.slop, inverseH);
            if (softScale == nullptr) {
                next(i) = std::max<Real>(0, old(i) - omega * p.normalMass * vn);
            } else {
                const Real scale = p.separation > 0 ? 1 : *softScale;
                const Real soft = scale * (old(i) - p.normalMass * vn);
                next(i) = std::max<Real>(0, old(i) + omega * (soft - old(i)));
            }
            applyNormal<kMovesA>(a, b, normal, p, next(i) - old(i));
        }
    }
    for (int i = 0; i < n; ++i)
        points[i].normalImpulse = next(i);
    // The velocity change each point sees: a shift of load between the legs of a face, which the
    // block's minimum-norm choice may make, moves nothing and does not count.
    if (settings.tolerance > 0) {
        const Vec4 change = *k * (next - old);
        for (int i = 0; i < n; ++i)
            largestChange = std::max(largestChange, std::abs(change(i)));
    }
}

/// The soft step's warm start of one point (Point: ContactConstraintPoint or SweepPoint): its
/// accumulated normal and friction impulses applied again.
template <class Point>
void warmStartPoint(SolverBody& a, SolverBody& b, const Vec3& normal,
                    const std::array<Vec3, 2>& tangents, const Point& p) {
    applyNormal(a, b, normal, p, p.normalImpulse);
    const Vec3 linear = p.tangentImpulse[0] * tangents[0] + p.tangentImpulse[1] * tangents[1];
    a.linearVelocity -= a.inverseMass * linear;
    a.angularVelocity -=
        p.tangentImpulse[0] * p.tangentImpulseA[0] + p.tangentImpulse[1] * p.tangentImpulseA[1];
    b.linearVelocity += b.inverseMass * linear;
    b.angularVelocity +=
        p.tangentImpulse[0] * p.tangentImpulseB[0] + p.tangentImpulse[1] * p.tangentImpulseB[1];
}

/// solveNormals on a constraint's own points and block.
inline void solveManifoldNormals(SolverBody& a, SolverBody& b, ContactConstraint& c,
                                 NormalFactor& factor, const SolverSettings& settings,
                                 Real inverseH, Real bias, Real& largestChange) {
    solveNormals(a, b, c.normal, &c.normalBlock, c.points.data(), c.pointCount, factor, settings,
                 inverseH, bias, largestChange);
}

}  // namespace tumble
