// ContactRows' sweep (contact_rows.h): four manifolds per bundle, one per lane.
#include "tumble/solver/contact_rows.h"

#include <algorithm>
#include <cmath>

#include "contact_kernels.h"
#include "normal_block.h"
#include "tumble/core/lane_kernel.h"

namespace tumble {
namespace {

[[gnu::always_inline]] inline Lane splat(Real x) {
    return Lane{x, x, x, x};
}

// a where m is set, b elsewhere.
[[gnu::always_inline]] inline Lane select(LaneMask m, Lane a, Lane b) {
    return reinterpret_cast<Lane>((reinterpret_cast<LaneMask>(a) & m) |
                                  (reinterpret_cast<LaneMask>(b) & ~m));
}

[[gnu::always_inline]] inline LaneMask greater(Lane a, Lane b) {
    return reinterpret_cast<LaneMask>(a > b);
}

// Halves folded in the vector before one element is read: element by element, the four
// extractions and three ors took nine instructions, on every point's friction (pyramid-20).
[[gnu::always_inline]] inline bool any(LaneMask m) {
    const LaneMask halves = m | __builtin_shufflevector(m, m, 2, 3, 0, 1);
    return (halves | __builtin_shufflevector(halves, halves, 1, 0, 3, 2))[0] != 0;
}

[[gnu::always_inline]] inline Lane dot(const Lane (&a)[3], const Lane* b) {
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

[[gnu::always_inline]] inline Real largestLane(Lane x) {
    return std::max({x[0], x[1], x[2], x[3]});
}

[[gnu::always_inline]] inline Lane absolute(Lane x) {
    return select(greater(Lane{}, x), -x, x);
}

// |x| with the sign bit cleared: absolute's value but for the sign of a zero or a NaN, which no
// comparison sees. For values only compared (one instruction, where absolute takes three).
[[gnu::always_inline]] inline Lane magnitude(Lane x) {
    return reinterpret_cast<Lane>(reinterpret_cast<LaneMask>(x) &
                                  (LaneMask{} + 0x7fffffffffffffff));
}

// max(0, x) as std::max<Real>(0, x) has it.
[[gnu::always_inline]] inline Lane positivePart(Lane x) {
    return select(greater(x, Lane{}), x, Lane{});
}

// L L' x = -c on the active rows (forward, then back substitution, in solveNormalBlock's
// order); zero on the others.
[[gnu::always_inline]] inline void solveFactoredLanes(const Lane* l, const Lane* inverseDiagonal,
                                                      const Lane (&c)[4],
                                                      const LaneMask (&active)[4], Lane (&x)[4]) {
    Lane y[4];
    for (int i = 0; i < 4; ++i) {
        Lane sum = select(active[i], -c[i], Lane{});
        for (int p = 0; p < i; ++p)
            sum -= l[4 * i + p] * y[p];
        y[i] = sum * inverseDiagonal[i];
    }
    for (int i = 3; i >= 0; --i) {
        Lane sum = y[i];
        for (int p = i + 1; p < 4; ++p)
            sum -= l[4 * p + i] * x[p];
        x[i] = sum * inverseDiagonal[i];
    }
}

// The checks of solveNormalBlock: on the active rows x >= 0 and w = K x + c = 0, elsewhere
// w >= 0, both to the tolerance.
[[gnu::always_inline]] inline void checkActiveSetLanes(const Lane* k, const LaneMask* hasPoint,
                                                       const Lane (&c)[4],
                                                       const LaneMask (&active)[4],
                                                       const Lane (&x)[4], LaneMask& ok) {
    // The magnitudes are only compared, and the tolerance formed from them (a zero's or a NaN's
    // sign aside, which gives the same masks: the floor is taken over either zero).
    Lane largestC = magnitude(c[0]);
    for (int i = 1; i < 4; ++i)
        largestC = select(greater(magnitude(c[i]), largestC), magnitude(c[i]), largestC);
    Lane tolerance = splat(kNormalTolerance) * largestC;
    tolerance = select(greater(splat(kNormalFloor), tolerance), splat(kNormalFloor), tolerance);
    ok = ~LaneMask{};
    for (int i = 0; i < 4; ++i) {
        const Lane w = (((k[4 * i] * x[0] + k[4 * i + 1] * x[1]) + k[4 * i + 2] * x[2]) +
                        k[4 * i + 3] * x[3]) +
                       c[i];
        const LaneMask activeOk = ~greater(Lane{}, x[i]) & ~greater(magnitude(w), tolerance);
        const LaneMask inactiveOk = ~greater(-tolerance, w) | ~hasPoint[i];
        ok &= (active[i] & activeOk) | (~active[i] & inactiveOk);
    }
}

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

namespace {

// Two lanes: the width of the x86-64 baseline's registers, whose interleaving loads and stores
// move two bodies' values at once.
using Pair = double __attribute__((vector_size(16)));

[[gnu::always_inline]] inline Pair loadPair(const Real* from) {
    Pair p;
    __builtin_memcpy(&p, from, sizeof(Pair));
    return p;
}

[[gnu::always_inline]] inline void storePair(Real* to, Pair p) {
    __builtin_memcpy(to, &p, sizeof(Pair));
}

}  // namespace

// Each lane's body velocity loaded two values at a time and interleaved into the lanes: element
// by element, the loads and inserts were 6 % of a pyramid's step. Lanes 0 and 2 (1 and 3) are
// joined into one vector first, so one unpack forms a whole lane of values: in the AVX2 clone
// that is a 256-bit unpack, where the baseline's two-lane unpacks took twice the instructions
// (gather and scatter, 123 and 118 instructions a bundle, were 4 % of pyramid-20's). Moves
// only: the same bits.
TUMBLE_LANE_KERNEL void ContactRows::gather(const Bundle& bundle, Lane (&v)[2][6]) const {
    gatherLanes(bundle, v);
}

// gather's body, inline so that gatherFriction's copies take it in.
[[gnu::always_inline]] inline void ContactRows::gatherLanes(const Bundle& bundle,
                                                            Lane (&v)[2][6]) const {
    for (int side = 0; side < 2; ++side) {
        const std::array<std::uint32_t, 4>& body = side == 0 ? bundle.bodyA : bundle.bodyB;
        const Real* lane[4];
        for (int i = 0; i < 4; ++i)
            lane[i] = velocities_[body[i]].v;
        for (int k = 0; k < 6; k += 2) {
            const Lane even =
                __builtin_shufflevector(loadPair(lane[0] + k), loadPair(lane[2] + k), 0, 1, 2, 3);
            const Lane odd =
                __builtin_shufflevector(loadPair(lane[1] + k), loadPair(lane[3] + k), 0, 1, 2, 3);
            v[side][k] = __builtin_shufflevector(even, odd, 0, 4, 2, 6);
            v[side][k + 1] = __builtin_shufflevector(even, odd, 1, 5, 3, 7);
        }
    }
}

// A body in two lanes of a bundle cannot move (colouring): every lane writes its unchanged
// velocity back. Lane by lane, A before B, as the element-wise stores were: the same last
// writer for each value.
TUMBLE_LANE_KERNEL void ContactRows::scatter(const Bundle& bundle, const Lane (&v)[2][6]) {
    scatterLanes(bundle, v);
}

// scatter's body, inline so that solveNormals' copies take it in: called, it was a call from
// the AVX2 copy to the AVX2 copy with its vzeroupper and four spilled lanes around it.
[[gnu::always_inline]] inline void ContactRows::scatterLanes(const Bundle& bundle,
                                                             const Lane (&v)[2][6]) {
    Pair rows[4][2][3];  // lane, side, pair of values
    for (int side = 0; side < 2; ++side) {
        for (int k = 0; k < 6; k += 2) {
            // (lane 0's pair, lane 2's) and (lane 1's, lane 3's)
            const Lane even = __builtin_shufflevector(v[side][k], v[side][k + 1], 0, 4, 2, 6);
            const Lane odd = __builtin_shufflevector(v[side][k], v[side][k + 1], 1, 5, 3, 7);
            rows[0][side][k / 2] = __builtin_shufflevector(even, even, 0, 1);
            rows[2][side][k / 2] = __builtin_shufflevector(even, even, 2, 3);
            rows[1][side][k / 2] = __builtin_shufflevector(odd, odd, 0, 1);
            rows[3][side][k / 2] = __builtin_shufflevector(odd, odd, 2, 3);
        }
    }
    // Through the vector, its data pointer was loaded again after every body's stores.
    Velocity* const velocities = velocities_.data();
    for (int lane = 0; lane < 4; ++lane) {
        Real* a = velocities[bundle.bodyA[lane]].v;
        for (int k = 0; k < 3; ++k)
            storePair(a + 2 * k, rows[lane][0][k]);
        Real* b = velocities[bundle.bodyB[lane]].v;
        for (int k = 0; k < 3; ++k)
            storePair(b + 2 * k, rows[lane][1][k]);
    }
}

Real ContactRows::sweep(std::span<SolverBody> bodies, std::span<ContactConstraint> constraints,
                        std::span<NormalFactor> factors, const SolverSettings& settings, Real bias,
                        Real inverseH, bool soft, bool resident, bool patches) {
    // No contact rows (a net in flight): copying every body's velocity in and out again changes
    // nothing, and was 5 % of the net-10 step (10 sweeps over 101 bodies).
    if (bundles_.empty())
        return 0;
    // Back-to-back sweeps (no springs, joints or exact groups between them): velocities_ still
    // holds what the last one stored, bit for bit (the copy in: 0.4 % of pyramid-20).
    for (std::size_t i = 0; i < (resident ? 0 : bodies.size()); ++i) {
        for (int k = 0; k < 3; ++k) {
            velocities_[i].v[k] = bodies[i].linearVelocity[k];
            velocities_[i].v[3 + k] = bodies[i].angularVelocity[k];
        }
    }
    Real largestChange = 0;
    for (Bundle& bundle : bundles_) {
        Lane v[2][6];
        if (!patches && !soft) {
            // The default step's sweep: no patches, no lanes held.
            largestChange = std::max(largestChange, gatherFriction(bundle, settings, v));
            if (bundle.angular) {
                scatter(bundle, v);
                largestChange = std::max(
                    largestChange, solveAngular(bundle, bodies, constraints, settings.relaxation));
                gather(bundle, v);
            }
            largestChange = std::max(
                largestChange,
                solveNormals(bundle, constraints, factors, settings, bias, inverseH, soft, v));
            continue;
        }
        gather(bundle, v);
        const unsigned slid =
            patches && bundle.maxPoints > 1 && settings.friction == FrictionModel::Coupled
                ? slidePatches(bundle, bodies, settings, soft, ~0u, v)
                : 0u;
        // The biased sweep leaves the points' rows of exactly solved groups to the relax sweep
        // (ContactSolver::softSweep), and those of a face whose patch slid (slide_patch.cpp).
        if (patches && soft)
            bundle.slidBiased = slid;
        const bool relax = patches && !soft;  // the soft step's relax sweep
        unsigned held = soft ? slid : 0u;
        for (int lane = 0; soft && bundle.grouped && lane < bundle.laneCount; ++lane)
            held |= bundle.normals[lane] ? 0u : 1u << lane;
        largestChange =
            std::max(largestChange, held != 0 ? solveFrictionHolding(bundle, settings, v, held)
                                              : solveFriction(bundle, settings, v));
        if (bundle.angular && !relax) {
            scatter(bundle, v);
            largestChange = std::max(
                largestChange, solveAngular(bundle, bodies, constraints, settings.relaxation));
            gather(bundle, v);
        }
        largestChange = std::max(largestChange, solveNormals(bundle, constraints, factors, settings,
                                                             bias, inverseH, soft, v));
        if (relax) {
            largestChange = std::max(
                largestChange, relaxAfterNormals(bundle, bodies, constraints, settings, slid, v));
        }
    }
    for (std::size_t i = 0; i < bodies.size(); ++i) {
        for (int k = 0; k < 3; ++k) {
            bodies[i].linearVelocity[k] = velocities_[i].v[k];
            bodies[i].angularVelocity[k] = velocities_[i].v[3 + k];
        }
    }
    return largestChange;
}

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

// The soft relax sweep after its normal rows (solveNormals stored the velocities): the lone
// points' friction again (the lanes of one point whose normal rows it solves, the others held),
// the angular rows, and the faces whose patch slid solved again (ContactSolver::softSweep,
// slide_patch.cpp say why). Out of line: in ContactRows::sweep, the lanes' test took the default
// step's sweep 6-16 % more of its own instructions (pyramid-20).
[[gnu::noinline]] Real ContactRows::relaxAfterNormals(Bundle& bundle,
                                                      std::span<const SolverBody> bodies,
                                                      std::span<ContactConstraint> constraints,
                                                      const SolverSettings& settings, unsigned slid,
                                                      Lane (&v)[2][6]) {
    Real largestChange = 0;
    unsigned lone = 0;
    for (int lane = 0; lane < bundle.laneCount; ++lane)
        lone |= bundle.points[lane] == 1 && bundle.normals[lane] ? 1u << lane : 0u;
    if (lone != 0) {
        const unsigned lanes = (1u << bundle.laneCount) - 1;
        gather(bundle, v);
        largestChange = lone != lanes ? solveFrictionHolding(bundle, settings, v, lanes & ~lone)
                                      : solveFriction(bundle, settings, v);
        scatter(bundle, v);
    }
    if (bundle.angular) {
        largestChange =
            std::max(largestChange, solveAngular(bundle, bodies, constraints, settings.relaxation));
    }
    // The faces whose patch slid in either sweep, solved again at these normals: their patch,
    // then their points' rows (slide_patch.cpp says why).
    unsigned again = 0;
    for (int lane = 0; lane < bundle.laneCount; ++lane)
        again |= bundle.normals[lane] ? (slid | bundle.slidBiased) & (1u << lane) : 0u;
    if (again != 0) {
        const unsigned lanes = (1u << bundle.laneCount) - 1;
        gather(bundle, v);
        slidePatches(bundle, bodies, settings, false, again, v);
        largestChange =
            std::max(largestChange, again != lanes
                                        ? solveFrictionHolding(bundle, settings, v, lanes & ~again)
                                        : solveFriction(bundle, settings, v));
        scatter(bundle, v);
    }
    return largestChange;
}

Real ContactRows::solveAngular(Bundle& bundle, std::span<const SolverBody> bodies,
                               std::span<ContactConstraint> constraints, Real omega) {
    Real largestChange = 0;
    for (int lane = 0; lane < bundle.laneCount; ++lane) {
        ContactConstraint& c = constraints[bundle.constraint[lane]];
        if (c.spinMass > 0 || c.rollingActive) {
            largestChange =
                std::max(largestChange, solveAngularAlone(bundle, lane, bodies, c, omega));
        }
    }
    return largestChange;
}

Real ContactRows::solveAngularAlone(Bundle& bundle, int lane, std::span<const SolverBody> bodies,
                                    ContactConstraint& c, Real omega) {
    SolverBody a = bodies[c.bodyA];
    SolverBody b = bodies[c.bodyB];
    Velocity& va = velocities_[c.bodyA];
    Velocity& vb = velocities_[c.bodyB];
    a.linearVelocity = Vec3(va.v[0], va.v[1], va.v[2]);
    a.angularVelocity = Vec3(va.v[3], va.v[4], va.v[5]);
    b.linearVelocity = Vec3(vb.v[0], vb.v[1], vb.v[2]);
    b.angularVelocity = Vec3(vb.v[3], vb.v[4], vb.v[5]);
    for (int i = 0; i < c.pointCount; ++i)
        c.points[i].normalImpulse = points_[bundle.firstPoint + i].normalImpulse[lane];
    const Real change = solveAngularFriction(a, b, c, omega);
    for (int k = 0; k < 3; ++k) {
        va.v[3 + k] = a.angularVelocity[k];
        vb.v[3 + k] = b.angularVelocity[k];
    }
    return change;
}

// The normal block of each lane's manifold, as solveManifoldNormals solves it. In the lanes: a
// manifold of one point, and the block whose last active set (the points carrying load) is the
// one factored -- the first set solveNormalBlock tries, solved with the same factor; the
// inactive rows of the embedded factor are the identity with a zero right-hand side, so they
// stay zero. A lane whose set changed, or whose answer fails the set's checks, is solved alone.
// A pyramid's four-point bundles have their own copy: the loops over the points without their
// tests of the count (pyramid-20: ~30 of the kernel's ~720 instructions a bundle).
TUMBLE_LANE_KERNEL Real ContactRows::solveNormals(Bundle& bundle,
                                                  std::span<ContactConstraint> constraints,
                                                  std::span<NormalFactor> factors,
                                                  const SolverSettings& settings, Real bias,
                                                  Real inverseH, bool soft, Lane (&v)[2][6]) {
    if (bundle.maxPoints == 4) {
        return solveNormalsLanes<4>(bundle, constraints, factors, settings, bias, inverseH, soft,
                                    v);
    }
    return solveNormalsLanes<0>(bundle, constraints, factors, settings, bias, inverseH, soft, v);
}

// kPoints: the bundle's point slots, or 0 for bundle.maxPoints.
template <int kPoints>
[[gnu::always_inline]] inline Real ContactRows::solveNormalsLanes(
    Bundle& bundle, std::span<ContactConstraint> constraints, std::span<NormalFactor> factors,
    const SolverSettings& settings, Real bias, Real inverseH, bool soft, Lane (&v)[2][6]) {
    const Lane omega = splat(settings.relaxation);
    const Lane biasH = splat(bias * inverseH);
    Lane dv[3];
    for (int k = 0; k < 3; ++k)
        dv[k] = v[1][k] - v[0][k];
    const Lane normalDv = dot(bundle.normal, dv);
    // The bundle's point slots from one pointer: indexed through the vector, each access
    // formed firstPoint + i and its 1,888-byte offset again.
    Point* const slots = points_.data() + bundle.firstPoint;
    // Slots past maxPoints are empty in every lane (zero impulses, rows and block entries).
    // The arrays' zeros past them are stored one by one, in the loops: initialised as `= {}`,
    // each array was a rep stos (17 instructions by callgrind, five a call: 6 % of the kernel).
    const int points = kPoints > 0 ? kPoints : bundle.maxPoints;
    Lane old[4];
    for (int i = 0; i < 4; ++i)
        old[i] = i < points ? slots[i].normalImpulse : Lane{};
    // v_n - target of point i with the current impulses. Only the block's lanes read those of
    // points past the first, so they are formed in its branch: formed here, GCC sank their
    // arithmetic into it but left their loads here, 30 lanes through spill slots a bundle.
    const auto gapAt = [&](int i) {
        const Point& q = slots[i];
        const Lane target = (q.targetBase + biasH * q.depth) - q.correction;
        const Lane speed = (normalDv + dot(q.angularB, v[1] + 3)) - dot(q.angularA, v[0] + 3);
        return select(bundle.hasPoint[i], speed - target, Lane{});
    };
    const Lane gap0 = points > 0 ? gapAt(0) : Lane{};
    // Only a bundle of several points, or one measuring the change, has a block.
    Block* const block = bundle.block == Bundle::kNoBlock ? nullptr : &blocks_[bundle.block];
    // Per lane whose normal rows this sweep solves (a manifold with points: hasPoint[0]; none
    // past laneCount): the guessed set, the points that carry load. In the lanes, as masks:
    // lane by lane, these tests were 3 % of a pyramid's step.
    const LaneMask solved = bundle.solved;
    const LaneMask several = solved & bundle.hasPoint[1];
    const LaneMask single = solved & ~bundle.hasPoint[1];
    LaneMask active[4];
    LaneMask guess{};
    for (int i = 0; i < 4; ++i) {
        active[i] = solved & bundle.hasPoint[i] & greater(old[i], Lane{});
        guess |= active[i] & (LaneMask{} + (1 << i));
    }
    const LaneMask factorSet{bundle.factorSet[0], bundle.factorSet[1], bundle.factorSet[2],
                             bundle.factorSet[3]};
    const LaneMask fast = several & ((guess == 0) | (guess == factorSet));
    LaneMask alone = several & ~fast;
    Lane next[4];
    LaneMask update = single;
    if (any(fast)) {
        const Lane* k = block->block;
        Lane c[4];  // the gaps with no normal impulse
        for (int i = 0; i < 4; ++i) {
            c[i] =
                i < points
                    ? (i == 0 ? gap0 : gapAt(i)) -
                          (((k[4 * i] * old[0] + k[4 * i + 1] * old[1]) + k[4 * i + 2] * old[2]) +
                           k[4 * i + 3] * old[3])
                    : Lane{};
        }
        Lane x[4];
        solveFactoredLanes(block->factor, block->inverseDiagonal, c, active, x);
        LaneMask ok;
        checkActiveSetLanes(k, bundle.hasPoint, c, active, x, ok);
        alone |= fast & ~ok;
        if (soft) {
            for (int i = 0; i < points; ++i)
                x[i] = x[i] * soft_[bundle.firstPoint + i].scale;
        }
        for (int i = 0; i < 4; ++i)
            next[i] = positivePart(old[i] + omega * (x[i] - old[i]));
        update |= fast & ok;
    } else {
        next[0] = next[1] = next[2] = next[3] = Lane{};
    }
    if (points > 0) {
        const Lane mass = slots[0].normalMass;
        Lane one;
        if (soft) {
            const Lane scaled = soft_[bundle.firstPoint].scale * (old[0] - mass * gap0);
            one = positivePart(old[0] + omega * (scaled - old[0]));
        } else {
            one = positivePart(old[0] - (omega * mass) * gap0);
        }
        next[0] = select(single, one, next[0]);
    }
    Lane delta[4];
    Lane linearA[4];  // m_A^-1 delta, m_B^-1 delta
    Lane linearB[4];
    for (int i = 0; i < 4; ++i) {
        if (i >= points) {
            delta[i] = Lane{};
            continue;
        }
        delta[i] = select(update, next[i] - old[i], Lane{});
        linearA[i] = bundle.inverseMassA * delta[i];
        linearB[i] = bundle.inverseMassB * delta[i];
    }
    // Each velocity value takes the points' changes in point order, as one point after another
    // did, but is loaded and stored once: with the impulses' stores between the points (which
    // might have aliased v), every value went through memory at every point, and m^-1 delta was
    // formed again for each of the three axes.
    // Stored before the velocities' update, which then reads v again after these stores (they
    // might alias it), where it kept the values read for the gaps, six of them in spill slots.
    for (int i = 0; i < points; ++i)
        slots[i].normalImpulse = select(update, next[i], old[i]);
    for (int j = 0; j < 3; ++j) {
        Lane a = v[0][j];
        Lane b = v[1][j];
        Lane angularA = v[0][3 + j];
        Lane angularB = v[1][3 + j];
        for (int i = 0; i < points; ++i) {
            const Point& q = slots[i];
            a -= linearA[i] * bundle.normal[j];
            angularA -= delta[i] * q.impulseA[j];
            b += linearB[i] * bundle.normal[j];
            angularB += delta[i] * q.impulseB[j];
        }
        v[0][j] = a;
        v[0][3 + j] = angularA;
        v[1][j] = b;
        v[1][3 + j] = angularB;
    }
    scatterLanes(bundle, v);
    Real largestChange = 0;
    if (settings.tolerance > 0) {
        const Lane* k = block->block;
        for (int i = 0; i < points; ++i) {
            const Lane change =
                ((k[4 * i] * delta[0] + k[4 * i + 1] * delta[1]) + k[4 * i + 2] * delta[2]) +
                k[4 * i + 3] * delta[3];
            largestChange = std::max(largestChange, largestLane(absolute(change)));
        }
    }
    // Most bundles have no such lane: one test, not one a lane.
    if (!any(alone))
        return largestChange;
    for (int lane = 0; lane < bundle.laneCount; ++lane) {
        if (alone[lane] != 0) {
            const std::uint32_t index = bundle.constraint[lane];
            largestChange = std::max(
                largestChange, solveNormalsAlone(bundle, lane, constraints[index], factors[index],
                                                 settings, bias, inverseH, soft));
        }
    }
    return largestChange;
}

Real ContactRows::solveNormalsAlone(Bundle& bundle, int lane, ContactConstraint& c,
                                    NormalFactor& factor, const SolverSettings& settings, Real bias,
                                    Real inverseH, bool soft) {
    SolverBody a;
    SolverBody b;
    Velocity& va = velocities_[c.bodyA];
    Velocity& vb = velocities_[c.bodyB];
    a.linearVelocity = Vec3(va.v[0], va.v[1], va.v[2]);
    a.angularVelocity = Vec3(va.v[3], va.v[4], va.v[5]);
    a.inverseMass = bundle.inverseMassA[lane];
    b.linearVelocity = Vec3(vb.v[0], vb.v[1], vb.v[2]);
    b.angularVelocity = Vec3(vb.v[3], vb.v[4], vb.v[5]);
    b.inverseMass = bundle.inverseMassB[lane];
    for (int i = 0; i < c.pointCount; ++i)
        c.points[i].normalImpulse = points_[bundle.firstPoint + i].normalImpulse[lane];
    Real change = 0;
    if (softTargets_) {
        // The constraint keeps the step's separations: the substep's ones only for this solve.
        std::array<Real, 4> start{};
        for (int i = 0; i < c.pointCount; ++i) {
            start[i] = c.points[i].separation;
            c.points[i].separation = soft_[bundle.firstPoint + i].separation[lane];
        }
        const Real* scale = soft ? &softScales_[c.bodyA == 0 || c.bodyB == 0 ? 2 : 1] : nullptr;
        tumble::solveNormals(a, b, c.normal, &c.normalBlock, c.points.data(), c.pointCount, factor,
                             settings, inverseH, bias, change, scale);
        for (int i = 0; i < c.pointCount; ++i)
            c.points[i].separation = start[i];
    } else {
        solveManifoldNormals(a, b, c, factor, settings, inverseH, bias, change);
    }
    for (int k = 0; k < 3; ++k) {
        va.v[k] = a.linearVelocity[k];
        va.v[3 + k] = a.angularVelocity[k];
        vb.v[k] = b.linearVelocity[k];
        vb.v[3 + k] = b.angularVelocity[k];
    }
    for (int i = 0; i < c.pointCount; ++i)
        points_[bundle.firstPoint + i].normalImpulse[lane] = c.points[i].normalImpulse;
    // The factor it cached, embedded in the identity.
    Block& block = blocks_[bundle.block];
    Lane* embedded = block.factor;
    for (int e = 0; e < 16; ++e)
        embedded[e][lane] = e % 5 == 0 ? 1 : 0;
    for (Lane& inverse : block.inverseDiagonal)
        inverse[lane] = 1;
    bundle.factorSet[lane] = factor.set;
    if (factor.set != NormalFactor::kNone) {
        for (int i = 0; i < factor.size; ++i) {
            for (int j = 0; j <= i; ++j)
                embedded[4 * factor.rows[i] + factor.rows[j]][lane] = factor.l[i][j];
            block.inverseDiagonal[factor.rows[i]][lane] = factor.inverseDiagonal[i];
        }
    }
    return change;
}

}  // namespace tumble
