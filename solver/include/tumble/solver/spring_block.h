#pragma once
/// The implicit spring rows solved together, exactly, by a sparse LDL' factorisation.
///
/// Gauss-Seidel over stiff soft rows converges slowly (a chain of N links needs ~N^2 sweeps to
/// pass a load from end to end), and an unconverged implicit step is not implicit Euler: a
/// hanging chain of 16 links with omega_e h = 16 blew up at 10 + 10 sweeps. Here the rows are one
/// block: with K = J M^-1 J' + Gamma (Gamma the rows' softness, spring_row.h) the update
///
///     K dlambda = -(J v + bias + Gamma lambda)
///
/// meets every row's equation at once, which is implicit Euler on the springs (linearised about
/// the step's start) at any stiffness and any N. Contacts and springs then meet by block
/// Gauss-Seidel: each solver sweep runs the contacts' PGS rows and one exact spring solve; both
/// blocks are symmetric positive definite, so the alternation converges.
///
/// K is sparse (two rows couple only through a body they share, never through the static body
/// 0) and its pattern is fixed while the rows join the same bodies, so the analysis -- a
/// minimum-degree ordering (Eigen's AMD) and the elimination tree -- is redone only when the
/// pattern changes, and a step refactors K in place. Only that analysis allocates.
///
/// Tension-only rows (threads) make it an LCP: an active set. A slack thread's row is left out
/// (lambda = 0); rows whose solution pushes are dropped, dropped rows that would be stretched are
/// taken back, for a few rounds at the first solve of a step. Later solves (after contacts have
/// moved the bodies) keep the set: a taut thread stays a two-sided row until the step ends, and
/// a slack one that contacts begin to stretch pulls by Gauss-Seidel on its own row. Clamping
/// the taut rows in those later solves instead left the block's other rows answering a push that
/// was then taken away: a 40 x 40 net draping a cylinder gained 98 % of its energy that way,
/// against 4 % without the clamp.
///
/// Geometric stiffness. A row pulls along the line between its anchors at the step's start, so
/// a taut element's transverse stiffness T / L (the string's restoring force) is explicit, and
/// a taut chain's transverse modes blew up once omega_t h > ~2.2 (a 30-bead hanging chain at
/// h = 1/55). With prepare()'s step h, every taut row marked geometricStiffness whose transverse
/// mode the step does not resolve adds two transverse rows, directions t perpendicular to n:
/// soft rows of stiffness T / L (T the last step's tension, >= 0, so the block stays positive
/// definite for threads) and no stretch at the step's start, in the row's own scheme -- their
/// impulse is the change of the transverse force over the step, -h T / L (w1 h J_t v1 -
/// w_1 h J_t v0). They follow their element in the tension-only active set and report nothing.
/// A settled first solve that leaves a taut element's transverse stiffness explicit beyond
/// leapfrog's limit (the first step, a catch) is undone and solved again with rows from its
/// tensions.
///
/// Deterministic: rows in array order, fixed ordering for a fixed pattern.

#include <cstdint>
#include <span>
#include <vector>

#include "tumble/solver/solver_body.h"
#include "tumble/solver/spring_row.h"

namespace tumble {

class SpringBlockSolver {
public:
    /// Analyses the rows' pattern if it changed, assembles and factors K with every usable row
    /// active. Call after prepareSpringRows(). h > 0 (the step) adds the taut elements'
    /// transverse rows (see above); 0 leaves them out (rigid rows, projections). The rows are
    /// not copied: solve() works on them in place.
    void prepare(std::span<const SolverBody> bodies, std::span<SpringRow> rows, Real h = 0);

    /// One exact update of every active row given the bodies' current velocities (contacts
    /// included); the first call after prepare() also settles which tension-only rows are
    /// active. `rows` are prepare()'s, unmoved (their impulses and biases may have changed).
    /// Returns the largest change of a row's J v (m/s), for the solver's tolerance.
    Real solve(std::span<SolverBody> bodies, std::span<SpringRow> rows);

