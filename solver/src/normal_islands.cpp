#include "tumble/solver/normal_islands.h"

#include <algorithm>
#include <cmath>
#include <numeric>

#include "normal_block.h"
#include "tumble/solver/contact_solver.h"

namespace tumble {
namespace {

// As in normal_block.cpp: the regularisation that picks the minimum-norm split of a face's load,
// and the feasibility tolerance as a fraction of the largest |c| (m/s).
constexpr Real kRegularisation = 1e-10;
constexpr Real kTolerance = 1e-9;
constexpr Real kFloor = 1e-14;  // (m/s)
// Block pivots that do not reduce the number of infeasible rows before single (Murty) pivots.
constexpr int kBlockPivotTries = 3;

bool movable(const SolverBody& body) {
    return body.inverseMass > 0 || !body.inverseInertia.isZero();
}

std::uint32_t findRoot(std::vector<std::uint32_t>& parent, std::uint32_t i) {
    while (parent[i] != i) {
        parent[i] = parent[parent[i]];
        i = parent[i];
    }
    return i;
}

// Normal velocity change at point p of constraint c per unit normal impulse at point q of
// constraint d, through the bodies the two share (J_p M^-1 J_q').
Real coupling(std::span<const SolverBody> bodies, const ContactConstraint& c,
              const ContactConstraintPoint& p, const ContactConstraint& d,
              const ContactConstraintPoint& q) {
    const std::uint32_t bodyOf[2][2] = {{c.bodyA, c.bodyB}, {d.bodyA, d.bodyB}};
    const Vec3* angularP[2] = {&p.angularA, &p.angularB};
    const Vec3* impulseQ[2] = {&q.angularImpulseA, &q.angularImpulseB};
    Real k = 0;
    for (int i = 0; i < 2; ++i) {
        for (int j = 0; j < 2; ++j) {
            if (bodyOf[0][i] != bodyOf[1][j])
                continue;
            // A is pushed along -n, B along +n: the signs of the two rows multiply.
            const Real sign = (i == j) ? 1 : -1;
            const SolverBody& body = bodies[bodyOf[0][i]];
            k +=
                sign * (body.inverseMass * c.normal.dot(d.normal) + angularP[i]->dot(*impulseQ[j]));
        }
    }
    return k;
}

// Cholesky of the rows `active` of the n x n matrix k (+ eps on the diagonal) into l, then the
// solution of (k + eps 1)_SS x_S = -c_S; x is zero off S. False if not positive definite.
bool solveActiveRows(const Real* k, int n, const std::uint8_t* active, const Real* c, Real eps,
                     Real* l, Real* x, Real* y) {
    int rows[NormalIslands::kMaxRows];
    int m = 0;
    for (int i = 0; i < n; ++i) {
        x[i] = 0;
        if (active[i])
            rows[m++] = i;
    }
    for (int i = 0; i < m; ++i) {
        for (int j = 0; j <= i; ++j) {
            Real sum = k[rows[i] * n + rows[j]] + (i == j ? eps : 0);
            for (int p = 0; p < j; ++p)
                sum -= l[i * m + p] * l[j * m + p];
            if (i == j) {
                if (!(sum > 0))
                    return false;
                l[i * m + i] = std::sqrt(sum);
            } else {
                l[i * m + j] = sum / l[j * m + j];
            }
        }
    }
    for (int i = 0; i < m; ++i) {
        Real sum = -c[rows[i]];
        for (int p = 0; p < i; ++p)
            sum -= l[i * m + p] * y[p];
        y[i] = sum / l[i * m + i];
    }
    for (int i = m - 1; i >= 0; --i) {
        Real sum = y[i];
        for (int p = i + 1; p < m; ++p)
            sum -= l[p * m + i] * x[rows[p]];
        x[rows[i]] = sum / l[i * m + i];
    }
    return true;
}

}  // namespace

void NormalIslands::prepare(std::span<const SolverBody> bodies,
                            std::span<ContactConstraint> constraints) {
    selectGroups(bodies, constraints);
    buildMatrices(bodies, constraints);
}

// Union-find over the movable bodies; per group its manifolds, rows, lightest and heaviest body
// and whether a point bounces; the groups solved here numbered in order of first appearance, and
// each constraint marked, with its group's row count in groupBegin_[group + 1].
void NormalIslands::selectGroups(std::span<const SolverBody> bodies,
                                 std::span<ContactConstraint> constraints) {
    const auto bodyCount = static_cast<std::uint32_t>(bodies.size());
    parent_.resize(bodyCount);
    std::iota(parent_.begin(), parent_.end(), 0u);
    for (ContactConstraint& c : constraints) {
        c.normalGroup = kNone;
        if (c.pointCount > 0 && movable(bodies[c.bodyA]) && movable(bodies[c.bodyB]))
            parent_[findRoot(parent_, c.bodyA)] = findRoot(parent_, c.bodyB);
    }
    // Per root: manifolds, rows and the lightest and heaviest body; candidates get a group.
    rootGroup_.assign(bodyCount, kNone);
    groupBegin_.clear();
    groupMass_[0].clear();
    groupMass_[1].clear();
    groupBounces_.clear();
    std::vector<std::uint32_t>& manifolds = counts_[0];
    manifolds.clear();
    const auto rootOf = [&](const ContactConstraint& c) {
        return findRoot(parent_, movable(bodies[c.bodyA]) ? c.bodyA : c.bodyB);
    };
    for (const ContactConstraint& c : constraints) {
        if (c.pointCount == 0 || !(movable(bodies[c.bodyA]) || movable(bodies[c.bodyB])))
            continue;
        std::uint32_t& group = rootGroup_[rootOf(c)];
        if (group == kNone) {
            group = static_cast<std::uint32_t>(groupBegin_.size());
            groupBegin_.push_back(0);
            manifolds.push_back(0);
            groupMass_[0].push_back(INFINITY);
            groupMass_[1].push_back(0);
            groupBounces_.push_back(0);
        }
        for (int i = 0; i < c.pointCount; ++i)
            groupBounces_[group] |= static_cast<std::uint8_t>(c.points[i].bounces);
        groupBegin_[group] += c.pointCount;
        manifolds[group] += 1;
        for (const std::uint32_t body : {c.bodyA, c.bodyB}) {
            if (bodies[body].inverseMass > 0) {
                const Real mass = 1 / bodies[body].inverseMass;
                groupMass_[0][group] = std::min(groupMass_[0][group], mass);
                groupMass_[1][group] = std::max(groupMass_[1][group], mass);
            }
        }
    }
    // Renumber: only the groups solved here keep a number, in order of first appearance.
    std::vector<std::uint32_t>& renumber = counts_[1];
    renumber.assign(groupBegin_.size(), kNone);
    groupCount_ = 0;
    for (std::size_t g = 0; g < groupBegin_.size(); ++g) {
        if (manifolds[g] > 1 && groupBegin_[g] <= static_cast<std::uint32_t>(kMaxRows) &&
            (groupBounces_[g] || groupMass_[1][g] >= kMassRatio * groupMass_[0][g]))
            renumber[g] = static_cast<std::uint32_t>(groupCount_++);
    }
    for (std::uint32_t& group : rootGroup_) {
        if (group != kNone)
            group = renumber[group];
    }
    groupBegin_.assign(groupCount_ + 1, 0);
    if (groupCount_ == 0)
        return;  // every normalGroup is kNone already: no third pass (a pile has no groups)
    for (ContactConstraint& c : constraints) {
        if (c.pointCount == 0 || !(movable(bodies[c.bodyA]) || movable(bodies[c.bodyB])))
            continue;
        c.normalGroup = rootGroup_[rootOf(c)];
        if (c.normalGroup != kNone)
            groupBegin_[c.normalGroup + 1] += c.pointCount;
    }
}

// The rows of each group in constraint order, and each group's K.
void NormalIslands::buildMatrices(std::span<const SolverBody> bodies,
                                  std::span<const ContactConstraint> constraints) {
    std::partial_sum(groupBegin_.begin(), groupBegin_.end(), groupBegin_.begin());
    rows_.resize(groupBegin_.back());
    std::vector<std::uint32_t>& cursor = counts_[0];
    cursor.assign(groupBegin_.begin(), groupBegin_.end());
    for (std::uint32_t index = 0; groupCount_ > 0 && index < constraints.size(); ++index) {
        const ContactConstraint& c = constraints[index];
        if (c.normalGroup == kNone)
            continue;
        for (int i = 0; i < c.pointCount; ++i)
            rows_[cursor[c.normalGroup]++] = Row{index, i};
    }
    matrixBegin_.assign(groupCount_ + 1, 0);
    for (int g = 0; g < groupCount_; ++g) {
        const std::uint32_t n = groupBegin_[g + 1] - groupBegin_[g];
        matrixBegin_[g + 1] = matrixBegin_[g] + n * n;
    }
    matrix_.resize(matrixBegin_.back());
    for (int g = 0; g < groupCount_; ++g) {
        const std::uint32_t first = groupBegin_[g];
        const std::uint32_t n = groupBegin_[g + 1] - first;
        Real* k = matrix_.data() + matrixBegin_[g];
        for (std::uint32_t i = 0; i < n; ++i) {
            const Row& ri = rows_[first + i];
            const ContactConstraint& c = constraints[ri.constraint];
            for (std::uint32_t j = 0; j < n; ++j) {
                const Row& rj = rows_[first + j];
                const ContactConstraint& d = constraints[rj.constraint];
                k[i * n + j] = coupling(bodies, c, c.points[ri.point], d, d.points[rj.point]);
            }
        }
    }
}

Real NormalIslands::solve(std::span<SolverBody> bodies, std::span<ContactConstraint> constraints,
                          Real relaxation, Real bias, Real slop, Real inverseH) {
    Real largestChange = 0;
    for (int g = 0; g < groupCount_; ++g) {
        const std::uint32_t first = groupBegin_[g];
        const int n = static_cast<int>(groupBegin_[g + 1] - first);
        const Real* k = matrix_.data() + matrixBegin_[g];
        gap_.resize(n);
        impulse_.resize(n);
        for (int i = 0; i < n; ++i) {
            const Row& row = rows_[first + i];
            const ContactConstraint& c = constraints[row.constraint];
            const ContactConstraintPoint& p = c.points[row.point];
            impulse_[i] = p.normalImpulse;
            gap_[i] = normalSpeed(bodies[c.bodyA], bodies[c.bodyB], c.normal, p) -
                      normalTarget(p, bias, slop, inverseH);
        }
        // c = g - K lambda0: the velocities with no normal impulse in the group.
        for (int i = 0; i < n; ++i) {
            for (int j = 0; j < n; ++j)
                gap_[i] -= k[i * n + j] * impulse_[j];
        }
        exact_.assign(impulse_.begin(), impulse_.end());
        solveGroup(g, gap_, exact_);
        for (int i = 0; i < n; ++i) {
            const Row& row = rows_[first + i];
            ContactConstraint& c = constraints[row.constraint];
            ContactConstraintPoint& p = c.points[row.point];
            const Real next =
                std::max<Real>(0, impulse_[i] + relaxation * (exact_[i] - impulse_[i]));
            applyNormal(bodies[c.bodyA], bodies[c.bodyB], c.normal, p, next - impulse_[i]);
            exact_[i] = next - impulse_[i];
            p.normalImpulse = next;
        }
        for (int i = 0; i < n; ++i) {
            Real change = 0;
            for (int j = 0; j < n; ++j)
                change += k[i * n + j] * exact_[j];
            largestChange = std::max(largestChange, std::abs(change));
        }
    }
    return largestChange;
}

// The LCP of the class comment for group g, on K + eps 1: lambda comes in as the last answer
// (its positive entries are the first active set) and goes out as the new one. Block principal
// pivoting (Judice & Pires): with the active set S, solve the equalities on S; rows of S with a
// negative impulse and rows off S with a negative velocity are infeasible; flip them all. When
// that fails kBlockPivotTries times to reduce their number, flip only the last one (Murty's
// least-index rule, from the end), which terminates for a P-matrix. Returns false, leaving a
// projected Gauss-Seidel answer, if the budget runs out (not seen; a guard against rounding).
bool NormalIslands::solveGroup(int g, const std::vector<Real>& c, std::vector<Real>& lambda) {
    const int n = static_cast<int>(groupBegin_[g + 1] - groupBegin_[g]);
    const Real* k = matrix_.data() + matrixBegin_[g];
    Real largestDiagonal = 0;
    Real largestC = 0;
    for (int i = 0; i < n; ++i) {
        largestDiagonal = std::max(largestDiagonal, k[i * n + i]);
        largestC = std::max(largestC, std::abs(c[i]));
    }
    const Real eps = kRegularisation * largestDiagonal;
    const Real tolerance = std::max(kTolerance * largestC, kFloor);
    active_.resize(n);
    for (int i = 0; i < n; ++i)
        active_[i] = lambda[i] > 0;
    factor_.resize(n * n);
    work_.resize(2 * n);
    Real* x = work_.data();
    Real* y = work_.data() + n;
    int best = n + 1;
    int tries = kBlockPivotTries;
    for (int iteration = 0; iteration < 4 * n + 20; ++iteration) {
        if (!solveActiveRows(k, n, active_.data(), c.data(), eps, factor_.data(), x, y))
            break;
        int infeasible = 0;
        int last = -1;
        for (int i = 0; i < n; ++i) {
            Real w = c[i];
            for (int j = 0; j < n; ++j)
                w += k[i * n + j] * x[j];
            const bool bad = active_[i] ? x[i] * k[i * n + i] < -tolerance : w < -tolerance;
            if (bad) {
                ++infeasible;
                last = i;
                y[i] = 1;
            } else {
                y[i] = 0;
            }
        }
        if (infeasible == 0) {
            for (int i = 0; i < n; ++i)
                lambda[i] = std::max<Real>(0, x[i]);
            return true;
        }
        if (infeasible < best) {
            best = infeasible;
            tries = kBlockPivotTries;
        }
        if (tries > 0) {
            --tries;
            for (int i = 0; i < n; ++i)
                active_[i] ^= static_cast<std::uint8_t>(y[i] != 0);
        } else {
            active_[last] ^= 1;
        }
    }
    // Projected Gauss-Seidel on the group's rows from the incoming impulses.
    for (int sweep = 0; sweep < 50; ++sweep) {
        for (int i = 0; i < n; ++i) {
            Real w = c[i];
            for (int j = 0; j < n; ++j)
                w += k[i * n + j] * lambda[j];
            if (k[i * n + i] > 0)
                lambda[i] = std::max<Real>(0, lambda[i] - w / k[i * n + i]);
        }
    }
    return false;
}

}  // namespace tumble
