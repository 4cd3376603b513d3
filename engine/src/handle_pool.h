#pragma once
/// The table behind every id the world hands out (BodyId, ShapeId, JointId, SpringId).
///
/// An id names a slot and the slot's generation at the time, plus the tag of the world that made
/// it. The pool maps live slots to a dense index 0..size()-1, which is where the owning store
/// keeps the element in its parallel arrays. Removing an element moves the last dense element
/// into the freed index (the store moves its arrays' last element the same way, see
/// moveLastInto), and the freed slot is reused last-in first-out with its generation bumped.
///
/// Determinism: the dense order and the slot each add() takes depend only on the sequence of
/// add() and remove() calls -- never on addresses, hashing or the world tag -- and the solver
/// sweeps the stores in dense order. The world tag only decides which ids are accepted: it is
/// never compared with anything but itself, never saved in a checkpoint, and never read by a
/// step.

#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "tumble/core/error.h"

namespace tumble {

/// One slot table for ids of type Id (a struct of index, generation and world; generation 0 is
/// the null id).
template <typename Id>
class HandlePool {
    friend struct CheckpointAccess;  ///< checkpoint.cpp saves and restores the tables
public:
    /// How refusals name the id and what it names: ("BodyId", "body").
    HandlePool(const char* idName, const char* what) : idName_(idName), what_(what) {}

    /// Takes a slot (the last one freed, or a new one) and appends it at dense index size()-1.
    Id add() {
        std::uint32_t slotIndex;
        if (freeSlots_.empty()) {
            slotIndex = static_cast<std::uint32_t>(slots_.size());
            slots_.push_back({});
        } else {
            slotIndex = freeSlots_.back();
            freeSlots_.pop_back();
        }
        Slot& slot = slots_[slotIndex];
        slot.generation += 1;
        slot.dense = size();
        slot.alive = true;
        slotOf_.push_back(slotIndex);
        return makeId(slotIndex);
    }

    /// Frees a valid id's slot; the last dense element takes its dense index, which is
    /// returned: the store moves its own last elements there (moveLastInto).
    std::uint32_t remove(Id id) {
        const std::uint32_t index = indexOf(id);
        const std::uint32_t last = size() - 1;
        slotOf_[index] = slotOf_[last];
        slots_[slotOf_[index]].dense = index;
        slotOf_.pop_back();
        slots_[id.index].alive = false;
        freeSlots_.push_back(id.index);
        return index;
    }

    /// Names a live element of this world (generation matching, world tag matching).
    bool isValid(Id id) const {
        return id.generation != 0 && id.world == world_ && id.index < slots_.size() &&
               slots_[id.index].alive && slots_[id.index].generation == id.generation;
    }

    /// Dense index of a valid id; refuses (InvalidArgument) a null id, another world's id and a
    /// stale or unknown one, saying which.
    std::uint32_t indexOf(Id id) const {
        if (!isValid(id)) {
            if (id.generation == 0)
                fail(idName_, " is null");
            if (id.world != world_) {
                fail(idName_, " {index ", id.index, ", generation ", id.generation,
                     "} belongs to another world");
            }
            fail(idName_, " {index ", id.index, ", generation ", id.generation,
                 "} does not name a live ", what_, " (destroyed, or never created)");
        }
        return slots_[id.index].dense;
    }

    /// Dense index of an id already checked at the boundary (a spring's or joint's ends: destroying
    /// a body destroys them). No check: the per-step passes over every spring looked each end up
    /// with the refusal's tests (~2 % of a net's step).
    std::uint32_t checkedIndexOf(Id id) const { return slots_[id.index].dense; }

    /// Why a non-null id is not valid, for refusals that name a field: "belongs to another
    /// world" or "is not a live body (destroyed or unknown)".
    std::string whyInvalid(Id id) const {
        if (id.world != world_)
            return "belongs to another world";
        return std::string("is not a live ") + what_ + " (destroyed or unknown)";
    }

    /// The id of the element at a dense index.
    Id idAt(std::uint32_t index) const { return makeId(slotOf_[index]); }
    /// The id of a live slot (stores that keep their elements by slot).
    Id idOfSlot(std::uint32_t slot) const { return makeId(slot); }
    bool isAlive(std::uint32_t slot) const { return slots_[slot].alive; }

    std::uint32_t size() const { return static_cast<std::uint32_t>(slotOf_.size()); }
    std::uint32_t slotCount() const { return static_cast<std::uint32_t>(slots_.size()); }
    void reserve(std::size_t count) {
        slots_.reserve(count);
        slotOf_.reserve(count);
    }

    /// The tag the world puts in its ids (World::Impl::setWorldTag); not state.
    void setWorld(std::uint32_t world) { world_ = world; }

private:
    struct Slot {
        std::uint32_t generation = 0;  ///< of the element living here, or of the last one that did
        std::uint32_t dense = 0;       ///< its dense index, while alive
        bool alive = false;
    };
    Id makeId(std::uint32_t slot) const {
        Id id;
        id.index = slot;
        id.generation = slots_[slot].generation;
        id.world = world_;
        return id;
    }

    std::vector<Slot> slots_;
    std::vector<std::uint32_t> slotOf_;     ///< per dense index
    std::vector<std::uint32_t> freeSlots_;  ///< reused last-in first-out
    std::uint32_t world_ = 0;
    const char* idName_;
    const char* what_;
};

/// Base of the stores that keep their elements in parallel arrays at a HandlePool's dense
/// indices (bodies, joints, springs): the id queries they all answer alike.
template <typename Id>
class DenseStore {
public:
    /// Names a live element of this world.
    bool isValid(Id id) const { return pool_.isValid(id); }
    /// Dense index of a valid id; refuses (InvalidArgument) a null, foreign, stale or unknown id.
    std::uint32_t indexOf(Id id) const { return pool_.indexOf(id); }
    /// Dense index of an id the boundary checked (HandlePool::checkedIndexOf).
    std::uint32_t checkedIndexOf(Id id) const { return pool_.checkedIndexOf(id); }
    Id idAt(std::uint32_t index) const { return pool_.idAt(index); }
    std::uint32_t count() const { return pool_.size(); }
    /// Why a non-null id is not valid, for refusals that name a field (HandlePool::whyInvalid).
    std::string whyInvalid(Id id) const { return pool_.whyInvalid(id); }
    /// The tag of the world that owns the store (World::Impl::setWorldTag).
    void setWorld(std::uint32_t world) { pool_.setWorld(world); }

protected:
    DenseStore(const char* idName, const char* what) : pool_(idName, what) {}
    HandlePool<Id> pool_;
};

/// The swap-with-last removal of a store's parallel arrays, after HandlePool::remove returned
/// `index`: each array's last element moves into `index` and the array shrinks by one.
template <typename... Arrays>
void moveLastInto(std::uint32_t index, Arrays&... arrays) {
    const auto one = [index](auto& array) {
        if (index + 1 != array.size())
            array[index] = std::move(array.back());
        array.pop_back();
    };
    (one(arrays), ...);
}

}  // namespace tumble
