#pragma once
/// The collision stages of a step: broadphase (bounds and pairs) and narrowphase (manifolds),
/// with the contact cache that carries impulses from one step to the next.
///
/// Contacts are kept in the broadphase's pair order (sorted by proxy ids), so the narrowphase
/// and everything after it see pairs in an order that depends only on the scene's history,
/// never on addresses or hashing.

#include <span>
#include <vector>

#include "body_store.h"
#include "shape_store.h"
#include "step_context.h"
#include "tumble/collision/broadphase.h"
#include "tumble/contact.h"

namespace tumble {

class ContactManager {
public:
    /// Registers a shape with the broadphase at its body's current pose.
    void addShape(ShapeStore& shapes, std::uint32_t slot, const BodyStore& bodies, Real h);
    void removeShape(ShapeStore& shapes, std::uint32_t slot);
    /// Re-reads one shape's bounds after a teleport (setTransform) or a new pose.
    void refreshShape(ShapeStore& shapes, std::uint32_t slot, const BodyStore& bodies, Real h);

    /// After the bodies moved: refresh the tight bounds of every non-static shape and move the
    /// proxies whose box, swept over the next step, left their fat box. Bounds are therefore
    /// always those of the current poses, and queries between steps see them.
    void refreshBounds(ShapeStore& shapes, const BodyStore& bodies, const StepContext& context);
    /// Broadphase stage: update the pair set from the fat boxes.
    void updatePairs() { broadphase_.update(); }
    /// Narrowphase stage: a manifold for every broadphase pair that may touch, with impulses of
    /// persisting points carried over (matched by feature id, else by proximity).
    void updateContacts(const ShapeStore& shapes, const BodyStore& bodies,
                        const StepContext& context);

    std::span<const Contact> contacts() const { return contacts_; }
    /// For the solve stage, which writes the impulses it found back into the cache.
    std::span<Contact> mutableContacts() { return contacts_; }
    const SweepAndPrune& broadphase() const { return broadphase_; }
    std::uint32_t shapeOfProxy(std::uint32_t proxy) const { return proxyToShape_[proxy]; }

    Real contactMargin = 0.02;  ///< speculative distance added to h |v_rel| (m)
    Real aabbMargin = 0.1;      ///< fat box growth (m)

private:
    SweepAndPrune broadphase_;
    std::vector<std::uint32_t> proxyToShape_;
    std::vector<Contact> contacts_;
    std::vector<ProxyPair> contactKeys_;
    std::vector<Contact> nextContacts_;
    std::vector<ProxyPair> nextKeys_;
};

/// The world pose of a shape on a body (body origin pose composed with the shape's local pose).
Transform shapePose(const ShapeRecord& shape, const BodyStore& bodies);

}  // namespace tumble
