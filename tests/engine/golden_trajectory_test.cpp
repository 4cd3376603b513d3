// Golden trajectories: the hash of every body's state after every step of a few built-in scenes,
// compared against the values committed in tests/golden/trajectories.txt. A refactor that changes
// any bit of any trajectory fails here; a change meant to alter results updates that file in its
// own commit and says why. Which builds share the hashes: docs/determinism.md.
//
// To rewrite the file after an intended change:
//   TUMBLE_UPDATE_GOLDEN=1 build/release/tests/tumble-cli-tests --gtest_filter='GoldenTrajectory.*'

#include <gtest/gtest.h>

#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include "testkit/state_hash.h"
#include "tumble/scene/scene.h"

namespace tumble {
namespace {

/// A built-in scene run for a fixed number of steps.
struct GoldenCase {
    const char* scene;
    int steps;
};

/// The pyramid (resting contact, 55 boxes), the rain (216 mixed shapes falling into a pile: GJK,
/// cylinders, hulls, sleeping), the capture net (implicit threads, colliding nodes) and the
/// five-body pendulum (ball joints, four substeps): together they reach every solver stage.
constexpr GoldenCase kCases[] = {
    {"pyramid", 150},
    {"rain", 150},
    {"net-capture", 120},
    {"pendulum", 240},
};

const char* goldenFile() {
    return TUMBLE_GOLDEN_FILE;
}

/// The committed hashes, by scene name; "<scene> <steps> <hex hash>" per line, '#' comments.
std::map<std::string, std::pair<int, std::uint64_t>> readGolden() {
    std::map<std::string, std::pair<int, std::uint64_t>> golden;
    std::ifstream in(goldenFile());
    std::string line;
    while (std::getline(in, line)) {
        if (line.empty() || line[0] == '#')
            continue;
        std::istringstream fields(line);
        std::string name, hex;
        int steps = 0;
        fields >> name >> steps >> hex;
        golden[name] = {steps, std::stoull(hex, nullptr, 16)};
    }
    return golden;
}

/// Hash of the whole trajectory: each step's state hash folded into one.
/// scalarContacts: with the scalar contact sweep in place of the (default) coloured rows.
/// softSubsteps > 0: under the soft step with that many substeps.
std::uint64_t trajectoryHash(const GoldenCase& c, bool scalarContacts = false,
                             int softSubsteps = 0) {
    cli::Scene scene = cli::loadScene(c.scene, {}, cli::sceneDirectory());
    scene.world.solver.colouredContacts = scene.world.solver.colouredContacts && !scalarContacts;
    if (softSubsteps > 0)
        scene.world.solver.softSubsteps = softSubsteps;
    cli::BuiltScene built = cli::buildScene(scene);
    testkit::Hash trajectory;
    trajectory.add(testkit::stateHash(built.world, built.bodies));
    for (int i = 0; i < c.steps; ++i) {
        EXPECT_TRUE(built.world.step().ok()) << c.scene << " step " << i;
        trajectory.add(testkit::stateHash(built.world, built.bodies));
    }
    return trajectory.value();
}

TEST(GoldenTrajectory, EveryBitMatchesTheCommittedHashes) {
    std::map<std::string, std::uint64_t> measured;
    for (const GoldenCase& c : kCases)
        measured[c.scene] = trajectoryHash(c);

    const char* update = std::getenv("TUMBLE_UPDATE_GOLDEN");
    if (update != nullptr && std::string(update) == "1") {
        std::ofstream out(goldenFile());
        out << "# Golden trajectory hashes: <scene> <steps> <hash of every body's state after "
               "every "
               "step>.\n# Checked by tests/engine/golden_trajectory_test.cpp; what may change "
               "them: docs/determinism.md.\n";
        for (const GoldenCase& c : kCases) {
            char hex[17];
            std::snprintf(hex, sizeof hex, "%016llx",
                          static_cast<unsigned long long>(measured[c.scene]));
            out << c.scene << ' ' << c.steps << ' ' << hex << '\n';
        }
        GTEST_SKIP() << "rewrote " << goldenFile();
    }

    const auto golden = readGolden();
    for (const GoldenCase& c : kCases) {
        const auto it = golden.find(c.scene);
        ASSERT_NE(it, golden.end()) << c.scene << " has no line in " << goldenFile();
        EXPECT_EQ(it->second.first, c.steps) << c.scene << ": step count differs from the file";
        EXPECT_EQ(it->second.second, measured[c.scene])
            << c.scene << ": the trajectory changed (measured " << std::hex << measured[c.scene]
            << "). If the change is intended, rewrite " << goldenFile()
            << " with TUMBLE_UPDATE_GOLDEN=1 in its own commit and say why.";
    }
}

// The coloured wide rows (the default) keep every body's manifolds in constraint order
// (contact_rows.h), so the scalar sweep must reproduce their hashes bit for bit.
TEST(GoldenTrajectory, TheScalarSweepMatchesTheCommittedHashes) {
    const auto golden = readGolden();
    for (const GoldenCase& c : kCases) {
        const auto it = golden.find(c.scene);
        ASSERT_NE(it, golden.end()) << c.scene << " has no line in " << goldenFile();
        EXPECT_EQ(it->second.second, trajectoryHash(c, true)) << c.scene;
    }
}

// The soft step's sweeps on the coloured rows (the default) and on the scalar rows: the same
// order per body, so the same bits. The contact scenes leave the default step's trajectory (the
// soft step ran); the net has springs, which keep the default step. The pendulum asks for the
// default step's substeps, which a world takes without the soft step's (one count).
TEST(GoldenTrajectory, TheSoftStepIsTheSameOnBothSweeps) {
    const auto golden = readGolden();
    for (const GoldenCase& c : kCases) {
        if (cli::loadScene(c.scene, {}, cli::sceneDirectory()).world.substeps > 1)
            continue;
        const std::uint64_t coloured = trajectoryHash(c, false, 4);
        EXPECT_EQ(coloured, trajectoryHash(c, true, 4)) << c.scene;
        const bool soft = c.scene == std::string("pyramid") || c.scene == std::string("rain");
        EXPECT_EQ(coloured != golden.at(c.scene).second, soft) << c.scene;
    }
}

}  // namespace
}  // namespace tumble
