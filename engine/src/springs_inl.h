#pragma once
// Template part of springs.h.

#include <cmath>

namespace tumble {

/// Velocity at the start of the (sub)step of the point at offset r from a body's centre of mass
/// (m/s): what it moved with over the last step. Zero for the world and sleeping bodies (awake
/// false).
inline Vec3 startAnchorVelocity(const BodyStore& bodies, std::uint32_t index, bool awake,
                                const Vec3& r) {
    if (!awake)
        return Vec3::Zero();
    const BodyMotion& start = bodies.previousMotion[index];
    return start.linearVelocity + start.angularVelocity.cross(r);
}

/// The fields of a SpringRow that buildSpringRows() does not set, as a default row holds them
/// (prepareSpringRows() and the block solve read some of them before writing them, e.g. a
/// deferred row's mass).
inline void resetRow(SpringRow& row) {
    // A field added to SpringRow is set by buildSpringRows() or here.
    static_assert(sizeof(SpringRow) == 400, "SpringRow changed: set its new field");
    row.levelGradient = false;
    row.lastStretch = 0;
    row.span = Vec3::Zero();
    row.linearisedAt = 0;
    row.turn = Vec3::Zero();
    row.angularA = Vec3::Zero();
    row.angularB = Vec3::Zero();
    row.angularImpulseA = Vec3::Zero();
    row.angularImpulseB = Vec3::Zero();
    row.mass = 0;
    row.softness = 0;
    row.bias = 0;
    row.knownImpulse = 0;
    row.deferred = false;
}

template <typename SolverIndex>
void buildSpringRows(const SpringStore& springs, const BodyStore& bodies, Real h,
                     SolverIndex&& solverIndex, std::vector<SpringRow>& rows,
                     std::vector<std::uint32_t>& rowSpring, std::vector<RowBodies>& rowBodies) {
    const std::size_t most = springs.implicitCount;
    if (most == 0) {
        rows.clear();
        rowSpring.clear();
        rowBodies.clear();
        return;
    }
    // The last step's rows are written over, every field (resetRow), rather than default ones
    // constructed (a default row was a sixth of building a net's row); new ones are added only
    // while the scene grows. Sized for every implicit spring first and written through indices:
    // push_back's checks were a tenth of building a net's row.
    if (rows.size() < most)
        rows.resize(most);
    rowSpring.resize(most);
    rowBodies.resize(most);
    // Through pointers: a row's bool stores may alias anything, and the vectors' would be
    // reloaded after each.
    SpringRow* const rowOut = rows.data();
    std::uint32_t* const springOut = rowSpring.data();
    RowBodies* const bodiesOut = rowBodies.data();
    std::size_t used = 0;
    const std::uint32_t count = springs.count();
    // Through pointers too: the vectors' data would be reloaded after each row's bool stores.
    const SpringDef* const defs = springs.defs.data();
    const SpringStepState* const states = springs.state.data();
    for (std::uint32_t i = 0; i < count; ++i) {
        const SpringDef& def = defs[i];
        const SpringStepState& state = states[i];
        if (def.formulation == SpringFormulation::Explicit)
            continue;
        const std::uint32_t a = bodies.checkedIndexOf(def.bodyA);
        const bool world = def.bodyB.isNull();
        const std::uint32_t b = world ? 0 : bodies.checkedIndexOf(def.bodyB);
        if (!bodies.isAwakeDynamic(a) && (world || !bodies.isAwakeDynamic(b)))
            continue;
        // Asked before the row's stores: its bools may alias the body data, which the compiler
        // would then load again for each (~9 of the ~320 instructions a net's row took).
        const std::uint32_t solverA = solverIndex(a);
        const std::uint32_t solverB = world ? 0 : solverIndex(b);
        const bool awakeA = bodies.isAwake(a);
        const bool awakeB = !world && bodies.isAwake(b);
        // Built in place: a default row copied in (~300 B each) was a share of the nets' step.
        SpringRow& row = rowOut[used];
        const bool centredA = anchorCentred(bodies, a, def.localAnchorA);
        const bool centredB = !world && anchorCentred(bodies, b, def.localAnchorB);
        const Vec3& centerA = bodies.motion[a].center;
        const Vec3& centerB = bodies.motion[b].center;  // a world end: body 0, unread
        const Vec3 pA = centredA ? centerA : anchorAt(bodies, a, def.localAnchorA);
        const Vec3 pB = world      ? def.localAnchorB
                        : centredB ? centerB
                                   : anchorAt(bodies, b, def.localAnchorB);
        row.bodyA = solverA;
        row.bodyB = solverB;
        row.rA = pA - centerA;
        row.rB = world ? Vec3::Zero() : Vec3(pB - centerB);
        row.centred = centredA && centredB;  // x - x is +0: rA = rB = 0
        const Vec3 d = pB - pA;
        row.length = d.norm();
        row.direction = row.length > 0 ? Vec3(d / row.length) : Vec3::UnitX();
        row.restLength = def.restLength;
        row.stiffness = def.stiffness;
        row.damping = def.damping;
        row.tensionOnly = def.tensionOnly;
        row.impulse = -state.tension * h;  // tension kept in N: h may change
        const bool trapezoidal = def.formulation == SpringFormulation::Implicit;
        // A thread that was slack may take implicit Euler for the step that catches it
        // (spring_row.h).
        row.catching = def.tensionOnly && state.tension <= 0;
        row.spectralRadius = trapezoidal ? 1 - def.numericalDamping : 0;
        row.geometricStiffness = trapezoidal;
        // An undamped thread conserves its energy through catches (spring_row.h).
        row.discreteGradient = trapezoidal && def.tensionOnly && def.numericalDamping == 0;
        row.carried = state.carried;
        row.startVelocity = row.spectralRadius > 0
                                ? Vec3(startAnchorVelocity(bodies, b, awakeB, row.rB) -
                                       startAnchorVelocity(bodies, a, awakeA, row.rA))
                                : Vec3::Zero();
        resetRow(row);  // last: its bool stores would make the reads above load again
        springOut[used] = i;
        bodiesOut[used] = {a, b, world, centredA && centredB};
        ++used;
    }
    // Shrinks: no allocation.
    rows.resize(used);
    rowSpring.resize(used);
    rowBodies.resize(used);
}

}  // namespace tumble
