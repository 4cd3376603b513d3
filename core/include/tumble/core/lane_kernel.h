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
//
// Under AddressSanitizer neither clones nor flatten (TUMBLE_FLATTEN is empty too): GCC 12's
// instrumentation of the flattened sweeps took 40 min and 3.3 GB for sweep_rows.cpp alone (25 s
// without), most of the CI's time. That build checks memory and undefined behaviour, not the
// kernels' code; the bits stay the same, since no FMA is formed either way.
#if defined(__SANITIZE_ADDRESS__)
#define TUMBLE_SANITIZED
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
#define TUMBLE_SANITIZED
#endif
#endif

#if defined(__x86_64__) && defined(__GNUC__) && !defined(__clang__) && \
    !defined(TUMBLE_NO_LANE_CLONES) && !defined(TUMBLE_SANITIZED)
#define TUMBLE_LANE_KERNEL __attribute__((target_clones("avx2", "default"), flatten))
#else
#define TUMBLE_LANE_KERNEL
#endif

// Every call in the function inlined, for speed (sweep_rows.h); nothing under the sanitizers.
#if defined(TUMBLE_SANITIZED)
#define TUMBLE_FLATTEN
#else
#define TUMBLE_FLATTEN [[gnu::flatten]]
#endif
