#include "joint_store.h"

#include "tumble/core/error.h"

namespace tumble {

JointId JointStore::add(const JointRecord& record) {
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
    slot.dense = count();
    slot.alive = true;
    records.push_back(record);
    state.push_back({});
    previousState.push_back({});
    slotOf_.push_back(slotIndex);
    return JointId{slotIndex, slot.generation};
}

void JointStore::remove(JointId id) {
    const std::uint32_t index = indexOf(id);
    const std::uint32_t last = count() - 1;
    if (index != last) {
        records[index] = records[last];
        state[index] = state[last];
        previousState[index] = previousState[last];
        slotOf_[index] = slotOf_[last];
        slots_[slotOf_[index]].dense = index;
    }
    records.pop_back();
    state.pop_back();
    previousState.pop_back();
    slotOf_.pop_back();
    slots_[id.index].alive = false;
    freeSlots_.push_back(id.index);
}

bool JointStore::isValid(JointId id) const {
    return id.generation != 0 && id.index < slots_.size() && slots_[id.index].alive &&
           slots_[id.index].generation == id.generation;
}

std::uint32_t JointStore::indexOf(JointId id) const {
    if (!isValid(id)) {
        fail("JointId {index ", id.index, ", generation ", id.generation,
             "} is null, stale or unknown");
    }
    return slots_[id.index].dense;
}

JointId JointStore::idAt(std::uint32_t index) const {
    const std::uint32_t slot = slotOf_[index];
    return JointId{slot, slots_[slot].generation};
}

}  // namespace tumble
