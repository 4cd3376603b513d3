#pragma once
/// The solve stage: contacts -> solver rows -> constrained velocities and split-impulse
/// pseudo-velocities, with impulses written back to the contact cache for warm starting.
///
/// Only awake bodies enter the solver: solver body 0 stands for every static body (at rest,
/// infinite mass, so no impulse changes it) and solver body 1 + k for BodyStore::awake[k]. The
/// islands are not solved one by one: they share no body, so one Gauss-Seidel pass over all
/// active contacts gives each island exactly the result it would get alone.

#include <span>
#include <vector>

#include "anchor_table.h"
#include "body_store.h"
#include "contact_manager.h"
#include "joint_store.h"
#include "shape_store.h"
#include "spring_store.h"
#include "springs.h"
#include "step_context.h"
#include "thread_contacts.h"
#include "tumble/contact.h"
#include "tumble/solver/constraint_solver.h"
#include "tumble/solver/friction_anchors.h"

namespace tumble {

class SolveStage {
    friend struct CheckpointAccess;  ///< checkpoint.cpp saves and restores the anchors

public:
    /// Solves every active contact with points between awake (or static) bodies; velocities of
    /// the awake dynamic bodies are updated, and pseudoVelocities() holds the split-impulse
    /// velocities for integratePositions. Implicit springs with an awake dynamic body at either
    /// end are solved as soft rows with the contacts; their tensions go back into `springs`.
    /// Joints likewise (unless broken); their forces go back into `joints`, and the joints that
    /// broke in this step are listed by brokenJoints().
    SolverStats run(BodyStore& bodies, const ShapeStore& shapes, ContactManager& contacts,
                    SpringStore& springs, JointStore& joints, const StepContext& context,
                    const SolverSettings& settings);
    /// The soft step instead of run() (SolverSettings::softSubsteps > 0; soft_step.cpp): the
    /// contacts of the one collision solved over n substeps of h / n, each integrating the
    /// velocities (gravity, applied forces), one soft biased sweep, the positions, one rigid
    /// relax sweep; restitution once at the end. Moves the bodies itself (no pseudo-velocities,
    /// nothing for integratePositions). The contacts' impulses are the step's sums. No springs
    /// or joints: the world keeps run() for them.
    SolverStats runSoft(BodyStore& bodies, const ShapeStore& shapes, ContactManager& contacts,
                        const StepContext& context, const SolverSettings& settings);
    /// Before the step's rollback state is saved (World::step): the velocity changes the
    /// application gave the kinematic bodies since the last step began, which the next soft
    /// step's friction spreads over its substeps (ContactSolver::beginSoft says why). Kept for
    /// the step's first runSoft only.
    void noteKinematicChanges(const BodyStore& bodies, bool soft);
    /// Time of each of the solver's stages in the last run.
    const SolverProfile& solverProfile() const {
        return softRun_ ? softProfile_ : solver_.profile();
    }
    /// Dense indices of the joints that broke in the last run.
    std::span<const std::uint32_t> brokenJoints() const { return brokenJoints_; }

    /// One per awake body, in BodyStore::awake order (empty if the solver gave none).
    std::span<const PseudoVelocity> pseudoVelocities() const;

