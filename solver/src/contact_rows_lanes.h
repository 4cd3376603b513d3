#pragma once
// The lane helpers (namespace wide) and the velocities' gather and scatter of ContactRows'
// kernels (contact_rows.h), shared by the sweep's kernels (contact_rows.cpp) and the friction's
// (contact_rows_friction.cpp). Always inline: the kernels are compiled twice
// (TUMBLE_LANE_KERNEL), and a helper that stayed a call would run in its baseline copy.
#include <algorithm>

#include "tumble/solver/contact_rows.h"

namespace tumble {
namespace wide {

[[gnu::always_inline]] inline Lane splat(Real x) {
    return Lane{x, x, x, x};
}

// a where m is set, b elsewhere.
[[gnu::always_inline]] inline Lane select(LaneMask m, Lane a, Lane b) {
    return reinterpret_cast<Lane>((reinterpret_cast<LaneMask>(a) & m) |
                                  (reinterpret_cast<LaneMask>(b) & ~m));
}

[[gnu::always_inline]] inline LaneMask greater(Lane a, Lane b) {
    return reinterpret_cast<LaneMask>(a > b);
}

// Halves folded in the vector before one element is read: element by element, the four
// extractions and three ors took nine instructions, on every point's friction (pyramid-20).
[[gnu::always_inline]] inline bool any(LaneMask m) {
    const LaneMask halves = m | __builtin_shufflevector(m, m, 2, 3, 0, 1);
    return (halves | __builtin_shufflevector(halves, halves, 1, 0, 3, 2))[0] != 0;
}

[[gnu::always_inline]] inline Lane dot(const Lane (&a)[3], const Lane* b) {
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

[[gnu::always_inline]] inline Real largestLane(Lane x) {
    return std::max({x[0], x[1], x[2], x[3]});
}

[[gnu::always_inline]] inline Lane absolute(Lane x) {
    return select(greater(Lane{}, x), -x, x);
}

// max(0, x) as std::max<Real>(0, x) has it.
[[gnu::always_inline]] inline Lane positivePart(Lane x) {
    return select(greater(x, Lane{}), x, Lane{});
}

// Two lanes: the width of the x86-64 baseline's registers, whose interleaving loads and stores
// move two bodies' values at once.
using Pair = double __attribute__((vector_size(16)));

[[gnu::always_inline]] inline Pair loadPair(const Real* from) {
    Pair p;
    __builtin_memcpy(&p, from, sizeof(Pair));
    return p;
}

[[gnu::always_inline]] inline void storePair(Real* to, Pair p) {
    __builtin_memcpy(to, &p, sizeof(Pair));
}

}  // namespace wide

// gather's body, inline so that gatherFriction's copies take it in.
[[gnu::always_inline]] inline void ContactRows::gatherLanes(const Bundle& bundle,
                                                            Lane (&v)[2][6]) const {
    for (int side = 0; side < 2; ++side) {
        const std::array<std::uint32_t, 4>& body = side == 0 ? bundle.bodyA : bundle.bodyB;
        const Real* lane[4];
        for (int i = 0; i < 4; ++i)
            lane[i] = velocities_[body[i]].v;
        for (int k = 0; k < 6; k += 2) {
            const Lane even = __builtin_shufflevector(wide::loadPair(lane[0] + k),
                                                      wide::loadPair(lane[2] + k), 0, 1, 2, 3);
            const Lane odd = __builtin_shufflevector(wide::loadPair(lane[1] + k),
                                                     wide::loadPair(lane[3] + k), 0, 1, 2, 3);
            v[side][k] = __builtin_shufflevector(even, odd, 0, 4, 2, 6);
            v[side][k + 1] = __builtin_shufflevector(even, odd, 1, 5, 3, 7);
        }
    }
}

// scatter's body, inline so that solveNormals' copies take it in: called, it was a call from
// the AVX2 copy to the AVX2 copy with its vzeroupper and four spilled lanes around it.
[[gnu::always_inline]] inline void ContactRows::scatterLanes(const Bundle& bundle,
                                                             const Lane (&v)[2][6]) {
    wide::Pair rows[4][2][3];  // lane, side, pair of values
    for (int side = 0; side < 2; ++side) {
        for (int k = 0; k < 6; k += 2) {
            // (lane 0's pair, lane 2's) and (lane 1's, lane 3's)
            const Lane even = __builtin_shufflevector(v[side][k], v[side][k + 1], 0, 4, 2, 6);
            const Lane odd = __builtin_shufflevector(v[side][k], v[side][k + 1], 1, 5, 3, 7);
            rows[0][side][k / 2] = __builtin_shufflevector(even, even, 0, 1);
            rows[2][side][k / 2] = __builtin_shufflevector(even, even, 2, 3);
            rows[1][side][k / 2] = __builtin_shufflevector(odd, odd, 0, 1);
            rows[3][side][k / 2] = __builtin_shufflevector(odd, odd, 2, 3);
        }
    }
    // Through the vector, its data pointer was loaded again after every body's stores.
    Velocity* const velocities = velocities_.data();
    for (int lane = 0; lane < 4; ++lane) {
        Real* a = velocities[bundle.bodyA[lane]].v;
        for (int k = 0; k < 3; ++k)
            wide::storePair(a + 2 * k, rows[lane][0][k]);
        Real* b = velocities[bundle.bodyB[lane]].v;
        for (int k = 0; k < 3; ++k)
            wide::storePair(b + 2 * k, rows[lane][1][k]);
    }
}

}  // namespace tumble
