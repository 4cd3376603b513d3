#pragma once
/// The solve stage: contacts -> solver rows -> constrained velocities and split-impulse
/// pseudo-velocities, with impulses written back to the contact cache for warm starting.

#include <span>
#include <vector>

#include "body_store.h"
#include "shape_store.h"
#include "step_context.h"
#include "tumble/contact.h"
#include "tumble/solver/contact_solver.h"

namespace tumble {

class SolveStage {
public:
    /// Solves every contact with points; body velocities in `bodies` are updated, and
    /// pseudoVelocities() holds the split-impulse velocities for integratePositions.
    SolverStats run(BodyStore& bodies, const ShapeStore& shapes, std::span<Contact> contacts,
                    const StepContext& context, const SolverSettings& settings);

    std::span<const PseudoVelocity> pseudoVelocities() const { return pseudo_; }

private:
    ContactSolver solver_;
    std::vector<SolverBody> solverBodies_;
    std::vector<ContactConstraint> constraints_;
    std::vector<std::uint32_t> constraintContact_;  ///< contact index of each constraint
    std::vector<PseudoVelocity> pseudo_;
};

/// Mixing rules for a pair of materials: friction by geometric mean (a frictionless surface
/// makes any pair frictionless), restitution by the maximum (a bouncy ball bounces on anything).
Real mixFriction(Real a, Real b);
Real mixRestitution(Real a, Real b);

}  // namespace tumble
