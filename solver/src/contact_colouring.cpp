// ContactRows' build: the colouring, the bundles, and the copies in and out of the constraints.
#include <algorithm>

#include "tumble/solver/contact_rows.h"
#include "tumble/solver/contact_solver.h"

namespace tumble {
namespace {

// Static and kinematic bodies: the rows never change their velocity, so they never colour.
bool moves(const SolverBody& body) {
    return body.inverseMass > 0 || (body.inverseInertia.array() != 0).any();
}

void setLane(Lane& lane, int index, Real value) {
    lane[index] = value;
}

void setLanes(Lane (&lanes)[3], int index, const Vec3& value) {
    for (int k = 0; k < 3; ++k)
        lanes[k][index] = value[k];
}

}  // namespace

// Each manifold takes the colour after the last one either of its moving bodies had: every body
// meets its manifolds in constraint order, and manifolds on disjoint bodies commute exactly, so a
// sweep in colour order is the scalar sweep's Gauss-Seidel in constraint order to the bit. A
// column of n levels has n colours (its chain is kept); a pyramid's rows fill the lanes.
void ContactRows::colour(std::span<const SolverBody> bodies,
                         std::span<const ContactConstraint> constraints) {
    bodyNext_.assign(bodies.size(), 0);
    constraintColour_.resize(constraints.size());
    std::uint32_t colours = 0;
    for (std::size_t i = 0; i < constraints.size(); ++i) {
        const ContactConstraint& c = constraints[i];
        const bool movesA = moves(bodies[c.bodyA]);
        const bool movesB = moves(bodies[c.bodyB]);
        const std::uint32_t colour =
            std::max(movesA ? bodyNext_[c.bodyA] : 0u, movesB ? bodyNext_[c.bodyB] : 0u);
        constraintColour_[i] = colour;
        if (movesA)
            bodyNext_[c.bodyA] = colour + 1;
        if (movesB)
            bodyNext_[c.bodyB] = colour + 1;
        colours = std::max(colours, colour + 1);
    }
    colourCount_ = static_cast<int>(colours);
    // Constraints sorted by colour and, within one, by point count, in constraint order within
    // each group (a counting sort). A colour's manifolds share no moving body, so their order
    // within it does not change a bit; grouped by count, a bundle of one-point manifolds (most of
    // a pile of spheres and capsules) sweeps one point slot, not the four of its largest lane.
    const auto group = [&](std::size_t i) {
        const auto count = static_cast<std::uint32_t>(std::clamp(constraints[i].pointCount, 0, 4));
        return constraintColour_[i] * kGroupsPerColour + count;
    };
    groupBegin_.assign(std::size_t{colours} * kGroupsPerColour + 1, 0);
    for (std::size_t i = 0; i < constraints.size(); ++i)
        ++groupBegin_[group(i) + 1];
    for (std::size_t k = 1; k < groupBegin_.size(); ++k)
        groupBegin_[k] += groupBegin_[k - 1];
    groupNext_.assign(groupBegin_.begin(), groupBegin_.end() - 1);
    order_.resize(constraints.size());
    for (std::size_t i = 0; i < constraints.size(); ++i)
        order_[groupNext_[group(i)]++] = static_cast<std::uint32_t>(i);
}

bool ContactRows::build(std::span<const SolverBody> bodies,
                        std::span<const ContactConstraint> constraints,
                        const SolverSettings& settings, Real inverseH) {
    // Mostly one-point manifolds (a pile of spheres and capsules, 1.2 points a manifold): the
    // scalar sweep's compact rows. Bundled by point count, the rows ran pile-1000 at 0.9x its
    // CPU but pile-4000 at 1.08-1.25x (bench/README.md), so the pile keeps the scalar sweep.
    std::size_t points = 0;
    for (const ContactConstraint& c : constraints)
        points += static_cast<std::size_t>(c.pointCount);
    if (!enoughPoints(points, constraints.size()))
        return false;
    colour(bodies, constraints);
    softTargets_ = false;
    // A bundle sweeps as many point slots as its manifolds have points. Where the colours leave
    // the lanes or the slots mostly empty (a lone column), the scalar sweep's compact rows give
    // the same bits for less work.
    const auto hasBlock = [&](std::size_t count) { return count > 1 || settings.tolerance > 0; };
    std::size_t bundleCount = 0;
    std::size_t slots = 0;
    std::size_t blockCount = 0;
    for (std::size_t g = 0; g + 1 < groupBegin_.size(); ++g) {
        const std::size_t bundles = (groupBegin_[g + 1] - groupBegin_[g] + kWidth - 1) / kWidth;
        bundleCount += bundles;
        slots += bundles * kWidth * (g % kGroupsPerColour);
        blockCount += hasBlock(g % kGroupsPerColour) ? bundles : 0;
    }
    if (constraints.size() * kMinimumFillDenominator < bundleCount * kWidth ||
        points * kMinimumFillDenominator < slots)
        return false;
    bundles_.resize(bundleCount);
    points_.resize(slots / kWidth);
    blocks_.resize(blockCount);
    const auto dummy = static_cast<std::uint32_t>(bodies.size());
    // One blank slot to copy from: a Point{} in the loop was zeroed again for every bundle
    // (1,888 bytes; 1 % of ContactSolver::prepare's instructions on pyramid-20). Only a bundle
    // with padding lanes copies it: a colour's group has one point count, so fill() writes
    // every field of every slot of a full bundle's lanes (the copies were 0.8 % of pyramid-20's
    // instructions).
    const Point blank{};
    std::size_t next = 0;
    std::uint32_t nextPoint = 0;
    std::uint32_t nextBlock = 0;
    for (std::size_t g = 0; g + 1 < groupBegin_.size(); ++g) {
        const std::uint32_t end = groupBegin_[g + 1];
        const auto count = static_cast<std::uint32_t>(g % kGroupsPerColour);
        for (std::uint32_t start = groupBegin_[g]; start < end; start += kWidth) {
            Bundle& bundle = bundles_[next++];
            bundle = Bundle{};
            bundle.firstPoint = nextPoint;
            const std::uint32_t lanes = std::min<std::uint32_t>(kWidth, end - start);
            if (lanes < kWidth)
                std::fill_n(points_.begin() + nextPoint, count, blank);
            nextPoint += count;
            bundle.bodyA.fill(dummy);
            bundle.bodyB.fill(dummy);
            if (hasBlock(count)) {
                bundle.block = nextBlock++;
                Block& block = blocks_[bundle.block];
                for (int k = 0; k < 16; ++k) {
                    block.block[k] = Lane{};
                    block.factor[k] = Lane{} + (k % 5 == 0 ? 1.0 : 0.0);  // identity
                }
                for (Lane& inverse : block.inverseDiagonal)
                    inverse = Lane{} + 1.0;
            }
            bundle.factorSet.fill(NormalFactor::kNone);
            bundle.laneCount = static_cast<std::uint8_t>(lanes);
            for (std::uint32_t lane = 0; lane < lanes; ++lane) {
                const std::uint32_t index = order_[start + lane];
                fill(bundle, static_cast<int>(lane), constraints[index], index, settings.slop,
                     inverseH);
                const ContactConstraint& c = constraints[index];
                bundle.inverseMassA[lane] = bodies[c.bodyA].inverseMass;
                bundle.inverseMassB[lane] = bodies[c.bodyB].inverseMass;
            }
        }
    }
    velocities_.resize(bodies.size() + 1);
    velocities_.back() = Velocity{};
    return true;
}

// One manifold into one lane: the constraint's prepared Jacobians, masses and impulses, and its
// normal target split so that the sweep's bias can enter (normal_block.h, normalTarget).
void ContactRows::fill(Bundle& bundle, int lane, const ContactConstraint& c, std::uint32_t index,
                       Real slop, Real inverseH) {
    bundle.bodyA[lane] = c.bodyA;
    bundle.bodyB[lane] = c.bodyB;
    bundle.constraint[lane] = index;
    bundle.points[lane] = static_cast<std::uint8_t>(c.pointCount);
    bundle.maxPoints = std::max(bundle.maxPoints, bundle.points[lane]);
    bundle.normals[lane] = c.normalGroup == NormalIslands::kNone;
    bundle.solved[lane] = bundle.normals[lane] && c.pointCount > 0 ? -1 : 0;
    bundle.grouped = bundle.grouped || !bundle.normals[lane];
    bundle.angular = bundle.angular || c.spinMass > 0 || c.rollingActive;
    setLanes(bundle.normal, lane, c.normal);
    setLanes(bundle.tangents[0], lane, c.tangents[0]);
    setLanes(bundle.tangents[1], lane, c.tangents[1]);
    setLane(bundle.friction, lane, c.friction);
    if (bundle.block != Bundle::kNoBlock) {
        for (int i = 0; i < 4; ++i) {
            for (int j = 0; j < 4; ++j)
                setLane(blocks_[bundle.block].block[4 * i + j], lane, c.normalBlock(i, j));
        }
    }
    for (int i = 0; i < c.pointCount; ++i) {
        const ContactConstraintPoint& p = c.points[i];
        Point& q = points_[bundle.firstPoint + i];
        bundle.hasPoint[i][lane] = -1;
        setLanes(q.angularA, lane, p.angularA);
        setLanes(q.angularB, lane, p.angularB);
        setLanes(q.impulseA, lane, p.angularImpulseA);
        setLanes(q.impulseB, lane, p.angularImpulseB);
        for (int r = 0; r < 2; ++r) {
            setLanes(q.tangentAngularA[r], lane, p.tangentAngularA[r]);
            setLanes(q.tangentAngularB[r], lane, p.tangentAngularB[r]);
            setLanes(q.tangentImpulseA[r], lane, p.tangentImpulseA[r]);
            setLanes(q.tangentImpulseB[r], lane, p.tangentImpulseB[r]);
            setLane(q.tangentMass[r], lane, p.tangentMass[r]);
            setLane(q.tangentImpulse[r], lane, p.tangentImpulse[r]);
        }
        for (int k = 0; k < 4; ++k) {
            setLane(q.tangentBlock[k], lane, p.tangent.block(k / 2, k % 2));
            setLane(q.tangentInverse[k], lane, p.tangent.inverse(k / 2, k % 2));
            setLane(q.tangentAxes[k], lane, p.tangent.axes(k / 2, k % 2));
        }
        setLane(q.tangentMoments[0], lane, p.tangent.moments(0));
        setLane(q.tangentMoments[1], lane, p.tangent.moments(1));
        setLane(q.normalMass, lane, p.normalMass);
        setLane(q.normalImpulse, lane, p.normalImpulse);
        const bool speculative = p.separation > 0;
        setLane(q.depth, lane, speculative ? 0 : std::max<Real>(0, -p.separation - slop));
        Real base = speculative ? -p.separation * inverseH : 0;
        if (p.bounces)
            base = p.reboundSpeed;
        setLane(q.targetBase, lane, base);
        setLane(q.correction, lane, p.bounces ? p.bounceCorrection * inverseH : 0);
    }
}

// normalTarget's split (fill) at the substep's separations: a speculative gap to close at
// inverseH, or the depth the biased sweep pushes out.
void ContactRows::softTargets(std::span<const Real> separations,
                              std::span<const std::uint32_t> firstPoint,
                              std::span<const std::array<Real, 2>> tangentTargets,
                              const std::array<Real, 3>& scales, Real slop, Real inverseH) {
    softScales_ = scales;
    softTargets_ = true;
    soft_.resize(points_.size());
    for (Bundle& bundle : bundles_) {
        for (int i = 0; i < bundle.maxPoints; ++i)
            soft_[bundle.firstPoint + i].scale = Lane{} + 1.0;
        for (int lane = 0; lane < bundle.laneCount; ++lane) {
            const std::uint32_t first = firstPoint[bundle.constraint[lane]];
            bundle.tangentTarget[0][lane] = tangentTargets[bundle.constraint[lane]][0];
            bundle.tangentTarget[1][lane] = tangentTargets[bundle.constraint[lane]][1];
            const Real scale = scales[bundle.bodyA[lane] == 0 || bundle.bodyB[lane] == 0 ? 2 : 1];
            for (int i = 0; i < bundle.points[lane]; ++i) {
                const Real s = separations[first + i];
                const bool speculative = s > 0;
                Point& q = points_[bundle.firstPoint + i];
                q.depth[lane] = speculative ? 0 : std::max<Real>(0, -s - slop);
                q.targetBase[lane] = speculative ? -s * inverseH : 0;
                q.correction[lane] = 0;
                soft_[bundle.firstPoint + i].separation[lane] = s;
                soft_[bundle.firstPoint + i].scale[lane] = speculative ? 1 : scale;
            }
        }
    }
}

void ContactRows::readGroupImpulses(std::span<const ContactConstraint> constraints) {
    for (Bundle& bundle : bundles_) {
        if (!bundle.grouped)
            continue;
        for (int lane = 0; lane < bundle.laneCount; ++lane) {
            if (bundle.normals[lane])
                continue;
            const ContactConstraint& c = constraints[bundle.constraint[lane]];
            for (int i = 0; i < c.pointCount; ++i)
                points_[bundle.firstPoint + i].normalImpulse[lane] = c.points[i].normalImpulse;
        }
    }
}

void ContactRows::dropBounceCorrections() {
    for (Bundle& bundle : bundles_) {
        for (int i = 0; i < bundle.maxPoints; ++i)
            points_[bundle.firstPoint + i].correction = Lane{};
    }
}

void ContactRows::store(std::span<ContactConstraint> constraints) const {
    for (const Bundle& bundle : bundles_) {
        for (int lane = 0; lane < bundle.laneCount; ++lane) {
            ContactConstraint& c = constraints[bundle.constraint[lane]];
            for (int i = 0; i < c.pointCount; ++i) {
                const Point& q = points_[bundle.firstPoint + i];
                c.points[i].normalImpulse = q.normalImpulse[lane];
                c.points[i].tangentImpulse = {q.tangentImpulse[0][lane], q.tangentImpulse[1][lane]};
            }
        }
    }
}

}  // namespace tumble
