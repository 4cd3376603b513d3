#pragma once
/// The acceleration a bouncing point sees from the supports of its bodies.
///
/// Restitution places the bounce on the parabola of the point's normal motion under the step's
/// normal acceleration a (ContactSolver::prepare, impactWithinStep): the impact speed is the
/// parabola's, and the rebound continues it for the rest of the step. The engine computes a from
/// the step's forces alone, so for a ball falling on a box that rests on the ground it saw the
/// box fall with the ball (a = 0, not -g), and the ball's rebound came out ~(1 + e) g h / 2 slow:
/// 3-5 % of the bounce height at h = 1/240. What holds the box is the other contacts' impulses,
/// which the warm start of this step is the best estimate of. This adds, to each point of a
/// manifold that can bounce, the normal acceleration that the warm-start impulses of all the
/// OTHER manifolds give its two bodies: at rest on the ground the box's own support cancels its
/// weight exactly. The same support also stops the box's fall within the step, so the point's
/// speed at the end of the step before contact, from which the impact is found, includes it too
/// (ContactConstraintPoint::supportSpeed).

#include <span>
#include <vector>

#include "tumble/solver/contact_solver.h"

namespace tumble {

/// When and how fast a point hits within a step (impactWithinStep).
struct Impact {
    Real time = 0;   ///< within the step (s)
    Real speed = 0;  ///< normal velocity then (m/s), of the parabola of the point's motion
};

/// The impact of a point at separation s (m) under a constant normal acceleration a, given its
/// normal velocity vEnd at the end of a step of h before contact (contact_solver.cpp).
Impact impactWithinStep(Real s, Real vEnd, Real a, Real h);

/// For every constraint with restitution > 0, sets its points' supportSpeed to the normal velocity
/// change the warm-start impulses of the other constraints give (m/s) and adds that / h to their
/// normalAcceleration (m/s^2); zero elsewhere. Called with warm starting on and some restitution
/// (otherwise every supportSpeed is zero, which prepare sets itself). Uses the cached impulses as
/// they come in; `scratch` holds the bodies' velocity changes (grows only).
void addSupportAcceleration(std::span<const SolverBody> bodies,
                            std::span<ContactConstraint> constraints, Real h,
                            std::vector<SolverBody>& scratch);

}  // namespace tumble
