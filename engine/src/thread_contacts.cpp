#include "thread_contacts.h"

#include <algorithm>
#include <cmath>

#include "solve_stage.h"
#include "springs.h"
#include "tumble/collision/narrowphase.h"
#include "tumble/solver/contact_solver.h"

namespace tumble {
namespace {

// Solver body of a spring end: the awake body's own, else the one every static body shares.
std::uint32_t endBody(const BodyStore& bodies, std::uint32_t index, bool world) {
    return !world && bodies.isAwake(index) ? solverBodyIndex(bodies, index) : 0u;
}

// A row between bodies a and b (b unused when `world`) moves something.
bool eitherAwakeDynamic(const BodyStore& bodies, std::uint32_t a, std::uint32_t b, bool world) {
    return bodies.isAwakeDynamic(a) || (!world && bodies.isAwakeDynamic(b));
}

// Capsule pose along the segment from a to b: its local z on the segment, centred on it.
Transform segmentPose(const Vec3& a, const Vec3& b) {
    const Vec3 d = b - a;
    const Quat turn =
        d.squaredNorm() > 0 ? Quat::FromTwoVectors(Vec3::UnitZ(), d) : Quat::Identity();
    return Transform{Vec3((a + b) / 2), turn.normalized()};
}

// How a node touches body `s`, for a row of normal `normal`: it rests on s on the row's side
// when one of its contacts with s has a point whose normal (from s to the node) is within ~40
// degrees of the row's. Nodes on either side of a thin wall only touch it (their normals are the
// wall's, the rim's row points up). `facesAway`: one of those normals points away from the
// thread's other node, along `away` (the thread's axis from that node), by more than 30 degrees
// out of the plane normal to the thread.
enum class Touch { None, Touches, RestsOnSide };

struct NodeTouch {
    Touch touch = Touch::None;
    bool facesAway = false;
};

NodeTouch nodeTouch(std::span<const ThreadContacts::NodeContact> nodeContacts, std::uint32_t s,
                    const Vec3& normal, const Vec3& away) {
    constexpr Real kSameSide = 0.75;  // cos ~41 degrees
    constexpr Real kAway = 0.5;       // sin 30 degrees
    NodeTouch touch;
    for (const ThreadContacts::NodeContact& contact : nodeContacts) {
        if (contact.body != s)
            continue;
        if (contact.out.dot(normal) > kSameSide)
            touch.touch = Touch::RestsOnSide;
        else if (touch.touch == Touch::None)
            touch.touch = Touch::Touches;
        touch.facesAway = touch.facesAway || contact.out.dot(away) > kAway;
    }
    return touch;
}

}  // namespace

// Where both nodes rest on S on the row's side, their contacts carry the thread: the row allows
// a sag of up to one radius, 4 t (1 - t) r, and pushes out no depth (velocity only; the nodes'
// contacts correct the positions). The chord between two nodes resting on a convex wall of
// radius R lies L^2 / (8 R) inside the line of the wall through them, and a capsule as thick as
// the nodes held them that far off it, where they swung free (an 8 x 8 net on a 24-sided
// cylinder of r = 0.15 m: 12 mm/s after 2 s). The sag alone, with the rows' push-out, stretched
// the threads over the cylinder's rim until they slipped (energy gained); without the side test
// the net slid over dustbin-mesh's thin rim, whose nodes rest on the wall's two faces.
//
// Where both nodes touch S otherwise, the row pushes out no depth either when the thread lies
// along S's rim: between two nodes on a thin rim the thread lies along the wall with its axis ~1
// mm off the wall's plane, its rows' face normal sideways; their push, against the nodes' own
// contacts on the edge, held the rows at the slop and pumped the net (an 8 x 8 net across an
// open 24-sided bin of r = 0.15 m: 3.1 mm/s after 2 s; without those rows' push below 0.05
// mm/s). A thread crossing over an edge instead -- each node's contact facing away from the
// other node, so the edge lies between them -- keeps its depth and push: held, the rows of a net
// landing across a thin wall's edge sank 10.7 mm over it while their nodes touched the wall's two
// faces, and when a node left the wall the push resumed at its cap (+58 mJ in one step,
// ThreadRestThinWall).
//
// Where only one node touches S, a point within the first radius past the trim over another
// feature than the node's face (a thin wall's edge beside the face the node rests on) is the
// capsule leaving the node over that edge: it reaches over it by up to r (1 - cos phi) past the
// node's sphere (phi the thread's slope down from the node's contact plane), where a real thread
// bends over the edge and the node's contact holds it. It counts no depth (never a gap) while the
// thread's axis stays out of S (depth < r; deeper, the thread cuts through). Pushed at its cap,
// that 5 - 7 mm lifted the nodes with their threads (ThreadRestThinWall, 5 cm, 9 rows: +1.9 mJ
// in one step). Only a thread heading into the node's contact plane, towards the feature and
// across it: a thread along a rim keeps the rim's rule.
void setRowDepth(SegmentContactRow& row, Real separation, Real radius, const Vec3& axis,
                 std::span<const ThreadContacts::NodeContact> contactsA,
                 std::span<const ThreadContacts::NodeContact> contactsB, std::uint32_t s,
                 const Vec3& fromA, const Vec3& fromB) {
    const NodeTouch a = nodeTouch(contactsA, s, row.normal, Vec3(-axis));
    const NodeTouch b = nodeTouch(contactsB, s, row.normal, axis);
    const bool resting = a.touch == Touch::RestsOnSide && b.touch == Touch::RestsOnSide;
    const bool crossing = a.facesAway && b.facesAway;
    row.separation = separation + (resting ? 4 * radius * row.t * (1 - row.t) : 0);
    row.pushOut = a.touch == Touch::None || b.touch == Touch::None || (crossing && !resting);
    // Left to a node that alone touches S: row normal more than ~8 degrees off its contact's
    // (another feature), the thread heading into its contact plane, towards the row's normal.
    const auto leftTo = [&](std::span<const ThreadContacts::NodeContact> contacts, const Vec3& away,
                            const Vec3& from) {
        constexpr Real kSameFace = 0.99;  // cos ~8 degrees
        constexpr Real kAcross = 0.7;     // sin ~45 degrees
        bool touches = false, dips = false;
        for (const ThreadContacts::NodeContact& contact : contacts) {
            if (contact.body != s)
                continue;
            if (contact.out.dot(row.normal) > kSameFace)
                return false;
            touches = true;
            // The feature's edge runs along row.normal x out; the thread leaves across it (within
            // 45 degrees of its normal plane), not along it.
            const Vec3 edge = row.normal.cross(contact.out).normalized();
            dips = dips || (contact.out.dot(away) < 0 && (row.normal - contact.out).dot(away) > 0 &&
                            std::abs(edge.dot(away)) < kAcross);
        }
        return touches && dips && from.norm() < 2 * radius;
    };
    const bool left = b.touch == Touch::None
                          ? leftTo(contactsA, axis, fromA)
                          : a.touch == Touch::None && leftTo(contactsB, Vec3(-axis), fromB);
    if (left && separation > -radius)  // deeper, the thread's axis is in S: it cuts through
        row.separation = std::max(row.separation, Real(0));
}

namespace {

// A thread through a thin sheet of a mesh (nodes on either side of an open bin's wall) leaves
// over the sheet's edge: its one contact replaces the capsule's manifolds, whose face normal
// pushed the thread sideways through the wall against its nodes held on both sides (on
// dustbin-mesh rows 1.3 - 3.7 cm deep below the rim, pushed 0.2 x depth a step: single-step
// kicks of 0.3 J of spring energy).
void leaveOverBorder(const Shape& surface, const Transform& pose, const Vec3& pA, const Vec3& pB,
                     Real radius, ManifoldSet& manifolds) {
    SheetCrossing crossing;
    if (!crossingOverBorder(surface, pose, pA, pB, radius, crossing))
        return;
    manifolds.count = 1;
    Manifold& manifold = manifolds.manifolds[0];
    manifold = Manifold{};
    manifold.normal = -crossing.normal;  // from the capsule to the surface
    manifold.add(crossing.point, crossing.separation, 0);
}

}  // namespace

std::span<SegmentContactRow> ThreadContacts::build(const SpringStore& springs,
                                                   const BodyStore& bodies,
                                                   const ShapeStore& shapes,
                                                   const ContactManager& contacts,
                                                   const StepContext& context) {
    rows_.clear();
    keys_.clear();
    lent_.assign(cache_.size(), 0);
    cursor_ = 0;
    gathered_ = false;
    if (springs.contactCount == 0)
        return {};
    listFixedShapes(bodies, shapes);
    for (std::uint32_t i = 0; i < springs.count(); ++i) {
        if (springs.defs[i].contactRadius > 0)
            collideThread(i, springs, bodies, shapes, contacts, context.h);
    }
    return rows_;
}

// A few static and kinematic shapes (a bin, a floor) are found faster by testing each one's box
// than through the broadphase, whose cells around a net hold its hundreds of nodes (the query
// was 6.5 % of dustbin-mesh's step). Above kScanned shapes the broadphase is asked.
constexpr std::size_t kScanned = 32;

void ThreadContacts::listFixedShapes(const BodyStore& bodies, const ShapeStore& shapes) {
    fixedShapes_.clear();
    for (std::uint32_t slot = 0; slot < shapes.records.size(); ++slot) {
        if (!shapes.isAlive(slot))
            continue;
        const BodyId body = shapes.records[slot].body;
        if (bodies.info[bodies.indexOf(body)].type != BodyType::Dynamic) {
            fixedShapes_.push_back(slot);
            if (fixedShapes_.size() > kScanned)
                return;  // candidates() asks the broadphase
        }
    }
}

void ThreadContacts::candidates(const Aabb& box, bool planes, const BodyStore& bodies,
                                const ShapeStore& shapes, const ContactManager& contacts) {
    shapes_.clear();
    const auto meets = [&](std::uint32_t slot) {
        const ShapeRecord& shape = shapes.records[slot];
        return (planes || typeOf(shape.def.geometry) != ShapeType::HalfSpace) &&
               shape.bounds.overlaps(box);
    };
    if (fixedShapes_.size() <= kScanned) {
        // Every shape's fat box holds its tight one, so the broadphase would have found exactly
        // these (and in slot order, as they are listed).
        for (const std::uint32_t slot : fixedShapes_) {
            if (meets(slot))
                shapes_.push_back(slot);
        }
        return;
    }
    contacts.broadphase().query(box, [&](std::uint32_t proxy) {
        const std::uint32_t slot = contacts.shapeOfProxy(proxy);
        const ShapeRecord& shape = shapes.records[slot];
        if (bodies.info[bodies.indexOf(shape.body)].type != BodyType::Dynamic && meets(slot))
            shapes_.push_back(slot);
    });
    // The broadphase's visiting order follows its cells; the rows' order must not.
    std::sort(shapes_.begin(), shapes_.end());
}

void ThreadContacts::collideThread(std::uint32_t index, const SpringStore& springs,
                                   const BodyStore& bodies, const ShapeStore& shapes,
                                   const ContactManager& contacts, Real h) {
    const SpringDef& def = springs.defs[index];
    const std::uint32_t a = bodies.indexOf(def.bodyA);
    const bool world = def.bodyB.isNull();
    const std::uint32_t b = world ? 0 : bodies.indexOf(def.bodyB);
    if (!eitherAwakeDynamic(bodies, a, b, world))
        return;  // nothing it could move
    const Vec3 pA = anchorAt(bodies, a, def.localAnchorA);
    const Vec3 pB = world ? def.localAnchorB : anchorAt(bodies, b, def.localAnchorB);
    const Real speed = std::max(bodies.motion[a].linearVelocity.norm(),
                                world ? 0 : bodies.motion[b].linearVelocity.norm());
    const Real margin = contacts.contactMargin + h * speed;
    const Vec3 grow = Vec3::Constant(def.contactRadius + margin);
    // A node with shapes of its own touches with them what lies within the radius of its
    // centre: the capsule starts a radius further along. Dropping the capsule's points near
    // such a node instead either kept the cap's points, duplicating the node's (t off 0 by the
    // tilt), or, by distance, dropped a 5 cm wall's near edge under a node hanging beside it,
    // and the thread sank through.
    const Real trimA = bodies.info[a].firstShape != BodyInfo::kNoShape ? def.contactRadius : 0;
    const Real trimB =
        !world && bodies.info[b].firstShape != BodyInfo::kNoShape ? def.contactRadius : 0;
    // Against a plane the depth is linear along the segment, deepest at an end: where both
    // ends are such nodes, the capsule could only repeat their contacts (a net lying on the
    // ground had a row for every thread).
    const bool planes = trimA == 0 || trimB == 0;
    candidates(Aabb{Vec3(pA.cwiseMin(pB) - grow), Vec3(pA.cwiseMax(pB) + grow)}, planes, bodies,
               shapes, contacts);
    if (shapes_.empty())
        return;
    const Vec3 d = pB - pA;
    const Real length = d.norm();
    if (!(length > 0))
        return;  // the nodes' own contacts, if any, are all there is
    const Real core = length - trimA - trimB;
    if (!(core > 0))
        return;
    const Vec3 axis = d / length;
    const Shape capsule = Capsule{def.contactRadius, core / 2};
    const Transform pose = segmentPose(pA + trimA * axis, pB - trimB * axis);
    for (const std::uint32_t slot : shapes_) {
        const ShapeRecord& shape = shapes.records[slot];
        const Transform shapeAt = shapePose(shape, bodies);
        collide(capsule, pose, shape.def.geometry, shapeAt, margin, manifolds_);
        if (manifolds_.count == 0)
            continue;
        leaveOverBorder(shape.def.geometry, shapeAt, pA, pB, def.contactRadius, manifolds_);
        const std::uint32_t s = bodies.indexOf(shape.body);
        // Without shapes at both ends, the rows push out (no node contact carries the thread).
        const bool shapedEnds = trimA > 0 && trimB > 0;
        constexpr std::span<const NodeContact> noContacts;
        for (int m = 0; m < manifolds_.count; ++m) {
            const Manifold& manifold = manifolds_.manifolds[m];
            for (int k = 0; k < manifold.pointCount; ++k) {
                const ContactPoint& point = manifold.points[k];
                // The capsule's end cap reaches past the trim: a point whose surface point on S
                // lies inside a node's sphere is that node's contact's. Kept, the rows of threads
                // leaving a node on a thin wall's edge down its two faces overlapped the faces
                // beside the node and squeezed it from both sides, levering the hanging nodes out
                // at 16 : 1 (0.04 - 0.08 N s a row and step; the net rose, +3 - 8 mJ a step).
                const Vec3 onS = point.position + point.separation / 2 * manifold.normal;
                if (shapedEnds && ((onS - pA).norm() < trimA || (onS - pB).norm() < trimB))
                    continue;
                const Real t =
                    std::clamp((point.position - pA).dot(d) / (length * length), Real(0), Real(1));
                SegmentContactRow& row = rows_.emplace_back();
                row.bodyA = endBody(bodies, a, false);
                row.bodyB = endBody(bodies, b, world);
                row.bodyS = endBody(bodies, s, false);
                row.t = t;
                row.rA = pA - bodies.motion[a].center;
                row.rB = world ? Vec3::Zero() : Vec3(pB - bodies.motion[b].center);
                row.rS = point.position - bodies.motion[s].center;
                row.normal = -manifold.normal;  // the manifold's runs from the capsule to S
                setRowDepth(row, point.separation, def.contactRadius, axis,
                            shapedEnds ? nodeContacts(a, bodies, contacts) : noContacts,
                            shapedEnds ? nodeContacts(b, bodies, contacts) : noContacts, s,
                            onS - pA, onS - pB);
                row.friction = mixFriction(def.contactFriction, shape.def.material.friction);
                keys_.push_back(Cached{.spring = index, .slot = slot});
                warmStart(row, index, slot, length, def.contactRadius);
            }
        }
    }
}

std::span<const ThreadContacts::NodeContact> ThreadContacts::nodeContacts(
    std::uint32_t index, const BodyStore& bodies, const ContactManager& contacts) {
    if (!gathered_)
        gatherNodeContacts(bodies, contacts);
    return {nodeContacts_.data() + nodeFirst_[index], nodeContacts_.data() + nodeFirst_[index + 1]};
}

// Every body's active contacts with points, from the touching list the solve walks: two passes
// (count, then fill) over it. Walking each asked node's linked contact list instead missed the
// cache on every 400-byte record (6.5 % of dustbin-mesh's step). The order within a body's
// range differs from its list's, which nodeTouch does not read.
void ThreadContacts::gatherNodeContacts(const BodyStore& bodies, const ContactManager& contacts) {
    gathered_ = true;
    nodeFirst_.assign(bodies.count() + 1, 0);
    const auto touching = [&](std::uint32_t slot) {
        return contacts.isActive(slot) && contacts.contact(slot).manifold.pointCount > 0;
    };
    for (const std::uint32_t slot : contacts.touchingSlots()) {
        if (!touching(slot))
            continue;
        const Contact& contact = contacts.contact(slot);
        ++nodeFirst_[bodies.indexOf(contact.bodyA) + 1];
        ++nodeFirst_[bodies.indexOf(contact.bodyB) + 1];
    }
    for (std::size_t i = 1; i < nodeFirst_.size(); ++i)
        nodeFirst_[i] += nodeFirst_[i - 1];
    nodeContacts_.resize(nodeFirst_.back());
    nodeFill_.assign(nodeFirst_.begin(), nodeFirst_.end() - 1);
    for (const std::uint32_t slot : contacts.touchingSlots()) {
        if (!touching(slot))
            continue;
        // The manifold's normal runs from A to B.
        const Contact& contact = contacts.contact(slot);
        const std::uint32_t a = bodies.indexOf(contact.bodyA);
        const std::uint32_t b = bodies.indexOf(contact.bodyB);
        nodeContacts_[nodeFill_[a]++] = {b, Vec3(-contact.manifold.normal)};
        nodeContacts_[nodeFill_[b]++] = {a, contact.manifold.normal};
    }
}

void ThreadContacts::warmStart(SegmentContactRow& row, std::uint32_t spring, std::uint32_t slot,
                               Real length, Real radius) {
    while (cursor_ < cache_.size() && cache_[cursor_].spring < spring)
        ++cursor_;
    constexpr Real kSameNormal = 0.9;  // cos ~25 degrees
    const Real window = radius / length;
    std::size_t best = cache_.size();
    for (std::size_t k = cursor_; k < cache_.size() && cache_[k].spring == spring; ++k) {
        const Cached& old = cache_[k];
        if (old.slot != slot || lent_[k] != 0 || old.normal.dot(row.normal) < kSameNormal ||
            std::abs(old.t - row.t) > window)
            continue;
        if (best == cache_.size() || std::abs(old.t - row.t) < std::abs(cache_[best].t - row.t))
            best = k;
    }
    if (best == cache_.size())
        return;
    lent_[best] = 1;
    const Cached& old = cache_[best];
    row.normalImpulse = old.normalImpulse;
    const std::array<Vec3, 2> tangents = frictionBasis(row.normal);
    row.tangentImpulse = {old.tangentImpulse.dot(tangents[0]), old.tangentImpulse.dot(tangents[1])};
}

void ThreadContacts::store() {
    cache_.resize(rows_.size());
    for (std::size_t k = 0; k < rows_.size(); ++k) {
        const SegmentContactRow& row = rows_[k];
        cache_[k] = Cached{
            keys_[k].spring,
            keys_[k].slot,
            row.t,
            row.normal,
            row.normalImpulse,
            row.tangentImpulse[0] * row.tangents[0] + row.tangentImpulse[1] * row.tangents[1]};
    }
}

}  // namespace tumble
