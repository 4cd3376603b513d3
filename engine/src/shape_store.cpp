#include "shape_store.h"

namespace tumble {

ShapeId ShapeStore::add(const ShapeDef& def, BodyId body) {
    const ShapeId id = pool_.add();
    if (id.index == records.size())
        records.emplace_back();
    ShapeRecord& record = records[id.index];
    record = ShapeRecord{};
    record.def = def;
    record.body = body;
    return id;
}

void ShapeStore::remove(ShapeId id) {
    const std::uint32_t slot = slotOf(id);
    pool_.remove(id);
    records[slot].def.geometry = Sphere{};  // release shared hull data
}

}  // namespace tumble