    /// Post-stabilisation of the implicit springs, after the positions are integrated. The
    /// solve linearised each spring about the step's start: it held the anchors' separation
    /// along the OLD direction, so a spring that turned within the step ends longer than the
    /// solve believed by L - n0 . d >= 0 (second order in the turn; a 5 cm link whose ends
    /// cross at 2 m/s at h = 1/60 gains 28 %). Stiff elements turn that into energy from
    /// nothing (a falling 40 x 40 net with omega_e h = 20 gained 37x its energy). This removes
    /// the error by one more block solve on positions only, at the new configuration, leaving
    /// velocities as they are -- the nonlinear implicit step approximated one Gauss-Newton
    /// step further. Slack threads are left alone.
    void projectSprings(BodyStore& bodies, const SpringStore& springs, const StepContext& context,
                        const SolverSettings& settings);

private:
    std::span<ContactConstraint> buildConstraints(const BodyStore& bodies, const ShapeStore& shapes,
                                                  const ContactManager& contacts,
                                                  const StepContext& context);
    void loadSolverBodies(const BodyStore& bodies, Real h);
    void storeVelocities(BodyStore& bodies) const;
    void storeImpulses(ContactManager& contacts, std::span<ContactConstraint> constraints,
                       bool anchored);
    /// The soft step's substeps on the prepared constraints (soft_step.cpp).
    void softSubsteps(BodyStore& bodies, std::span<ContactConstraint> constraints,
                      const StepContext& context, const SolverSettings& settings);
    /// Constraint j's (c's) anchors kept or seated and their drifts, over a step h, into
    /// anchorDrifts_ (AnchorTable::drifts; `reseatStale`: the default step's, whose drifts are
    /// complete there). Inline: holdAnchors calls it for every constraint.
    void anchorDrift(const BodyStore& bodies, const ContactManager& contacts, std::size_t j,
                     const ContactConstraint& c, Real h, const AnchorLengths& lengths,
                     bool reseatStale) {
        const ConstraintSource& source = constraintSources_[j];
        anchors_.drifts(source.slot, contacts.contact(source.slot), bodies.motion[source.indexA],
                        bodies.motion[source.indexB], h, c, lengths, reseatStale,
                        &anchorDrifts_[4 * j]);
    }
    /// The soft step's friction anchors (soft_step.cpp): their drifts as the default step's,
    /// at the step's start; after the substeps, the anchor pass as one displacement.
    void seatSoftAnchors(const BodyStore& bodies, const ContactManager& contacts,
                         std::span<const ContactConstraint> constraints,
                         const AnchorLengths& lengths);
    void addSoftSlips(std::span<const ContactConstraint> constraints);
    void holdSoftAnchors(BodyStore& bodies, std::span<const ContactConstraint> constraints,
                         const StepContext& context, const AnchorLengths& lengths);
    /// Takes from softChange_ the applied forces' impulse beyond a substep's share
    /// (`beyond` = h - h / n of it), which the first substep gave.
    void meanForcesChange(const BodyStore& bodies, Real beyond);
    /// Every awake body's displacement since the step began (into moved_), after a substep
    /// of length h.
    void measureDisplacements(const BodyStore& bodies, Real h);
    struct ProjectedGeometry;
    /// Row j's geometry at the new positions, for projectSprings().
    ProjectedGeometry projectedGeometry(const BodyStore& bodies, const SpringStore& springs,
                                        std::size_t j) const;
    /// Row j's anchor B minus anchor A at the new positions (m).
    Vec3 projectedSpan(const BodyStore& bodies, const SpringStore& springs, std::size_t j) const;
    /// projectSprings()'s rows' errors at the new positions (and the geometry of those that may
    /// have one); returns the largest (m).
    Real projectionErrors(const BodyStore& bodies, const SpringStore& springs,
                          const StepContext& context);
    /// sprung_ for this step's solver bodies (split impulse): their contacts push out no depth
    /// in the biased sweeps (ContactConstraint::pushOut, sprung_push_out.h) and hold no anchors.
    /// Reads this step's rowBodies_: after buildSpringRows. Left as it was without contacts.
    void markSprung(const BodyStore& bodies, const SpringStore& springs);
    /// Friction anchors (split impulse): this solve's drifts and the anchor pass on pseudo_.
    /// Contacts of a body a spring holds (sprung_, marked by run()) are left out (see the
    /// definition).
    void holdAnchors(const BodyStore& bodies, const ContactManager& contacts,
                     std::span<const ContactConstraint> constraints, const StepContext& context,
                     const AnchorLengths& lengths);

