#pragma once
/// The normal rows of one contact manifold (up to four points between the same two bodies) solved
/// together, exactly, as a small linear complementarity problem:
///
///     find lambda >= 0 with  w = K lambda + c >= 0  and  lambda_i w_i = 0,
///
/// K the manifold's normal block (K_ij: normal velocity change at point i per unit impulse at
/// point j), c the normal velocities, less their targets, that remain with lambda = 0.
///
/// Why a block: solving the points one after another (plain Gauss-Seidel) hands each increment of
/// load to the first corner it reaches, so a box that is still taking up load is tipped a little
/// every sweep. In a tall stack that bias never settles within ten sweeps and the stack leans
/// until it falls (a 20-cube stack fell within 5 s). The exact block solve has no order.
///
/// Method: the active sets are enumerated, largest first (at rest all four points carry load).
/// For each set S the equalities K_SS lambda_S = -c_S are solved by Cholesky; the set is the
/// answer when lambda_S >= 0 and w >= 0 off S. Four coplanar points give a singular 4x4 block
/// (a rigid face has three contact degrees of freedom, not four): a small diagonal
/// regularisation then picks the minimum-norm split of the load, the symmetric one, and a set
/// whose equalities cannot be met (w_S != 0) is rejected.

#include <Eigen/Core>
#include <algorithm>

#include "tumble/core/math.h"
#include "tumble/solver/contact_solver.h"

