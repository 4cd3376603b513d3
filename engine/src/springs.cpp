#include "springs.h"

#include <algorithm>
#include <cmath>

namespace tumble {
namespace {

// No body: a spring end fixed in the world.
constexpr std::uint32_t kWorld = ~std::uint32_t(0);

// A thread whose length changes by less than this share of its rest length over a step asks for
// no substeps (threadSubsteps): a net hanging at rest keeps its one step.
constexpr Real kStillStretch = 1e-4;

// One end of an explicit spring: its body's dense index (looked up once a step), where its
// anchor is, and the anchor's offset from the body's centre, zero for a lumped node (whose
// threads meet at its centre: no rotation, no lever arm).
struct End {
    std::uint32_t index = kWorld;
    Vec3 position = Vec3::Zero();  // of the anchor (m)
    Vec3 arm = Vec3::Zero();       // position - centre (m)
    bool pushed = false;           // an awake dynamic body: forces act on it
};

End endOf(const BodyStore& bodies, BodyId body, const Vec3& localAnchor) {
    if (body.isNull())
        return {kWorld, localAnchor};
    const std::uint32_t i = bodies.checkedIndexOf(body);
    const Vec3 position = anchorAt(bodies, i, localAnchor);
    return {i, position, position - bodies.motion[i].center, bodies.isAwakeDynamic(i)};
}

// What a spring end adds to its row's inverse mass (1/kg, linear): nothing but for an awake
// dynamic body.
Real endInverseMass(const BodyStore& bodies, BodyId body) {
    if (body.isNull())
        return 0;
    const std::uint32_t i = bodies.checkedIndexOf(body);
    return bodies.isAwakeDynamic(i) ? bodies.inertia[i].inverseMass : 0;
}

Vec3 anchorVelocity(const BodyStore& bodies, const End& end) {
    if (end.index == kWorld)
        return Vec3::Zero();
    const BodyMotion& m = bodies.motion[end.index];
    return end.arm.isZero() ? m.linearVelocity
                            : Vec3(m.linearVelocity + m.angularVelocity.cross(end.arm));
}

void addForce(BodyStore& bodies, const End& end, const Vec3& force) {
    if (!end.pushed)
        return;
    bodies.forces[end.index].force += force;
    if (!end.arm.isZero())
        bodies.forces[end.index].torque += end.arm.cross(force);
}

}  // namespace

Vec3 anchorPosition(const BodyStore& bodies, BodyId body, const Vec3& localAnchor) {
    return body.isNull() ? localAnchor : anchorAt(bodies, bodies.indexOf(body), localAnchor);
}

Real springLength(const SpringStore& springs, const BodyStore& bodies, std::uint32_t index) {
    const SpringDef& def = springs.defs[index];
    return (anchorPosition(bodies, def.bodyB, def.localAnchorB) -
            anchorPosition(bodies, def.bodyA, def.localAnchorA))
        .norm();
}

Real springPotentialEnergy(const SpringStore& springs, const BodyStore& bodies) {
    Real energy = 0;
    for (std::uint32_t i = 0; i < springs.count(); ++i) {
        const SpringDef& def = springs.defs[i];
        const Real stretch = springLength(springs, bodies, i) - def.restLength;
        if (def.tensionOnly && stretch <= 0)
            continue;
        energy += 0.5 * def.stiffness * stretch * stretch;
    }
    return energy;
}

void wakeSpringLinked(const SpringStore& springs, BodyStore& bodies, ContactManager& contacts,
                      Islands& islands) {
    // Cheap tests first: nothing sleeps in most scenes that have springs.
    if (bodies.awake.size() == bodies.count())
        return;
    bool anySleeping = false;
    for (std::uint32_t i = 0; i < springs.count() && !anySleeping; ++i) {
        const SpringDef& def = springs.defs[i];
        anySleeping = bodies.isSleeping(bodies.indexOf(def.bodyA)) ||
                      (!def.bodyB.isNull() && bodies.isSleeping(bodies.indexOf(def.bodyB)));
    }
    if (!anySleeping)
        return;
    auto drives = [&](std::uint32_t i) {
        return bodies.isAwakeDynamic(i) || bodies.isMovingKinematic(i);
    };
    for (bool woke = true; woke;) {
        woke = false;
        for (std::uint32_t i = 0; i < springs.count(); ++i) {
            const SpringDef& def = springs.defs[i];
            if (def.bodyB.isNull())
                continue;
            const std::uint32_t a = bodies.indexOf(def.bodyA);
            const std::uint32_t b = bodies.indexOf(def.bodyB);
            if (bodies.isSleeping(a) && drives(b)) {
                islands.wake(bodies, contacts, a);
                woke = true;
            } else if (bodies.isSleeping(b) && drives(a)) {
                islands.wake(bodies, contacts, b);
                woke = true;
            }
        }
    }
}

namespace {

// Whether every undamped thread is below the discrete gradient's band, from the stiffest thread
// and the lightest awake dynamic body alone: h^2 k_max (2 / m_min) bounds every thread's (omega
// h)^2 as computed below (rounding is monotone), so this answers exactly, and a net whose threads
// are all resolved (the net-10 sweep's from 1/240) skips looking up each thread's ends (~4 % of
// its step).
bool belowBand(const SpringStore& springs, const BodyStore& bodies, Real h) {
    const Real stiffest = springs.stiffestThread();
    Real lightest = 0;  // the largest inverse mass (1/kg)
    for (const std::uint32_t i : bodies.awake) {
        if (bodies.isAwakeDynamic(i))
            lightest = std::max(lightest, bodies.inertia[i].inverseMass);
    }
    return h * h * stiffest * (lightest + lightest) < discreteGradientBandStart();
}

}  // namespace

int threadSubsteps(const SpringStore& springs, const BodyStore& bodies, Real h) {
    if (belowBand(springs, bodies, h))
        return 1;
    int substeps = 0;  // 0: no thread at work
    for (std::uint32_t i = 0; i < springs.count(); ++i) {
        const SpringDef& def = springs.defs[i];
        if (!isUndampedThread(def))
            continue;
        // The band first, from the masses alone: most nets' threads are outside it, and the
        // geometry was most of this pass (~50 ns a thread).
        const Real inverseMass =
            endInverseMass(bodies, def.bodyA) + endInverseMass(bodies, def.bodyB);
        const int most = discreteGradientSubsteps(h * h * def.stiffness * inverseMass);
        if (most == 0)
            continue;
        const End a = endOf(bodies, def.bodyA, def.localAnchorA);
        const End b = endOf(bodies, def.bodyB, def.localAnchorB);
        const Vec3 d = b.position - a.position;
        const Real length = d.norm();
        if (!(length > 0))
            continue;
        const Real change =
            h * (d / length).dot(anchorVelocity(bodies, b) - anchorVelocity(bodies, a));
        const Real stretch = length - def.restLength;
        const bool works = (stretch >= 0 || stretch + change > 0) &&
                           std::abs(change) > kStillStretch * def.restLength;
        if (works)
            substeps = substeps == 0 ? most : std::min(substeps, most);
        if (substeps == 1)
            return 1;
    }
    return std::max(substeps, 1);
}

void ForceElements::apply(SpringStore& springs, const DragStore& drag, BodyStore& bodies) {
    applied_ = springs.count() > springs.implicitCount || !drag.empty();
    if (!applied_)
        return;
    savedBodies_.assign(bodies.awake.begin(), bodies.awake.end());
    saved_.resize(savedBodies_.size());
    for (std::size_t k = 0; k < savedBodies_.size(); ++k)
        saved_[k] = bodies.forces[savedBodies_[k]];

    for (std::uint32_t i = 0; i < springs.count(); ++i) {
        const SpringDef& def = springs.defs[i];
        if (def.formulation != SpringFormulation::Explicit)
            continue;
        const End a = endOf(bodies, def.bodyA, def.localAnchorA);
        const End b = endOf(bodies, def.bodyB, def.localAnchorB);
        if (!a.pushed && !b.pushed)
            continue;
        const Vec3 d = b.position - a.position;
        const Real length = d.norm();
        const Vec3 n = length > 0 ? Vec3(d / length) : Vec3::Zero();
        const Real lengthRate = n.dot(anchorVelocity(bodies, b) - anchorVelocity(bodies, a));
        Real tension = def.stiffness * (length - def.restLength) + def.damping * lengthRate;
        if (def.tensionOnly)
            tension = length > def.restLength ? std::max<Real>(tension, 0) : 0;
        springs.state[i] = {tension, def.tensionOnly && tension == 0};
        const Vec3 force = tension * n;  // on A, towards B
        addForce(bodies, a, force);
        addForce(bodies, b, -force);
    }

    for (std::size_t j = 0; j < drag.bodies.size(); ++j) {
        const std::uint32_t i = bodies.indexOf(drag.bodies[j]);
        if (!bodies.isAwakeDynamic(i))
            continue;
        const Drag& d = drag.drags[j];
        const Vec3 u = d.projection * bodies.motion[i].linearVelocity;
        bodies.forces[i].force -= (d.linear + d.quadratic * u.norm()) * u;
    }
}

void ForceElements::restore(BodyStore& bodies) {
    if (!applied_)
        return;
    // The bodies saved, not today's awake list: the soft step restores after the solve, and a
    // touch may have woken bodies in between (ASan: the awake list outgrew saved_).
    for (std::size_t k = 0; k < savedBodies_.size(); ++k)
        bodies.forces[savedBodies_[k]] = saved_[k];
    applied_ = false;
}

}  // namespace tumble