    ConstraintSolver solver_;
    std::vector<SolverBody> solverBodies_;
    std::vector<ContactConstraint>
        constraints_;  ///< reused: only grows; the first n are this step's
    /// Where each constraint comes from: its contact's slot and its bodies' dense indices, as
    /// buildConstraints looked them up (anchorDrift's lookups by id were 0.5 % of pyramid-20).
    struct ConstraintSource {
        std::uint32_t slot = 0;
        std::uint32_t indexA = 0;
        std::uint32_t indexB = 0;
    };
    std::vector<ConstraintSource> constraintSources_;  ///< by constraint
    std::vector<PseudoVelocity> pseudo_;
    std::vector<SpringRow> springRows_;
    std::vector<std::uint32_t> rowSpring_;  ///< spring index of each row
    std::vector<RowBodies> rowBodies_;      ///< dense body indices of each row
    // projectSprings(): the rows at the new configuration, bodies at rest, the corrections.
    SpringBlockSolver projector_;
    std::vector<SpringRow> projectedRows_;
    /// Each row's geometry at the new configuration: the rows themselves are copied only when
    /// a correction is needed (most steps need none, and a row is ~300 bytes).
    struct ProjectedGeometry {
        Vec3 direction;
        Vec3 rA;
        Vec3 rB;
        Real length;
    };
    std::vector<ProjectedGeometry> projectedGeometry_;
    std::vector<Real> projectionError_;  ///< of each projected row (m)
    std::vector<SolverBody> projectedBodies_;
    std::vector<PseudoVelocity> corrections_;
    ThreadContacts threadContacts_;  ///< rows of the threads touching shapes
    std::vector<JointRow> jointRows_;
    std::vector<std::uint32_t> rowJoint_;  ///< joint index of each row
    std::vector<std::uint32_t> brokenJoints_;
    AnchorTable anchors_;  ///< empty unless SolverSettings::frictionAnchors
    FrictionAnchorPass anchorPass_;
    std::vector<Vec3> anchorDrifts_;  ///< 4 per constraint
    std::vector<char> sprung_;        ///< by solver body: a spring ends on it
    /// By constraint: AnchorTable::slips() as the anchor pass found it (1 slips, 0 sticks), for
    /// storeImpulses' release (taken again there, it was 0.3 % of pyramid-20); kUnmeasured
    /// where the pass left the constraint out without it (a sprung body).
    std::vector<char> slipping_;
    static constexpr char kUnmeasured = 2;
    // The soft step.
    bool softRun_ = false;                  ///< the last solve was a soft step
    SolverProfile softProfile_;             ///< its stages' times
    std::vector<Vec3> softStart_;           ///< awake bodies' centres at the step's start
    std::vector<BodyDisplacement> moved_;   ///< by solver body: since the step's start
    std::vector<SolverBody> softChange_;    ///< by solver body: the first substep's velocity change
    std::vector<PseudoVelocity> softLift_;  ///< by solver body: the bounces' displacements (m)
    struct KinematicChange {
        std::uint32_t body = 0;  ///< dense index
        PseudoVelocity change;   ///< linear (m/s) and angular (rad/s)
    };
    std::vector<KinematicChange> kinematicChanges_;  ///< noteKinematicChanges'
    std::vector<PseudoVelocity> softJumps_;          ///< by solver body: those changes
    std::vector<SolverBody> softStartBodies_;        ///< with them: the step's start velocities
};

/// Solver body 0 is every static body; awake body k is solver body 1 + k.
inline std::uint32_t solverBodyIndex(const BodyStore& bodies, std::uint32_t index) {
    return bodies.info[index].type == BodyType::Static ? 0 : 1 + bodies.info[index].awakeIndex;
}

/// Mixing rules for a pair of materials: friction by geometric mean (a frictionless surface
/// makes any pair frictionless), restitution by the maximum (a bouncy ball bounces on anything).
Real mixFriction(Real a, Real b);
Real mixRestitution(Real a, Real b);

}  // namespace tumble
