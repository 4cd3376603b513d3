#include "tumble/solver/sweep_rows.h"

#include <algorithm>
#include <bit>

#include "contact_kernels.h"
#include "normal_block.h"
#include "slide_patch.h"
#include "tumble/core/lane_kernel.h"
#include "tumble/solver/contact_solver.h"

namespace tumble {
namespace {

using Vec2 = Eigen::Matrix<Real, 2, 1>;

// Two lanes (GCC/Clang vector extension, the x86-64 baseline's register): the friction's two
// tangent rows side by side.
using Pair = double __attribute__((vector_size(16)));

[[gnu::always_inline]] inline Pair loadPair(const Real* from) {
    Pair p;
    __builtin_memcpy(&p, from, sizeof(Pair));
    return p;
}

// The two rows' dot products with v, u . v = (u_x v_x + u_y v_y) + u_z v_z as Eigen forms it for
// a Vec3, in the two lanes: row by row, each took its own horizontal sum.
// v's x and y are read as one pair, as Eigen's packets read a Vec3: mixed with scalar reads of
// the same bytes, they kept GCC from holding the bodies' angular velocities in registers (each
// manifold stored them to the stack and loaded them back in pieces).
[[gnu::always_inline]] inline Pair dotPair(const std::array<std::array<Real, 2>, 3>& rows,
                                           const Vec3& v) {
    const Pair xy = loadPair(v.data());
    const Pair x = {xy[0], xy[0]};
    const Pair y = {xy[1], xy[1]};
    return (loadPair(rows[0].data()) * x + loadPair(rows[1].data()) * y) +
           loadPair(rows[2].data()) * v.z();
}

// A manifold's body while its rows are solved: a local copy of what the rows read and write.
// Through references into the bodies' array, every point's velocity update was a store that the
// next point loaded back (the compiler cannot keep them in registers past the points' own
// stores, which might alias): a store-to-load delay per point on the sweep's critical path, a
// lone column being one chain of manifolds. The values and operations are the same.
struct SweepBody {
    static constexpr Real kStaticMass = 0;
    Vec3 linearVelocity = Vec3::Zero();
    Vec3 angularVelocity = Vec3::Zero();
    /// The body's own, read where it is used: copied, it was parked on the stack for the
    /// manifold (a store and a load for each body).
    const Real& inverseMass = kStaticMass;

