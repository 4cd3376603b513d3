#pragma once
/// Split impulse's push-out of the contacts of bodies that springs end on (net nodes, anchored
/// bodies): ContactConstraint::pushOut false. Their depth beyond the slop is left out of the
/// biased sweeps and driven out afterwards on the pseudo-velocities alone, as the thread
/// contacts' (solveSegmentPositions).
///
/// Why: the spring block is solved exactly in every sweep, so a node's push in the biased sweeps
/// reached the whole net, and the relax sweeps did not take all of it back out of the velocities.
/// A 9.9 kg sphere resting under a net kept rocking at ~0.1 m/s, 2 Hz, for 9 s and more: energy
/// pumped in by the push-out. On the pseudo-velocities the push moves positions only.
///
/// Deterministic: points in constraint order. Allocates only when the list grows.

#include <cstdint>
#include <span>
#include <vector>

#include "tumble/solver/contact_solver.h"
#include "tumble/solver/solver_body.h"

namespace tumble {

class SprungPushOut {
public:
    /// Before prepare: every point of a manifold without pushOut deeper than the slop keeps its
    /// separation here and reads -slop in the constraint, so the sweeps' rows still hold it
    /// (v_n >= 0) but push none of it out. Returns the deepest depth held (m, 0 if none).
    Real hold(std::span<ContactConstraint> constraints, Real slop);
    bool empty() const { return held_.empty(); }
    /// The position pass: `iterations` sweeps on `bodies` (pseudo-velocities; the constraints'
    /// prepared rows), each point driving its depth beyond the slop out at factor / h.
    void solve(std::span<SolverBody> bodies, std::span<const ContactConstraint> constraints,
               Real factor, Real inverseH, Real slop, int iterations);
    /// The held separations back into the constraints.
    void restore(std::span<ContactConstraint> constraints) const;

private:
    struct Held {
        std::uint32_t constraint = 0;
        int point = 0;
        Real separation = 0;  ///< (m), < -slop
        Real impulse = 0;     ///< the pass's accumulated push (N s)
    };
    std::vector<Held> held_;
};

}  // namespace tumble
