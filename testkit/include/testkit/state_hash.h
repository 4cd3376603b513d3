#pragma once
/// Bitwise hashes of a world's state, for the determinism and golden-trajectory tests.
///
/// The hash covers the bit patterns of every listed body's position, orientation, velocities and
/// awake flag (so -0.0 and 0.0 differ), with the step count and time: two states hash alike
/// exactly when they are bitwise identical, up to FNV-1a collisions.

#include <bit>
#include <cstdint>
#include <span>

#include "tumble/world.h"

namespace tumble::testkit {

/// FNV-1a over 64-bit words: enough to tell two trajectories apart, cheap enough to run per step.
class Hash {
public:
    void add(std::uint64_t word) {
        for (int byte = 0; byte < 8; ++byte) {
            value_ ^= (word >> (8 * byte)) & 0xffu;
            value_ *= 0x100000001b3ull;
        }
    }
    void add(Real x) { add(std::bit_cast<std::uint64_t>(x)); }  // -0.0 and NaN payloads count
    void add(const Vec3& v) {
        for (int k = 0; k < 3; ++k)
            add(v[k]);
    }
    std::uint64_t value() const { return value_; }

private:
    std::uint64_t value_ = 0xcbf29ce484222325ull;
};

/// Every listed body's full state, in the order given: pose, velocities, awake flag.
inline std::uint64_t stateHash(const World& w, std::span<const BodyId> bodies) {
    Hash h;
    h.add(w.stepCount());
    h.add(w.time());
    for (const BodyId b : bodies) {
        h.add(w.position(b));
        const Quat q = w.orientation(b);
        h.add(q.w());
        h.add(q.x());
        h.add(q.y());
        h.add(q.z());
        h.add(w.linearVelocity(b));
        h.add(w.angularVelocity(b));
        h.add(std::uint64_t{w.isAwake(b)});
    }
    return h.value();
}

}  // namespace tumble::testkit
