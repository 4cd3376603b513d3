// ContactRows' build: the colouring, the bundles, and the copies in and out of the constraints.
#include <algorithm>
#include <bit>

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

// Greedy, in constraint order: each manifold takes the lowest colour neither of its moving
// bodies has yet. Deterministic, and a manifold keeps its colour while the contacts before it
// do not change.
void ContactRows::colour(std::span<const SolverBody> bodies,
                         std::span<const ContactConstraint> constraints) {
    bodyColours_.assign(bodies.size(), 0);
    constraintColour_.resize(constraints.size());
    colourCounts_.assign(kColours + 1, 0);
    for (std::size_t i = 0; i < constraints.size(); ++i) {
        const ContactConstraint& c = constraints[i];
        const bool movesA = moves(bodies[c.bodyA]);
        const bool movesB = moves(bodies[c.bodyB]);
        const std::uint64_t used =
            (movesA ? bodyColours_[c.bodyA] : 0) | (movesB ? bodyColours_[c.bodyB] : 0);
        const int colour = used == ~std::uint64_t{0} ? kColours : std::countr_one(used);
        constraintColour_[i] = static_cast<std::uint8_t>(colour);
        ++colourCounts_[colour];
        if (colour == kColours)
            continue;
        if (movesA)
            bodyColours_[c.bodyA] |= std::uint64_t{1} << colour;
        if (movesB)
            bodyColours_[c.bodyB] |= std::uint64_t{1} << colour;
    }
    // Constraints sorted by colour, in constraint order within one (a counting sort).
    std::vector<std::uint32_t>& begin = colourCounts_;
    std::uint32_t offset = 0;
    colourCount_ = 0;
    for (int colour = 0; colour <= kColours; ++colour) {
        const std::uint32_t count = begin[colour];
        if (count > 0 && colour < kColours)
            colourCount_ = colour + 1;
        begin[colour] = offset;
        offset += count;
    }
    order_.resize(constraints.size());
    for (std::size_t i = 0; i < constraints.size(); ++i)
        order_[begin[constraintColour_[i]]++] = static_cast<std::uint32_t>(i);
}

void ContactRows::build(std::span<const SolverBody> bodies,
                        std::span<const ContactConstraint> constraints,
                        const SolverSettings& settings, Real inverseH) {
    colour(bodies, constraints);
    // After the sort colourCounts_[k] is the end of colour k.
    std::size_t bundleCount = 0;
    std::uint32_t first = 0;
    for (int colour = 0; colour <= kColours; ++colour) {
        const std::uint32_t count = colourCounts_[colour] - first;
        bundleCount += colour < kColours ? (count + kWidth - 1) / kWidth : count;
        first = colourCounts_[colour];
    }
    bundles_.resize(bundleCount);
    const auto dummy = static_cast<std::uint32_t>(bodies.size());
    std::size_t next = 0;
    first = 0;
    for (int colour = 0; colour <= kColours; ++colour) {
        const std::uint32_t end = colourCounts_[colour];
        const std::uint32_t width = colour < kColours ? kWidth : 1;
        for (std::uint32_t start = first; start < end; start += width) {
            Bundle& bundle = bundles_[next++];
            bundle = Bundle{};
            bundle.bodyA.fill(dummy);
            bundle.bodyB.fill(dummy);
            for (int k = 0; k < 16; ++k)
                bundle.factor[k] = Lane{} + (k % 5 == 0 ? 1.0 : 0.0);  // identity
            bundle.factorSet.fill(NormalFactor::kNone);
            const std::uint32_t lanes = std::min(width, end - start);
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
        first = end;
    }
    velocities_.resize(bodies.size() + 1);
    velocities_.back() = Velocity{};
}

// One manifold into one lane: the constraint's prepared Jacobians, masses and impulses, and its
// normal target split so that the sweep's bias can enter (normal_block.h, normalTarget).
void ContactRows::fill(Bundle& bundle, int lane, const ContactConstraint& c, std::uint32_t index,
                       Real slop, Real inverseH) const {
    bundle.bodyA[lane] = c.bodyA;
    bundle.bodyB[lane] = c.bodyB;
    bundle.constraint[lane] = index;
    bundle.points[lane] = static_cast<std::uint8_t>(c.pointCount);
    bundle.maxPoints = std::max(bundle.maxPoints, bundle.points[lane]);
    bundle.normals[lane] = c.normalGroup == NormalIslands::kNone;
    bundle.grouped = bundle.grouped || !bundle.normals[lane];
    bundle.angular = bundle.angular || c.spinMass > 0 || c.rollingActive;
    setLanes(bundle.normal, lane, c.normal);
    setLanes(bundle.tangents[0], lane, c.tangents[0]);
    setLanes(bundle.tangents[1], lane, c.tangents[1]);
    setLane(bundle.friction, lane, c.friction);
    for (int i = 0; i < 4; ++i) {
        for (int j = 0; j < 4; ++j)
            setLane(bundle.block[4 * i + j], lane, c.normalBlock(i, j));
    }
    for (int i = 0; i < c.pointCount; ++i) {
        const ContactConstraintPoint& p = c.points[i];
        Point& q = bundle.point[i];
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
        }
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

void ContactRows::readGroupImpulses(std::span<const ContactConstraint> constraints) {
    for (Bundle& bundle : bundles_) {
        if (!bundle.grouped)
            continue;
        for (int lane = 0; lane < bundle.laneCount; ++lane) {
            if (bundle.normals[lane])
                continue;
            const ContactConstraint& c = constraints[bundle.constraint[lane]];
            for (int i = 0; i < c.pointCount; ++i)
                bundle.point[i].normalImpulse[lane] = c.points[i].normalImpulse;
        }
    }
}

void ContactRows::dropBounceCorrections() {
    for (Bundle& bundle : bundles_) {
        for (Point& q : bundle.point)
            q.correction = Lane{};
    }
}

void ContactRows::store(std::span<ContactConstraint> constraints) const {
    for (const Bundle& bundle : bundles_) {
        for (int lane = 0; lane < bundle.laneCount; ++lane) {
            ContactConstraint& c = constraints[bundle.constraint[lane]];
            for (int i = 0; i < c.pointCount; ++i) {
                const Point& q = bundle.point[i];
                c.points[i].normalImpulse = q.normalImpulse[lane];
                c.points[i].tangentImpulse = {q.tangentImpulse[0][lane], q.tangentImpulse[1][lane]};
            }
        }
    }
}

}  // namespace tumble
