#pragma once
/// The soft step's sliding patch (slide_patch.cpp): a manifold's friction solved as one row at
/// its centre of pressure before its points' rows, which SweepRows and ContactRows share.

#include <array>
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

/// When the manifold slides as a whole, sets every point's friction to its share of the
/// patch's rim answer (N_i / sum N) and applies the changes to the bodies; returns whether it
/// did. `normal` n, `tangents` t_1, t_2 (orthonormal), `target` the rows' v_t target,
/// `friction` mu.
bool slidePatch(PatchBodies& bodies, const Vec3& normal, const std::array<Vec3, 2>& tangents,
                const std::array<Real, 2>& target, Real friction, Real omega,
                std::span<PatchPoint> points);

/// After the relax sweep's normal rows: when the patch slid in either sweep of the substep
/// (`slid`), its friction split again by the normal impulses they left (the sum kept, so the
/// bodies' momentum is).
void settlePatch(PatchBodies& bodies, const std::array<Vec3, 2>& tangents, bool slid,
                 std::span<PatchPoint> points);

}  // namespace tumble
