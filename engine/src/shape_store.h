#pragma once
/// Shapes attached to bodies, stored by slot: the slot of a HandlePool (handle_pool.h), whose
/// dense order shapes do not use. Bodies, broadphase proxies and contacts refer to shapes by
/// slot, and shapes are few compared to per-step work, so they are not kept dense; slot order is
/// creation order with reuse of the latest freed slot, which is deterministic.

#include <cstdint>
#include <vector>

#include "handle_pool.h"
#include "tumble/body.h"
#include "tumble/collision/aabb.h"
#include "tumble/shape.h"

namespace tumble {

struct ShapeRecord {
    ShapeDef def;
    BodyId body;
    std::uint32_t proxy = 0;           ///< broadphase proxy
    Aabb fatBounds;                    ///< what the broadphase holds (m)
    Aabb bounds;                       ///< tight, at the current pose (m)
    std::uint32_t nextInBody = kNone;  ///< slot of the body's next shape

    static constexpr std::uint32_t kNone = 0xFFFFFFFF;
};

class ShapeStore {
    friend struct CheckpointAccess;  ///< checkpoint.cpp saves and restores the private state
public:
    /// Stores a shape (checked by the caller); returns its id.
    ShapeId add(const ShapeDef& def, BodyId body);
    void remove(ShapeId id);
    bool isValid(ShapeId id) const { return pool_.isValid(id); }
    /// Slot of a valid id; refuses (InvalidArgument) a null, foreign, stale or unknown id.
    std::uint32_t slotOf(ShapeId id) const {
        pool_.indexOf(id);
        return id.index;
    }
    ShapeId idAt(std::uint32_t slot) const { return pool_.idOfSlot(slot); }
    bool isAlive(std::uint32_t slot) const { return pool_.isAlive(slot); }
    /// The tag of the world that owns the store (World::Impl::setWorldTag).
    void setWorld(std::uint32_t world) { pool_.setWorld(world); }

    std::vector<ShapeRecord> records;  ///< by slot; a dead slot's record is not isAlive

private:
    HandlePool<ShapeId> pool_{"ShapeId", "shape"};
};

}  // namespace tumble
