#include "tumble/lumped.h"

#include <cmath>
#include <string>

#include "checks.h"
#include "tumble/core/error.h"
#include "tumble/world.h"

namespace tumble {
namespace {

bool finite(const Vec3& v) {
    return v.allFinite();
}

// Everything World::createBody/createShape/createSpring would refuse, checked before the first
// node exists so a refused definition leaves the world untouched.
void checkNode(const NodeDef& node, const std::string& where) {
    if (!(std::isfinite(node.mass) && node.mass > 0))
        fail(where, ".node.mass = ", node.mass, " (kg) must be finite and > 0");
    if (!(std::isfinite(node.radius) && node.radius > 0))
        fail(where, ".node.radius = ", node.radius, " (m) must be finite and > 0");
    // The node's mass is given and its density ignored (NodeDef), but createShape checks the
    // whole material of a colliding node.
    if (node.collide)
        checks::material(node.material, where + ".node.material");
    else
        checks::surface(node.material, where + ".node.material");
}

void checkThread(const ThreadDef& thread, const std::string& where) {
    if (!(std::isfinite(thread.axialRigidity) && thread.axialRigidity > 0)) {
        fail(where, ".thread.axialRigidity = ", thread.axialRigidity,
             " (N) must be finite and > 0");
    }
    if (!(std::isfinite(thread.damping) && thread.damping >= 0))
        fail(where, ".thread.damping = ", thread.damping, " (N s/m) must be finite and >= 0");
    if (!(thread.numericalDamping >= 0 && thread.numericalDamping <= 1)) {
        fail(where, ".thread.numericalDamping = ", thread.numericalDamping, " must be in [0, 1]");
    }
}

BodyId addNode(World& world, const NodeDef& node, Real mass, const Vec3& position,
               const Vec3& velocity) {
    BodyDef body;
    body.position = position;
    body.linearVelocity = velocity;
    body.mass.mass = mass;
    body.mass.inertia = Mat3::Identity() * (0.4 * mass * node.radius * node.radius);
    body.fixedRotation = node.fixedRotation;
    const BodyId id = world.createBody(body);
    if (node.collide) {
        // Built whole: assigning the variant member of a default ShapeDef tripped GCC 12's
        // -Wmaybe-uninitialized (a false positive on the hull alternative's shared_ptr).
        const ShapeDef shape{.geometry = Sphere{node.radius},
                             .material = node.material,
                             .filter = node.filter,
                             .updateBodyMass = false};
        world.createShape(id, shape);
    }
    return id;
}

SpringId addThread(World& world, const ThreadDef& thread, const NodeDef& node, BodyId a, BodyId b,
                   const Vec3& worldAnchor, Real restLength) {
    SpringDef spring;
    spring.bodyA = a;
    spring.bodyB = b;
    if (b.isNull())
        spring.localAnchorB = worldAnchor;
    spring.restLength = restLength;
    spring.stiffness = thread.axialRigidity / restLength;
    spring.damping = thread.damping;
    spring.tensionOnly = thread.tensionOnly;
    spring.formulation = thread.formulation;
    spring.numericalDamping = thread.numericalDamping;
    if (thread.collide) {
        spring.contactRadius = node.radius;
        spring.contactFriction = node.material.friction;
    }
    return world.createSpring(spring);
}

}  // namespace

Lumped createString(World& world, const StringDef& def) {
    const int minimum = def.fixedStart || def.fixedEnd ? 1 : 2;
    if (def.count < minimum)
        fail("StringDef.count = ", def.count, " must be >= ", minimum);
    if (!finite(def.start) || !finite(def.end) || !finite(def.velocity))
        fail("StringDef.start, end and velocity must be finite");
    if (!(std::isfinite(def.restLengthRatio) && def.restLengthRatio > 0)) {
        fail("StringDef.restLengthRatio = ", def.restLengthRatio, " must be finite and > 0");
    }
    checkNode(def.node, "StringDef");
    checkThread(def.thread, "StringDef");
    const int segments = def.count - 1 + (def.fixedStart ? 1 : 0) + (def.fixedEnd ? 1 : 0);
    const Vec3 step = (def.end - def.start) / segments;
    const Real restLength = step.norm() * def.restLengthRatio;
    if (!(restLength > 0))
        fail("StringDef.start and end coincide: the segments would have no length");

    Lumped out;
    out.nodes.reserve(def.count);
    out.threads.reserve(segments);
    world.reserveSprings(world.springCount() + segments);
    const int first = def.fixedStart ? 1 : 0;
    for (int j = 0; j < def.count; ++j) {
        out.nodes.push_back(
            addNode(world, def.node, def.node.mass, def.start + (first + j) * step, def.velocity));
    }
    if (def.fixedStart) {
        out.threads.push_back(addThread(world, def.thread, def.node, out.nodes.front(), BodyId{},
                                        def.start, restLength));
    }
    for (int j = 0; j + 1 < def.count; ++j) {
        out.threads.push_back(addThread(world, def.thread, def.node, out.nodes[j], out.nodes[j + 1],
                                        Vec3::Zero(), restLength));
    }
    if (def.fixedEnd) {
        out.threads.push_back(addThread(world, def.thread, def.node, out.nodes.back(), BodyId{},
                                        def.end, restLength));
    }
    return out;
}

Lumped createNet(World& world, const NetDef& def) {
    if (def.rows < 2 || def.columns < 2) {
        fail("NetDef.rows x columns = ", def.rows, " x ", def.columns,
             ": a net needs at least 2 x 2 nodes");
    }
    if (!(std::isfinite(def.meshSize) && def.meshSize > 0))
        fail("NetDef.meshSize = ", def.meshSize, " (m) must be finite and > 0");
    if (!(std::isfinite(def.cornerMass) && def.cornerMass >= 0))
        fail("NetDef.cornerMass = ", def.cornerMass, " (kg) must be finite and >= 0");
    if (!(std::isfinite(def.spreadSpeed)))
        fail("NetDef.spreadSpeed = ", def.spreadSpeed, " (m/s) must be finite");
    if (!finite(def.center) || !finite(def.velocity))
        fail("NetDef.center and velocity must be finite");
    if (!(std::abs(def.orientation.norm() - 1) <= 1e-6))
        fail("NetDef.orientation must be a unit quaternion (norm ", def.orientation.norm(), ")");
    checkNode(def.node, "NetDef");
    checkThread(def.thread, "NetDef");

    const int n = def.rows;
    const int m = def.columns;
    const Mat3 axes = def.orientation.toRotationMatrix();
    const Vec3 x = axes.col(0);
    const Vec3 y = axes.col(1);
    // Distance from the centre to a corner: the spread speed's unit of length.
    const Real cornerDistance = 0.5 * def.meshSize * std::hypot(n - 1, m - 1);
    Lumped out;
    out.nodes.reserve(static_cast<std::size_t>(n) * m);
    const int threads = n * (m - 1) + m * (n - 1);
    out.threads.reserve(threads);
    world.reserveSprings(world.springCount() + threads);
    for (int i = 0; i < n; ++i) {
        for (int j = 0; j < m; ++j) {
            const Vec3 offset = def.meshSize * ((i - 0.5 * (n - 1)) * x + (j - 0.5 * (m - 1)) * y);
            const bool corner = (i == 0 || i == n - 1) && (j == 0 || j == m - 1);
            const Real mass = corner && def.cornerMass > 0 ? def.cornerMass : def.node.mass;
            const Vec3 velocity = def.velocity + (def.spreadSpeed / cornerDistance) * offset;
            out.nodes.push_back(addNode(world, def.node, mass, def.center + offset, velocity));
        }
    }
    auto node = [&](int i, int j) { return out.nodes[static_cast<std::size_t>(i) * m + j]; };
    for (int i = 0; i < n; ++i) {
        for (int j = 0; j < m; ++j) {
            if (j + 1 < m) {
                out.threads.push_back(addThread(world, def.thread, def.node, node(i, j),
                                                node(i, j + 1), Vec3::Zero(), def.meshSize));
            }
            if (i + 1 < n) {
                out.threads.push_back(addThread(world, def.thread, def.node, node(i, j),
                                                node(i + 1, j), Vec3::Zero(), def.meshSize));
            }
        }
    }
    out.corners = {node(0, 0), node(0, m - 1), node(n - 1, 0), node(n - 1, m - 1)};
    return out;
}

}  // namespace tumble
