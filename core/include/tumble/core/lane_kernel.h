#pragma once
// TUMBLE_LANE_KERNEL: a function compiled twice, for AVX2 and for the x86-64 baseline, the copy
// chosen when the program loads (GCC's target_clones), with every call in it inlined (flatten)
// so that the helpers run in the chosen copy too. Every operation is the same IEEE operation in
// both and no FMA is formed (-ffp-contract=off), so the bits are the same on every machine
// (tests: solver.lane-clone-bits builds the baseline alone under TUMBLE_NO_LANE_CLONES).
// The contact rows' lane kernels (contact_rows.cpp, contact_rows_friction.cpp), prepare's passes
// and the residual (contact_solver.cpp), the default step's scalar sweep (sweep_rows.cpp,
// SweepRows::sweepPlain: its AVX2 copy's three-operand forms drop the baseline's register
// copies), the box-box narrowphase (collide_box.cpp, clipping.cpp), the friction anchors' pass
// and drifts (friction_anchors.cpp, ldlt4.cpp, anchor_table.cpp) and the constraint builder
// (solve_stage.cpp, fillConstraint). A function it calls that is not inline
// stays a call to its baseline code (flatten does not take it in): make such helpers inline.
// Internal: not installed (docs/ARCHITECTURE.md, Public headers).
#if defined(__x86_64__) && defined(__GNUC__) && !defined(__clang__) && \
    !defined(TUMBLE_NO_LANE_CLONES)
#define TUMBLE_LANE_KERNEL __attribute__((target_clones("avx2", "default"), flatten))
#else
#define TUMBLE_LANE_KERNEL
#endif
