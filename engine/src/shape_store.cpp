#include "shape_store.h"

#include "tumble/core/error.h"

namespace tumble {

ShapeId ShapeStore::add(const ShapeDef& def, BodyId body) {
    std::uint32_t slot;
    if (freeSlots_.empty()) {
        slot = static_cast<std::uint32_t>(records.size());
        records.emplace_back();
    } else {
        slot = freeSlots_.back();
        freeSlots_.pop_back();
    }
    ShapeRecord& record = records[slot];
    const std::uint32_t generation = record.generation + 1;
    record = ShapeRecord{};
    record.def = def;
    record.body = body;
    record.generation = generation;
    record.alive = true;
    return {slot, generation};
}

void ShapeStore::remove(ShapeId id) {
    const std::uint32_t slot = slotOf(id);
    records[slot].alive = false;
    records[slot].def.geometry = Sphere{};  // release shared hull data
    freeSlots_.push_back(slot);
}

bool ShapeStore::isValid(ShapeId id) const {
    return id.generation != 0 && id.index < records.size() && records[id.index].alive &&
           records[id.index].generation == id.generation;
}

std::uint32_t ShapeStore::slotOf(ShapeId id) const {
    if (!isValid(id)) {
        if (id.isNull())
            fail("shape id is null");
        fail("shape id {index ", id.index, ", generation ", id.generation,
             "} does not name a live shape (destroyed, or from another world)");
    }
    return id.index;
}

}  // namespace tumble
