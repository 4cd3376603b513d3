// Sticking friction: the carried friction impulses of a manifold without their self-equilibrated
// part (equilibrateFriction).

#include "tumble/solver/friction_anchors.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

#include "ldlt4.h"
#include "normal_block.h"
#include "tumble/core/lane_kernel.h"

namespace tumble {
namespace {

using Vec2 = Eigen::Matrix<Real, 2, 1>;

Real cross(const Vec2& a, const Vec2& b) {
    return a.x() * b.y() - a.y() * b.x();
}

// Sweeps of the anchor pass: a sticking manifold's drift is one step's lag, the same at its
// points, which a few sweeps remove.
constexpr int kSweeps = 4;
// Share of a point's Coulomb disc beyond which a manifold's carried friction is equilibrated.
constexpr Real kCrowdedShare = 0.5;
// Relative slack on a point's Coulomb disc for the equilibrated friction (rounding).
constexpr Real kDiscTolerance = 1e-9;

// The share of a disc of radius `limit` that an impulse of size `size` uses (infinite where a
// point without load carries friction).
Real share(Real size, Real limit) {
    if (size == 0)
        return 0;
    return limit > 0 ? size / limit : std::numeric_limits<Real>::infinity();
}

// Whether a point of the manifold uses at least kCrowdedShare of its disc: most manifolds do
// not, and equilibrateFriction leaves them as they are (squares, so no root for each point).
bool crowded(const ContactConstraint& c) {
    for (int i = 0; i < c.pointCount; ++i) {
        const ContactConstraintPoint& p = c.points[i];
        const Real size2 =
            p.tangentImpulse[0] * p.tangentImpulse[0] + p.tangentImpulse[1] * p.tangentImpulse[1];
        const Real limit = kCrowdedShare * c.friction * p.normalImpulse;
        if (size2 > 0 && (limit <= 0 || size2 >= limit * limit))
            return true;
    }
    return false;
}

bool drifting(const ContactConstraint& c, const Vec3* drifts, Real deadband) {
    if (c.friction == 0)
        return false;
    for (int i = 0; i < c.pointCount; ++i)
        if (drifts[i].squaredNorm() > deadband * deadband)
            return true;
    return false;
}

// The inverse of a face's normal block, regularised: it is singular (three degrees of freedom,
// four rows), and the regularisation picks the minimum-norm split, as in solveNormalBlock.
Mat4 normalBlockInverse(const ContactConstraint& c) {
    const int n = c.pointCount;
    Mat4 k = Mat4::Identity();
    k.topLeftCorner(n, n) = c.normalBlock.topLeftCorner(n, n);
    const Real scale = k.diagonal().head(n).maxCoeff();
    k.diagonal().head(n).array() += 1e-9 * scale;
    return ldltInverse(k);
}

// Holds the manifold's normal pseudo-velocities where the pass found them (rows[i].z()), with
// impulses of either sign: the face's normal block answers the tangential pull's moment with a
// shift of load between its points, as the velocity solve does; one-sided, it would lift the
// body off its inner points instead.
template <int N>
void holdNormals(SolverBody& a, SolverBody& b, const ContactConstraint& c, const Vec3* rows,
                 const Mat4& inverse) {
    Vec4 gap = Vec4::Zero();
#pragma GCC unroll 4
    for (int i = 0; i < N; ++i)
        gap(i) = normalSpeed(a, b, c.normal, c.points[i]) - rows[i].z();
    const Vec4 impulse = -(inverse * gap);
#pragma GCC unroll 4
    for (int i = 0; i < N; ++i)
        applyNormal(a, b, c.normal, c.points[i], impulse(i));
}

// The velocity a point's drift asks for (m/s): at most catchUp of it closed in one step.
Vec3 pullOf(const Vec3& drift, Real inverseH, Real catchUp) {
    const Real length = drift.norm();
    const Vec3 aim = length > catchUp ? Vec3((catchUp / length) * drift) : drift;
    return inverseH * aim;
}

// One sweep over a manifold's friction rows: the sticking answer, clamped to the Coulomb disc
// (a point that needs more lets its anchors go after the step, so the rim is not worth the
// exact solve of the velocity sweeps).
template <int N>
void pullPoints(SolverBody& a, SolverBody& b, const ContactConstraint& c, const Vec3* pulls,
                Vec3* rows) {
#pragma GCC unroll 4
    for (int i = 0; i < N; ++i) {
        const ContactConstraintPoint& p = c.points[i];
        const Vec3 v = b.velocityAt(p.rB) - a.velocityAt(p.rA) + pulls[i];
        const Vec2 slip(c.tangents[0].dot(v), c.tangents[1].dot(v));
        const Vec2 old = rows[i].head<2>();
        Vec2 next = old - p.tangent.inverse * slip;
        const Real radius = c.friction * p.normalImpulse;
        if (next.squaredNorm() > radius * radius)
            next *= radius / next.norm();
        const Vec2 delta = next - old;
        const Vec3 impulse = delta.x() * c.tangents[0] + delta.y() * c.tangents[1];
        applyImpulse(a, -impulse, p.rA);
        applyImpulse(b, impulse, p.rB);
        rows[i].head<2>() = next;
    }
}

// One sweep of the pass over a manifold of N points: its friction rows, then its normal block.
// N is a template argument so that the points' loops unroll (the same operations in the same
// order; the loop counters were a tenth of the pass).
template <int N>
void sweepManifold(SolverBody& a, SolverBody& b, const ContactConstraint& c, const Vec3* pulls,
                   Vec3* rows, const Mat4& inverse) {
    pullPoints<N>(a, b, c, pulls, rows);
    if constexpr (N > 1)
        holdNormals<N>(a, b, c, rows, inverse);
}

// sweepManifold on copies of the two bodies, their velocities stored back once: through the
// references, every update was stored and loaded again, and the constraint's fields with it
// (the compiler cannot tell the bodies from each other, from the rows or from the constraint).
// Two bodies, so each one's updates are the same operations in the same order.
template <int N>
void sweepManifoldApart(SolverBody& a, SolverBody& b, const ContactConstraint& c, const Vec3* pulls,
                        Vec3* rows, const Mat4& inverse) {
    SolverBody localA = a;
    SolverBody localB = b;
    sweepManifold<N>(localA, localB, c, pulls, rows, inverse);
    a.linearVelocity = localA.linearVelocity;
    a.angularVelocity = localA.angularVelocity;
    b.linearVelocity = localB.linearVelocity;
    b.angularVelocity = localB.angularVelocity;
}

// The pass's arithmetic over its active manifolds: the normal speeds, pulls and normal block
// inverses it starts from, then its sweeps. Compiled for AVX2 and the baseline like the contact
// kernels (lane_kernel.h, the same bits): the baseline's two-operand SSE2 copied every Eigen
// temporary through extra registers, and the pass took 10.3 % of pyramid-20's instructions.
TUMBLE_LANE_KERNEL void sweepAnchors(SolverBody* bodies, const ContactConstraint* constraints,
                                     const std::uint32_t* active, std::size_t count,
                                     const Vec3* drifts, Real inverseH, Real catchUp, Vec3* rows,
                                     Mat4* inverses, Vec3* pulls) {
    for (std::size_t k = 0; k < count; ++k) {
        const ContactConstraint& c = constraints[active[k]];
        for (int i = 0; i < c.pointCount; ++i) {
            rows[4 * k + i].z() =
                normalSpeed(bodies[c.bodyA], bodies[c.bodyB], c.normal, c.points[i]);
            pulls[4 * k + i] = pullOf(drifts[4 * active[k] + i], inverseH, catchUp);
        }
        if (c.pointCount > 1)
            inverses[k] = normalBlockInverse(c);
    }
    for (int sweep = 0; sweep < kSweeps; ++sweep) {
        for (std::size_t k = 0; k < count; ++k) {
            const ContactConstraint& c = constraints[active[k]];
            SolverBody& a = bodies[c.bodyA];
            SolverBody& b = bodies[c.bodyB];
            withPointCount(c.pointCount, [&]<int N>() {
                if (&a != &b)
                    sweepManifoldApart<N>(a, b, c, &pulls[4 * k], &rows[4 * k], inverses[k]);
                else
                    sweepManifold<N>(a, b, c, &pulls[4 * k], &rows[4 * k], inverses[k]);
            });
        }
    }
}

}  // namespace

AnchorLengths AnchorLengths::of(Real slop, Real contactMargin) {
    Real length = slop > 0 ? slop : contactMargin;
    if (!(length > 0))
        length = SolverSettings{}.slop;
    return {length / 500, 2 * length, length / 3};
}

void FrictionAnchorPass::run(std::span<const SolverBody> bodies,
                             std::span<const ContactConstraint> constraints,
                             std::span<const Vec3> drifts, std::vector<PseudoVelocity>& pseudo,
                             Real inverseH, const AnchorLengths& lengths) {
    active_.clear();
    for (std::size_t j = 0; j < constraints.size(); ++j)
        if (drifting(constraints[j], &drifts[4 * j], lengths.deadband))
            active_.push_back(static_cast<std::uint32_t>(j));
    if (active_.empty())
        return;
    loadPseudoBodies(bodies, pseudo, bodies_);
    rows_.assign(4 * active_.size(), Vec3::Zero());
    inverses_.resize(active_.size());
    pulls_.resize(4 * active_.size());  // the drifts are the same in every sweep
    sweepAnchors(bodies_.data(), constraints.data(), active_.data(), active_.size(), drifts.data(),
                 inverseH, lengths.catchUp, rows_.data(), inverses_.data(), pulls_.data());
    storePseudoBodies(bodies_, pseudo);
}

// Minimise sum |f_i|^2 / w_i (w_i = lambda_n,i) subject to sum f_i = F and
// sum d_i x f_i = M (d_i: the point from the load-weighted centre, on the tangent plane). The
// Lagrange conditions give f_i = w_i (a + s perp(d_i)); sum w_i d_i = 0 separates the two:
// a = F / sum w_i, s = M / sum w_i |d_i|^2. Compiled for AVX2 and the baseline like the pass
// (lane_kernel.h, the same bits): most of pyramid-20's manifolds get past crowded().
TUMBLE_LANE_KERNEL bool equilibrateFriction(ContactConstraint& c) {
    const int n = c.pointCount;
    if (n < 2 || c.friction == 0 || !crowded(c))
        return false;
    std::array<Vec2, 4> d;
    Real load = 0;  // N s
    Vec2 center = Vec2::Zero();
    Vec2 force = Vec2::Zero();  // N s
    for (int i = 0; i < n; ++i) {
        const ContactConstraintPoint& p = c.points[i];
        d[i] = Vec2(p.rB.dot(c.tangents[0]), p.rB.dot(c.tangents[1]));
        load += p.normalImpulse;
        center += p.normalImpulse * d[i];
        force += Vec2(p.tangentImpulse[0], p.tangentImpulse[1]);
    }
    if (load <= 0)
        return false;
    center /= load;
    Real moment = 0;  // N m s
    Real spread = 0;  // N s m^2
    for (int i = 0; i < n; ++i) {
        const ContactConstraintPoint& p = c.points[i];
        d[i] -= center;
        moment += cross(d[i], Vec2(p.tangentImpulse[0], p.tangentImpulse[1]));
        spread += p.normalImpulse * d[i].squaredNorm();
    }
    // One loaded point (or all at the centre) cannot carry a moment by its friction: keep what
    // the solve found.
    if (spread <= 0 && moment != 0)
        return false;
    const Vec2 shift = force / load;
    const Real spin = spread > 0 ? moment / spread : 0;
    std::array<Vec2, 4> f;
    Real before = 0;  // the largest share of its disc a point uses, as solved
    Real after = 0;   // and equilibrated
    for (int i = 0; i < n; ++i) {
        const ContactConstraintPoint& p = c.points[i];
        const Real limit = c.friction * p.normalImpulse;
        f[i] = p.normalImpulse * (shift + spin * Vec2(-d[i].y(), d[i].x()));
        before =
            std::max(before, share(std::hypot(p.tangentImpulse[0], p.tangentImpulse[1]), limit));
        const Real next = share(f[i].norm(), limit);
        if (!(next <= 1 + kDiscTolerance))  // off its disc, or not finite
            return false;
        after = std::max(after, next);
    }
    if (!(before >= kCrowdedShare && after < before))
        return false;
    for (int i = 0; i < n; ++i)
        c.points[i].tangentImpulse = {f[i].x(), f[i].y()};
    return true;
}

}  // namespace tumble