    /// The static body 0 (SolverBody{}, every field +0: SweepRows::sweepPlain checks its bits):
    /// constants, so its velocities are not loaded and v - 0 folds to v.
    SweepBody() = default;
    explicit SweepBody(const SolverBody& body)
        : linearVelocity(body.linearVelocity),
          angularVelocity(body.angularVelocity),
          inverseMass(body.inverseMass) {}
    void load(const SolverBody& body) {
        linearVelocity = body.linearVelocity;
        angularVelocity = body.angularVelocity;
    }
    void store(SolverBody& body) const {
        body.linearVelocity = linearVelocity;
        body.angularVelocity = angularVelocity;
    }
};

// The friction rows of one manifold's points (contact_solver.h): coupled on the disc, or the
// box model with its masses from the constraint. Returns the largest change when measuring.
// The model and the measuring are template arguments, and the manifold's basis is held in
// locals: the points' stores might alias it, so it was loaded again for every point.
// kPoints: the manifold's point count when known at compile time (SweepRows::sweepWith), else 0.
// kMovesA: as applyNormal's (normal_block.h).
template <bool kCoupled, bool kMeasure, int kPoints, bool kMovesA>
Real solveFriction(SweepBody& a, SweepBody& b, const SweepManifold& m, SweepPoint* points,
                   const ContactConstraint& c, Real omega) {
    Real largestChange = 0;
    const Pair target = loadPair(m.tangentTarget.data());
    const Real friction = m.friction;
    const int count = kPoints > 0 ? kPoints : m.pointCount;
    for (int i = 0; i < count; ++i) {
        SweepPoint& p = points[i];
        // v_t(k) = (t_k . dv + (rB x t_k) . wB - (rA x t_k) . wA) - target_k
        const auto slip = [&] {
            const Vec3 dv = b.linearVelocity - a.linearVelocity;
            const Pair s =
                ((dotPair(m.tangentAxes, dv) + dotPair(p.tangentAngularB, b.angularVelocity)) -
                 dotPair(p.tangentAngularA, a.angularVelocity)) -
                target;
            return Vec2(s[0], s[1]);
        };
        const Vec2 old(p.tangentImpulse[0], p.tangentImpulse[1]);
        const Real limit = friction * p.normalImpulse;
        Vec2 next;
        Vec2 delta;
        if constexpr (kCoupled) {
            if (limit > 0) {
                solveRelaxedDisc(p.tangent, old, slip(), limit, omega, next, delta);
            } else {
                // No load (a third of pile-1000's one-point manifolds): solveRelaxedDisc's
                // answer 0, relaxed, which needs neither the slip nor the block. Tested first,
                // the slip's rows are not loaded (and spilled) for it.
                next = Vec2(old(0) + omega * (0 - old(0)), old(1) + omega * (0 - old(1)));
                delta = Vec2(next(0) - old(0), next(1) - old(1));
            }
        } else {
            const Vec2 vt = slip();
            const std::array<Real, 2>& mass = c.points[i].tangentMass;
            next = (old - omega * Vec2(mass[0] * vt(0), mass[1] * vt(1)))
                       .cwiseMax(-limit)
                       .cwiseMin(limit);
            delta = next - old;
        }
        // delta_1 t_1 + delta_2 t_2, coefficient by coefficient as Eigen forms it, read from the
        // basis by axis: m.tangents()'s two vectors were assembled on the stack for it (six
        // instructions a manifold on pile-1000).
        const std::array<std::array<Real, 2>, 3>& axes = m.tangentAxes;
        const Vec3 linear(delta.x() * axes[0][0] + delta.y() * axes[0][1],
                          delta.x() * axes[1][0] + delta.y() * axes[1][1],
                          delta.x() * axes[2][0] + delta.y() * axes[2][1]);
        if constexpr (kMovesA) {
            a.linearVelocity -= a.inverseMass * linear;
            a.angularVelocity -=
                delta.x() * p.tangentImpulseA[0] + delta.y() * p.tangentImpulseA[1];
        }
        b.linearVelocity += b.inverseMass * linear;
        b.angularVelocity += delta.x() * p.tangentImpulseB[0] + delta.y() * p.tangentImpulseB[1];
        p.tangentImpulse = {next.x(), next.y()};
        if constexpr (kMeasure)
            largestChange = std::max(largestChange, (p.tangent.block * delta).norm());
    }
    return largestChange;
}

// What a sweep reads of the settings, read once: the points' stores might alias the settings,
// so their fields were loaded again for every manifold.
struct SweepSettings {
    bool coupled;  ///< FrictionModel::Coupled
    bool measure;  ///< tolerance > 0
    Real omega;    ///< relaxation
    Real slop;     ///< (m)
};

template <int kPoints, bool kMovesA>
Real solveFriction(SweepBody& a, SweepBody& b, const SweepManifold& m, SweepPoint* points,
                   const ContactConstraint& c, const SweepSettings& s) {
    if (s.coupled) {
        return s.measure
                   ? solveFriction<true, true, kPoints, kMovesA>(a, b, m, points, c, s.omega)
                   : solveFriction<true, false, kPoints, kMovesA>(a, b, m, points, c, s.omega);
    }
    return s.measure ? solveFriction<false, true, kPoints, kMovesA>(a, b, m, points, c, s.omega)
                     : solveFriction<false, false, kPoints, kMovesA>(a, b, m, points, c, s.omega);
}

// The soft step's patch of a manifold of several points (slide_patch.h), on the sweep's copies:
// `solve` (slidePatch) on them, kept when it returns true. Out of line: inlined,
// it grew SweepRows::sweep until GCC called the normal rows' kernel out of line, +16 % on the
// default step's sweeps (pile-1000), which never take a patch.
template <class Solve>
[[gnu::noinline]] bool onPatch(SweepBody& a, SweepBody& b, const SolverBody& bodyA,
                               const SolverBody& bodyB, const SweepManifold& m, SweepPoint* points,
                               Solve&& solve) {
    std::array<PatchPoint, 4> patch;
    for (int i = 0; i < m.pointCount; ++i) {
        const SweepPoint& p = points[i];
        PatchPoint& q = patch[i];
        q.normalImpulse = p.normalImpulse;
        q.tangentImpulse = p.tangentImpulse;
        for (int k = 0; k < 2; ++k) {
            q.angularA[k] =
                Vec3(p.tangentAngularA[0][k], p.tangentAngularA[1][k], p.tangentAngularA[2][k]);
            q.angularB[k] =
                Vec3(p.tangentAngularB[0][k], p.tangentAngularB[1][k], p.tangentAngularB[2][k]);
            q.impulseA[k] = p.tangentImpulseA[k];
            q.impulseB[k] = p.tangentImpulseB[k];
        }
    }
    PatchBodies bodies{a.linearVelocity,
                       a.angularVelocity,
                       b.linearVelocity,
                       b.angularVelocity,
                       a.inverseMass,
                       b.inverseMass,
                       m.normal.dot(bodyA.inverseInertia * m.normal),
                       m.normal.dot(bodyB.inverseInertia * m.normal)};
    if (!solve(bodies, std::span<PatchPoint>(patch.data(), m.pointCount)))
        return false;
    a.linearVelocity = bodies.linearA;
    a.angularVelocity = bodies.angularA;
    b.linearVelocity = bodies.linearB;
    b.angularVelocity = bodies.angularB;
    for (int i = 0; i < m.pointCount; ++i)
        points[i].tangentImpulse = patch[i].tangentImpulse;
    return true;
}

// Rare: these rows read the constraint, which gets the current normal impulses, and the
// bodies, which get the sweep's velocities.
Real angularRows(SweepBody& a, SweepBody& b, SolverBody& bodyA, SolverBody& bodyB,
                 const SweepManifold& m, const SweepPoint* points,
                 std::span<ContactConstraint> constraints, Real omega) {
    ContactConstraint& c = constraints[m.constraint];
    for (int i = 0; i < m.pointCount; ++i)
        c.points[i].normalImpulse = points[i].normalImpulse;
    a.store(bodyA);
    b.store(bodyB);
    const Real change = solveAngularFriction(bodyA, bodyB, c, omega);
    a.load(bodyA);
    b.load(bodyB);
    return change;
}

// Whether a manifold's patch surely sticks (patchSticks), from the sweep's copies: one pass over
// the points' impulses and slips instead of onPatch's copy of their levers, so a face well short
// of sliding costs little (stack-20's faces all stick: the patch's 3.5 M instructions in 0.5 s at
// 3 x 45 became 0.6 M). Inlined: out of line as onPatch is, pile-1000's soft step took 0.3 % more
// instructions.
[[gnu::always_inline]] inline bool patchSticks(const SweepBody& a, const SweepBody& b,
                                               const SweepManifold& m, const SweepPoint* points) {
    Real total = 0;
    Pair old = {0, 0};
    Pair turn = {0, 0};  // sum N_i ((rB x t_k) . wB - (rA x t_k) . wA)
    for (int i = 0; i < m.pointCount; ++i) {
        const SweepPoint& p = points[i];
        total += p.normalImpulse;
        old += loadPair(p.tangentImpulse.data());
        turn += p.normalImpulse * (dotPair(p.tangentAngularB, b.angularVelocity) -
                                   dotPair(p.tangentAngularA, a.angularVelocity));
    }
    if (!(total > 0))
        return true;  // slidePatch does nothing
    const Pair slip = (dotPair(m.tangentAxes, b.linearVelocity - a.linearVelocity) + turn / total) -
                      loadPair(m.tangentTarget.data());
    return tumble::patchSticks(total, {old[0], old[1]}, {slip[0], slip[1]},
                               a.inverseMass + b.inverseMass, m.friction);
}

// The plain sweep skips body 0's updates, which is exact only while body 0 is the static
// SolverBody{} (every +0: the engine's solver body 0, joints.cpp). A caller whose body 0 moves
// gets the general sweep: the same operations, so the same bits, at its cost.
bool staticBodyZero(std::span<const SolverBody> bodies) {
    if (bodies.empty())
        return false;
    const SolverBody& s = bodies[0];
    const auto zero = [](Real x) { return std::bit_cast<std::uint64_t>(x) == 0; };
    if (!zero(s.inverseMass))
        return false;
    for (int i = 0; i < 3; ++i)
        if (!zero(s.linearVelocity[i]) || !zero(s.angularVelocity[i]))
            return false;
    for (int i = 0; i < 9; ++i)
        if (!zero(s.inverseInertia.data()[i]))
            return false;
    return true;
}

}  // namespace

void SweepRows::clear() {
    manifolds_.clear();
    pointCount_ = 0;
    blocks_.clear();
    grouped_.clear();
    targetsStale_ = true;
}

void SweepRows::add(const ContactConstraint& c, std::uint32_t index,
                    const SolverSettings& settings) {
    SweepManifold& m = manifolds_.emplace_back();
    m.bodyA = c.bodyA;
    m.bodyB = c.bodyB;
    m.constraint = index;
    m.firstPoint = static_cast<std::uint32_t>(pointCount_);
    m.pointCount = static_cast<std::uint8_t>(c.pointCount);
    m.angular = c.spinMass > 0 || c.rollingActive;
    m.grouped = c.normalGroup != NormalIslands::kNone;
    m.normal = c.normal;
    for (int axis = 0; axis < 3; ++axis)
        m.tangentAxes[axis] = {c.tangents[0](axis), c.tangents[1](axis)};
    m.friction = c.friction;
    targetsStale_ = true;
    if (m.grouped)
        grouped_.push_back(static_cast<std::uint32_t>(manifolds_.size() - 1));
    else if (c.pointCount > 1 || settings.tolerance > 0) {
        m.block = static_cast<std::uint32_t>(blocks_.size());
        blocks_.push_back(c.normalBlock);
    }
    for (int i = 0; i < c.pointCount; ++i) {
        const ContactConstraintPoint& q = c.points[i];
        // Every field is written: a slot kept from an earlier step is not zeroed first, as
        // emplace_back() would (the zeroing was 4 % of prepare's instructions on stack-20).
        if (pointCount_ == points_.size())
            points_.emplace_back();
        SweepPoint& p = points_[pointCount_++];
        for (int axis = 0; axis < 3; ++axis) {
            p.tangentAngularA[axis] = {q.tangentAngularA[0](axis), q.tangentAngularA[1](axis)};
            p.tangentAngularB[axis] = {q.tangentAngularB[0](axis), q.tangentAngularB[1](axis)};
        }
        p.tangent = q.tangent;
        p.tangentImpulse = q.tangentImpulse;
        p.normalImpulse = q.normalImpulse;
        p.normalMass = q.normalMass;
        p.tangentImpulseA = q.tangentImpulseA;
        p.tangentImpulseB = q.tangentImpulseB;
        p.angularA = q.angularA;
        p.angularB = q.angularB;
        p.separation = q.separation;
        p.reboundSpeed = q.reboundSpeed;
        p.bounceCorrection = q.bounceCorrection;
        p.angularImpulseA = q.angularImpulseA;
        p.angularImpulseB = q.angularImpulseB;
        p.bounces = q.bounces;
    }
}

Real SweepRows::sweep(std::span<SolverBody> bodies, std::span<ContactConstraint> constraints,
                      std::span<NormalFactor> factors, const SolverSettings& settings,
                      Real inverseH, Real bias, const Real* softScales, bool patches) {
    if (patches)
        return sweepWith<true, false>(bodies, constraints, factors, settings, inverseH, bias,
                                      softScales);
    if (softScales == nullptr && !(settings.tolerance > 0) &&
        settings.friction == FrictionModel::Coupled && staticBodyZero(bodies))
        return sweepPlain(bodies, constraints, factors, settings, inverseH, bias);
    return sweepWith<false, false>(bodies, constraints, factors, settings, inverseH, bias,
                                   softScales);
}

TUMBLE_LANE_KERNEL Real SweepRows::sweepPlain(std::span<SolverBody> bodies,
                                              std::span<ContactConstraint> constraints,
                                              std::span<NormalFactor> factors,
                                              const SolverSettings& settings, Real inverseH,
                                              Real bias) {
    return sweepWith<false, true>(bodies, constraints, factors, settings, inverseH, bias, nullptr);
}

// The default step's sweeps never take a patch: compiled without the patches' branches. Flat
// (sweep_rows.h), since with two callers GCC would call the kernels out of line: the patches'
// branches alone cost +16 % on pile-1000's sweeps, two plain instantiations +14 %.
// Plain: the default step's (no soft scales, not measuring, coupled friction), whose tests on
// them fold.
template <bool Patches, bool Plain>
Real SweepRows::sweepWith(std::span<SolverBody> bodies, std::span<ContactConstraint> constraints,
                          std::span<NormalFactor> factors, const SolverSettings& given,
                          Real inverseH, Real bias, const Real* softScalesGiven) {
    const Real* softScales = Plain ? nullptr : softScalesGiven;
    // A local copy, which the points' stores cannot alias: its fields are not loaded again for
    // every manifold, and a plain sweep's tolerance is known to be 0.
    SolverSettings settings = given;
    if (Plain)
        settings.tolerance = 0;
    Real largestChange = 0;
    // The targets are the same in every sweep of a phase (biased, relax): the first computes
    // them. Compared as bits, so a -0 bias or a NaN is not taken for another value.
    const std::array<std::uint64_t, 3> inputs = {std::bit_cast<std::uint64_t>(bias),
                                                 std::bit_cast<std::uint64_t>(settings.slop),
                                                 std::bit_cast<std::uint64_t>(inverseH)};
    const bool refresh = targetsStale_ || inputs != targetInputs_;
    targetsStale_ = false;
    targetInputs_ = inputs;
    if (Patches && softScales != nullptr)
        slidBiased_.assign(manifolds_.size(), 0);  // capacity kept from step to step
    // Held in a local: the points' stores might alias the vector, so its data pointer was loaded
    // again through `this` for every manifold.
    SweepPoint* const pointData = points_.data();
    const SweepSettings local{Plain || settings.friction == FrictionModel::Coupled,
                              settings.tolerance > 0, settings.relaxation, settings.slop};
    // One manifold's rows, with its point count a constant when kPoints > 0 (0: m.pointCount):
    // the points' loops unroll and the one-point tests fold, the same operations in the same
    // order. Most of a pile's manifolds have one or two points (1.23 on average). kMovesA false:
    // A is the static body 0, whose updates leave it +0 and are skipped (applyNormal); a fifth
    // to a quarter of a pile's manifolds lie on its floor and walls.
    const auto solveManifold = [&]<int kPoints, bool kMovesA>(const SweepManifold& m) {
        const int pointCount = kPoints > 0 ? kPoints : m.pointCount;
        // Not measuring, the friction's change is 0 and leaves the largest as it is.
        const auto friction = [&](SweepBody& a, SweepBody& b, SweepPoint* points) {
            const Real change =
                solveFriction<kPoints, kMovesA>(a, b, m, points, constraints[m.constraint], local);
            if (local.measure)
                largestChange = std::max(largestChange, change);
        };
        SolverBody& bodyA = bodies[m.bodyA];
        SolverBody& bodyB = bodies[m.bodyB];
        SweepBody a = kMovesA ? SweepBody(bodyA) : SweepBody();
        SweepBody b(bodyB);
        SweepPoint* points = pointData + m.firstPoint;
        if (refresh) {
            for (int i = 0; i < pointCount; ++i)
                points[i].target = normalTarget(points[i], bias, local.slop, inverseH);
        }
        // Friction first, with the normal impulses of the last sweep: non-penetration, solved
        // last, matters more. The soft step's biased sweep leaves the friction of exactly
        // solved groups to its relax sweep (ContactSolver::softSweep says why).
        bool slid = false;
        // The soft step's relax sweep solves a lone point's friction again after its normal
        // row, so its bound is the substep's whole normal impulse (ContactSolver::softSweep).
        const bool frictionAgain =
            Patches && softScales == nullptr && pointCount == 1 && !m.grouped;
        if (m.friction > 0 && !(m.grouped && softScales != nullptr)) {
            if (Patches && pointCount > 1 && local.coupled && !patchSticks(a, b, m, points)) {
                slid = onPatch(a, b, bodyA, bodyB, m, points,
                               [&](PatchBodies& on, std::span<PatchPoint> patch) {
                                   return slidePatch(on, m.normal, m.tangents(), m.tangentTarget,
                                                     m.friction, local.omega, patch);
                               });
            }
            // The biased sweep keeps a sliding face's patch: the points' rows would meet the
            // tipping its friction gives before the normal rows hold it, read it as slip
            // reversed at the points and let go of a fifth of the friction (the pushed cube's
            // first substep moved 3e-5 m too far, its velocity right after the relax sweep).
            if (Patches && softScales != nullptr)
                slidBiased_[&m - manifolds_.data()] = slid ? 1 : 0;
            if (!(slid && softScales != nullptr)) {
                friction(a, b, points);
            }
        }
        // The soft step's relax sweep solves them after its normal rows (ContactSolver::softSweep).
        const bool angularLast = Patches && softScales == nullptr;
        if (m.angular && !angularLast) {
            largestChange = std::max(largestChange, angularRows(a, b, bodyA, bodyB, m, points,
                                                                constraints, local.omega));
        }
        if (!m.grouped) {
            const Mat4* block = m.block == SweepManifold::kNoBlock ? nullptr : &blocks_[m.block];
            // The soft step's kinds (SoftContact): 2 against a static body (body 0), else 1.
            const Real* softScale = softScales == nullptr
                                        ? nullptr
                                        : softScales + (m.bodyA == 0 || m.bodyB == 0 ? 2 : 1);
            solveNormals<kMovesA>(a, b, m.normal, block, points, pointCount, factors[m.constraint],
                                  settings, inverseH, bias, largestChange, softScale);
        }
        if (frictionAgain && m.friction > 0) {
            friction(a, b, points);
        }
        if (m.angular && angularLast) {
            largestChange = std::max(largestChange, angularRows(a, b, bodyA, bodyB, m, points,
                                                                constraints, local.omega));
        }
        // A face whose patch slid in either sweep of the substep is solved again at the relax
        // sweep's normals (slide_patch.cpp says why): its patch, then its points' rows. Only such
        // a face: the rest kept their bits (onPatch's gather on every face of several points was
        // a fifth of the patch's cost).
        if (Patches && softScales == nullptr && !m.grouped && m.friction > 0 && pointCount > 1 &&
            local.coupled && (slid || slidBiased_[&m - manifolds_.data()] != 0)) {
            if (!patchSticks(a, b, m, points)) {
                onPatch(a, b, bodyA, bodyB, m, points,
                        [&](PatchBodies& on, std::span<PatchPoint> patch) {
                            return slidePatch(on, m.normal, m.tangents(), m.tangentTarget,
                                              m.friction, local.omega, patch);
                        });
            }
            friction(a, b, points);
        }
        if (kMovesA)
            a.store(bodyA);
        b.store(bodyB);
    };
    // The plain sweep's manifolds whose A is the static body skip its updates; the others take
    // the general code (B was the static body in none of pile-1000's or pile-4000's manifolds).
    const auto solveMoving = [&]<bool kMovesA>(const SweepManifold& m) {
        if (m.pointCount == 1)
            solveManifold.template operator()<1, kMovesA>(m);
        else if (m.pointCount == 2)
            solveManifold.template operator()<2, kMovesA>(m);
        else
            solveManifold.template operator()<0, kMovesA>(m);
    };
    for (const SweepManifold& m : manifolds_) {
        if (Plain && m.bodyA == 0)
            solveMoving.template operator()<false>(m);
        else
            solveMoving.template operator()<true>(m);
    }
    return largestChange;
}

void SweepRows::softTargets(std::span<const Real> separations,
                            std::span<const std::array<Real, 2>> tangentTargets) {
    for (std::size_t k = 0; k < pointCount_; ++k)
        points_[k].separation = separations[k];
    for (SweepManifold& m : manifolds_)
        m.tangentTarget = tangentTargets[m.constraint];
    targetsStale_ = true;
}

void SweepRows::dropBounces() {
    for (SweepPoint& p : points()) {
        p.bounces = false;
        p.bounceCorrection = 0;
    }
    targetsStale_ = true;
}

void SweepRows::warmStart(std::span<SolverBody> bodies,
                          std::span<const ContactConstraint> constraints) {
    for (const SweepManifold& m : manifolds_) {
        SolverBody& a = bodies[m.bodyA];
        SolverBody& b = bodies[m.bodyB];
        const std::array<Vec3, 2> tangents = m.tangents();
        for (int i = 0; i < m.pointCount; ++i)
            warmStartPoint(a, b, m.normal, tangents, points_[m.firstPoint + i]);
        if (m.angular) {
            const Vec3& turn = constraints[m.constraint].angularImpulse;
            a.angularVelocity -= a.inverseInertia * turn;
            b.angularVelocity += b.inverseInertia * turn;
        }
    }
}

void SweepRows::readGroupImpulses(std::span<const ContactConstraint> constraints) {
    for (std::uint32_t index : grouped_) {
        const SweepManifold& m = manifolds_[index];
        const ContactConstraint& c = constraints[m.constraint];
        for (int i = 0; i < m.pointCount; ++i)
            points_[m.firstPoint + i].normalImpulse = c.points[i].normalImpulse;
    }
}

void SweepRows::dropBounceCorrections() {
    for (SweepPoint& p : points())
        p.bounceCorrection = 0;
    targetsStale_ = true;
}

void SweepRows::store(std::span<ContactConstraint> constraints) const {
    for (const SweepManifold& m : manifolds_) {
        ContactConstraint& c = constraints[m.constraint];
        for (int i = 0; i < m.pointCount; ++i) {
            const SweepPoint& p = points_[m.firstPoint + i];
            c.points[i].normalImpulse = p.normalImpulse;
            c.points[i].tangentImpulse = p.tangentImpulse;
        }
    }
}

}  // namespace tumble
