#pragma once
/// The soft step's sliding patch (slide_patch.cpp): a manifold's friction solved as one row at
/// its centre of pressure before its points' rows, which SweepRows and ContactRows share.

#include <array>
#include <cmath>
#include <span>

#include "tumble/core/math.h"

namespace tumble {

/// A point of the manifold as the patch reads it: its normal impulse, its friction impulse along
/// t_1, t_2 (written when the patch slides), and its rows' levers r x t_k and I^-1 (r x t_k)
/// for either body.
struct PatchPoint {
    Real normalImpulse = 0;
    std::array<Real, 2> tangentImpulse{};
    std::array<Vec3, 2> angularA, angularB, impulseA, impulseB;
};

/// The manifold's two bodies while its rows are solved; `yawA`, `yawB`: n' I^-1 n of each.
struct PatchBodies {
    Vec3 linearA, angularA, linearB, angularB;
    Real inverseMassA, inverseMassB, yawA, yawB;
};

/// Whether the patch surely sticks, so slidePatch would return false, from sums the caller forms
/// on its own layout without copying the points' levers: `total` sum N_i, `old` the points'
/// summed friction, `slip` v_t at the centre of pressure less the target, `inverseMasses`
/// 1/mA + 1/mB. slidePatch slides when |K^-1 (K old - v_t)| > mu sum N_i, and K is
/// (1/mA + 1/mB) I plus the turn's positive semidefinite terms, so |old| + |v_t| / (1/mA + 1/mB)
/// bounds the left side. The margin keeps the bound clear of slidePatch's rounding (relative
/// 1e-16 times K's condition number, a few for any body's lever and yaw): where the bound holds,
/// the full test does too, bit for bit.
inline bool patchSticks(Real total, const std::array<Real, 2>& old, const std::array<Real, 2>& slip,
                        Real inverseMasses, Real friction) {
    if (!(total > 0 && friction > 0))
        return true;  // slidePatch does nothing either
    const Real held = std::sqrt(old[0] * old[0] + old[1] * old[1]);
    const Real stop = std::sqrt(slip[0] * slip[0] + slip[1] * slip[1]) / inverseMasses;
    return held + stop <= (1 - 1e-6) * friction * total;  // false on a NaN: the full test decides
}

/// When the manifold slides as a whole, sets every point's friction to its share of the
/// patch's rim answer (N_i / sum N) and applies the changes to the bodies; returns whether it
/// did. `normal` n, `tangents` t_1, t_2 (orthonormal), `target` the rows' v_t target,
/// `friction` mu.
bool slidePatch(PatchBodies& bodies, const Vec3& normal, const std::array<Vec3, 2>& tangents,
                const std::array<Real, 2>& target, Real friction, Real omega,
                std::span<PatchPoint> points);

}  // namespace tumble
