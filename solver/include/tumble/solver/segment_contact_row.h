#pragma once
/// Contact rows of a segment -- a thread between two lumped-mass nodes -- against another body's
/// shape, solved in ConstraintSolver's sweeps after the contacts.
///
/// The segment's point at parameter t, p = (1 - t) xA + t xB, touches the shape's body S with
/// normal n (from S towards the segment). Its velocity is the nodes' velocities at their anchors
/// blended by the weights wA = 1 - t, wB = t, so the normal row reads
///
///     J v = n . (wA vA(rA) + wB vB(rB) - vS(rS)) >= target,   vX(r) = vX + wX x r,
///
/// and an impulse lambda n on the segment splits as wA lambda n on A and wB lambda n on B (the
/// statics of a massless beam), -lambda n on S. The effective mass is the inverse of
///
///     K = wA^2 kA + wB^2 kB + kS,   kX = 1/mX + (rX x n)' IX^-1 (rX x n),
///
/// for point-mass nodes on a static shape 1 / ((1 - t)^2 / mA + t^2 / mB). The target is the
/// contacts' (normal_block.h): -s / h for a speculative point (s > 0), else the Baumgarte push-out
/// of the depth beyond the slop; under split impulse the sweeps take no push-out and
/// solveSegmentPositions drives it out on the pseudo-velocities alone (ConstraintSolver). A row
/// without pushOut has none (its nodes' own contacts correct the positions). Coulomb friction on
/// the two tangents with the same weights, each with its own effective mass, the pair clamped to
/// the disc |lambda_t| <= mu lambda_n. No restitution: a thread lands inelastically.
///
/// Deterministic: rows are solved in array order.

#include <array>
#include <cstdint>
#include <span>
#include <vector>

#include "tumble/solver/solver_body.h"
#include "tumble/solver/spring_row.h"

namespace tumble {

struct SegmentContactRow {
    std::uint32_t bodyA = 0;      ///< the segment's first node (index into the body array)
    std::uint32_t bodyB = 0;      ///< its second node
    std::uint32_t bodyS = 0;      ///< the body of the shape it touches
    Real t = 0;                   ///< the point's parameter along A -> B, in [0, 1]
    Vec3 rA = Vec3::Zero();       ///< from A's centre of mass to its anchor (world, m)
    Vec3 rB = Vec3::Zero();       ///< from B's centre of mass to its anchor (world, m)
    Vec3 rS = Vec3::Zero();       ///< from S's centre of mass to the point (world, m)
    Vec3 normal = Vec3::UnitZ();  ///< from S towards the segment, unit
    Real separation = 0;          ///< along the normal at the step's start (m); < 0 penetrating
    Real friction = 0;            ///< Coulomb mu, >= 0
    bool pushOut = true;          ///< pushes out depth beyond the slop (else velocity only)
    Real normalImpulse = 0;       ///< accumulated (N s): warm start in, result out
    std::array<Real, 2> tangentImpulse{};  ///< along tangents[0], tangents[1] (N s)

    // Filled by prepareSegmentContacts().
    std::array<Vec3, 2> tangents{Vec3::UnitX(), Vec3::UnitY()};
    Real normalMass = 0;                ///< 1 / K along the normal (kg)
    std::array<Real, 2> tangentMass{};  ///< 1 / K along each tangent (kg)
    Real positionImpulse = 0;           ///< solveSegmentPositions' accumulated push (N s)
    /// S cannot move and is at rest (a static shape's): the velocity sweeps leave it out.
    bool fixedS = false;
};

/// Tangent bases and effective masses of every row, then the warm start (each row's cached
/// impulses applied to the bodies, or dropped when `warmStart` is off).
void prepareSegmentContacts(std::span<SolverBody> bodies, std::span<SegmentContactRow> rows,
                            bool warmStart);

/// A thread's pull-only row in solveSegmentPositions (scratch, one per tension-only spring).
struct ThreadPull {
    std::uint32_t spring = 0;  ///< index into the springs
    Real target = 0;           ///< largest rate of stretching the pass may add (m/s)
    Real mass = 0;             ///< 1 / (J M^-1 J') (kg)
    Real impulse = 0;          ///< accumulated, <= 0: a pull (N s)
};

/// Split impulse's position pass for the rows: `iterations` sweeps on the pseudo-velocities of
/// `bodies`, each row with pushOut driving the depth beyond the slop out at factor / h, each
/// followed by a sweep over the tension-only springs (threads) as rigid pull-only rows on the
/// pseudo-velocity the pass itself adds: a push moves the taut threads with the nodes instead of
/// stretching them, and the nodes' own contacts' push-out (before it) reaches no further.
/// Needs prepareSpringRows()'s Jacobians; `pulls` is scratch.
void solveSegmentPositions(std::span<SolverBody> bodies, std::span<SegmentContactRow> rows,
                           std::span<const SpringRow> springs, std::vector<ThreadPull>& pulls,
                           Real factor, Real inverseH, Real slop, int iterations);

/// One projected Gauss-Seidel sweep over the rows with the given bias factor and slop (m), as
/// the contacts'; returns the largest velocity change an impulse made (m/s).
Real solveSegmentContacts(std::span<SolverBody> bodies, std::span<SegmentContactRow> rows,
                          Real inverseH, Real bias, Real slop);

}  // namespace tumble
