#pragma once
/// Scenes at the solver's level (no World): the rows the solver tests and benchmarks feed it.

#include <cstdint>

#include "tumble/solver/contact_solver.h"

namespace tumble::testkit {

/// The manifold of a unit cube resting face down on the ground: solver body 0 is the ground
/// (A), `cube` is B, normal +Z, four points at the cube's bottom corners, each `separation`
/// (m) apart, with Coulomb `friction`.
inline ContactConstraint cubeOnGround(std::uint32_t cube, Real friction, Real separation = 0) {
    ContactConstraint c;
    c.bodyA = 0;
    c.bodyB = cube;
    c.normal = Vec3::UnitZ();
    c.friction = friction;
    c.pointCount = 4;
    int i = 0;
    for (Real x : {-0.5, 0.5}) {
        for (Real y : {-0.5, 0.5}) {
            c.points[i].rA = Vec3(x, y, 0);
            c.points[i].rB = Vec3(x, y, -0.5);
            c.points[i].separation = separation;
            ++i;
        }
    }
    return c;
}

}  // namespace tumble::testkit
