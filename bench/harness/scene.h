#pragma once
/// The harness's scenes, built the same way in every engine: a column of unit cubes or a pyramid.

#include <string>
#include <vector>

#include "peer.h"

namespace tumble::bench {

struct Scene {
    std::string name;
    int size;  ///< cubes in the column, or the pyramid's base
    bool pyramid;
};

/// Builds the scene in `world`; returns the cubes' start positions (the top cube last).
inline std::vector<Vec3> build(PeerWorld& world, const Scene& scene) {
    world.addGround();
    std::vector<Vec3> start;
    if (!scene.pyramid) {
        for (int i = 0; i < scene.size; ++i)
            start.push_back(Vec3(0, 0, 0.5 + i));
    } else {
        constexpr double kPitch = 1.05;  // 5 cm between neighbours, as in the `pyramid` case
        for (int row = 0; row < scene.size; ++row) {
            const int n = scene.size - row;
            for (int i = 0; i < n; ++i)
                start.push_back(Vec3((i - 0.5 * (n - 1)) * kPitch, 0, 0.5 + row));
        }
    }
    for (const Vec3& p : start)
        world.addCube(p);
    return start;
}

}  // namespace tumble::bench
