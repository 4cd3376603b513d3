// ContactRows' friction kernels (contact_rows.h): every point's friction rows, four manifolds
// at a time, for the sweep (contact_rows.cpp). Their own file: the kernels are called, never
// inlined into the sweep (each is a TUMBLE_LANE_KERNEL, chosen at load), and take in only the
// helpers of contact_rows_lanes.h.
#include <algorithm>
#include <cmath>

#include "contact_rows_lanes.h"
#include "tumble/core/lane_kernel.h"

namespace tumble {

using namespace wide;

namespace {

[[gnu::always_inline]] inline Lane squareRoot(Lane x) {
    Lane root;
    for (int lane = 0; lane < 4; ++lane)
        root[lane] = std::sqrt(x[lane]);
    return root;
}

// solveDisc's sliding case (contact_solver.cpp) in the lanes of `rim`, from b = K old - vt: the
// same operations in the same order per lane, each lane stopping where solveDisc stops, so the
// same bits. A pile's sliding points spent a fifth of its step in that Newton iteration, one
// lane after another.
template <class Point>
[[gnu::always_inline]] inline void solveRimLanes(const Point& q, LaneMask rim, Lane b0, Lane b1,
                                                 Lane radius, Lane& solved0, Lane& solved1) {
    const Lane* axes = q.tangentAxes;
    const Lane m0 = q.tangentMoments[0];
    const Lane m1 = q.tangentMoments[1];
    const Lane c0 = axes[0] * b0 + axes[2] * b1;  // axes' b
    const Lane c1 = axes[1] * b0 + axes[3] * b1;
    const Lane one = splat(1);
    const Lane bound0 = squareRoot(c0 * c0 + c1 * c1) / radius - m1;
    const Lane bound1 = absolute(c0) / radius - m0;
    Lane nu = positivePart(select(greater(bound1, bound0), bound1, bound0));
    LaneMask going = rim;
    for (int iteration = 0; iteration < 20 && any(going); ++iteration) {
        const Lane s0 = one / (m0 + nu);
        const Lane s1 = one / (m1 + nu);
        const Lane q0 = c0 * s0;
        const Lane q1 = c1 * s1;
        const Lane squared = q0 * q0 + q1 * q1;
        const Lane length = squareRoot(squared);
        const Lane step = squared * (one - length / radius) / (q0 * q0 * s0 + q1 * q1 * s1);
        const Lane next = positivePart(nu - step);
        nu = select(going, next, nu);
        // solveDisc stops once |step| <= tol: a NaN step goes on there, and here.
        going &= ~reinterpret_cast<LaneMask>(absolute(step) <= splat(1e-5) * (next + m1));
    }
    const Lane q0 = c0 / (m0 + nu);
    const Lane q1 = c1 / (m1 + nu);
    const Lane lambda0 = axes[0] * q0 + axes[1] * q1;
    const Lane lambda1 = axes[2] * q0 + axes[3] * q1;
    const Lane scale = radius / squareRoot(lambda0 * lambda0 + lambda1 * lambda1);
    solved0 = select(rim, lambda0 * scale, solved0);
    solved1 = select(rim, lambda1 * scale, solved1);
}

}  // namespace

// The friction of every point, point by point as ContactSolver does, four manifolds at a time.
// Coupled: the free answer K^-1 (K old - vt) in the lanes, solveDisc for a lane whose answer
// leaves the disc. The default step's case (coupled, not measuring, no friction targets) and
// its four-point bundles (a pyramid's) have their own copies, without the tests of the model
// and of the tolerance at every point, the loop's counter, and the targets' subtraction (+0
// outside the soft step, and x - +0 is x, bit for bit): 5 of each point's 191 instructions
// (pyramid-20's solveFriction, 64.3M to 62.8M by callgrind).
TUMBLE_LANE_KERNEL Real ContactRows::solveFriction(Bundle& bundle, const SolverSettings& settings,
                                                   Lane (&v)[2][6]) {
    return frictionWith<false>(bundle, settings, v);
}

// gather, then solveFriction, in one kernel: the velocities go from the unpacks to the first
// point's rows in registers, one call, not two (the default step's sweep).
TUMBLE_LANE_KERNEL Real ContactRows::gatherFriction(Bundle& bundle, const SolverSettings& settings,
                                                    Lane (&v)[2][6]) {
    return frictionWith<true>(bundle, settings, v);
}

template <bool kGather>
[[gnu::always_inline]] inline Real ContactRows::frictionWith(Bundle& bundle,
                                                             const SolverSettings& settings,
                                                             Lane (&v)[2][6]) {
    if constexpr (kGather)
        gatherLanes(bundle, v);
    const bool plain =
        settings.friction == FrictionModel::Coupled && !(settings.tolerance > 0) && !softTargets_;
    if (!plain)
        return solveFrictionLanes<0, false>(bundle, settings, v);
    if (bundle.maxPoints == 4)
        return solveFrictionLanes<4, true>(bundle, settings, v);
    return solveFrictionLanes<0, true>(bundle, settings, v);
}

// kPoints: the bundle's point slots, or 0 for bundle.maxPoints. kPlain: coupled friction, no
// measuring, no friction targets (softTargets_ false: every bundle's tangentTarget is +0).
template <int kPoints, bool kPlain>
[[gnu::always_inline]] inline Real ContactRows::solveFrictionLanes(Bundle& bundle,
                                                                   const SolverSettings& settings,
                                                                   Lane (&v)[2][6]) {
    const Lane omega = splat(settings.relaxation);
    const bool coupled = kPlain || settings.friction == FrictionModel::Coupled;
    Point* const slots = points_.data() + bundle.firstPoint;
    // Read once: the impulses' and velocities' stores might alias them, and both were loaded
    // again at every point.
    const int points = kPoints > 0 ? kPoints : bundle.maxPoints;
    const bool measure = !kPlain && settings.tolerance > 0;
    Real largestChange = 0;
    for (int i = 0; i < points; ++i) {
        Point& q = slots[i];
        Lane dv[3];
        for (int k = 0; k < 3; ++k)
            dv[k] = v[1][k] - v[0][k];
        Lane vt[2];
        for (int r = 0; r < 2; ++r) {
            vt[r] = (dot(bundle.tangents[r], dv) + dot(q.tangentAngularB[r], v[1] + 3)) -
                    dot(q.tangentAngularA[r], v[0] + 3);
            if constexpr (!kPlain)
                vt[r] = vt[r] - bundle.tangentTarget[r];
        }
        const Lane old0 = q.tangentImpulse[0];
        const Lane old1 = q.tangentImpulse[1];
        const Lane limit = bundle.friction * q.normalImpulse;
        Lane next0;
        Lane next1;
        Lane delta0;
        Lane delta1;
        if (coupled) {
            // solveRelaxedDisc (contact_kernels.h) per lane.
            const Lane* inverse = q.tangentInverse;
            const Lane step0 = inverse[0] * vt[0] + inverse[1] * vt[1];
            const Lane step1 = inverse[2] * vt[0] + inverse[3] * vt[1];
            const Lane free0 = old0 - step0;
            const Lane free1 = old1 - step1;
            const LaneMask positive = greater(limit, Lane{});
            // As the scalar test: a NaN goes to the rim.
            const LaneMask sticking =
                positive &
                reinterpret_cast<LaneMask>(free0 * free0 + free1 * free1 <= limit * limit);
            const Lane stick0 = -(omega * step0);
            const Lane stick1 = -(omega * step1);
            if (!any(~sticking)) {
                // Every lane sticks (most points of a resting pyramid): the selects below
                // would take their sticking side, without the relaxed answers formed.
                delta0 = stick0;
                delta1 = stick1;
                next0 = old0 + stick0;
                next1 = old1 + stick1;
            } else {
                const LaneMask rim = positive & ~sticking;
                Lane solved0{};
                Lane solved1{};
                if (any(rim)) {
                    const Lane* k = q.tangentBlock;
                    const Lane b0 = (k[0] * old0 + k[1] * old1) - vt[0];
                    const Lane b1 = (k[2] * old0 + k[3] * old1) - vt[1];
                    solveRimLanes(q, rim, b0, b1, limit, solved0, solved1);
                }
                const Lane relaxed0 = old0 + omega * (solved0 - old0);
                const Lane relaxed1 = old1 + omega * (solved1 - old1);
                delta0 = select(sticking, stick0, relaxed0 - old0);
                delta1 = select(sticking, stick1, relaxed1 - old1);
                next0 = select(sticking, old0 + stick0, relaxed0);
                next1 = select(sticking, old1 + stick1, relaxed1);
            }
        } else {
            next0 = old0 - omega * (q.tangentMass[0] * vt[0]);
            next1 = old1 - omega * (q.tangentMass[1] * vt[1]);
            next0 = select(greater(-limit, next0), -limit, next0);
            next1 = select(greater(-limit, next1), -limit, next1);
            next0 = select(greater(next0, limit), limit, next0);
            next1 = select(greater(next1, limit), limit, next1);
            delta0 = next0 - old0;
            delta1 = next1 - old1;
        }
        // Stored before the velocities' update, which then reads v again after these stores
        // (they might alias it): stored after, the values read for vt were kept for the update,
        // in spill slots, six stores more a point (pyramid-20).
        q.tangentImpulse[0] = next0;
        q.tangentImpulse[1] = next1;
        for (int k = 0; k < 3; ++k) {
            const Lane linear = delta0 * bundle.tangents[0][k] + delta1 * bundle.tangents[1][k];
            v[0][k] -= bundle.inverseMassA * linear;
            v[0][3 + k] -= delta0 * q.tangentImpulseA[0][k] + delta1 * q.tangentImpulseA[1][k];
            v[1][k] += bundle.inverseMassB * linear;
            v[1][3 + k] += delta0 * q.tangentImpulseB[0][k] + delta1 * q.tangentImpulseB[1][k];
        }
        if (measure) {
            const Lane* k = q.tangentBlock;
            const Lane change0 = k[0] * delta0 + k[1] * delta1;
            const Lane change1 = k[2] * delta0 + k[3] * delta1;
            largestChange = std::max(largestChange,
                                     std::sqrt(largestLane(change0 * change0 + change1 * change1)));
        }
    }
    return largestChange;
}

// The soft step's biased sweep leaves the friction of exactly solved groups to its relax sweep
// (ContactSolver::softSweep says why): the bundle's friction solved, then its grouped lanes'
// velocities and impulses put back, which leaves them as if not solved (no two lanes of a
// bundle share a moving body), the other lanes as solveFriction leaves them, as SweepRows::sweep
// does manifold by manifold. The default step's kernel stays as it was.
Real ContactRows::solveFrictionHolding(Bundle& bundle, const SolverSettings& settings,
                                       Lane (&v)[2][6], unsigned held) {
    Lane kept[2][6];
    std::copy(&v[0][0], &v[0][0] + 12, &kept[0][0]);
    Lane impulses[4][2];
    for (int i = 0; i < bundle.maxPoints; ++i) {
        impulses[i][0] = points_[bundle.firstPoint + i].tangentImpulse[0];
        impulses[i][1] = points_[bundle.firstPoint + i].tangentImpulse[1];
    }
    const Real largestChange = solveFriction(bundle, settings, v);
    for (int lane = 0; lane < bundle.laneCount; ++lane) {
        if ((held & (1u << lane)) == 0)
            continue;
        for (int body = 0; body < 2; ++body) {
            for (int k = 0; k < 6; ++k)
                v[body][k][lane] = kept[body][k][lane];
        }
        for (int i = 0; i < bundle.maxPoints; ++i) {
            points_[bundle.firstPoint + i].tangentImpulse[0][lane] = impulses[i][0][lane];
            points_[bundle.firstPoint + i].tangentImpulse[1][lane] = impulses[i][1][lane];
        }
    }
    return largestChange;
}

}  // namespace tumble
