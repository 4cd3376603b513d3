#pragma once
/// Shapes attached to bodies, stored by slot (ids are slot + generation). Shapes are few compared
/// to per-step work, so slots are iterated directly (dead ones skipped) rather than kept dense;
/// slot order is creation order with reuse of the latest freed slot, which is deterministic.

#include <cstdint>
#include <vector>

#include "tumble/body.h"
#include "tumble/collision/aabb.h"
#include "tumble/shape.h"

namespace tumble {

struct ShapeRecord {
    ShapeDef def;
    BodyId body;
    std::uint32_t proxy = 0;  ///< broadphase proxy
    Aabb fatBounds;           ///< what the broadphase holds (m)
    Aabb bounds;              ///< tight, at the current pose (m)
    std::uint32_t generation = 0;
    std::uint32_t nextInBody = kNone;  ///< slot of the body's next shape
    bool alive = false;

    static constexpr std::uint32_t kNone = 0xFFFFFFFF;
};

class ShapeStore {
    friend struct CheckpointAccess;  ///< checkpoint.cpp saves and restores the private state
public:
    /// Stores a shape (checked by the caller); returns its id.
    ShapeId add(const ShapeDef& def, BodyId body);
    void remove(ShapeId id);
    bool isValid(ShapeId id) const;
    /// Slot of a valid id; refuses (InvalidArgument) a null, stale or unknown id.
    std::uint32_t slotOf(ShapeId id) const;
    ShapeId idAt(std::uint32_t slot) const { return {slot, records[slot].generation}; }

    std::vector<ShapeRecord> records;  ///< by slot; dead slots have alive == false

private:
    std::vector<std::uint32_t> freeSlots_;
};

}  // namespace tumble