    /// The change the next solve() would make to `change` -- velocity changes, e.g. of a unit
    /// contact impulse, on a copy of the bodies -- with the active set kept: the rows' impulses
    /// answering J change, added to `change`; the rows' own impulses untouched. Linear (the
    /// slack rows' Gauss-Seidel left out), so the held node contacts can be solved against the
    /// springs (SprungContacts). Only after a solve() of this step.
    void respond(std::span<SolverBody> change);

    /// solve() without the slack rows' Gauss-Seidel, after a solve() of this step: exactly what
    /// respond() predicts.
    Real solveActive(std::span<SolverBody> bodies, std::span<SpringRow> rows);

    /// Transverse rows added by the last prepare(), for the benchmarks.
    std::size_t transverseRows() const { return transverse_.size(); }

    /// Whether the last prepare() factored K (false without rows, or on a numerically singular
    /// K); the caller then solves the rows by Gauss-Seidel instead.
    bool ready() const { return factored_; }

    /// Stored entries of the factor L, for the benchmarks: the fill the ordering achieved.
    std::size_t factorSize() const { return lIndex_.size(); }

private:
    struct Reach {   // one column of row k's sparse triangular solve (factor())
        int column;  // i: the column of L the solve visits
        int first;   // its first slot in lIndex_ / lValue_
        int slot;    // where L(k, i) goes; the slots before it are the rows above k
    };
    struct CompactReach {  // a Reach that compactPattern() kept, in its compact L
        int column;
        int first;     // column's first slot in compactIndex_ / compactValue_
        int slot;      // where L(k, i) goes there
        int fullSlot;  // and in lIndex_ / lValue_
    };
    struct Coupling {         // one body's share of an off-diagonal entry of K
        std::uint32_t entry;  // into values_
        std::uint32_t rowI;
        std::uint32_t rowJ;
        std::uint32_t body;  // solver body both rows act on
        bool sideBI;         // row I acts on `body` as its B end (+J) or its A end (-J)
        bool sideBJ;
        bool first;  // the entry's first coupling: assemble() starts the entry from +0 here
    };

    void addTransverseRows(std::span<const SolverBody> bodies);
    /// Sets which rows start active, assembles and factors K.
    void start(std::span<const SolverBody> bodies);
    /// The first solve of a step: settles the tension-only active set.
    Real settle(std::span<SolverBody> bodies);
    /// Marks the discrete-gradient threads whose linear model misses the span the last round
    /// solved for (spring_row.h); whether any.
    bool findStaleThreads(std::span<const SolverBody> bodies);
    /// Linearises the marked threads again at that span (after the round is undone).
    /// lastRound: implicit Euler rows instead, for the last round.
    void relineariseStaleThreads(std::span<SolverBody> bodies, bool lastRound);
    /// Whether the settled solve's tensions leave a taut element's transverse rows far from
    /// the tension they were built with; if so, undoes the solve and rebuilds them with it.
    bool refreshTransverseRows(std::span<SolverBody> bodies);
    /// Each discrete-gradient thread's turn rows' impulse into its `turn` (part of the half it
    /// carries to the next step).
    void storeTurnImpulses();
    bool samePattern() const;
    void analyse();
    /// The elimination tree, L's pattern and each row's solve order (factor()'s walk, once).
    void symbolic();
    void assemble(std::span<const SolverBody> bodies);
    /// Whether values_'s zeros are those rememberNonzeros() kept.
    bool sameNonzeros() const;
    void rememberNonzeros();
    /// The rows' solves and the columns of L that K's nonzeros reach (factor()).
    void compactPattern();
    bool factor();
    bool factorWhole();
    bool factorCompact();
    Real scatterColumn(int k);
    /// delta = -K^-1 residual over the active rows (in original row order).
    void computeUpdate(std::span<const SolverBody> bodies);
    /// work_ = -residual of each active row, in the ordering's positions; 0 for the others.
    void loadResiduals(std::span<const SolverBody> bodies);
    /// computeUpdate()'s solves over compactPattern()'s L; false when one of its checks fails
    /// (work_ then holds nothing to keep).
    bool solveCompact();
    /// computeUpdate()'s solves over the whole of L, on work_.
    void solveFull();
    Real apply(std::span<SolverBody> bodies, bool clamp);
    /// Threads the active set left slack, by Gauss-Seidel: contacts solved after the set was
    /// chosen may stretch them, and nothing else would stop it.
    Real relaxSlackRows(std::span<SolverBody> bodies);

