#pragma once
/// Debug draw: a world described as drawing primitives, for whatever renders it. An embedding
/// application implements DebugDraw with its own renderer (lines, meshes, an SVG file...) and
/// calls describeWorld once per frame; the world never draws by itself.
///
/// Every primitive is given in world coordinates (m) at the bodies' current poses.

#include <cstdint>
#include <span>

#include "tumble/body.h"
#include "tumble/collision/aabb.h"
#include "tumble/collision/shape.h"
#include "tumble/core/math.h"
#include "tumble/joint.h"
#include "tumble/shape.h"
#include "tumble/spring.h"

namespace tumble {

class World;

/// Receives a world's drawing primitives. Every method has an empty default, so a renderer
/// overrides only what it can show.
class DebugDraw {
public:
    virtual ~DebugDraw() = default;

    /// Announces the body whose shapes follow (until the next beginBody), so a renderer can
    /// colour by body or by type.
    virtual void beginBody(BodyId /*body*/, BodyType /*type*/, bool /*awake*/) {}
    /// A box centred at the transform's origin, along its axes (half extents in m).
    virtual void drawBox(const Transform& /*pose*/, const Vec3& /*halfExtents*/) {}
    virtual void drawSphere(const Transform& /*pose*/, Real /*radius*/) {}
    /// Capsule and cylinder axes run along the transform's local z, from -halfLength to
    /// +halfLength.
    virtual void drawCapsule(const Transform& /*pose*/, Real /*radius*/, Real /*halfLength*/) {}
    virtual void drawCylinder(const Transform& /*pose*/, Real /*radius*/, Real /*halfLength*/) {}
    /// A convex hull: its vertices at `pose` are pose.apply(hull.vertices[i]).
    virtual void drawHull(const Transform& /*pose*/, const HullData& /*hull*/) {}
    /// The boundary of the solid {x : normal . x <= offset}, world frame; normal is unit.
    virtual void drawPlane(const Vec3& /*normal*/, Real /*offset*/) {}
    /// A contact point with its normal (unit, from shape A to shape B) and separation (m,
    /// negative when penetrating).
    virtual void drawContact(const Vec3& /*point*/, const Vec3& /*normal*/, Real /*separation*/) {}
    virtual void drawAabb(const Aabb& /*box*/) {}
    /// A spring-damper or thread between its anchors (m); its tension of the last step (N,
    /// positive pulling) and whether it was a slack tension-only element.
    virtual void drawSpring(const Vec3& /*anchorA*/, const Vec3& /*anchorB*/, Real /*tension*/,
                            bool /*slack*/) {}
    /// A joint: the anchors carried by A and by B (m; together while it holds, a distance
    /// joint's rod ends), the hinge or slider axis (unit) and whether it broke.
    virtual void drawJoint(JointType /*type*/, const Vec3& /*anchorA*/, const Vec3& /*anchorB*/,
                           const Vec3& /*axis*/, bool /*broken*/) {}
};

/// What describeWorld draws (bits, combined with |).
enum DebugDrawFlags : std::uint32_t {
    kDrawShapes = 1u << 0,    ///< every listed shape at its world pose
    kDrawContacts = 1u << 1,  ///< the points and normals of World::contacts() (touching only)
    kDrawAabbs = 1u << 2,     ///< the tight bounds of every listed bounded shape
    kDrawAll = kDrawShapes | kDrawContacts | kDrawAabbs,
};

/// Draws one shape at its world pose (after beginBody for its body). The id must be valid.
void describeShape(const World& world, ShapeId shape, DebugDraw& draw);

/// Describes the given shapes (grouped by consecutive body, each group opened with beginBody) and,
/// with kDrawContacts, every touching contact point of the last step. The caller lists the shapes
/// because the World has no public way yet to enumerate its bodies and shapes; invalid ids are
/// skipped.
void describeWorld(const World& world, std::span<const ShapeId> shapes, DebugDraw& draw,
                   std::uint32_t flags = kDrawShapes);

/// Draws the listed springs (threads of strings and nets included) at the current poses, with
/// the tension of the last step; invalid ids are skipped.
void describeSprings(const World& world, std::span<const SpringId> springs, DebugDraw& draw);

/// Draws the listed joints at the current poses; invalid ids are skipped.
void describeJoints(const World& world, std::span<const JointId> joints, DebugDraw& draw);

}  // namespace tumble
