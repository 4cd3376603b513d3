#include "solve_stage.h"

#include <algorithm>
#include <cmath>

#include "integrator.h"
#include "joints.h"
#include "springs.h"
#include "tumble/core/lane_kernel.h"
#include "tumble/solver/friction_anchors.h"

namespace tumble {

Real mixFriction(Real a, Real b) {
    return std::sqrt(a * b);
}
Real mixRestitution(Real a, Real b) {
    return std::max(a, b);
}

namespace {

constexpr Real kProjectionCompliance = 0.01;
// Relative stretch below which post-stabilisation leaves a spring alone.
constexpr Real kNegligibleStretch = 1e-12;

// What this step's forces did to a body's velocities: the change of its point at r is
// linear + angular x r, which the solver turns into the time and speed of an impact within the
// step. Taken once per manifold and body, not per point (the same operations: 0.9 % of
// pyramid-20's instructions were these differences, taken again for each point).
struct VelocityChange {
    Vec3 linear;
    Vec3 angular;
    VelocityChange(const BodyStore& bodies, std::uint32_t index)
        : linear(bodies.motion[index].linearVelocity - bodies.previousMotion[index].linearVelocity),
          angular(bodies.motion[index].angularVelocity -
                  bodies.previousMotion[index].angularVelocity) {}
    Vec3 at(const Vec3& r) const { return linear + angular.cross(r); }
};

// A constraint's fields from its contact (buildConstraints), but for its bodies. Compiled for
// AVX2 and the baseline like the solver's kernels (lane_kernel.h, the same bits): the
// baseline's two-operand SSE2 copied every temporary through extra registers.
TUMBLE_LANE_KERNEL void fillConstraint(ContactConstraint& c, const Contact& contact,
                                       const BodyStore& bodies, std::uint32_t indexA,
                                       std::uint32_t indexB, const Material& materialA,
                                       const Material& materialB, Real inverseH) {
    c.normal = contact.manifold.normal;
    c.friction = mixFriction(materialA.friction, materialB.friction);
    c.restitution = mixRestitution(materialA.restitution, materialB.restitution);
    c.spinningFriction = std::max(materialA.spinningFriction, materialB.spinningFriction);
    c.rollingFriction = std::max(materialA.rollingFriction, materialB.rollingFriction);
    c.angularImpulse = contact.angularImpulse;
    c.pointCount = contact.manifold.pointCount;
    c.pushOut = true;  // run() clears it for the contacts of sprung bodies
    // The solver builds its tangent basis from the normal; cached friction is kept in world
    // coordinates so a turning basis does not scramble it.
    c.tangents = frictionBasis(c.normal);
    c.tangentsSet = true;  // prepare() would take the same basis again (pile-1000: 0.3 %)
    const VelocityChange changeA(bodies, indexA);
    const VelocityChange changeB(bodies, indexB);
    for (int i = 0; i < c.pointCount; ++i) {
        const ContactPoint& point = contact.manifold.points[i];
        ContactConstraintPoint& p = c.points[i];
        p.rA = point.position - bodies.motion[indexA].center;
        p.rB = point.position - bodies.motion[indexB].center;
        p.separation = point.separation;
        p.normalImpulse = contact.normalImpulse[i];
        p.tangentImpulse = {contact.tangentImpulse[i].dot(c.tangents[0]),
                            contact.tangentImpulse[i].dot(c.tangents[1])};
        p.normalAcceleration = c.normal.dot(changeB.at(p.rB) - changeA.at(p.rA)) * inverseH;
    }
}

}  // namespace

std::span<const PseudoVelocity> SolveStage::pseudoVelocities() const {
    if (pseudo_.size() != solverBodies_.size())
        return {};
    return std::span<const PseudoVelocity>(pseudo_).subspan(1);
}

// Every active contact with points between awake (or static) bodies, written over last step's
// constraints: only the fields prepare() reads are set, the rest it fills. Building a default
// constraint and copying it in (3 KB each) was a tenth of a pile's step.
std::span<ContactConstraint> SolveStage::buildConstraints(const BodyStore& bodies,
                                                          const ShapeStore& shapes,
                                                          const ContactManager& contacts,
                                                          const StepContext& context) {
    std::size_t count = 0;
    constraintSources_.clear();
    for (const std::uint32_t slot : contacts.touchingSlots()) {
        const Contact& contact = contacts.contact(slot);
        if (!contacts.isActive(slot) || contact.manifold.pointCount == 0)
            continue;
        // Live while the contact is (shapePose says why): unchecked, as the narrowphase's.
        const std::uint32_t indexA = bodies.checkedIndexOf(contact.bodyA);
        const std::uint32_t indexB = bodies.checkedIndexOf(contact.bodyB);
        // A sleeping body resting on a kinematic body at rest: the pair stays collided (the
        // kinematic body may move) but the sleeper is not solved.
        if (bodies.isSleeping(indexA) || bodies.isSleeping(indexB))
            continue;
        const Material& materialA = shapes.records[contact.shapeA.index].def.material;
        const Material& materialB = shapes.records[contact.shapeB.index].def.material;
        if (count == constraints_.size())
            constraints_.emplace_back();
        ContactConstraint& c = constraints_[count++];
        c.bodyA = solverBodyIndex(bodies, indexA);
        c.bodyB = solverBodyIndex(bodies, indexB);
        fillConstraint(c, contact, bodies, indexA, indexB, materialA, materialB, context.inverseH);
        constraintSources_.push_back({slot, indexA, indexB});
    }
    return std::span<ContactConstraint>(constraints_).first(count);
}

// The awake bodies' velocities and the masses the rows see, for a step of length h.
void SolveStage::loadSolverBodies(const BodyStore& bodies, Real h) {
    const std::size_t awakeCount = bodies.awake.size();
    solverBodies_.resize(1 + awakeCount);
    solverBodies_[0] = SolverBody{};
    for (std::size_t k = 0; k < awakeCount; ++k) {
        const std::uint32_t i = bodies.awake[k];
        const BodyMotion& m = bodies.motion[i];
        const BodyInertia& inertia = bodies.inertia[i];
        SolverBody& s = solverBodies_[1 + k];
        s.linearVelocity = m.linearVelocity;
        s.angularVelocity = m.angularVelocity;
        // Implicit damping, (M + h D) u1 = M u0 + h f + J'lambda: integrateVelocity divided
        // u0 + h M^-1 f by 1 + h c; the rows' impulses must be divided by it too, or damping
        // would eat the part of the weight a spring or joint carries (rest 1/(1 + h c) short).
        // So the rows see the damped mass M (1 + h c). No damping: bitwise the plain mass.
        const BodyInfo& info = bodies.info[i];
        s.inverseMass = inertia.inverseMass / (1 + h * info.linearDamping);
        // A translation-only body (a lumped node): no rotation to apply to its zero inverse
        // inertia (integrateVelocity says why the bits hold).
        if (info.fixedRotation) {
            s.inverseInertia = Mat3::Zero();
            continue;
        }
        const Mat3 rotation = m.orientation.toRotationMatrix();
        s.inverseInertia = rotation * inertia.inverseInertiaLocal * rotation.transpose() /
                           (1 + h * info.angularDamping);
    }
}

// The solved velocities back to the awake dynamic bodies.
void SolveStage::storeVelocities(BodyStore& bodies) const {
    for (std::size_t k = 0; k < bodies.awake.size(); ++k) {
        const std::uint32_t i = bodies.awake[k];
        if (bodies.info[i].type != BodyType::Dynamic)
            continue;
        bodies.motion[i].linearVelocity = solverBodies_[1 + k].linearVelocity;
        bodies.motion[i].angularVelocity = solverBodies_[1 + k].angularVelocity;
    }
}

// The constraints' impulses back into the contact cache (warm start, reports).
void SolveStage::storeImpulses(ContactManager& contacts, std::span<ContactConstraint> constraints,
                               bool anchored) {
    for (std::size_t j = 0; j < constraints.size(); ++j) {
        ContactConstraint& c = constraints[j];
        if (anchored) {  // equilibrated before release reads the manifold's friction share
            // The anchor pass measured the share on these impulses, unless this changed them.
            const bool changed = equilibrateFriction(c);
            const bool slips = (changed || slipping_[j] == kUnmeasured) ? AnchorTable::slips(c)
                                                                        : slipping_[j] != 0;
            anchors_.release(constraintSources_[j].slot, slips);
        }
        Contact& contact = contacts.contact(constraintSources_[j].slot);
        contact.angularImpulse = c.angularImpulse;
        for (int i = 0; i < c.pointCount; ++i) {
            contact.normalImpulse[i] = c.points[i].normalImpulse;
            contact.tangentImpulse[i] = c.points[i].tangentImpulse[0] * c.tangents[0] +
                                        c.points[i].tangentImpulse[1] * c.tangents[1];
        }
    }
}

SolverStats SolveStage::run(BodyStore& bodies, const ShapeStore& shapes, ContactManager& contacts,
                            SpringStore& springs, JointStore& joints, const StepContext& context,
                            const SolverSettings& settings) {
    softRun_ = false;
    loadSolverBodies(bodies, context.h);

    const std::span<ContactConstraint> constraints =
        buildConstraints(bodies, shapes, contacts, context);
    buildSpringRows(
        springs, bodies, context.h,
        [&](std::uint32_t index) {
            return bodies.isAwake(index) ? solverBodyIndex(bodies, index) : 0u;
        },
        springRows_, rowSpring_, rowBodies_);
    // Only the contacts read sprung_ (here and holdAnchors()): a net in flight touches nothing.
    if (settings.stabilisation == Stabilisation::SplitImpulse && !constraints.empty()) {
        markSprung(bodies, springs);
        for (ContactConstraint& c : constraints)
            c.pushOut = sprung_[c.bodyA] == 0 && sprung_[c.bodyB] == 0;
    }

    buildJointRows(joints, bodies, context.h, jointRows_, rowJoint_);

    const std::span<SegmentContactRow> threadRows =
        threadContacts_.build(springs, bodies, shapes, contacts, context);

    const SolverStats stats = solver_.solve(solverBodies_, constraints, pseudo_, context.h,
                                            settings, springRows_, jointRows_, threadRows);
    threadContacts_.store();
    const bool anchored =
        settings.frictionAnchors && settings.stabilisation == Stabilisation::SplitImpulse;
    if (anchored)
        holdAnchors(bodies, contacts, constraints, context,
                    AnchorLengths::of(settings.slop, contacts.contactMargin));

    brokenJoints_.clear();
    storeJointResults(joints, jointRows_, rowJoint_, context.h, brokenJoints_);

    // Through locals, and the bool stored last: the compiler otherwise loaded the vectors and
    // the step's 1/h again after each row's store.
    const SpringRow* const rows = springRows_.data();
    const std::uint32_t* const springOf = rowSpring_.data();
    SpringStepState* const states = springs.state.data();
    const Real inverseH = context.inverseH;
    for (std::size_t j = 0, n = springRows_.size(); j < n; ++j) {
        const SpringRow& row = rows[j];
        // A discrete-gradient thread's tension is its new half's force (spring_row.h): the
        // step's impulse also holds last step's half, absent in a thread's first step.
        const Real tension = row.discreteGradient ? -2 * row.impulse * inverseH
                                                  : -(row.impulse + row.knownImpulse) * inverseH;
        const bool slack = row.tensionOnly && !(tension > 0);
        SpringStepState& state = states[springOf[j]];
        state.carried =
            row.discreteGradient ? Vec3(row.impulse * row.direction + row.turn) : Vec3::Zero();
        state.tension = tension;
        state.slack = slack;
    }

    storeImpulses(contacts, constraints, anchored);
    storeVelocities(bodies);
    return stats;
}

// Which solver bodies a spring ends on (awake dynamic ones: not a kinematic platform a spring
// hangs from). The implicit springs' ends are this step's rowBodies_ (buildSpringRows leaves out
// only springs without an awake dynamic end): looking each id up again was 1 % of a net's step.
void SolveStage::markSprung(const BodyStore& bodies, const SpringStore& springs) {
    sprung_.assign(solverBodies_.size(), 0);
    const auto mark = [&](std::uint32_t index) {
        if (bodies.isAwakeDynamic(index))
            sprung_[solverBodyIndex(bodies, index)] = 1;
    };
    for (const RowBodies& ends : rowBodies_) {
        mark(ends.a);
        if (!ends.world)
            mark(ends.b);
    }
    if (springs.implicitCount == springs.count())
        return;
    for (const SpringDef& def : springs.defs) {
        if (def.formulation != SpringFormulation::Explicit)
            continue;
        for (const BodyId body : {def.bodyA, def.bodyB}) {
            if (!body.isNull())
                mark(bodies.indexOf(body));
        }
    }
}

// The anchors' drifts are those of the poses the step starts from, as the constraints' points.
//
// A manifold whose friction reached its limit in this step's velocity solve slides: it has no
// place to hold, and is left out (and seated afresh when it sticks again). Pulled, the 1,000-body
// pile's landing bodies (1.3-2 m/s) went deeper into the terrain than the same pile on a
// half-space by more than 1 cm (hull 0.051 against 0.041 m; TerrainTunnel): the pull at a
// sliding corner under the centre of mass turned the body into the ground, and the push-out
// acts only the step after.
//
// A body a spring ends on is left out: the pass moves positions and sees no spring, and a
// spring's state is its length, so what the pass moves such a body by comes back as force next
// step. A net node (20 g) on a thread of 1e4 N/m pulled back 10 um (the deadband) gets 0.1 N,
// half its weight, and 0.08 m/s a step: the soak's net kept jittering at that speed with anchors
// on and held its pile (one island, 1,382 bodies at 1,000) awake for good.
void SolveStage::holdAnchors(const BodyStore& bodies, const ContactManager& contacts,
                             std::span<const ContactConstraint> constraints,
                             const StepContext& context, const AnchorLengths& lengths) {
    anchors_.beginSolve();
    anchorDrifts_.assign(4 * constraints.size(), Vec3::Zero());
    slipping_.assign(constraints.size(), kUnmeasured);
    for (std::size_t j = 0; j < constraints.size(); ++j) {
        const ContactConstraint& c = constraints[j];
        if (sprung_[c.bodyA] != 0 || sprung_[c.bodyB] != 0)
            continue;
        slipping_[j] = AnchorTable::slips(c) ? 1 : 0;
        if (slipping_[j] != 0)
            continue;
        anchorDrift(bodies, contacts, j, c, context.h, lengths, true);
    }
    anchorPass_.run(solverBodies_, constraints, anchorDrifts_, pseudo_, context.inverseH, lengths);
}

// A row's geometry at the positions the step ended on.
SolveStage::ProjectedGeometry SolveStage::projectedGeometry(const BodyStore& bodies,
                                                            const SpringStore& springs,
                                                            std::size_t j) const {
    const SpringRow& solved = springRows_[j];
    const SpringDef& def = springs.defs[rowSpring_[j]];
    const RowBodies& ends = rowBodies_[j];  // the bodies cannot change within a step
    const Vec3 pA = anchorAt(bodies, ends.a, def.localAnchorA);
    const Vec3 pB = ends.world ? def.localAnchorB : anchorAt(bodies, ends.b, def.localAnchorB);
    const Vec3 d = pB - pA;  // projectedSpan()
    ProjectedGeometry row;
    row.length = d.norm();
    row.direction = row.length > 0 ? Vec3(d / row.length) : solved.direction;
    row.rA = pA - bodies.motion[ends.a].center;
    row.rB = ends.world ? Vec3::Zero() : Vec3(pB - bodies.motion[ends.b].center);
    return row;
}

Vec3 SolveStage::projectedSpan(const BodyStore& bodies, const SpringStore& springs,
                               std::size_t j) const {
    const RowBodies& ends = rowBodies_[j];
    if (ends.centred)
        return bodies.motion[ends.b].center - bodies.motion[ends.a].center;
    const SpringDef& def = springs.defs[rowSpring_[j]];
    const Vec3 pA = anchorAt(bodies, ends.a, def.localAnchorA);
    const Vec3 pB = ends.world ? def.localAnchorB : anchorAt(bodies, ends.b, def.localAnchorB);
    return pB - pA;
}

// What each row must correct at the positions the step ended on (m): returns the largest. Rows
// whose scheme owns their error skip the geometry (length -1), which projectSprings() fills in
// only when a correction is needed: most steps need none, and on the 40 x 40 net the anchors'
// transforms were ~5 % of a step.
Real SolveStage::projectionErrors(const BodyStore& bodies, const SpringStore& springs,
                                  const StepContext& context) {
    const std::size_t count = springRows_.size();
    projectedGeometry_.resize(count);
    projectionError_.resize(count);
    // Spans, not the members: the stores below would make the compiler reload each vector's
    // bounds every row (most rows of a net in flight are deferred, a few dozen instructions).
    const std::span<SpringRow> rows(springRows_);
    const std::span<ProjectedGeometry> geometry(projectedGeometry_);
    const std::span<Real> errors(projectionError_);
    const std::span<const RowBodies> ends(rowBodies_);
    const BodyMotion* const motion = bodies.motion.data();  // else reloaded every row
    Real worst = 0;
    for (std::size_t j = 0; j < count; ++j) {
        SpringRow& solved = rows[j];
        ProjectedGeometry& row = geometry[j];
        errors[j] = 0;
        if (solved.deferred) {
            // Slack at the step's start and never caught (no impulse): no error unless its ends
            // now lie past its rest length, whichever scheme owns it. Only then is the rest of
            // its preparation read. A net's thread spans its nodes' centres (projectedSpan()).
            const Real length =
                (ends[j].centred ? Vec3(motion[ends[j].b].center - motion[ends[j].a].center)
                                 : projectedSpan(bodies, springs, j))
                    .norm();  // as the geometry's
            if (length > 0 &&
                length - solved.restLength <= kNegligibleStretch * solved.restLength) {
                row.length = -1;
                continue;
            }
            finishSpringRow(solverBodies_[solved.bodyA], solverBodies_[solved.bodyB], solved,
                            context.h);
        }
        const bool taut = !solved.tensionOnly || solved.impulse < 0;
        // A resolved element's turning and catch are the scheme's own second-order error
        // (spring_row.h); correcting them made the net-10 sweep's error 2-3x larger at h =
        // 1/240 ... 1/2000. A discrete-gradient thread's row is linearised at its end-of-step
        // span already.
        if ((solved.spectralRadius > 0 && !springRowUnresolved(solved, context.h)) ||
            (solved.discreteGradient && taut)) {
            row.length = -1;
            continue;
        }
        row = projectedGeometry(bodies, springs, j);
        // A taut element: what the step's linearisation believed its length to be, against
        // the true one. A slack thread: whatever stretched it past its rest length without a
        // pull (contacts pushing its ends apart).
        Real error = taut ? row.length - solved.direction.dot(row.length * row.direction)
                          : std::max<Real>(0, row.length - solved.restLength);
        if (error <= kNegligibleStretch * solved.restLength)
            error = 0;  // rounding: not worth a factorisation
        errors[j] = error;
        worst = std::max(worst, error);
    }
    return worst;
}

void SolveStage::projectSprings(BodyStore& bodies, const SpringStore& springs,
                                const StepContext& context, const SolverSettings& settings) {
    if (springRows_.empty() || !settings.projectSprings)
        return;
    if (projectionErrors(bodies, springs, context) <= 0)
        return;
    const std::size_t awakeCount = bodies.awake.size();
    projectedBodies_.resize(1 + awakeCount);
    projectedBodies_[0] = SolverBody{};
    for (std::size_t k = 0; k < awakeCount; ++k) {
        const std::uint32_t i = bodies.awake[k];
        const BodyMotion& m = bodies.motion[i];
        SolverBody& s = projectedBodies_[1 + k];
        s = SolverBody{};
        s.inverseMass = bodies.inertia[i].inverseMass;
        if (bodies.info[i].fixedRotation)
            continue;  // its inverse inertia stays zero, as in run()
        const Mat3 rotation = m.orientation.toRotationMatrix();
        s.inverseInertia = rotation * bodies.inertia[i].inverseInertiaLocal * rotation.transpose();
    }
    projectedRows_.assign(springRows_.begin(), springRows_.end());
    for (std::size_t j = 0; j < projectedRows_.size(); ++j) {
        SpringRow& row = projectedRows_[j];
        if (projectedGeometry_[j].length < 0)
            projectedGeometry_[j] = projectedGeometry(bodies, springs, j);
        const ProjectedGeometry& geometry = projectedGeometry_[j];
        row.length = geometry.length;
        row.direction = geometry.direction;
        row.rA = geometry.rA;
        row.rB = geometry.rB;
        row.impulse = 0;
        row.spectralRadius = 0;  // a position correction: the element's whole stiffness
        row.discreteGradient = false;
    }
    prepareSpringRows(projectedBodies_, projectedRows_, context.h, false);
    for (std::size_t j = 0; j < projectedRows_.size(); ++j) {
        SpringRow& row = projectedRows_[j];
        row.bias = projectionError_[j] * context.inverseH;
        // Compliance of 1 % of the row's own inverse mass: a cell of the net folded flat puts
        // four rows on one line, dependent, and their slightly inconsistent errors came back as
        // huge displacements (a thread 4.7x its length for a step; the 40 x 40 net on a
        // cylinder gained 7x its energy). 10 % left too much error each step (+27 %); 0.1 % and
        // 1 % both kept the net below its initial energy.
        if (row.mass > 0) {
            const Real inverseMass = 1 / row.mass - row.softness;
            row.softness += kProjectionCompliance * inverseMass;
            row.mass = 1 / (inverseMass + row.softness);
        }
    }
    projector_.prepare(projectedBodies_, projectedRows_);
    if (!projector_.ready())
        return;
    projector_.solve(projectedBodies_, projectedRows_);
    corrections_.resize(awakeCount);
    for (std::size_t k = 0; k < awakeCount; ++k) {
        corrections_[k].linear = projectedBodies_[1 + k].linearVelocity;
        corrections_[k].angular = projectedBodies_[1 + k].angularVelocity;
    }
    displaceBodies(bodies, corrections_, context.h);
}

}  // namespace tumble
