#pragma once
/// The constraint solve of one step: every row -- implicit springs, joints, contacts -- on one
/// set of solver bodies, in a fixed list of stages (solve()), each timed into a SolverProfile:
///
///   prepare    effective masses and warm start of every row, bounces (restitution targets
///              of the contact rows), the contact groups solved exactly; the springs' and the
///              ball joints' block factorisations; the joints' geometric stiffness
///   velocity   `iterations` PGS sweeps: springs, joints, contacts (biased under split impulse);
///              `linkIterations` if larger and the solve holds springs, joints or thread contacts
///   relax      split impulse: `relaxIterations` (or `linkRelaxIterations`) sweeps without the
///              bias; the difference is the pseudo-velocity
///   residual   the contacts' complementarity residual after the sweeps
///   positions  split impulse's position pass of the joints, the thread contacts and the
///              contacts without pushOut on the pseudo-velocities
///
/// The rows' own derivations are with them: contact_solver.h, spring_row.h and spring_block.h,
/// joint_row.h. Deterministic: every row kind is solved in array order, in the same order in
/// every sweep.

#include <cstdint>
#include <span>
#include <vector>

#include "tumble/core/solver_types.h"
#include "tumble/solver/contact_solver.h"
#include "tumble/solver/joint_row.h"
#include "tumble/solver/segment_contact_row.h"
#include "tumble/solver/solver_body.h"
#include "tumble/solver/spring_block.h"
#include "tumble/solver/spring_row.h"
#include "tumble/solver/sprung_push_out.h"

namespace tumble {

class ConstraintSolver {
public:
    /// Solves the rows for one step of length h. `bodies` hold the velocities after forces;
    /// on return they hold the constrained velocities, `pseudo` the split-impulse velocities
    /// (zero under Baumgarte) to add when integrating positions only. Impulses are written back
    /// into `constraints` for warm starting the next step. Allocates only when the arrays grow.
    /// Implicit spring rows (spring_row.h), when given, are solved first in every biased and
    /// relax sweep alike (they are forces, not stabilisation); their impulses are written back.
    /// Joint rows (joint_row.h), when given, are solved after the springs and before the
    /// contacts in every sweep, with the same bias as the contacts; impulses written back.
    /// Segment contact rows (segment_contact_row.h), when given, are solved after the contacts
    /// in every sweep, as contacts; impulses written back.
    SolverStats solve(std::span<SolverBody> bodies, std::span<ContactConstraint> constraints,
                      std::vector<PseudoVelocity>& pseudo, Real h, const SolverSettings& settings,
                      std::span<SpringRow> springs = {}, std::span<JointRow> joints = {},
                      std::span<SegmentContactRow> segments = {});
    /// Time of each stage of the last solve.
    const SolverProfile& profile() const { return profile_; }
    /// The contact rows alone, for the soft step (SolveStage::runSoft runs its substeps; the
    /// solver's stages above are not used).
    ContactSolver& contacts() { return contacts_; }

private:
    /// The prepare stage; returns the deepest penetration (m).
    Real prepare(std::span<SolverBody> bodies, std::span<ContactConstraint> constraints,
                 std::span<SpringRow> springs, std::span<JointRow> joints, Real h,
                 const SolverSettings& settings);
    /// The relax stage: fills `pseudo` (split impulse) or zeroes it (Baumgarte).
    void relax(std::span<SolverBody> bodies, std::span<ContactConstraint> constraints,
               std::span<SpringRow> springs, std::vector<PseudoVelocity>& pseudo,
               const SolverSettings& settings, Real inverseH);
    /// Runs up to `sweeps` PGS sweeps with the given bias factor; returns the number run.
    int runSweeps(std::span<SolverBody> bodies, std::span<ContactConstraint> constraints,
                  std::span<SpringRow> springs, const SolverSettings& settings, Real inverseH,
                  Real bias, int sweeps);
    /// Split impulse's position pass for the joints (solveJointPositions), the contacts without
    /// pushOut (SprungPushOut) and the thread contacts (solveSegmentPositions) on `pseudo`.
    void correctPositions(std::span<const SolverBody> bodies,
                          std::span<const ContactConstraint> constraints,
                          std::vector<PseudoVelocity>& pseudo, Real inverseH,
                          const SolverSettings& settings);

    /// After the relax sweeps (split impulse): the normal rows of the contacts without pushOut
    /// (net nodes' and other sprung bodies') solved exactly against the spring block, then the
    /// springs once more (sprung_contacts.cpp).
    void settleSprungContacts(std::span<SolverBody> bodies,
                              std::span<ContactConstraint> constraints,
                              std::span<SpringRow> springs, const SolverSettings& settings,
                              Real inverseH);

    ContactSolver contacts_;
    SolverProfile profile_;
    SpringBlockSolver springBlock_;
    bool directSprings_ = false;             ///< this step's springs go through springBlock_
    std::span<JointRow> joints_;             ///< of the solve in progress
    std::span<SegmentContactRow> segments_;  ///< of the solve in progress
    std::span<const SpringRow> springs_;     ///< of the solve in progress
    std::vector<ThreadPull> threadPulls_;    ///< solveSegmentPositions' scratch
    bool segmentPositions_ = false;          ///< their push-out goes to a position pass
    int biasedSweeps_ = 0;                   ///< this solve's budget: the links' when it holds any
    int relaxSweeps_ = 0;
    Real jointBias_ = 0;                    ///< their bias in the velocity sweeps (Baumgarte only)
    std::vector<Mat3> geometricStiffness_;  ///< scratch of applyJointGeometricStiffness
    SpringBlockSolver jointBlock_;          ///< ball joints' point rows (jointSolve Direct)
    std::vector<SpringRow> jointBlockRows_;
    bool directJoints_ = false;             ///< this step's ball joints go through jointBlock_
    std::vector<SolverBody> pseudoBodies_;  ///< the joints' position pass works on these
    SprungPushOut sprungPushOut_;           ///< the contacts without pushOut, this step
    // settleSprungContacts' scratch.
    struct SprungPoint {
        std::uint32_t index = 0;  ///< of the constraint, or of the segment row
        int point = 0;            ///< in the constraint
        bool segment = false;
    };
    Real sprungSpeed(std::span<const SolverBody> bodies,
                     std::span<const ContactConstraint> constraints,
                     const SprungPoint& point) const;
    void applySprung(std::span<SolverBody> bodies, std::span<const ContactConstraint> constraints,
                     const SprungPoint& point, Real lambda) const;
    /// Calls f with each body a point's normal row moves.
    template <class F>
    void forEachSprungBody(std::span<const ContactConstraint> constraints, const SprungPoint& point,
                           F&& f) const;
    /// Keeps the kMostRows points furthest from complementarity (sprung_contacts.cpp).
    void keepWorstSprung();
    std::vector<SprungPoint> sprungPoints_;
    std::vector<Real> sprungResidual_;        ///< each point's complementarity residual (m/s)
    std::vector<std::uint32_t> sprungOrder_;  ///< keepWorstSprung's scratch
    std::vector<Real> sprungMatrix_;    ///< W, column-major: v_n of point k per unit impulse at j
    std::vector<Real> sprungGap_;       ///< v_n - target of each point (m/s)
    std::vector<Real> sprungDelta_;     ///< the impulse added at each point (N s)
    std::vector<SolverBody> response_;  ///< velocity changes of one unit impulse
};

}  // namespace tumble
