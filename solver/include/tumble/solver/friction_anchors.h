#pragma once
/// What keeps a sticking contact stuck: the friction a manifold carries from step to step
/// (equilibrateFriction) and, optionally, where its points stuck (friction anchors).

#include "tumble/solver/contact_solver.h"

namespace tumble {

/// Removes the self-equilibrated part of a manifold's friction impulses: the part whose forces
/// and moment about the normal add up to zero. It moves no body, so no velocity sweep corrects
/// it, but it is carried to the next step as warm start and counts against each point's Coulomb
/// disc. Gauss-Seidel leaves a little of it every step (the points are solved in turn), and on a
/// cube turning with a kinematic platform it grew until the points were at their limits while
/// the net friction was a fifth of mu sum(lambda_n); the cube then slipped at 0.82 of the
/// friction it could have. What is kept is the distribution of least sum |lambda_t,i|^2 /
/// lambda_n,i with the same net tangential impulse and moment about the normal: every point at
/// the same share of its own disc under a pure pull, as a rigid patch slipping as a whole.
/// The points are taken as one plane, as a manifold's are (the tipping moment of the tangential
/// impulses is then fixed by their sum). Left as solved where that distribution would take a
/// point off its disc (sliding or spinning at the limit). Call after a solve, on the impulses to
/// be carried. Returns whether it changed them (false: c is as it was).
bool equilibrateFriction(ContactConstraint& c);

/// The anchors' lengths, from the scene's own length settings, so that a scene scaled by
/// dynamic similarity (lengths by s: slop, margins) keeps its anchors in proportion: fixed in
/// metres, they made a 1 mm cube land 9.6e-4 of its half side away from a metre cube's pose.
struct AnchorLengths {
    /// A manifold whose anchors all lie within this of each other (m) skips the pass: it is
    /// held in velocity, and resting contacts drift by the solve's residual, far less, so a
    /// pile at rest skips it. slop / 500: 1e-5 m at the default slop.
    Real deadband = 0;
    /// A manifold's anchors are seated afresh once its points moved this far from them (m)
    /// along the surfaces: a sliding manifold that never reaches its limit. 2 slop.
    Real reach = 0;
    /// The most the pass moves a point towards its anchors in one step (m): slop / 3, 1.7 mm
    /// (0.1 m/s at 60 Hz). Unbounded, it removed a landing body's drift of a few mm in one step
    /// with a pull as strong as the impact's disc allows, which turned the body at up to 22 rad/s
    /// of pseudo-velocity: a hull's corner 6.7 cm into a height field (TerrainTunnel), a sphere
    /// under a net rocked for good (StickingFriction.APileUnderANet...).
    Real catchUp = 0;
    /// From the scene's slop, or where that is 0 its contact margin, or where both are 0 the
    /// default slop (a deadband of 0 would send a pile at rest through the pass every step).
    static AnchorLengths of(Real slop, Real contactMargin);
};

/// Split impulse's friction anchor pass: after the relax sweeps, moves each sticking point back
/// onto its anchors through the pseudo-velocities, which change positions only. A few sweeps of
/// the friction rows, cold-started, aim each point's tangential pseudo-velocity at -drift / h
/// within the Coulomb disc of its final normal impulse; after each manifold's friction its
/// normal block holds the normal pseudo-velocities where the pass found them (the tangential
/// pull acts below the centre of mass, and alone it tipped a cube on a turning platform onto its
/// outer edge, within the slop where push-out does not act, and let it go at omega = 0.69 of
/// 1.98). Its impulses are dropped, never carried.
class FrictionAnchorPass {
public:
    /// `drifts`: 4 per constraint, each point's anchor drift (m, world, tangent plane, B's anchor
    /// - A's; AnchorTable). `pseudo`: one per body, updated.
    /// `lengths`: the deadband and the catch-up (AnchorLengths).
    void run(std::span<const SolverBody> bodies, std::span<const ContactConstraint> constraints,
             std::span<const Vec3> drifts, std::vector<PseudoVelocity>& pseudo, Real inverseH,
             const AnchorLengths& lengths);

private:
    std::vector<SolverBody> bodies_;     ///< the bodies at their pseudo-velocities
    std::vector<std::uint32_t> active_;  ///< the constraints whose anchors drifted apart
    std::vector<Vec3>
        rows_;  ///< per active point: tangential impulses (N s), normal pseudo-velocity (m/s)
    /// per active manifold: its regularised normal block's inverse (friction_anchors.cpp)
    std::vector<Eigen::Matrix<Real, 4, 4>> inverses_;
    /// per active point: the velocity its drift asks for (m/s), the same in every sweep
    std::vector<Vec3> pulls_;
};

}  // namespace tumble
