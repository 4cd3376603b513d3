#pragma once
// Helpers of the checkpoint tests: a scene of bodies kept by id, their state as raw bits, a
// bitwise resume check, and the header's little-endian words.

#include <gtest/gtest.h>

#include <bit>
#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "checkpoint_io.h"
#include "refusal.h"
#include "testkit/same_ids.h"
#include "testkit/scenes.h"
#include "tumble/checkpoint.h"
#include "tumble/world.h"

namespace tumble::test {

/// Every body's pose, velocities and awake flag, as raw bits, in dense-slot order of the ids
/// given.
inline std::vector<std::uint64_t> stateBits(const World& world, const std::vector<BodyId>& bodies) {
    std::vector<std::uint64_t> bits;
    const auto add = [&](const Vec3& v) {
        for (int k = 0; k < 3; ++k)
            bits.push_back(std::bit_cast<std::uint64_t>(v[k]));
    };
    for (const BodyId b : bodies) {
        add(world.position(b));
        add(world.orientation(b).coeffs().head<3>());
        bits.push_back(std::bit_cast<std::uint64_t>(world.orientation(b).w()));
        add(world.linearVelocity(b));
        add(world.angularVelocity(b));
        bits.push_back(world.isAwake(b) ? 1 : 0);
        add(world.interpolatedTransform(b, 0.25).position);  // the previous pose counts too
    }
    return bits;
}

struct Scene {
    World world;
    std::vector<BodyId> bodies;
    std::vector<SpringId> springs;
};

inline BodyId addBody(Scene& scene, const Vec3& position, BodyType type = BodyType::Dynamic) {
    BodyDef def;
    def.type = type;
    def.position = position;
    const BodyId id = scene.world.createBody(def);
    scene.bodies.push_back(id);
    return id;
}

/// Runs `warmup` steps, checkpoints, restores into a default world, and steps both for `further`
/// steps comparing every body's state bitwise at every step, and the whole checkpoint at the end.
inline void expectBitwiseResume(Scene& original, int warmup, int further) {
    ASSERT_TRUE(testkit::simulate(original.world, warmup));
    const std::vector<std::uint8_t> saved = checkpointBytes(original.world);
    World resumed;  // a different (empty) world: everything must come from the checkpoint
    restoreCheckpoint(resumed, saved);
    ASSERT_EQ(checkpointBytes(resumed), saved) << "the restored world saves differently";
    ASSERT_EQ(resumed.stepCount(), original.world.stepCount());
    ASSERT_EQ(std::bit_cast<std::uint64_t>(resumed.time()),
              std::bit_cast<std::uint64_t>(original.world.time()));
    const std::vector<BodyId> resumedBodies = sameBodies(resumed, original.bodies);
    ASSERT_EQ(stateBits(original.world, original.bodies), stateBits(resumed, resumedBodies))
        << "differs before any step";
    for (int i = 0; i < further; ++i) {
        ASSERT_TRUE(original.world.step().ok());
        ASSERT_TRUE(resumed.step().ok());
        ASSERT_EQ(stateBits(original.world, original.bodies), stateBits(resumed, resumedBodies))
            << "diverged at step " << i + 1 << " after the checkpoint";
    }
    EXPECT_EQ(checkpointBytes(original.world), checkpointBytes(resumed));
}

inline std::uint64_t readU64(const std::vector<std::uint8_t>& b, std::size_t at) {
    std::uint64_t v = 0;
    for (int i = 0; i < 8; ++i)
        v |= std::uint64_t{b[at + i]} << (8 * i);
    return v;
}
inline void writeU64(std::vector<std::uint8_t>& b, std::size_t at, std::uint64_t v) {
    for (int i = 0; i < 8; ++i)
        b[at + i] = static_cast<std::uint8_t>(v >> (8 * i));
}

/// Rewrites the header's payload length and checksum to agree with the payload (so that the
/// reader, not the checksum, must notice what is wrong in it).
inline void sealPayload(std::vector<std::uint8_t>& bytes) {
    writeU64(bytes, 16, bytes.size() - 32);
    writeU64(bytes, 24, checkpoint_io::fnv1a(std::span<const std::uint8_t>(bytes).subspan(32)));
}

/// A world that refused checkpoints are loaded into, with the checkpoint it must keep.
class CheckpointRefusalBase : public ::testing::Test {
protected:
    /// good: the checkpoint of `saved` after `savedSteps`; target: `other` after `otherSteps`.
    void prepare(Scene saved, int savedSteps, Scene other, int otherSteps) {
        ASSERT_TRUE(testkit::simulate(saved.world, savedSteps));
        good = checkpointBytes(saved.world);
        target = std::move(other.world);
        ASSERT_TRUE(testkit::simulate(target, otherSteps));
        before = checkpointBytes(target);
    }
    /// The message of restoring `bytes` into `target` from `source`; the world must be left
    /// untouched and the message name the source.
    std::string refuse(const std::vector<std::uint8_t>& bytes, const std::string& source) {
        const std::string message = refusal([&] { restoreCheckpoint(target, bytes, source); });
        EXPECT_EQ(checkpointBytes(target), before) << "a refused checkpoint changed the world";
        EXPECT_TRUE(contains(message, "checkpoint " + source + ": "));
        return message;
    }
    std::vector<std::uint8_t> good;    ///< a checkpoint of another world
    std::vector<std::uint8_t> before;  ///< target's own checkpoint
    World target;
};

}  // namespace tumble::test