    /// Row i of the block: the elements' rows (the caller's), then their transverse rows.
    SpringRow& row(std::size_t i) {
        return i < elementCount_ ? elements_[i] : transverse_[i - elementCount_];
    }
    const SpringRow& row(std::size_t i) const {
        return i < elementCount_ ? elements_[i] : transverse_[i - elementCount_];
    }
    std::size_t rowCount() const { return elementCount_ + transverse_.size(); }

    std::span<SpringRow> elements_;      ///< prepare()'s rows, solved in place
    std::vector<SpringRow> transverse_;  ///< owner_: the element of each
    std::vector<std::uint32_t> owner_;
    std::size_t elementCount_ = 0;
    Real h_ = 0;                 ///< prepare()'s step; 0: no transverse rows
    std::vector<Real> warm_;     ///< the elements' impulses at prepare()
    std::vector<Real> tension_;  ///< each element's tension for its transverse rows (N)
    // Pattern key: the rows' bodies.
    std::vector<std::uint32_t> keyA_;
    std::vector<std::uint32_t> keyB_;
    // position_[row] = where the ordering puts it; rowAt_[position] = row.
    std::vector<int> position_;
    std::vector<int> rowAt_;
    // Upper triangle of the permuted K, compressed by column; diagonal last in each column.
    std::vector<int> columnStart_;
    std::vector<int> rowIndex_;
    std::vector<Real> values_;
    std::vector<Coupling> couplings_;
    // L D L' by Davis's up-looking algorithm (the LDL package): elimination tree and fill.
    std::vector<int> parent_;
    std::vector<int> lStart_;
    std::vector<int> lCount_;
    std::vector<int> lIndex_;
    std::vector<Real> lValue_;
    std::vector<Real> diagonal_;
    std::vector<char> zeroRow_;  ///< row k of L holds only +0 (an inactive row's, factor())
    std::vector<int> flag_;
    std::vector<int> pattern_;
    // Row k of L: the columns reach_[reachStart_[k] ...] in solve order.
    std::vector<int> reachStart_;
    std::vector<Reach> reach_;
    // L's entries that K's nonzeros reach (compactPattern()): which entries of values_ were
    // nonzero, and L compressed to the entries kept (column by column).
    std::vector<std::uint64_t> nonzero_;  ///< 0 or 1, as wide as the values compared
    std::vector<char> mark_;
    std::vector<int> columnHead_;  ///< per column: its first kept entry (-1: none yet)
    std::vector<int> columnTail_;
    std::vector<int> keptRow_;   ///< per kept entry (compactReach_'s order): its row
    std::vector<int> keptNext_;  ///< the next kept entry of its column, -1 for none
    std::vector<int> compactCount_;
    std::vector<int> compactStart_;
    std::vector<int> compactIndex_;
    std::vector<Real> compactValue_;
    std::vector<int> compactReachStart_;
    std::vector<CompactReach> compactReach_;
    std::vector<Real> work_;
    std::vector<Real> delta_;
    std::vector<char> active_;
    std::vector<char> wanted_;   ///< the next round's active set
    std::vector<char> stale_;    ///< per element: findStaleThreads() marked it
    std::vector<Vec3> endSpan_;  ///< per element: the span it found
    bool compacted_ = false;     ///< compactPattern() holds nonzero_'s pattern
    bool compactWorth_ = false;  ///< the last factorWhole()'s solves met 3/4 zeros
    bool settled_ = false;
    bool factored_ = false;
};

}  // namespace tumble
