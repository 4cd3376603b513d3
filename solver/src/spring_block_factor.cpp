#include "tumble/solver/spring_block.h"

// SpringBlockSolver's factorisation: the symbolic analysis of L's pattern, the entries K's
// nonzeros reach, and the numeric LDL' (spring_block.h).

#include <algorithm>
#include <cmath>

namespace tumble {

namespace {

// One column i of row k's sparse triangular solve (ldl_numeric), shared by both
// factorisations: y_i taken out of work, subtracted along column i of L (its entries in
// [first, slot), rows index[p]), L(k, i) = y_i / D_i handed to store and its share taken off
// the diagonal d. A y_i of +0 (a slack thread's row couples nothing; work never holds -0: it
// sums from +0 and subtracts, and x - x is +0) stores +0 and skips the subtractions, which
// would subtract only +0 * l and change no value: the bits are kept. Returns whether y_i was
// nonzero.
template <class Store>
inline bool eliminateColumn(Real* work, const int* index, const Real* value, const Real* diagonal,
                            int column, int first, int slot, Real& d, Store store) {
    const Real yi = work[column];
    work[column] = 0;
    if (yi == 0) {
        store(Real(0));
        return false;
    }
    for (int p = first; p < slot; ++p)
        work[index[p]] -= value[p] * yi;
    const Real lki = yi / diagonal[column];
    d -= lki * yi;
    store(lki);
    return true;
}

}  // namespace

// ldl_symbolic's elimination tree and column counts, then the numeric factorisation's sparse
// triangular solves done once on the pattern: each row k of L as the columns its solve visits,
// in the order it visits them, and the slot of L each result goes to. factor() then repeats
// the same arithmetic in the same order (bitwise the walk's result) without walking the tree:
// the walk was a sixth of the factorisation of a 40 x 40 net.
void SpringBlockSolver::symbolic() {
    const int n = static_cast<int>(columnStart_.size()) - 1;
    parent_.assign(n, -1);
    lCount_.assign(n, 0);
    flag_.assign(n, 0);
    for (int k = 0; k < n; ++k) {
        flag_[k] = k;
        for (int p = columnStart_[k]; p < columnStart_[k + 1]; ++p) {
            for (int i = rowIndex_[p]; i < k && flag_[i] != k; i = parent_[i]) {
                if (parent_[i] == -1)
                    parent_[i] = k;
                ++lCount_[i];
                flag_[i] = k;
            }
        }
    }
    lStart_.assign(n + 1, 0);
    for (int k = 0; k < n; ++k)
        lStart_[k + 1] = lStart_[k] + lCount_[k];
    lIndex_.resize(lStart_[n]);
    lValue_.resize(lStart_[n]);
    reachStart_.assign(n + 1, 0);
    reach_.resize(lStart_[n]);
    pattern_.resize(n);
    std::fill(lCount_.begin(), lCount_.end(), 0);
    for (int k = 0; k < n; ++k) {
        int top = n;
        flag_[k] = k;
        for (int p = columnStart_[k]; p < columnStart_[k + 1]; ++p) {
            int length = 0;
            for (int i = rowIndex_[p]; flag_[i] != k; i = parent_[i]) {
                pattern_[length++] = i;
                flag_[i] = k;
            }
            while (length > 0)
                pattern_[--top] = pattern_[--length];
        }
        int q = reachStart_[k];
        for (; top < n; ++top, ++q) {
            const int i = pattern_[top];
            const int slot = lStart_[i] + lCount_[i]++;
            lIndex_[slot] = k;
            reach_[q] = {i, lStart_[i], slot};
        }
        reachStart_[k + 1] = q;
    }
    zeroRow_.assign(n, 0);
    nonzero_.clear();  // factorWhole() first
    diagonal_.resize(n);
    work_.resize(n);
    delta_.resize(n);
}

// The entries of L that can be nonzero given which entries of K are (factor()'s walk on
// booleans): an entry of K that is +0 -- a slack row's, or two threads crossing at right angles in
// a flat net, exactly perpendicular -- leaves entries of L at +0, and a flat 40 x 40 net's L was
// 94 % such zeros. Each row's columns keep symbolic()'s order and each column its rows' order, so
// the factorisation does the same arithmetic on the rest in the same order; the rest of L is +0.
void SpringBlockSolver::compactPattern() {
    const int n = static_cast<int>(diagonal_.size());
    std::fill(lValue_.begin(), lValue_.end(), Real(0));  // factorWhole() left values anywhere
    compactCount_.assign(n, 0);
    mark_.assign(n, 0);
    columnHead_.assign(n, -1);
    columnTail_.resize(n);
    keptRow_.clear();
    keptNext_.clear();
    compactReach_.clear();
    compactReachStart_.assign(n + 1, 0);
    for (int k = 0; k < n; ++k) {
        // An inactive row's column is its diagonal alone (assemble()): nothing to keep.
        if (!active_[rowAt_[k]]) {
            compactReachStart_[k + 1] = static_cast<int>(compactReach_.size());
            zeroRow_[k] = 1;
            continue;
        }
        for (int p = columnStart_[k]; p < columnStart_[k + 1]; ++p)
            mark_[rowIndex_[p]] = nonzero_[p] != 0;
        mark_[k] = 0;
        for (int q = reachStart_[k]; q < reachStart_[k + 1]; ++q) {
            const Reach& r = reach_[q];
            if (!mark_[r.column])
                continue;
            mark_[r.column] = 0;
            // The column's kept entries so far (rows above k), not its whole pattern: most of a
            // flat net's is +0.
            for (int e = columnHead_[r.column]; e >= 0; e = keptNext_[e])
                mark_[keptRow_[e]] = 1;
            const int e = static_cast<int>(compactReach_.size());
            keptRow_.push_back(k);
            keptNext_.push_back(-1);
            if (columnHead_[r.column] < 0)
                columnHead_[r.column] = e;
            else
                keptNext_[columnTail_[r.column]] = e;
            columnTail_[r.column] = e;
            // first: filled in below, once the columns' starts are known; slot: the offset
            compactReach_.push_back({r.column, 0, compactCount_[r.column]++, r.slot});
        }
        compactReachStart_[k + 1] = static_cast<int>(compactReach_.size());
        zeroRow_[k] = compactReachStart_[k + 1] == compactReachStart_[k];
    }
    compactStart_.assign(n + 1, 0);
    for (int i = 0; i < n; ++i)
        compactStart_[i + 1] = compactStart_[i] + compactCount_[i];
    compactIndex_.resize(compactStart_[n]);
    compactValue_.assign(compactStart_[n], 0);
    for (int k = 0; k < n; ++k) {
        for (int q = compactReachStart_[k]; q < compactReachStart_[k + 1]; ++q) {
            CompactReach& r = compactReach_[q];
            r.first = compactStart_[r.column];
            r.slot += r.first;
            compactIndex_[r.slot] = k;
        }
    }
}

bool SpringBlockSolver::sameNonzeros() const {
    if (values_.size() != nonzero_.size())
        return false;
    // No early exit: the zeros rarely change, and a branch per entry cost more.
    std::uint64_t differ = 0;
    for (std::size_t p = 0; p < values_.size(); ++p)
        differ |= static_cast<std::uint64_t>(values_[p] != 0) ^ nonzero_[p];
    return differ == 0;
}

void SpringBlockSolver::rememberNonzeros() {
    nonzero_.resize(values_.size());
    for (std::size_t p = 0; p < values_.size(); ++p)
        nonzero_[p] = values_[p] != 0;
}

bool SpringBlockSolver::factor() {
    // K's zeros seen for the first time are factored over symbolic()'s whole pattern; seen
    // again, compacted once and factored over what compactPattern() keeps. Compacting costs
    // about a whole factorisation: done at once, a stiff net's, whose slack threads change
    // every few steps, cost 10 % more. Zeros are looked for only where the whole pattern's
    // solves met mostly zeros: comparing them cost a stiff net 1 % (a third of its solves'
    // subtractions were of +0).
    if (compactWorth_ && sameNonzeros()) {
        if (!compacted_) {
            compactPattern();
            compacted_ = true;
        }
        return factorCompact();
    }
    compacted_ = false;
    const bool factored = factorWhole();
    if (compactWorth_)
        rememberNonzeros();
    else
        nonzero_.clear();
    return factored;
}

bool SpringBlockSolver::factorWhole() {
    // ldl_numeric: row k of L from a sparse triangular solve over the columns symbolic() found.
    const int n = static_cast<int>(diagonal_.size());
    std::size_t visits = 0;
    std::size_t zeros = 0;
    for (int k = 0; k < n; ++k) {
        // An inactive row's column holds only its unit diagonal (assemble()): every y of its
        // solve is +0, so its row of L is +0 and its diagonal 1 -- what the solve below would
        // compute, without scattering or reading.
        // Its zeros are written once: they stay until the row takes part again (scattered
        // stores, a quarter of the factorisation of a 40 x 40 net when rewritten every step).
        if (!active_[rowAt_[k]]) {
            if (!zeroRow_[k]) {
                for (int q = reachStart_[k]; q < reachStart_[k + 1]; ++q)
                    lValue_[reach_[q].slot] = 0;
                zeroRow_[k] = 1;
            }
            work_[k] = 0;  // may hold the last solve's result: later rows read it as +0
            diagonal_[k] = 1;
            continue;
        }
        zeroRow_[k] = 0;
        Real d = scatterColumn(k);
        for (int q = reachStart_[k]; q < reachStart_[k + 1]; ++q) {
            const Reach& r = reach_[q];
            ++visits;
            if (!eliminateColumn(work_.data(), lIndex_.data(), lValue_.data(), diagonal_.data(),
                                 r.column, r.first, r.slot, d,
                                 [&](Real lki) { lValue_[r.slot] = lki; }))
                ++zeros;
        }
        diagonal_[k] = d;
        // K is positive definite (every active row has a positive softness or a movable body);
        // anything else is rounding on a near-rigid loop, and the solve must not divide by it.
        if (!(d > 0) || !std::isfinite(d)) {
            compactWorth_ = false;
            return false;
        }
    }
    compactWorth_ = 4 * zeros > 3 * visits;
    return true;
}

// Column k of K's lower triangle scattered into work_ (from +0), its diagonal taken out and
// returned: where both factorisations start row k of L.
Real SpringBlockSolver::scatterColumn(int k) {
    work_[k] = 0;
    for (int p = columnStart_[k]; p < columnStart_[k + 1]; ++p)
        work_[rowIndex_[p]] += values_[p];
    const Real d = work_[k];
    work_[k] = 0;
    return d;
}

bool SpringBlockSolver::factorCompact() {
    // ldl_numeric as factorWhole(), over the columns compactPattern() kept.
    const int n = static_cast<int>(diagonal_.size());
    for (int k = 0; k < n; ++k) {
        // An inactive row's row of L is +0 (compactPattern() keeps none of it), its diagonal 1.
        if (!active_[rowAt_[k]]) {
            work_[k] = 0;  // may hold the last solve's result
            diagonal_[k] = 1;
            continue;
        }
        Real d = scatterColumn(k);
        // The columns left out have y = +0 (work_ never holds -0: it sums from +0 and
        // subtracts, and x - x is +0), and so have the entries left out of a column: each
        // subtracted only +0 * y, which changes no value.
        for (int q = compactReachStart_[k]; q < compactReachStart_[k + 1]; ++q) {
            const CompactReach& r = compactReach_[q];
            eliminateColumn(work_.data(), compactIndex_.data(), compactValue_.data(),
                            diagonal_.data(), r.column, r.first, r.slot, d, [&](Real lki) {
                                compactValue_[r.slot] = lki;
                                lValue_[r.fullSlot] = lki;
                            });
        }
        diagonal_[k] = d;
        // K is positive definite (every active row has a positive softness or a movable body);
        // anything else is rounding on a near-rigid loop, and the solve must not divide by it.
        if (!(d > 0) || !std::isfinite(d))
            return false;
    }
    return true;
}

}  // namespace tumble
