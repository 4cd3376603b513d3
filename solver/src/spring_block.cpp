#include "tumble/solver/spring_block.h"

#include <Eigen/OrderingMethods>
#include <Eigen/SparseCore>
#include <algorithm>
#include <cmath>
#include <utility>

namespace tumble {
namespace {

// Rounds of the tension-only active set at the first solve of a step. A net falling flat settles
// in one or two; a crumpled one may flip a few threads back and forth, and the later sweeps'
// clamping then takes over. 12, not 6: a tumbling net's discrete-gradient threads settled at 0.1 %
// (the tolerance then) in 4-7 rounds a step (`net-energy`, omega_e h = 1.5-7); with 6 some fell
// back to implicit Euler.
constexpr int kActiveSetRounds = 12;

// Velocity (m/s) below which a thread's push or pull does not change the active set.
constexpr Real kFlipSpeed = 1e-9;

// (omega_t h)^2 of an element's transverse mode above which it gets transverse rows. Below,
// the explicit direction is leapfrog on that mode (second order, stable to omega_t h = 2 for
// one element; a chain's top bead went at ~2.2 measured with both its threads).
constexpr Real kResolvedTransverse = 1;

// A settled solve whose tension in a taut element leaves more of its transverse stiffness
// explicit than leapfrog holds ((omega_t h)^2 of the excess over the tension its transverse
// rows were built with >= this) builds them again, once per step: the first step of a string
// released at omega_t h = 14 has no tension history, and its transverse motion, explicit,
// took 8x the string's energy. (Rebuilding whenever the tension was 2x off cost the 40 x 40
// stiff net 11 % more time.)
constexpr Real kExplicitTransverseLimit = 4;

bool usable(const SpringRow& row) {
    return row.mass > 0 && row.bodyA != row.bodyB;
}

// A unit vector perpendicular to unit n, chosen by a fixed rule.
Vec3 perpendicular(const Vec3& n) {
    const Vec3 axis = std::abs(n.x()) < 0.57 ? Vec3::UnitX() : Vec3::UnitY();
    return n.cross(axis).normalized();
}

}  // namespace

bool SpringBlockSolver::samePattern() const {
    if (rowCount() != keyA_.size())
        return false;
    for (std::size_t i = 0; i < rowCount(); ++i) {
        if (row(i).bodyA != keyA_[i] || row(i).bodyB != keyB_[i])
            return false;
    }
    return true;
}

void SpringBlockSolver::analyse() {
    const int n = static_cast<int>(rowCount());
    keyA_.resize(n);
    keyB_.resize(n);
    std::uint32_t bodyCount = 0;
    for (int i = 0; i < n; ++i) {
        keyA_[i] = row(i).bodyA;
        keyB_[i] = row(i).bodyB;
        bodyCount = std::max({bodyCount, keyA_[i] + 1, keyB_[i] + 1});
    }

    // Rows meeting at each movable body (body 0 is the static world: it couples nothing).
    std::vector<std::vector<std::pair<std::uint32_t, bool>>> atBody(bodyCount);
    for (int i = 0; i < n; ++i) {
        if (keyA_[i] == keyB_[i])
            continue;
        if (keyA_[i] != 0)
            atBody[keyA_[i]].emplace_back(i, false);
        if (keyB_[i] != 0)
            atBody[keyB_[i]].emplace_back(i, true);
    }
    std::vector<Eigen::Triplet<double, int>> triplets;
    for (int i = 0; i < n; ++i)
        triplets.emplace_back(i, i, 1.0);
    couplings_.clear();
    for (std::uint32_t body = 0; body < bodyCount; ++body) {
        const auto& list = atBody[body];
        for (std::size_t p = 0; p < list.size(); ++p) {
            for (std::size_t q = p + 1; q < list.size(); ++q) {
                couplings_.push_back(
                    {0, list[p].first, list[q].first, body, list[p].second, list[q].second, false});
                triplets.emplace_back(list[p].first, list[q].first, 1.0);
                triplets.emplace_back(list[q].first, list[p].first, 1.0);
            }
        }
    }

    // Fill-reducing order: a net's rows in array order factor with a band as wide as a row of
    // the net; minimum degree keeps the fill near linear.
    Eigen::SparseMatrix<double, Eigen::ColMajor, int> pattern(n, n);
    pattern.setFromTriplets(triplets.begin(), triplets.end());
    Eigen::PermutationMatrix<Eigen::Dynamic, Eigen::Dynamic, int> order;
    Eigen::AMDOrdering<int>()(pattern, order);
    rowAt_.assign(order.indices().data(), order.indices().data() + n);
    position_.assign(n, 0);
    for (int k = 0; k < n; ++k)
        position_[rowAt_[k]] = k;

    // Upper triangle by column, rows ascending, so each column's diagonal comes last.
    std::vector<std::pair<int, int>> entries;  // (column, row) in the new order
    for (int k = 0; k < n; ++k)
        entries.emplace_back(k, k);
    for (const Coupling& c : couplings_) {
        const int pi = position_[c.rowI];
        const int pj = position_[c.rowJ];
        entries.emplace_back(std::max(pi, pj), std::min(pi, pj));
    }
    std::sort(entries.begin(), entries.end());
    entries.erase(std::unique(entries.begin(), entries.end()), entries.end());
    columnStart_.assign(n + 1, 0);
    rowIndex_.resize(entries.size());
    for (std::size_t e = 0; e < entries.size(); ++e) {
        ++columnStart_[entries[e].first + 1];
        rowIndex_[e] = entries[e].second;
    }
    for (int k = 0; k < n; ++k)
        columnStart_[k + 1] += columnStart_[k];
    values_.assign(entries.size(), 0);
    std::vector<char> seen(entries.size(), 0);
    for (Coupling& c : couplings_) {
        const int pi = position_[c.rowI];
        const int pj = position_[c.rowJ];
        const std::pair<int, int> key(std::max(pi, pj), std::min(pi, pj));
        c.entry = static_cast<std::uint32_t>(std::lower_bound(entries.begin(), entries.end(), key) -
                                             entries.begin());
        c.first = seen[c.entry] == 0;
        seen[c.entry] = 1;
    }

    symbolic();
}

void SpringBlockSolver::assemble(std::span<const SolverBody> bodies) {
    // values_ is not cleared first: every entry is written, the diagonal below and each
    // off-diagonal one (all couple two rows through a body) from +0 at its first coupling --
    // the same sums in the same order as on a cleared array, so the same bits. Clearing it
    // was a fifth of assembling a net's K.
    const int n = static_cast<int>(rowCount());
    for (int k = 0; k < n; ++k) {
        // An inactive row is the identity: its update is minus its residual, which is zero.
        values_[columnStart_[k + 1] - 1] = active_[rowAt_[k]] ? 1 / row(rowAt_[k]).mass : 1;
    }
    for (const Coupling& c : couplings_) {
        Real& value = values_[c.entry];
        if (!active_[c.rowI] || !active_[c.rowJ]) {
            if (c.first)
                value = 0;
            continue;
        }
        const SpringRow& p = row(c.rowI);
        const SpringRow& q = row(c.rowJ);
        const SolverBody& body = bodies[c.body];
        // (J_p M^-1 J_q') through this body: the rows' linear parts meet its inverse mass, their
        // angular parts its inverse inertia; a row pulls its A end with -J.
        const Real sign = c.sideBI == c.sideBJ ? 1 : -1;
        const Vec3& angularP = c.sideBI ? p.angularB : p.angularA;
        const Vec3& impulseQ = c.sideBJ ? q.angularImpulseB : q.angularImpulseA;
        value = (c.first ? Real(0) : value) +
                sign * (body.inverseMass * p.direction.dot(q.direction) + angularP.dot(impulseQ));
    }
}

void SpringBlockSolver::addTransverseRows(std::span<const SolverBody> bodies) {
    const Real h = h_;
    for (std::size_t i = 0; i < elementCount_; ++i) {
        const SpringRow& row = elements_[i];
        // Pushing elements would make K indefinite.
        // A discrete-gradient thread's turn rows are Newton's, holding nothing once its end span
        // is right: every such thread has them, taut at the start or not (spring_row.h).
        const bool turns = row.discreteGradient;
        if (!row.geometricStiffness || !usable(row) || !(turns || tension_[i] > 0))
            continue;
        const Real stiffness = tension_[i] / row.length;  // T / L (N/m)
        const SolverBody& a = bodies[row.bodyA];
        const SolverBody& b = bodies[row.bodyB];
        if (!turns && stiffness * h * h * (a.inverseMass + b.inverseMass) < kResolvedTransverse)
            continue;
        const Vec3 first = perpendicular(row.direction);
        for (const Vec3& t : {first, Vec3(row.direction.cross(first))}) {
            SpringRow transverse = row;
            transverse.direction = t;
            transverse.restLength = row.length;  // no transverse stretch at the step's start
            transverse.stiffness = stiffness;
            transverse.damping = 0;
            transverse.tensionOnly = false;
            transverse.geometricStiffness = false;
            transverse.discreteGradient = false;
            transverse.impulse = 0;
            if (turns)
                lineariseThreadTurn(a, b, row, transverse, h);
            else
                prepareSpringRow(a, b, transverse, h);
            if (transverse.mass > 0) {
                transverse_.push_back(transverse);
                owner_.push_back(static_cast<std::uint32_t>(i));
            }
        }
    }
}

void SpringBlockSolver::prepare(std::span<const SolverBody> bodies, std::span<SpringRow> rows,
                                Real h) {
    factored_ = false;
    settled_ = false;
    h_ = h;
    elements_ = rows;
    elementCount_ = rows.size();
    transverse_.clear();
    owner_.clear();
    if (rows.empty())
        return;
    warm_.resize(elementCount_);
    tension_.resize(elementCount_);
    for (std::size_t i = 0; i < elementCount_; ++i) {
        warm_[i] = rows[i].impulse;
        // The warm start is last step's tension, -T h (with a thread's known levels,
        // spring_row.h).
        tension_[i] = h > 0 ? -(rows[i].impulse + rows[i].knownImpulse) / h : 0;
    }
    if (h > 0)
        addTransverseRows(bodies);
    start(bodies);
}

void SpringBlockSolver::start(std::span<const SolverBody> bodies) {
    if (!samePattern())
        analyse();
    const std::size_t n = rowCount();
    active_.resize(n);
    wanted_.resize(n);
    // A thread starts active when it is stretched at the step's start; the first solve corrects
    // the guess. Transverse rows follow their element.
    for (std::size_t i = 0; i < elementCount_; ++i) {
        const SpringRow& row = elements_[i];
        active_[i] = usable(row) &&
                     (!row.tensionOnly || row.length >= row.restLength || threadRowPulls(row));
    }
    for (std::size_t i = elementCount_; i < n; ++i)
        active_[i] = active_[owner_[i - elementCount_]];
    assemble(bodies);
    factored_ = factor();
    // The caller then solves every row by Gauss-Seidel.
    if (!factored_)
        finishSpringRows(bodies, elements_, h_);
}

void SpringBlockSolver::loadResiduals(std::span<const SolverBody> bodies) {
    const int n = static_cast<int>(rowCount());
    for (int i = 0; i < n; ++i) {
        const SpringRow& r = row(i);
        work_[position_[i]] = active_[i] ? -(springRowSpeed(bodies[r.bodyA], bodies[r.bodyB], r) +
                                             r.bias + r.softness * r.impulse)
                                         : 0;
    }
}

namespace {

// Every value finite and none -0: then subtracting +0 * y (y finite) changes none, and no
// subtraction makes a -0 (x - x is +0).
bool plain(std::span<const Real> values) {
    bool plain = true;
    for (const Real v : values)
        plain = plain && std::isfinite(v) && !(v == 0 && std::signbit(v));
    return plain;
}

}  // namespace

bool SpringBlockSolver::solveCompact() {
    const int n = static_cast<int>(rowCount());
    if (!plain(work_))
        return false;
    for (int j = 0; j < n; ++j) {  // L y = b
        const Real y = work_[j];
        for (int p = compactStart_[j]; p < compactStart_[j + 1]; ++p)
            work_[compactIndex_[p]] -= compactValue_[p] * y;
    }
    // Each y was final when its column was applied: all were finite, so each +0 * y left out
    // was a zero, and no value it would have met was -0.
    if (!plain(work_))
        return false;
    for (int j = 0; j < n; ++j)
        work_[j] /= diagonal_[j];
    if (!plain(work_))
        return false;
    for (int j = n - 1; j >= 0; --j) {  // L' x = y
        Real x = work_[j];
        for (int p = compactStart_[j]; p < compactStart_[j + 1]; ++p)
            x -= compactValue_[p] * work_[compactIndex_[p]];
        work_[j] = x;
    }
    return plain(work_);
}

void SpringBlockSolver::computeUpdate(std::span<const SolverBody> bodies) {
    const int n = static_cast<int>(rowCount());
    loadResiduals(bodies);
    // Over the entries of L that compactPattern() kept, when the values it leaves out (+0)
    // change no bit: otherwise (a -0, an overflow, a NaN) again over the whole of L.
    if (!compacted_ || !solveCompact()) {
        if (compacted_)
            loadResiduals(bodies);
        solveFull();
    }
    for (int i = 0; i < n; ++i)
        delta_[i] = active_[i] ? work_[position_[i]] : 0;
}

void SpringBlockSolver::solveFull() {
    const int n = static_cast<int>(rowCount());
    // An inactive row's row and column of L are +0 (factor()), so its value stays +0 and its
    // column subtracts only +0 * +0: skipping it keeps every bit (x - +0 is x, -0 included).
    // Column j of L holds rows below j only, so work_[j] is not written while its column is
    // applied: held in a register, not loaded (or stored) again per entry.
    for (int j = 0; j < n; ++j) {  // L y = b
        if (!active_[rowAt_[j]])
            continue;
        const Real y = work_[j];
        for (int p = lStart_[j]; p < lStart_[j + 1]; ++p)
            work_[lIndex_[p]] -= lValue_[p] * y;
    }
    for (int j = 0; j < n; ++j)
        work_[j] /= diagonal_[j];
    for (int j = n - 1; j >= 0; --j) {  // L' x = y
        if (!active_[rowAt_[j]])
            continue;
        Real x = work_[j];
        for (int p = lStart_[j]; p < lStart_[j + 1]; ++p)
            x -= lValue_[p] * work_[lIndex_[p]];
        work_[j] = x;
    }
}

Real SpringBlockSolver::apply(std::span<SolverBody> bodies, bool clamp) {
    Real largestChange = 0;
    for (std::size_t i = 0; i < rowCount(); ++i) {
        if (!active_[i])
            continue;
        SpringRow& r = row(i);
        Real next = r.impulse + delta_[i];
        if (clamp && r.tensionOnly)
            next = std::min<Real>(next, 0);
        const Real change = next - r.impulse;
        applySpringImpulse(bodies[r.bodyA], bodies[r.bodyB], r, change);
        r.impulse = next;
        largestChange = std::max(largestChange, std::abs(change) / r.mass);
    }
    return largestChange;
}

void SpringBlockSolver::respond(std::span<SolverBody> change) {
    if (!factored_)
        return;
    const int n = static_cast<int>(rowCount());
    auto load = [&] {
        for (int i = 0; i < n; ++i) {
            const SpringRow& r = row(i);
            work_[position_[i]] =
                active_[i] ? 0 - springRowSpeed(change[r.bodyA], change[r.bodyB], r) : 0;
        }
    };
    load();
    // computeUpdate()'s solves.
    if (!compacted_ || !solveCompact()) {
        load();
        solveFull();
    }
    for (int i = 0; i < n; ++i) {
        if (!active_[i])
            continue;
        const SpringRow& r = row(i);
        applySpringImpulse(change[r.bodyA], change[r.bodyB], r, work_[position_[i]]);
    }
}

Real SpringBlockSolver::relaxSlackRows(std::span<SolverBody> bodies) {
    Real largestChange = 0;
    for (std::size_t i = 0; i < rowCount(); ++i) {
        if (active_[i])
            continue;
        SpringRow& r = row(i);
        SolverBody& a = bodies[r.bodyA];
        SolverBody& b = bodies[r.bodyB];
        if (r.deferred)
            finishSpringRow(a, b, r, h_);
        if (!r.tensionOnly || !usable(r))
            continue;
        const Real residual = springRowSpeed(a, b, r) + r.bias + r.softness * r.impulse;
        const Real next = std::min<Real>(0, r.impulse - r.mass * residual);
        applySpringImpulse(a, b, r, next - r.impulse);
        largestChange = std::max(largestChange, std::abs(next - r.impulse) / r.mass);
        r.impulse = next;
    }
    return largestChange;
}

Real SpringBlockSolver::solve(std::span<SolverBody> bodies, std::span<SpringRow> rows) {
    if (!factored_)
        return 0;
    // The rows are solved where they lie: the caller's targets and impulses between solves
    // (the joints' block: updateJointBlockTargets) are read as they are.
    // A discrete-gradient thread's row is the block's own: settle() linearises it again, in
    // place, and the engine moves no thread's target between solves.
    elements_ = rows;
    Real change = 0;
    if (settled_) {
        computeUpdate(bodies);
        change = std::max(apply(bodies, false), relaxSlackRows(bodies));
    } else {
        change = settle(bodies);
        if (factored_ && refreshTransverseRows(bodies) && factored_)
            change = settle(bodies);
    }
    storeTurnImpulses();
    return change;
}

Real SpringBlockSolver::solveActive(std::span<SolverBody> bodies, std::span<SpringRow> rows) {
    if (!factored_ || !settled_)
        return solve(bodies, rows);
    elements_ = rows;
    computeUpdate(bodies);
    const Real change = apply(bodies, false);
    storeTurnImpulses();
    return change;
}

void SpringBlockSolver::storeTurnImpulses() {
    for (SpringRow& row : elements_)
        row.turn = Vec3::Zero();
    for (std::size_t j = 0; j < transverse_.size(); ++j) {
        SpringRow& thread = elements_[owner_[j]];
        if (thread.discreteGradient && active_[elementCount_ + j])
            thread.turn += transverse_[j].impulse * transverse_[j].direction;
    }
}

bool SpringBlockSolver::refreshTransverseRows(std::span<SolverBody> bodies) {
    if (!(h_ > 0))
        return false;
    bool stale = false;
    for (std::size_t i = 0; i < elementCount_ && !stale; ++i) {
        const SpringRow& row = elements_[i];
        // A discrete-gradient thread's turn rows do not depend on its tension.
        if (!row.geometricStiffness || !usable(row) || row.discreteGradient)
            continue;
        // What its rows were built with is >= 0: an element that ends without tension (most of a
        // flying net's threads) cannot leave more of it explicit, and skips the division.
        const Real solved = -(row.impulse + row.knownImpulse) / h_;
        if (!(solved > 0))
            continue;
        // (omega_t h)^2 per newton of tension; the rows hold what they were built with, if any.
        const Real perTension =
            h_ * h_ * (bodies[row.bodyA].inverseMass + bodies[row.bodyB].inverseMass) / row.length;
        const Real built = tension_[i] * perTension >= kResolvedTransverse ? tension_[i] : 0;
        stale = (solved - built) * perTension >= kExplicitTransverseLimit;
    }
    if (!stale)
        return false;
    // Undo the solve, then build the transverse rows again from its tensions.
    for (std::size_t i = 0; i < rowCount(); ++i) {
        SpringRow& r = row(i);
        if (r.deferred)  // even a zero impulse along its Jacobians may flip a -0 velocity
            finishSpringRow(bodies[r.bodyA], bodies[r.bodyB], r, h_);
        const Real target = i < elementCount_ ? warm_[i] : 0;
        applySpringImpulse(bodies[r.bodyA], bodies[r.bodyB], r, target - r.impulse);
        if (i < elementCount_)
            tension_[i] = std::max<Real>(0, -(r.impulse + r.knownImpulse) / h_);
        r.impulse = target;
    }
    transverse_.clear();
    owner_.clear();
    addTransverseRows(bodies);
    start(bodies);
    return true;
}

bool SpringBlockSolver::findStaleThreads(std::span<const SolverBody> bodies) {
    stale_.assign(elementCount_, 0);
    endSpan_.resize(elementCount_);
    if (!(h_ > 0))
        return false;
    bool any = false;
    for (std::size_t i = 0; i < elementCount_; ++i) {
        const SpringRow& row = elements_[i];
        if (!(row.discreteGradient || row.levelGradient) || !wanted_[i])
            continue;
        // 1: a discrete-gradient row, whose turn rows follow it; 2: a three-level form's.
        const char mark = row.discreteGradient ? 1 : 2;
        if (!active_[i]) {  // caught in this round: linearised where it ends
            threadRowEndStretch(bodies[row.bodyA], bodies[row.bodyB], row, h_, endSpan_[i]);
            stale_[i] = mark;
            any = true;
            continue;
        }
        const bool stale =
            threadRowStale(bodies[row.bodyA], bodies[row.bodyB], row, h_, endSpan_[i]);
        stale_[i] = stale ? mark : 0;
        any = any || stale;
    }
    return any;
}

void SpringBlockSolver::relineariseStaleThreads(std::span<SolverBody> bodies, bool lastRound) {
    for (std::size_t i = 0; i < elementCount_; ++i) {
        if (!stale_[i])
            continue;
        SpringRow& row = elements_[i];
        SolverBody& a = bodies[row.bodyA];
        SolverBody& b = bodies[row.bodyB];
        // The row's impulse moves to its new line.
        applySpringImpulse(a, b, row, -row.impulse);
        // Unsettled for the last round: implicit Euler, which cannot gain (spring_row.h).
        if (lastRound)
            implicitEulerThreadRow(a, b, row, h_);
        else
            lineariseThreadRow(a, b, row, h_, endSpan_[i]);
        applySpringImpulse(a, b, row, row.impulse);
    }
    // Their turn rows follow the new line, from no impulse.
    for (std::size_t j = 0; j < transverse_.size(); ++j) {
        const std::uint32_t owner = owner_[j];
        if (stale_[owner] != 1)
            continue;
        const SpringRow& thread = elements_[owner];
        SpringRow& turn = transverse_[j];
        SolverBody& a = bodies[turn.bodyA];
        SolverBody& b = bodies[turn.bodyB];
        applySpringImpulse(a, b, turn, -turn.impulse);
        turn.impulse = 0;
        const Vec3 first = perpendicular(thread.direction);
        const bool second = j > 0 && owner_[j - 1] == owner;
        turn.direction = second ? Vec3(thread.direction.cross(first)) : first;
        lineariseThreadTurn(a, b, thread, turn, h_);
    }
}

Real SpringBlockSolver::settle(std::span<SolverBody> bodies) {
    const std::size_t n = rowCount();
    settled_ = true;
    // Rows left out keep no warm-start impulse. The active set through a local: GCC loaded
    // active_'s data and elementCount_ again for every row.
    const char* const wasActive = active_.data();
    for (std::size_t i = 0; i < n; ++i) {
        SpringRow& r = row(i);
        if (!wasActive[i] && r.impulse != 0) {
            applySpringImpulse(bodies[r.bodyA], bodies[r.bodyB], r, -r.impulse);
            r.impulse = 0;
        }
    }
    for (int round = 0;; ++round) {
        computeUpdate(bodies);
        const bool last = round + 1 == kActiveSetRounds;
        const Real change = apply(bodies, last);
        if (last)
            return change;
        // A thread that pushes goes slack; a slack one that would stretch takes load.
        bool changed = false;
        // Through locals: each char store to wanted may alias the members, which the compiler
        // would then load again for every row (most of a net's rows are deferred, ~55 each).
        const char* const active = active_.data();
        char* const wanted = wanted_.data();
        SpringRow* const elements = elements_.data();
        SpringRow* const transverse = transverse_.data();
        const std::size_t elementCount = elementCount_;
        const Real h = h_;
        for (std::size_t i = 0; i < n; ++i) {
            SpringRow& r = i < elementCount ? elements[i] : transverse[i - elementCount];
            wanted[i] = active[i];
            const SolverBody& a = bodies[r.bodyA];
            const SolverBody& b = bodies[r.bodyB];
            if (r.deferred) {
                // Slack at both levels, inactive: wanted exactly when usable and caught (below),
                // so prepared only then.
                if (!threadRowEndStretchExceeds(a, b, r, h, kFlipSpeed * h))
                    continue;
                finishSpringRow(a, b, r, h);
            }
            if (!r.tensionOnly || !usable(r))
                continue;
            // Pushes and pulls below kFlipSpeed are rounding (a net falling flat has threads at
            // exactly their rest length): flipping on them cost a refactorisation per round.
            // A discrete-gradient thread taut at the start pulls whatever its end stretch, and
            // a three-level form's taut at the level before it (spring_row.h): a push is its
            // linear model's, mended by linearising again.
            const bool pulls = threadRowPulls(r);
            if ((r.discreteGradient || r.levelGradient) && !pulls) {
                // One slack at the start pulls exactly when it ends stretched (its gradient is
                // positive there), whatever its linear model says: a catch's tangent crosses
                // zero above the rest length, and threads caught short of that were left out,
                // ended stretched without a pull and had the stretch projected away
                // (`net-energy` at omega_e h = 2 lost 74 %).
                wanted[i] = threadRowEndStretchExceeds(a, b, r, h, kFlipSpeed * h);
            } else {
                wanted[i] = active[i] ? pulls || r.impulse / r.mass <= kFlipSpeed
                                      : springRowSpeed(a, b, r) + r.bias > kFlipSpeed;
            }
            changed = changed || wanted[i] != active[i];
        }
        for (std::size_t i = elementCount_; i < n; ++i)
            wanted_[i] = wanted_[owner_[i - elementCount_]];
        const bool stale = findStaleThreads(bodies);
        changed = changed || stale;
        if (!changed)
            return change;
        // Undo the round, release the rows that leave, and solve again with the new set.
        for (std::size_t i = 0; i < n; ++i) {
            if (!active_[i])
                continue;
            SpringRow& r = row(i);
            const Real keep = wanted_[i] ? r.impulse - delta_[i] : 0;
            applySpringImpulse(bodies[r.bodyA], bodies[r.bodyB], r, keep - r.impulse);
            r.impulse = keep;
        }
        if (stale)
            relineariseStaleThreads(bodies, round + 2 == kActiveSetRounds);
        std::swap(active_, wanted_);
        assemble(bodies);
        if (!factor()) {
            factored_ = false;
            finishSpringRows(bodies, elements_, h_);  // for the caller's Gauss-Seidel
            return change;
        }
    }
}

}  // namespace tumble
