#pragma once
/// Ids carry the tag of the world that made them (BodyId::world): a world loaded from a
/// checkpoint refuses the saving world's ids. Tests that compare a saved world with a loaded one
/// name the same body in each by its slot and generation, which the checkpoint keeps.

#include <vector>

#include "tumble/world.h"

namespace tumble::test {

/// The body of `world` in the slot and generation of `id` (from another world); null if none.
inline BodyId sameBody(const World& world, BodyId id) {
    for (const BodyId body : world.bodies()) {
        if (body.index == id.index && body.generation == id.generation)
            return body;
    }
    return {};
}

inline std::vector<BodyId> sameBodies(const World& world, const std::vector<BodyId>& ids) {
    std::vector<BodyId> same;
    for (const BodyId id : ids)
        same.push_back(sameBody(world, id));
    return same;
}

}  // namespace tumble::test
