// ContactRows' sweep (contact_rows.h): four manifolds per bundle, one per lane. Its friction
// kernels are in contact_rows_friction.cpp, the soft step's patches in contact_rows_patch.cpp.
#include "tumble/solver/contact_rows.h"

#include <algorithm>

#include "contact_kernels.h"
#include "contact_rows_lanes.h"
#include "normal_block.h"
#include "tumble/core/lane_kernel.h"

namespace tumble {

using namespace wide;

namespace {

// |x| with the sign bit cleared: absolute's value but for the sign of a zero or a NaN, which no
// comparison sees. For values only compared (one instruction, where absolute takes three).
[[gnu::always_inline]] inline Lane magnitude(Lane x) {
    return reinterpret_cast<Lane>(reinterpret_cast<LaneMask>(x) &
                                  (LaneMask{} + 0x7fffffffffffffff));
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

// A body in two lanes of a bundle cannot move (colouring): every lane writes its unchanged
// velocity back. Lane by lane, A before B, as the element-wise stores were: the same last
// writer for each value.
TUMBLE_LANE_KERNEL void ContactRows::scatter(const Bundle& bundle, const Lane (&v)[2][6]) {
    scatterLanes(bundle, v);
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
    const bool relax = patches && !soft;  // the soft step's relax sweep
    for (Bundle& bundle : bundles_) {
        Lane v[2][6];
        unsigned slid = 0;
        if (!patches && !soft) {
            // The default step's sweep: no patches, no lanes held.
            largestChange = std::max(largestChange, gatherFriction(bundle, settings, v));
        } else {
            gather(bundle, v);
            slid = patches && bundle.maxPoints > 1 && settings.friction == FrictionModel::Coupled
                       ? slidePatches(bundle, bodies, settings, soft, ~0u, v)
                       : 0u;
            // The biased sweep leaves the points' rows of exactly solved groups to the relax
            // sweep (ContactSolver::softSweep), and those of a face whose patch slid
            // (slide_patch.cpp).
            if (patches && soft)
                bundle.slidBiased = slid;
            unsigned held = soft ? slid : 0u;
            for (int lane = 0; soft && bundle.grouped && lane < bundle.laneCount; ++lane)
                held |= bundle.normals[lane] ? 0u : 1u << lane;
            largestChange =
                std::max(largestChange, held != 0 ? solveFrictionHolding(bundle, settings, v, held)
                                                  : solveFriction(bundle, settings, v));
        }
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