// The soft step (SolverSettings::softSubsteps; docs/ARCHITECTURE.md, "The soft step").
#include <algorithm>

#include "integrator.h"
#include "solve_stage.h"
#include "tumble/core/timed.h"

namespace tumble {

SolverStats SolveStage::runSoft(BodyStore& bodies, const ShapeStore& shapes,
                                ContactManager& contacts, const StepContext& context,
                                const SolverSettings& settings) {
    softRun_ = true;
    softProfile_ = {};
    pseudo_.clear();  // the substeps move the bodies themselves
    const int n = settings.softSubsteps;
    // Every sweep of the budget runs (the rows, scalar or coloured, take softTargets' targets).
    SolverSettings rows = settings;
    rows.tolerance = 0;
    SolverStats stats;
    std::span<ContactConstraint> constraints;
    const bool anchored = settings.frictionAnchors;
    const AnchorLengths lengths = AnchorLengths::of(settings.slop, contacts.contactMargin);
    softProfile_.prepare = timed([&] {
        loadSolverBodies(bodies, context.h / n);
        softJumps_.clear();
        softStartBodies_.clear();
        if (!kinematicChanges_.empty()) {
            softJumps_.assign(solverBodies_.size(), PseudoVelocity{});
            for (const KinematicChange& k : kinematicChanges_)
                softJumps_[solverBodyIndex(bodies, k.body)] = k.change;
            kinematicChanges_.clear();  // a step of several substeps: its first only
        }
        constraints = buildConstraints(bodies, shapes, contacts, context);
        if (anchored)
            seatSoftAnchors(bodies, contacts, constraints, lengths);
        // The cache holds the step's sums: each substep starts from its share of them.
        const Real share = Real(1) / n;
        for (ContactConstraint& c : constraints) {
            c.angularImpulse *= share;
            for (int i = 0; i < c.pointCount; ++i) {
                // Each body's lever reaches its own surface point, s / 2 either side of the
                // manifold's midpoint: a soft contact sags (g / w^2), and a ball rolling on the
                // midpoint's lever, r - sag / 2, rolled down the rolling-resistance case's slope
                // 5.4e-4 too slowly (4 substeps, 30 Hz). Along the normal: the normal rows keep
                // their angular parts, and the default step (rigid, shallow) its bits.
                const Vec3 half = (0.5 * c.points[i].separation) * c.normal;
                c.points[i].rA -= half;
                c.points[i].rB += half;
                c.points[i].normalImpulse *= share;
                c.points[i].tangentImpulse[0] *= share;
                c.points[i].tangentImpulse[1] *= share;
            }
        }
        ContactSolver& solver = solver_.contacts();
        if (!softJumps_.empty())
            softStartBodies_.assign(solverBodies_.begin(), solverBodies_.end());
        stats.deepestPenetration = solver.prepare(solverBodies_, constraints, context.h, rows);
        solver.beginSoft(constraints, softJumps_, softStartBodies_);
    });
    // Into the stages as the default step's: velocity (integration, warm start, biased sweep,
    // bounces), relax (the sweep without bias), positions (the substeps' positions, the bounces'
    // lift, the anchor pass). No residual is measured (0).
    softSubsteps(bodies, constraints, context, rows);
    stats.iterations = n;
    softProfile_.positions += timed([&] {
        if (anchored)
            holdSoftAnchors(bodies, constraints, context, lengths);
    });
    storeImpulses(contacts, constraints, anchored);
    return stats;
}

void SolveStage::noteKinematicChanges(const BodyStore& bodies, bool soft) {
    kinematicChanges_.clear();
    for (std::size_t k = 0; soft && k < bodies.awake.size(); ++k) {
        const std::uint32_t i = bodies.awake[k];
        if (bodies.info[i].type != BodyType::Kinematic)
            continue;
        const BodyMotion& now = bodies.motion[i];
        const BodyMotion& before = bodies.previousMotion[i];  // as the last step began
        if (now.linearVelocity != before.linearVelocity ||
            now.angularVelocity != before.angularVelocity)
            kinematicChanges_.push_back({i,
                                         {now.linearVelocity - before.linearVelocity,
                                          now.angularVelocity - before.angularVelocity}});
    }
}

// The anchors' drifts as the default step's (holdAnchors): at the step's start, where the
// manifold's points were collided, plus what the substeps slid them by and the bend of the
// points' paths as the substeps turned them (addSoftSlips). The substeps' friction rows hold
// velocities on the levers of the step's start, as Box2D v3's and Jolt's (neither holds places), so
// sticking points still stray (without anchors the slab's cube of
// SceneSolver.FrictionAnchorsFromTheFile... crept 36 mm in 2 s at 3 x 45). Measured from the
// anchors' places after the substeps instead, the drift held the cycloid along which a rolling
// ball's material points leave its contact, R theta^3 / 6 a step, and the pass slowed validate's
// rolling-resistance ball on its slope by 1.8e-3 (limit 1e-6).
void SolveStage::seatSoftAnchors(const BodyStore& bodies, const ContactManager& contacts,
                                 std::span<const ContactConstraint> constraints,
                                 const AnchorLengths& lengths) {
    anchors_.beginSolve();
    anchorDrifts_.assign(4 * constraints.size(), Vec3::Zero());
    // No bend predicted here (h = 0): addSoftSlips adds the one the substeps' turn made. Nor
    // the default step's re-seat of stale anchors: these drifts are not yet what the pass aims at.
    for (std::size_t j = 0; j < constraints.size(); ++j)
        anchorDrift(bodies, contacts, j, constraints[j], 0, lengths, false);
}

// What the substeps' velocities, those the positions move with, slid each point by on the
// levers of the step's start (m): the soft rows' one iteration a substep leaves some slip that
// the default step's sweeps do not, and the drifts are to hold it too. Linear in the velocities,
// so once from the bodies' summed displacements (moved_: translation and summed turn), not
// from each substep's (that was 2.7 % of a soft pyramid's step). Not the anchors' places after
// the substeps: those part along the cycloid of a rolling ball's material points,
// R theta^3 / 6, which no slip made (see seatSoftAnchors).
//
// Plus the bend of the material points' paths, theta x (theta x r) / 2 of the summed turn
// (with a constant spin the default step's w x (w x r) h^2 / 2). Predicted from the spin of the
// step's start instead, it took what the soft normal rows leave: a cylinder rolling at 100
// rad/s on its line contact tips at ~1e-3 rad/s, which bent the line's ends by
// +-20 w_x h^2 / 2 along the roll; the pass yawed it, the yaw tipped it more (x1.4 a step), and
// at 10 m/s it rolled backwards after 4 s (3 x 45; RollingHalfSpaceSteps).
void SolveStage::addSoftSlips(std::span<const ContactConstraint> constraints) {
    for (std::size_t j = 0; j < constraints.size(); ++j) {
        const ContactConstraint& c = constraints[j];
        const BodyDisplacement& a = moved_[c.bodyA];
        const BodyDisplacement& b = moved_[c.bodyB];
        for (int i = 0; i < c.pointCount; ++i) {
            const Vec3 turnedB = b.turn.cross(c.points[i].rB);
            const Vec3 turnedA = a.turn.cross(c.points[i].rA);
            const Vec3 d = (b.translation + turnedB + 0.5 * b.turn.cross(turnedB)) -
                           (a.translation + turnedA + 0.5 * a.turn.cross(turnedA));
            anchorDrifts_[4 * j + i] += d - d.dot(c.normal) * c.normal;
        }
    }
}

// Once a step, after the substeps, through one displacement: the default step's anchor pass,
// whose pseudo-velocities move positions only. A manifold whose summed friction reached its
// limit slides and is left out (release() seats it afresh when it sticks again).
void SolveStage::holdSoftAnchors(BodyStore& bodies, std::span<const ContactConstraint> constraints,
                                 const StepContext& context, const AnchorLengths& lengths) {
    addSoftSlips(constraints);
    slipping_.resize(constraints.size());
    for (std::size_t j = 0; j < constraints.size(); ++j) {
        slipping_[j] = AnchorTable::slips(constraints[j]) ? 1 : 0;
        if (slipping_[j] != 0)
            std::fill_n(&anchorDrifts_[4 * j], 4, Vec3::Zero());
    }
    pseudo_.assign(solverBodies_.size(), PseudoVelocity{});
    anchorPass_.run(solverBodies_, constraints, anchorDrifts_, pseudo_, context.inverseH, lengths);
    displaceBodies(bodies, std::span<const PseudoVelocity>(pseudo_).subspan(1), context.h);
    pseudo_.clear();
}

// Per substep, as Box2D v3's solver stages: velocities (gravity at h / n), the warm start (the
// first is prepare's), one soft biased sweep at the separations where the bodies stand, the
// positions, one rigid sweep without bias at the new separations. The solver bodies carry the
// velocities; the body store integrates them.
void SolveStage::softSubsteps(BodyStore& bodies, std::span<ContactConstraint> constraints,
                              const StepContext& context, const SolverSettings& settings) {
    const int n = settings.softSubsteps;
    const StepContext sub{context.h / n, context.inverseH * n, context.gravity};
    const SoftContact soft = softContact(settings, sub.h);
    ContactSolver& solver = solver_.contacts();
    softStart_.resize(bodies.awake.size());
    for (std::size_t k = 0; k < bodies.awake.size(); ++k)
        softStart_[k] = bodies.motion[bodies.awake[k]].center;
    moved_.assign(solverBodies_.size(), BodyDisplacement{});
    for (int k = 0; k < n; ++k) {
        // The bounces' impacts need the normal acceleration: the first substep's change.
        const bool impacts = k == 0 && solver.softBounces();
        // The kinematic changes' share the bodies still lag by after this substep.
        const Real remaining = Real(n - 1 - k) / n;
        softProfile_.velocity += timed([&] {
            storeVelocities(bodies);
            if (impacts)
                softChange_.assign(solverBodies_.size(), SolverBody{});
            for (std::size_t b = 0; impacts && b < bodies.awake.size(); ++b) {
                const BodyMotion& m = bodies.motion[bodies.awake[b]];
                softChange_[1 + b].linearVelocity = -m.linearVelocity;
                softChange_[1 + b].angularVelocity = -m.angularVelocity;
            }
            // The applied forces and torques (the user's, drag's: summed once a step, at the
            // step's start, unlike gravity, a field) give the step's whole impulse h F in the first
            // substep and none after. Spread at h / n over substeps that move the body, a force
            // held from the start pose moved it by h^2 F (n + 1) / (2 n m): a spring F = -m w^2 x
            // got x' = x + h v - (n + 1) / (2n) (w h)^2 x, v' = v - h w^2 x, det 1 + (n - 1) / (2n)
            // (w h)^2 > 1, and gained energy at every w h (validate's oscillator: amplitude
            // error 2.4 at w h = 0.01, n = 3). First: v_1 = v + h F / m, kept by the n - 1 others,
            // so x' = x + h v + h^2 F / m, v' = v + h F / m, the default step's semi-implicit Euler
            // (det 1: it keeps v^2 + w^2 x^2 - h w^2 x v). Torques alike, the impulse at the
            // start's orientation as in the default step, then the substeps' torque-free midpoint
            // rule (it keeps w'Iw and |Iw|): a spin about a principal axis turns h w' a step.
            // Damping stays per substep: det (1 + c h / n)^-n < 1, still dissipative.
            integrateVelocities(bodies, sub, k == 0 ? Real(n) : Real(0));
            for (std::size_t b = 0; b < bodies.awake.size(); ++b) {
                const BodyMotion& m = bodies.motion[bodies.awake[b]];
                solverBodies_[1 + b].linearVelocity = m.linearVelocity;
                solverBodies_[1 + b].angularVelocity = m.angularVelocity;
                if (impacts) {
                    softChange_[1 + b].linearVelocity += m.linearVelocity;
                    softChange_[1 + b].angularVelocity += m.angularVelocity;
                }
            }
            if (impacts) {
                meanForcesChange(bodies, context.h - sub.h);
                solver.softImpacts(softChange_, constraints, context.h, sub.h,
                                   settings.restitutionThreshold);
            }
            if (k > 0)
                solver.softWarmStart(solverBodies_, constraints);
            solver.softTargets(constraints, solverBodies_, moved_, soft, sub.inverseH, remaining,
                               true, false);
            solver.softSweep(solverBodies_, constraints, settings, sub.inverseH, &soft);
            storeVelocities(bodies);
        });
        softProfile_.positions += timed([&] {
            integratePositions(bodies, {}, sub);
            measureDisplacements(bodies, sub.h);
        });
        softProfile_.relax += timed([&] {
            solver.softTargets(constraints, solverBodies_, moved_, soft, sub.inverseH, remaining,
                               false, k == n - 1);
            solver.softSweep(solverBodies_, constraints, settings, sub.inverseH, nullptr);
            solver.endSoftSubstep(constraints);
        });
    }
    softProfile_.velocity += timed([&] {
        softLift_.resize(solverBodies_.size());
        solver.endSoft(solverBodies_, constraints, moved_, softLift_, soft.slop, sub.inverseH);
        storeVelocities(bodies);
    });
    softProfile_.positions += timed([&] {
        if (solver.softBounces())
            displaceBodies(bodies, std::span<const PseudoVelocity>(softLift_).subspan(1), 1);
    });
}

// The bounces predict the impact from a constant acceleration over the step, read from the
// first substep's change: the forces' share of it is a substep's, h F / (n m), not the whole
// impulse the substep took (read as n F / m). Exact without damping and the gyroscopic term,
// which act on the first substep's velocity after the impulse.
void SolveStage::meanForcesChange(const BodyStore& bodies, Real beyond) {
    for (std::size_t b = 0; b < bodies.awake.size(); ++b) {
        const std::uint32_t i = bodies.awake[b];
        if (bodies.info[i].type != BodyType::Dynamic)
            continue;
        const BodyForces& f = bodies.forces[i];
        const BodyInertia& inertia = bodies.inertia[i];
        softChange_[1 + b].linearVelocity -= beyond * (inertia.inverseMass * f.force);
        if (bodies.info[i].fixedRotation)
            continue;
        const Mat3 rotation = bodies.motion[i].orientation.toRotationMatrix();
        softChange_[1 + b].angularVelocity -=
            beyond * (rotation * torqueAcceleration(inertia, rotation, f.torque));
    }
}

void SolveStage::measureDisplacements(const BodyStore& bodies, Real h) {
    for (std::size_t k = 0; k < bodies.awake.size(); ++k) {
        const BodyMotion& now = bodies.motion[bodies.awake[k]];
        BodyDisplacement& d = moved_[1 + k];
        d.translation = now.center - softStart_[k];
        d.turn += h * now.angularVelocity;  // what integratePositions turned it by
    }
}

}  // namespace tumble