namespace tumble {

using Mat4 = Eigen::Matrix<Real, 4, 4>;
using Vec4 = Eigen::Matrix<Real, 4, 1>;

/// Equalities and inequalities are checked to this fraction of the largest |c| (m/s), and to
/// kNormalFloor when every |c| is zero.
constexpr Real kNormalTolerance = 1e-7;
constexpr Real kNormalFloor = 1e-12;

/// Solves the LCP above for the first n (1..4) rows of k and c. `lambda` comes in as the last
/// answer (its positive entries are the first active set tried) and on success goes out as the
/// new one (entries past n zero); returns false when no active set checks out to rounding (a
/// degenerate block), leaving lambda unchanged. `factor` is the cache of this k (reset to
/// NormalFactor{} whenever k changes).
bool solveNormalBlock(const Mat4& k, int n, const Vec4& c, Vec4& lambda, NormalFactor& factor);

namespace detail {

// Solves L L' x_S = -c_S by forward and back substitution; x is zero off the set. Unrolled for
// each size M: y and z stay in registers and the rows are read once (the loop kept its eight
// dependent steps waiting on stack round trips, on the sweep's critical path: a stack's column
// is one chain of manifolds). Multiplying by the cached 1/L_ii keeps divisions off that path;
// ContactRows' solveFactoredLanes does the same operations.
template <int M>
[[gnu::always_inline]] inline void solveFactoredSize(const NormalFactor& f, const Vec4& c,
                                                     Vec4& x) {
    int rows[M];
    for (int i = 0; i < M; ++i)
        rows[i] = f.rows[i];
    Real y[M];
    for (int i = 0; i < M; ++i) {
        Real sum = -c(rows[i]);
        for (int p = 0; p < i; ++p)
            sum -= f.l[i][p] * y[p];
        y[i] = sum * f.inverseDiagonal[i];
    }
    Real z[M];
    for (int i = M - 1; i >= 0; --i) {
        Real sum = y[i];
        for (int p = i + 1; p < M; ++p)
            sum -= f.l[p][i] * z[p];
        z[i] = sum * f.inverseDiagonal[i];
    }
    x.setZero();
    for (int i = 0; i < M; ++i)
        x(rows[i]) = z[i];
}

inline void solveFactored(const NormalFactor& f, const Vec4& c, Vec4& x) {
    switch (f.size) {
        case 4:
            solveFactoredSize<4>(f, c, x);
            return;
        case 3:
            solveFactoredSize<3>(f, c, x);
            return;
        case 2:
            solveFactoredSize<2>(f, c, x);
            return;
        default:
            solveFactoredSize<1>(f, c, x);
            return;
    }
}

// max |c_i| over the first n rows, as c.head(n).cwiseAbs().maxCoeff() was (a maximum of
// magnitudes does not depend on the order; with a NaN in c every check fails whatever the
// tolerance), over a fixed four with the rest masked: unrolled, where the dynamic head looped.
// Forced inline, that head drew GCC 12's -Warray-bounds on its packet loads past n.
inline Real largestMagnitude(const Vec4& c, int n) {
    Real largest = 0;
    for (int i = 0; i < 4; ++i)
        largest = std::max(largest, i < n ? std::abs(c(i)) : Real(0));
    return largest;
}

// The rows of lambda's first n that carry load, as a bit mask. A fixed count of four with the
// rows past n masked: unrolled, without a branch per row.
inline unsigned loadedSet(const Vec4& lambda, int n) {
    unsigned set = 0;
    for (int i = 0; i < 4; ++i)
        set |= static_cast<unsigned>(i < n && lambda(i) > 0) << i;
    return set;
}

// Whether x, zero off `set`, solves the LCP with that active set: x >= 0 and w = K x + c = 0 on
// the set, w >= 0 off it, to the tolerance.
inline bool checksOut(const Mat4& k, int n, const Vec4& c, unsigned set, const Vec4& x,
                      Real tolerance) {
    const Vec4 w = k * x + c;
    // Every row checked, without early exit: unrolled and branch-free, the same answer.
    bool ok = true;
    for (int i = 0; i < 4; ++i) {
        const bool active = (set & (1u << i)) != 0;
        const bool holds = active ? (x(i) >= 0 && std::abs(w(i)) <= tolerance) : w(i) >= -tolerance;
        ok &= i >= n || holds;
    }
    return ok;
}

}  // namespace detail

/// Calls f.template operator()<N>() with N = n, a manifold's point count (1..4; nothing for
/// another n), so that loops over the points unroll with N a constant: the same operations in
/// the same order, without their counters (prepareManifold, the friction anchor pass).
template <class F>
[[gnu::always_inline]] inline void withPointCount(int n, F&& f) {
    if (n == 4)
        f.template operator()<4>();
    else if (n == 3)
        f.template operator()<3>();
    else if (n == 2)
        f.template operator()<2>();
    else if (n == 1)
        f.template operator()<1>();
}

/// solveNormalBlock's first attempt, inline: last answer's active set, solved with the factor
/// cached for it (or no load at all). Most sweeps end there, and the call, its vectors passed
/// through memory, sat on the sweep's critical path (a stack's column is one chain of
/// manifolds). False, lambda unchanged, when the factor is not that set's or the answer fails
/// the checks: solveNormalBlock then searches, trying this set first again (the same result).
/// GCC 12 keeps it (and solveFactored) out of line in SweepRows::sweep all the same; forced
/// inline ([[gnu::always_inline]]) it cut stack-20's instructions by 1 % but timed no faster
/// (median of eight interleaved runs 1.02x the call's, load 5-7), so the call stays.
inline bool solveNormalBlockCached(const Mat4& k, int n, const Vec4& c, Vec4& lambda,
                                   const NormalFactor& factor) {
    const unsigned set = detail::loadedSet(lambda, n);
    if (set != 0 && factor.set != set)
        return false;
    const Real tolerance =
        std::max(kNormalTolerance * detail::largestMagnitude(c, n), kNormalFloor);
    Vec4 x = Vec4::Zero();
    if (set != 0)
        detail::solveFactored(factor, c, x);
    if (!detail::checksOut(k, n, c, set, x, tolerance))
        return false;
    lambda = x;
    return true;
}

// v_n = n . (vB + wB x rB - vA - wA x rA), with the angular parts precomputed by prepare().
// Point: a ContactConstraintPoint or the sweep's SweepPoint (the same fields); Body: a
// SolverBody or any type with its velocities and inverse mass (SweepRows' local copies).
template <class Body, class Point>
inline Real normalSpeed(const Body& a, const Body& b, const Vec3& n, const Point& p) {
    return n.dot(b.linearVelocity - a.linearVelocity) + p.angularB.dot(b.angularVelocity) -
           p.angularA.dot(a.angularVelocity);
}

// A normal impulse lambda n on B at the point, -lambda n on A. kMovesA false: A is the static
// body 0 (SolverBody{}), whose zero velocities its updates leave +0 (+0 - (+-0) = +0, its inverse
// mass and inertia being 0), so they are skipped (SweepRows::sweepPlain).
template <bool kMovesA = true, class Body, class Point>
inline void applyNormal(Body& a, Body& b, const Vec3& n, const Point& p, Real lambda) {
    if constexpr (kMovesA) {
        a.linearVelocity -= (a.inverseMass * lambda) * n;
        a.angularVelocity -= lambda * p.angularImpulseA;
    }
    b.linearVelocity += (b.inverseMass * lambda) * n;
    b.angularVelocity += lambda * p.angularImpulseB;
}

// Velocity the normal row aims at, v_n >= target: close a speculative gap within the step but
// not beyond it; with a bias factor (Baumgarte's k_erp, or split impulse's factor in its biased
// sweeps), also push out that fraction of the penetration beyond the slop.
//
// Restitution is part of the same rows. A bouncing point (ContactConstraintPoint::bounces)
// demands v_n >= v+ (its rebound speed) instead of v_n >= 0, plus the push-out in the biased
// sweeps. Every row of the step is then one complementarity problem whose solution holds every
// contact at once: a ball striking a box that rests on the ground gets its rebound from the
// box-ground row pushing back, as from the ground itself. Applied afterwards as a pass over the
// bouncing points alone (the first design), the bounce's impulse pushed the box into the ground
// (-3 m/s for a 1 kg box under a 1 kg ball), whose row never answered, and the ball did not
// rebound at all. The biased and the relax sweeps carry the same rebound, so the pseudo-velocity,
// their difference, is still the push-out alone -- plus, in the biased sweeps, the pull-back of
// a speculative point that bounced (bounceCorrection), which so moves the position only. Solved
// as a separate pass on the bouncing points, that pull-back lifted a 0.1 kg box resting under a
// ball by 1.9 cm, and the ball's next apex with it.
template <class Point>
inline Real normalTarget(const Point& p, Real bias, Real slop, Real inverseH) {
    const Real push =
        p.separation > 0 ? 0 : bias * inverseH * std::max<Real>(0, -p.separation - slop);
    if (p.bounces)
        return p.reboundSpeed + push - p.bounceCorrection * inverseH;
    return p.separation > 0 ? -p.separation * inverseH : push;
}

}  // namespace tumble
