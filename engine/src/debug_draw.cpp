#include "tumble/debug_draw.h"

#include <type_traits>
#include <variant>

#include "tumble/world.h"

namespace tumble {

void describeShape(const World& world, ShapeId shape, DebugDraw& draw) {
    const Transform pose = world.shapeTransform(shape);
    std::visit(
        [&](const auto& g) {
            using G = std::decay_t<decltype(g)>;
            if constexpr (std::is_same_v<G, Sphere>) {
                draw.drawSphere(pose, g.radius);
            } else if constexpr (std::is_same_v<G, Box>) {
                draw.drawBox(pose, g.halfExtents);
            } else if constexpr (std::is_same_v<G, Capsule>) {
                draw.drawCapsule(pose, g.radius, g.halfLength);
            } else if constexpr (std::is_same_v<G, Cylinder>) {
                draw.drawCylinder(pose, g.radius, g.halfLength);
            } else if constexpr (std::is_same_v<G, ConvexHull>) {
                if (g.data)
                    draw.drawHull(pose, *g.data);
            } else if constexpr (std::is_same_v<G, HalfSpace>) {
                // {x : n.x <= d} in the shape frame; in the world, n' = R n and the offset
                // grows by n' . p because the plane moved with the frame's origin p.
                const Vec3 normal = pose.rotation * g.normal;
                draw.drawPlane(normal, g.offset + normal.dot(pose.position));
            }
            // Meshes and height fields: no triangle primitive in DebugDraw yet.
        },
        world.shapeDef(shape).geometry);
}

void describeWorld(const World& world, std::span<const ShapeId> shapes, DebugDraw& draw,
                   std::uint32_t flags) {
    BodyId current;
    for (const ShapeId shape : shapes) {
        if (!world.isValid(shape))
            continue;
        const BodyId body = world.shapeBody(shape);
        if (!(body == current)) {
            current = body;
            draw.beginBody(body, world.bodyType(body), world.isAwake(body));
        }
        if (flags & kDrawShapes)
            describeShape(world, shape, draw);
        if ((flags & kDrawAabbs) && typeOf(world.shapeDef(shape).geometry) != ShapeType::HalfSpace)
            draw.drawAabb(world.shapeBounds(shape));
    }
    if (flags & kDrawContacts) {
        for (const Contact& contact : world.contacts()) {
            for (int i = 0; i < contact.manifold.pointCount; ++i) {
                const ContactPoint& p = contact.manifold.points[i];
                if (p.separation <= 0)
                    draw.drawContact(p.position, contact.manifold.normal, p.separation);
            }
        }
    }
}

void describeSprings(const World& world, std::span<const SpringId> springs, DebugDraw& draw) {
    for (const SpringId spring : springs) {
        if (!world.isValid(spring))
            continue;
        const SpringDef& def = world.springDef(spring);
        const SpringState state = world.springState(spring);
        // A null bodyB means localAnchorB is already a world point.
        const Vec3 b = def.bodyB.isNull() ? def.localAnchorB
                                          : world.transform(def.bodyB).apply(def.localAnchorB);
        draw.drawSpring(world.transform(def.bodyA).apply(def.localAnchorA), b, state.tension,
                        state.slack);
    }
}

void describeJoints(const World& world, std::span<const JointId> joints, DebugDraw& draw) {
    for (const JointId joint : joints) {
        if (!world.isValid(joint))
            continue;
        const JointState state = world.jointState(joint);
        draw.drawJoint(world.jointDef(joint).type, state.anchorA, state.anchorB, state.axis,
                       state.broken);
    }
}

}  // namespace tumble
