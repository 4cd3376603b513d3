// Replay files (docs/replay.md): what is written is read back, a damaged file is refused by
// name, and `tumble run --replay/--gltf` writes both at the chosen rate.

#include <gtest/gtest.h>

#include <cmath>
#include <nlohmann/json.hpp>
#include <sstream>

#include "cli_helpers.h"
#include "tumble/replay/replay.h"
#include "tumble/scene/scene.h"

namespace tumble::cli {
namespace {

using test::scratch;
using test::slurp;
using test::tumbleRun;

BuiltScene built(const std::string& name) {
    return buildScene(loadScene(name, {}, sceneDirectory()));
}

std::string record(BuiltScene& scene, int steps, int every) {
    std::ostringstream bytes;
    ReplayContent content;
    content.bodies = scene.bodies;
    content.springs = scene.springs;
    ReplayWriter writer(bytes, scene.world, content);
    writer.addFrame(scene.world);
    for (int i = 1; i <= steps; ++i) {
        scene.world.step();
        if (i % every == 0)
            writer.addFrame(scene.world);
    }
    writer.finish();
    return bytes.str();
}

TEST(Replay, RoundTripKeepsTheDescriptionPosesTensionsAndContacts) {
    BuiltScene scene = built("table");
    const std::string bytes = record(scene, 200, 10);
    const Replay r = readReplayBytes(bytes, "table");
    EXPECT_EQ(r.version, kReplayVersion);
    ASSERT_EQ(r.frames.size(), 21u);
    EXPECT_EQ(r.bodyCount, static_cast<int>(scene.bodies.size()));
    const nlohmann::json d = nlohmann::json::parse(r.description);
    ASSERT_EQ(d["bodies"].size(), scene.bodies.size());
    // Every body's shapes are described with their sizes.
    for (std::size_t i = 0; i < scene.bodies.size(); ++i)
        EXPECT_EQ(d["bodies"][i]["shapes"].size(), scene.world.bodyShapes(scene.bodies[i]).size());
    // The last frame is the world as it is now, to float precision.
    const ReplayFrame& last = r.frames.back();
    EXPECT_DOUBLE_EQ(last.time, scene.world.time());
    for (std::size_t i = 0; i < scene.bodies.size(); ++i) {
        const Transform t = scene.world.transform(scene.bodies[i]);
        for (int k = 0; k < 3; ++k)
            EXPECT_NEAR(last.poses[i].position[k], t.position[k],
                        1e-6 * (1 + std::abs(t.position[k])));
        EXPECT_NEAR(last.poses[i].orientation[3], t.rotation.w(), 1e-6);
        EXPECT_NEAR(last.poses[i].kineticEnergy, scene.world.kineticEnergy(scene.bodies[i]),
                    1e-6 * (1 + scene.world.kineticEnergy(scene.bodies[i])));
    }
    // The table rests on its legs: the floor's touching points (z = 0) carry the table and the
    // box on it, pointing up.
    ASSERT_FALSE(last.contacts.empty());
    double support = 0;
    for (const ReplayContact& c : last.contacts) {
        if (std::abs(c.point[2]) < 0.01)
            support += c.force * std::abs(c.normal[2]);
    }
    double weight = 0;
    for (const BodyId b : scene.bodies) {
        if (scene.world.bodyType(b) == BodyType::Dynamic)
            weight += scene.world.massProperties(b).mass * 9.81;
    }
    EXPECT_NEAR(support, weight, 0.1 * weight);  // resting after 200 steps, within 10 %
}

TEST(Replay, ThreadsAreNodePairsWithTheirTensions) {
    BuiltScene scene = built("string");
    const Replay r = readReplayBytes(record(scene, 20, 20), "string");
    const nlohmann::json d = nlohmann::json::parse(r.description);
    ASSERT_EQ(d["springs"].size(), scene.springs.size());
    EXPECT_TRUE(d["springs"][1]["thread"].get<bool>());
    EXPECT_EQ(d["springs"][1]["bodyB"].get<int>() - d["springs"][1]["bodyA"].get<int>(), 1);
    ASSERT_EQ(r.frames.back().tensions.size(), scene.springs.size());
    for (std::size_t s = 0; s < scene.springs.size(); ++s)
        EXPECT_FLOAT_EQ(r.frames.back().tensions[s],
                        static_cast<float>(scene.world.springState(scene.springs[s]).tension));
    for (const float tension : r.frames.back().tensions)
        EXPECT_GE(tension, 0.0F);  // threads pull, never push
}

void expectRefusal(const std::string& bytes, const std::string& words) {
    try {
        readReplayBytes(bytes, "damaged.tumble");
        ADD_FAILURE() << "accepted; expected: " << words;
    } catch (const InvalidArgument& e) {
        EXPECT_NE(std::string(e.what()).find(words), std::string::npos) << e.what();
        EXPECT_NE(std::string(e.what()).find("damaged.tumble"), std::string::npos) << e.what();
    }
}

TEST(Replay, TruncatedWrongVersionAndForeignFilesAreRefusedByName) {
    BuiltScene scene = built("stack");
    const std::string bytes = record(scene, 10, 5);
    expectRefusal(bytes.substr(0, bytes.size() - 3), "truncated replay");
    expectRefusal(bytes.substr(0, bytes.size() / 2), "truncated replay");
    expectRefusal(bytes.substr(0, 20), "truncated replay");
    std::string newer = bytes;
    newer[8] = 2;
    expectRefusal(newer, "replay version 2 is not supported");
    expectRefusal("PK\x03\x04 not a replay at all", "not a Tumble replay");
    expectRefusal("TUM", "not a Tumble replay");
}

TEST(Replay, CommandWritesTheReplayAtItsRateAndTheGltf) {
    const auto dir = scratch("replay");
    const auto o =
        tumbleRun({"run", "pendulum", "--time", "0.5", "--replay-rate", "30", "-q", "--replay",
                   (dir / "p.tumble").string(), "--gltf", (dir / "p.glb").string()});
    ASSERT_EQ(o.status, 0) << o.err;
    const Replay r = readReplay((dir / "p.tumble").string());
    ASSERT_EQ(r.frames.size(), 16u);  // 0, 1/30, ..., 0.5 s
    EXPECT_NEAR(r.frames[3].time, 0.1, 1e-9);
    const nlohmann::json d = nlohmann::json::parse(r.description);
    EXPECT_EQ(d["title"], "pendulum");
    EXPECT_EQ(d["joints"].size(), 4u);
    EXPECT_EQ(d["bodies"][4]["name"], "ball");
    EXPECT_EQ(slurp(dir / "p.glb").substr(0, 4), "glTF");
    const auto bad = tumbleRun({"run", "pendulum", "--time", "0.1", "-q", "--replay",
                                (dir / "no" / "such" / "dir.tumble").string()});
    EXPECT_EQ(bad.status, 2);
    EXPECT_NE(bad.err.find("cannot be written"), std::string::npos) << bad.err;
}

}  // namespace
}  // namespace tumble::cli
