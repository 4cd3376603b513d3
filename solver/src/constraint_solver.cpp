#include "tumble/solver/constraint_solver.h"

#include <algorithm>

#include "tumble/core/timed.h"

namespace tumble {

SolverStats ConstraintSolver::solve(std::span<SolverBody> bodies,
                                    std::span<ContactConstraint> constraints,
                                    std::vector<PseudoVelocity>& pseudo, Real h,
                                    const SolverSettings& settings, std::span<SpringRow> springs,
                                    std::span<JointRow> joints,
                                    std::span<SegmentContactRow> segments) {
    segments_ = segments;
    springs_ = springs;
    const Real inverseH = 1 / h;
    const bool split = settings.stabilisation == Stabilisation::SplitImpulse;
    // The thread contacts' push-out in a position pass of their own, not in the biased sweeps:
    // there the spring block, solved exactly in every sweep, carried a row's push at a net's
    // rim to the whole net and a net's skirt on a curved wall never came to rest (~2 mm/s
    // median after 2 s against 0.6 mm/s, thread_rest_test.cpp).
    segmentPositions_ = split && !segments.empty();
    const Real bias = split ? settings.splitImpulseFactor : settings.baumgarte;
    const Real velocityBias = split ? 0 : bias;  // what stays in the real velocity
    SolverStats stats;
    profile_.prepare = timed([&] {
        const Real held = split ? sprungPushOut_.hold(constraints, settings.slop) : 0;
        stats.deepestPenetration =
            std::max(held, prepare(bodies, constraints, springs, joints, h, settings));
        jointBias_ = velocityBias;
    });
    // Links converge more slowly than rigid contacts: a solve holding any runs the links' budget
    // if it is the larger (SolverSettings::linkIterations).
    const bool links =
        !springs.empty() || !joints.empty() || !segments.empty() || !sprungPushOut_.empty();
    biasedSweeps_ =
        links ? std::max(settings.iterations, settings.linkIterations) : settings.iterations;
    relaxSweeps_ = links ? std::max(settings.relaxIterations, settings.linkRelaxIterations)
                         : settings.relaxIterations;
    profile_.velocity = timed([&] {
        stats.iterations =
            runSweeps(bodies, constraints, springs, settings, inverseH, bias, biasedSweeps_);
    });
    profile_.relax =
        timed([&] { relax(bodies, constraints, springs, pseudo, settings, inverseH); });
    contacts_.finish(constraints);
    // The sprung contacts converged with the springs, the step still ending on the springs
    // (sprung_contacts.cpp): runSweeps' last spring solve pushed net nodes back into their
    // contacts, and the push-out that took them out again stretched the threads at rest.
    if (split && directSprings_ && springBlock_.ready()) {
        profile_.relax +=
            timed([&] { settleSprungContacts(bodies, constraints, springs, settings, inverseH); });
    }
    profile_.residual = timed([&] {
        stats.maxResidual =
            contacts_.residual(bodies, constraints, settings, inverseH, velocityBias);
    });
    profile_.positions = timed([&] {
        if (split && (!joints.empty() || segmentPositions_ || !sprungPushOut_.empty()))
            correctPositions(bodies, constraints, pseudo, inverseH, settings);
    });
    sprungPushOut_.restore(constraints);
    return stats;
}

Real ConstraintSolver::prepare(std::span<SolverBody> bodies,
                               std::span<ContactConstraint> constraints,
                               std::span<SpringRow> springs, std::span<JointRow> joints, Real h,
                               const SolverSettings& settings) {
    if (settings.jointGeometricStiffness && !joints.empty())
        applyJointGeometricStiffness(bodies, joints, h, geometricStiffness_);
    const Real deepestPenetration = contacts_.prepare(bodies, constraints, h, settings);
    prepareSegmentContacts(bodies, segments_, settings.warmStart);
    directSprings_ = settings.springSolve == SpringSolve::Direct && !springs.empty();
    // The block solve prepares a slack thread when it reads it (spring_row.h); Gauss-Seidel
    // reads every row.
    prepareSpringRows(bodies, springs, h, settings.warmStart, directSprings_);
    if (directSprings_)
        springBlock_.prepare(bodies, springs, h);
    joints_ = joints;
    prepareJointRows(bodies, joints_, h, settings.warmStart);
    directJoints_ = false;
    if (settings.jointSolve == SpringSolve::Direct && !joints.empty()) {
        buildJointBlockRows(bodies, joints_, jointBlockRows_);
        jointBlock_.prepare(bodies, jointBlockRows_);
        directJoints_ = jointBlock_.ready();
        if (!directJoints_) {
            for (JointRow& row : joints_)
                row.blockSolved = false;
        }
    } else {
        for (JointRow& row : joints_)
            row.blockSolved = false;
    }
    return deepestPenetration;
}

void ConstraintSolver::relax(std::span<SolverBody> bodies, std::span<ContactConstraint> constraints,
                             std::span<SpringRow> springs, std::vector<PseudoVelocity>& pseudo,
                             const SolverSettings& settings, Real inverseH) {
    const bool split = settings.stabilisation == Stabilisation::SplitImpulse;
    pseudo.resize(bodies.size());
    for (std::size_t i = 0; i < bodies.size(); ++i) {
        pseudo[i].linear = split ? bodies[i].linearVelocity : Vec3::Zero();
        pseudo[i].angular = split ? bodies[i].angularVelocity : Vec3::Zero();
    }
    if (split) {
        // The bounce's position correction is part of the push-out: the relax sweeps aim at the
        // rebound alone, so it ends up in the pseudo-velocity (normalTarget).
        contacts_.dropBounceCorrections(constraints);
        // Springs alone, solved exactly, and no contact, thread contact or joint has moved their
        // bodies since: the relax sweeps would solve the block once more for a change of
        // rounding size (more only where the first solve's active set did not settle), a block
        // solve per step (~6 % of a free net's). Skipped, the pseudo-velocities are zero.
        const bool springsOnly = directSprings_ && springBlock_.ready() && constraints.empty() &&
                                 segments_.empty() && joints_.empty();
        if (!springsOnly)
            runSweeps(bodies, constraints, springs, settings, inverseH, 0, relaxSweeps_);
        for (std::size_t i = 0; i < bodies.size(); ++i) {
            pseudo[i].linear -= bodies[i].linearVelocity;
            pseudo[i].angular -= bodies[i].angularVelocity;
        }
    }
    // The last sweep is done: the ball joints' block impulses are final.
    if (directJoints_)
        storeJointBlockImpulses(joints_, jointBlockRows_);
}

void ConstraintSolver::correctPositions(std::span<const SolverBody> bodies,
                                        std::span<const ContactConstraint> constraints,
                                        std::vector<PseudoVelocity>& pseudo, Real inverseH,
                                        const SolverSettings& settings) {
    loadPseudoBodies(bodies, pseudo, pseudoBodies_);
    if (!joints_.empty())
        solveJointPositions(pseudoBodies_, joints_, settings.splitImpulseFactor, inverseH,
                            biasedSweeps_);
    if (!sprungPushOut_.empty())
        sprungPushOut_.solve(pseudoBodies_, constraints, settings.splitImpulseFactor, inverseH,
                             settings.slop, biasedSweeps_);
    if (segmentPositions_)
        solveSegmentPositions(pseudoBodies_, segments_, springs_, threadPulls_,
                              settings.splitImpulseFactor, inverseH, settings.slop, biasedSweeps_);
    storePseudoBodies(pseudoBodies_, pseudo);
}

int ConstraintSolver::runSweeps(std::span<SolverBody> bodies,
                                std::span<ContactConstraint> constraints,
                                std::span<SpringRow> springs, const SolverSettings& settings,
                                Real inverseH, Real bias, int sweeps) {
    // Only the contacts change the bodies between two contact sweeps: they may keep their copy.
    const bool contactsAlone =
        springs.empty() && joints_.empty() && segments_.empty() && !directJoints_;
    for (int sweep = 0; sweep < sweeps;) {
        // Springs first, contacts last: non-penetration matters most. The springs' rows take no
        // bias, so they are solved the same way in the biased and in the relax sweeps. Solved
        // exactly, they need solving again only when contacts have moved their bodies.
        Real springChange = 0;
        if (!directSprings_ || !springBlock_.ready())
            springChange = solveSpringRows(bodies, springs, settings.relaxation);
        else if (sweep == 0 || !constraints.empty() || !segments_.empty())
            springChange = springBlock_.solve(bodies, springs);
        if (directJoints_) {
            updateJointBlockTargets(bodies, joints_, jointBlockRows_, jointBias_, inverseH);
            springChange = std::max(springChange, jointBlock_.solve(bodies, jointBlockRows_));
        }
        springChange = std::max(springChange, solveJointRows(bodies, joints_, settings.relaxation,
                                                             jointBias_, inverseH));
        const Real contactChange =
            std::max(contacts_.solveVelocitySweep(bodies, constraints, settings, inverseH, bias,
                                                  contactsAlone && sweep > 0),
                     solveSegmentContacts(bodies, segments_, inverseH, segmentPositions_ ? 0 : bias,
                                          settings.slop));
        const Real largestChange = std::max(springChange, contactChange);
        ++sweep;
        if (settings.tolerance > 0 && largestChange <= settings.tolerance)
            return sweep;
    }
    // End on the springs: after the last contact sweep moved their bodies, the stiff rows would
    // otherwise act on stale velocities -- partly explicit at omega_e h >> 2 -- and a net
    // resting across gaps in a pile was pumped into a 0.1-0.2 m/s vibration that never let it
    // sleep at 10 sweeps (20 converge). The factorisation is reused: one more solve.
    if (directSprings_ && springBlock_.ready() && (!constraints.empty() || !segments_.empty()))
        springBlock_.solve(bodies, springs);
    return sweeps;
}

}  // namespace tumble
