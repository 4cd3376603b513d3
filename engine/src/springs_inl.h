#pragma once
// Template part of springs.h.

#include <cmath>

namespace tumble {

template <typename SolverIndex>
void buildSpringRows(const SpringStore& springs, const BodyStore& bodies, Real h,
                     SolverIndex&& solverIndex, std::vector<SpringRow>& rows,
                     std::vector<std::uint32_t>& rowSpring) {
    rows.clear();
    rowSpring.clear();
    if (springs.implicitCount == 0)
        return;
    for (std::uint32_t i = 0; i < springs.count(); ++i) {
        const SpringDef& def = springs.defs[i];
        if (def.formulation != SpringFormulation::Implicit)
            continue;
        const std::uint32_t a = bodies.indexOf(def.bodyA);
        const bool world = def.bodyB.isNull();
        const std::uint32_t b = world ? 0 : bodies.indexOf(def.bodyB);
        if (!bodies.isAwakeDynamic(a) && (world || !bodies.isAwakeDynamic(b)))
            continue;
        SpringRow row;
        const Vec3 pA = anchorPosition(bodies, def.bodyA, def.localAnchorA);
        const Vec3 pB = anchorPosition(bodies, def.bodyB, def.localAnchorB);
        row.bodyA = solverIndex(a);
        row.bodyB = world ? 0 : solverIndex(b);
        row.rA = pA - bodies.motion[a].center;
        row.rB = world ? Vec3::Zero() : Vec3(pB - bodies.motion[b].center);
        const Vec3 d = pB - pA;
        row.length = d.norm();
        row.direction = row.length > 0 ? Vec3(d / row.length) : Vec3::UnitX();
        row.restLength = def.restLength;
        row.stiffness = def.stiffness;
        row.damping = def.damping;
        row.tensionOnly = def.tensionOnly;
        row.impulse = -springs.state[i].tension * h;  // tension kept in N: h may change
        rows.push_back(row);
        rowSpring.push_back(i);
    }
}

}  // namespace tumble
