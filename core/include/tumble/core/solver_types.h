#pragma once
/// What the constraint solver and the public API both speak (a shared vocabulary, like math.h):
/// the solver's settings (WorldDef::solver), what it reports (World::solverStats, the solve's
/// stage times in Profile) and the joint types. solver/ reads them; users set and read them
/// through tumble/world.h, which includes this header.

#include <cstdint>

#include "tumble/core/math.h"

namespace tumble {

enum class FrictionModel : std::uint8_t {
    Coupled,  ///< disc projection: isotropic (default)
    Box,      ///< two independent tangent rows (the study's Bullet)
};

enum class Stabilisation : std::uint8_t {
    SplitImpulse,  ///< pseudo-velocities, never in the real velocity (default)
    Baumgarte,     ///< bias k_erp / h * depth in the velocity rows (Bullet's default)
};

/// How the implicit spring rows are solved (spring_block.h).
enum class SpringSolve : std::uint8_t {
    Direct,     ///< all rows at once by a sparse factorisation: implicit Euler at any stiffness
    Iterative,  ///< Gauss-Seidel next to the contacts: cheaper, wrong when unconverged
};

struct SolverSettings {
    /// PGS sweeps over the velocity rows of a solve of rigid contacts, >= 1. An unconverged
    /// solve lets a column's tilt grow: 20 cubes built exactly fell after 62 s at 8 + 4 and
    /// stand at 10 + 10; built 2 cm out of line they fell within 20 s at 8 + 4 and sway by
    /// centimetres at 10 + 10 (bench/README.md, "A column falls at 8 + 4").
    int iterations = 10;
    /// Split impulse: sweeps without the bias after the biased ones, removing the push-out
    /// velocity, >= 0. Too few leave some of it in the real velocity, and bodies settling under
    /// a push-out bounce (bench/README.md, "The sweep budget").
    int relaxIterations = 10;
    /// A solve that holds links -- springs, joints, thread contacts -- runs at least these
    /// many biased and relax sweeps (the larger of these and the counts above), >= 1 and >= 0:
    /// a hinge's limit overshoots and a net landing on a wall's edge kicks at 8 + 4, not at
    /// 10 + 10. Equal to the contacts' by default; a scene that lowers the contacts' budget
    /// pays for these only where it models links. Their position pass runs
    /// linkIterations sweeps too.
    int linkIterations = 10;
    int linkRelaxIterations = 10;
    Real tolerance = 0;   ///< (m/s), >= 0: stop early when no impulse changes a velocity
                          ///< by more than this in a sweep; 0 runs the full budget
    Real relaxation = 1;  ///< successive over-relaxation factor, in (0, 2)
    FrictionModel friction = FrictionModel::Coupled;
    Stabilisation stabilisation = Stabilisation::SplitImpulse;
    Real baumgarte = 0.2;  ///< k_erp, dimensionless, in [0, 1]
    Real splitImpulseFactor =
        0.2;  ///< fraction of the depth beyond the slop removed per step by split impulse, (0, 1]
    Real slop = 0.005;  ///< penetration left alone (m), >= 0
    Real restitutionThreshold =
        1;                  ///< approach speed below which contacts are inelastic (m/s), >= 0
    bool warmStart = true;  ///< start from the cached impulses
    SpringSolve springSolve = SpringSolve::Direct;
    /// Post-stabilisation of implicit springs: after the positions move, remove the length a
    /// spring gained by turning within the step, which the linearised solve cannot see (see
    /// SolveStage::projectSprings). Off reproduces the plain linearised implicit step.
    bool projectSprings = true;
    /// Implicit geometric stiffness of joints' point rows for the motion a step cannot resolve
    /// (see applyJointGeometricStiffness); off reproduces the explicit lever arms.
    bool jointGeometricStiffness = true;
    /// Ball joints' point rows: one exact sparse block solve per sweep (buildJointBlockRows)
    /// or Gauss-Seidel with the other joint rows.
    SpringSolve jointSolve = SpringSolve::Direct;
    /// Friction anchors (split impulse; the soft step: once, after its substeps): a sticking
    /// manifold's points are pulled back to where they stuck, so a box on a turning platform
    /// stays on its spot instead of creeping outward (engine/src/anchor_table.h). On by default
    /// since the 5,000-body soak pile sleeps with them (8.12 s; off 8.65 s).
    bool frictionAnchors = true;
    /// The contact sweeps on wide rows of four manifolds coloured so that none of a colour
    /// share a moving body (contact_rows.h): the same rows, coloured so that every body meets
    /// its manifolds in constraint order, so the same bits as the scalar sweep (ContactSolver,
    /// off). A step whose rows would be mostly padding (a lone column, a pile of one-point
    /// manifolds) takes the scalar sweep. On by default: pyramid-20 0.64x the scalar sweep's
    /// time, the rest unchanged (bench/README.md, the colour order).
    bool colouredContacts = true;
    /// Box2D v3's soft step (docs/ARCHITECTURE.md, "The soft step"), opt-in: > 0 collides once
    /// per step and runs this many substeps of one soft biased sweep, the positions, and one
    /// rigid relax sweep, with gravity at h / softSubsteps, on the rows colouredContacts picks;
    /// iterations, relaxIterations and tolerance are then unused; anchors act once a step. 0
    /// (default): the sweeps above. A world with springs or joints keeps the sweeps. >= 0; > 0
    /// only with WorldDef::substeps = 1 (one count of substeps per step; the World refuses both).
    int softSubsteps = 0;
    /// Soft step: natural frequency of a contact between two moving bodies (Hz), > 0; twice it
    /// against a static body; at most a quarter of the substep rate.
    Real contactHertz = 30;
    Real contactDampingRatio = 10;  ///< soft step: of the contact's spring-damper, >= 0
    Real maxPushOutSpeed = 3;       ///< soft step: fastest removal of penetration (m/s), > 0
};

enum class JointType : std::uint8_t {
    Ball,      ///< point coincidence: 3 linear rows
    Hinge,     ///< ball + 2 angular rows: rotation about one axis only (revolute)
    Slider,    ///< 2 linear + 3 angular rows: translation along one axis only (prismatic)
    Fixed,     ///< ball + 3 angular rows: weld
    Distance,  ///< one row along the line between the anchors: rod (equality) or rope (max)
};

/// Wall-clock time of each stage of one constraint solve (s), in the order the stages run
/// (ConstraintSolver::solve).
struct SolverProfile {
    double prepare = 0;    ///< effective masses and warm start of every row; the springs' and ball
                           ///< joints' block factorisations
    double velocity = 0;   ///< the velocity sweeps (biased under split impulse)
    double relax = 0;      ///< split impulse's sweeps without the bias
    double residual = 0;   ///< the complementarity residual measured after the sweeps (bounces
                           ///< are targets of the contact rows, solved in the sweeps)
    double positions = 0;  ///< split impulse's position pass of the joints

    SolverProfile& operator+=(const SolverProfile& other) {
        prepare += other.prepare;
        velocity += other.velocity;
        relax += other.relax;
        residual += other.residual;
        positions += other.positions;
        return *this;
    }
};

/// What a solve reports.
struct SolverStats {
    int iterations = 0;           ///< velocity sweeps actually run
    Real maxResidual = 0;         ///< largest complementarity residual after the solve (m/s)
    Real deepestPenetration = 0;  ///< largest -separation at the start of the step (m), >= 0
};

}  // namespace tumble
