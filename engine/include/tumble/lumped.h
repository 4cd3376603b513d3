#pragma once
/// Generators of lumped-mass strings and nets: point masses (small spheres) joined by
/// spring-dampers (spring.h), as in the ESA study's throw-net model.
///
/// A node is a dynamic body with the mass and inertia of a solid sphere of radius nodeRadius,
/// translation-only unless NodeDef::fixedRotation is off.
/// Whether nodes collide is a switch: when off they carry no shape and cost the broadphase
/// nothing (a scene pays only for what it models).

#include <array>
#include <vector>

#include "tumble/body.h"
#include "tumble/shape.h"
#include "tumble/spring.h"

namespace tumble {

class World;

/// The threads of a string or net: one spring-damper per segment between neighbouring nodes.
struct ThreadDef {
    Real axialRigidity = 1e3;  ///< E A (N), finite and > 0: k = E A / L0 per segment
    Real damping = 0;          ///< c per segment (N s/m), finite and >= 0
    bool tensionOnly = true;   ///< threads pull, never push
    SpringFormulation formulation = SpringFormulation::Implicit;
    Real numericalDamping = 0;  ///< in [0, 1], see SpringDef::numericalDamping
    /// Each segment touches static and kinematic shapes as a capsule of the node radius, with
    /// the node material's friction (SpringDef::contactRadius): a net caught on a thin rim
    /// between its nodes hangs on it. Off: only colliding nodes touch anything.
    bool collide = false;
};

/// The nodes of a string or net.
struct NodeDef {
    Real mass = 0.01;      ///< of each node (kg), finite and > 0
    Real radius = 0.005;   ///< sphere radius, for the inertia and collision (m), > 0
    bool collide = false;  ///< give each node a sphere shape
    /// Translation-only nodes (BodyDef::fixedRotation): a lumped node is a point mass, so a
    /// thread slides over what it touches instead of rolling on it. Rotating nodes pick up spin
    /// from contact friction on their tiny inertia that nothing damps, and a net resting on a
    /// pile never falls asleep.
    bool fixedRotation = true;
    Material material{};       ///< when colliding; density is ignored (mass is set above)
    CollisionFilter filter{};  ///< when colliding
};

/// A string of `count` nodes evenly spaced from `start` to `end`. With fixedStart the first
/// segment ties the first node to the world point `start` (nodes at start + j / count (end -
/// start), j = 1..count); with fixedEnd too, both ends are tied (j = 1..count over count + 1
/// segments); with neither, the nodes span start..end inclusive.
struct StringDef {
    Vec3 start = Vec3::Zero();
    Vec3 end = Vec3(0, 0, -1);
    int count = 30;  ///< nodes, >= 2 (>= 1 with a fixed end)
    bool fixedStart = true;
    bool fixedEnd = false;
    /// Rest length of each segment over its initial length, finite and > 0: < 1 starts the
    /// string under tension.
    Real restLengthRatio = 1;
    Vec3 velocity = Vec3::Zero();  ///< of every node (m/s)
    NodeDef node{};
    ThreadDef thread{};
};

/// An n x m square net in the plane through `center` spanned by the columns of `orientation`'s
/// x (rows) and y (columns) axes; node (i, j) sits at center + ((i - (n-1)/2) x + (j - (m-1)/2) y)
/// meshSize. Optional heavier corner masses, as in capture nets, and an initial velocity field:
/// a common velocity plus, when thrown open, a radial spread in the net's plane proportional to
/// the distance from the centre.
struct NetDef {
    int rows = 10;        ///< n nodes along x, >= 2
    int columns = 10;     ///< m nodes along y, >= 2
    Real meshSize = 0.1;  ///< node spacing = thread rest length (m), finite and > 0
    Vec3 center = Vec3::Zero();
    Quat orientation = Quat::Identity();  ///< unit; the net lies in its local x-y plane
    NodeDef node{};
    /// Mass of each of the four corner nodes (kg); 0 keeps node.mass. Finite and >= 0.
    Real cornerMass = 0;
    ThreadDef thread{};
    Vec3 velocity = Vec3::Zero();  ///< common to every node (m/s)
    /// Radial speed of the corners away from the centre, in the net's plane (m/s); other nodes
    /// in proportion to their distance. 0: dropped flat.
    Real spreadSpeed = 0;
};

/// What a generator made, in order: nodes along the string / row-major over the net
/// (node (i, j) at i * columns + j), then the segments.
struct Lumped {
    std::vector<BodyId> nodes;
    std::vector<SpringId> threads;
    std::array<BodyId, 4> corners{};  ///< nets: (0,0), (0,m-1), (n-1,0), (n-1,m-1)
};

/// Creates the string. Refuses (InvalidArgument, naming the field) bad definitions before
/// creating anything.
Lumped createString(World& world, const StringDef& def);

/// Creates the net. Refuses (InvalidArgument, naming the field) bad definitions -- fewer than 2
/// x 2 nodes, non-positive mesh size or mass, ... -- before creating anything.
Lumped createNet(World& world, const NetDef& def);

}  // namespace tumble
