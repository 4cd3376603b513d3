// Determinism: the same scene, settings and build give bitwise-identical trajectories, whatever
// else the process did before or does between steps. The scenes come from demos/scenes through
// the `tumble` command's loader (so this test lives in tumble-cli-tests). What may change results
// across builds is written in docs/determinism.md.

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <cstdio>
#include <string>
#include <tuple>
#include <utility>
#include <vector>

#include "testkit/state_hash.h"
#include "tumble/scene/scene.h"

namespace tumble {
namespace {

/// Every body of the scene, in scene order (testkit/state_hash.h).
std::uint64_t stateHash(const cli::BuiltScene& built) {
    return testkit::stateHash(built.world, built.bodies);
}

struct Trajectory {
    std::vector<std::uint64_t> hashes;      ///< after building, then after every step
    Real lowestStartZ = 0, lowestEndZ = 0;  ///< of the dynamic bodies (m)
    Real highestStartZ = 0, highestEndZ = 0;
    std::size_t queryAnswers = 0;  ///< contacts, overlaps and hits seen between steps
};

/// The lowest and highest origin heights of the dynamic bodies (m).
std::pair<Real, Real> heightRange(const cli::BuiltScene& built) {
    Real lowest = 1e300, highest = -1e300;
    for (const BodyId b : built.bodies) {
        if (built.world.bodyType(b) != BodyType::Dynamic)
            continue;
        lowest = std::min(lowest, built.world.position(b).z());
        highest = std::max(highest, built.world.position(b).z());
    }
    return {lowest, highest};
}

/// Simulated time of each run (s): the rain has landed and piled up by then (its top layer
/// falls 3.5 m in 0.85 s), and the test stays affordable under the sanitizers (GCC's ASan build
/// needs ~2 min of CPU for the whole 4 s scenes run six times).
constexpr Real kDuration = 2.5;

/// Runs a built-in scene for kDuration. When `other` is given, it takes a step between every two
/// steps of the scene (a second live world must not leak into the first), and the scene's world
/// answers queries between its steps.
Trajectory run(const std::string& name, cli::BuiltScene* other = nullptr, Real duration = kDuration,
               const std::vector<std::string>& overrides = {}) {
    const cli::Scene scene = cli::loadScene(name, overrides, cli::sceneDirectory());
    cli::BuiltScene built = cli::buildScene(scene);
    const auto steps = static_cast<int>(duration / scene.world.timeStep + 0.5);
    Trajectory t;
    std::tie(t.lowestStartZ, t.highestStartZ) = heightRange(built);
    t.hashes.reserve(steps + 1);
    t.hashes.push_back(stateHash(built));
    for (int i = 0; i < steps; ++i) {
        EXPECT_TRUE(built.world.step().ok()) << name << " step " << i;
        t.hashes.push_back(stateHash(built));
        if (other != nullptr) {
            other->world.step();
            // Read-only calls between steps must not change the next step either.
            const World& w = built.world;
            t.queryAnswers += w.contacts().size() +
                              w.overlapAabb(Aabb{Vec3(-1, -1, 0), Vec3(1, 1, 1)}).size() +
                              (w.castRayClosest(Vec3(0.1, 0.2, 5), Vec3(0, 0, -10)) ? 1 : 0);
        }
    }
    std::tie(t.lowestEndZ, t.highestEndZ) = heightRange(built);
    return t;
}

/// Unrelated work: a world whose bodies are created, stepped and destroyed in a scrambled order,
/// leaving the allocator, the narrowphase's per-thread scratch buffers and libccd in a different
/// state than a fresh process has.
void churn() {
    World world;
    BodyDef ground;
    ground.type = BodyType::Static;
    world.createShape(world.createBody(ground), {.geometry = HalfSpace{}});
    std::vector<BodyId> bodies;
    for (int i = 0; i < 40; ++i) {
        BodyDef def;
        def.position = Vec3(0.3 * (i % 7), 0.2 * (i % 5), 0.5 + 0.4 * i);
        def.orientation = Quat(Eigen::AngleAxisd(0.1 * i, Vec3(1, 2, 3).normalized()));
        const BodyId body = world.createBody(def);
        const Shape shapes[] = {Sphere{0.2}, Box{Vec3(0.2, 0.1, 0.15)}, Capsule{0.1, 0.2},
                                Cylinder{0.15, 0.1}};
        world.createShape(body, {.geometry = shapes[i % 4]});
        bodies.push_back(body);
    }
    for (int i = 0; i < 90; ++i) {
        world.step();
        if (i % 10 == 9) {
            const std::size_t k = (i * 7) % bodies.size();
            world.destroyBody(bodies[k]);
            bodies.erase(bodies.begin() + static_cast<std::ptrdiff_t>(k));
        }
    }
}

void expectSame(const Trajectory& first, const Trajectory& second, const std::string& name) {
    ASSERT_EQ(first.hashes.size(), second.hashes.size());
    for (std::size_t i = 0; i < first.hashes.size(); ++i)
        ASSERT_EQ(first.hashes[i], second.hashes[i])
            << name << ": first difference after step " << i;
}

TEST(Determinism, PyramidAndRainRepeatBitwiseAfterOtherWork) {
    const Trajectory pyramid = run("pyramid");
    const Trajectory rain = run("rain");

    churn();
    // The second runs step in lockstep with another live world (the stack scene) and follow
    // more unrelated work.
    cli::BuiltScene beside = cli::buildScene(cli::loadScene("stack", {}, cli::sceneDirectory()));
    const Trajectory pyramidAgain = run("pyramid", &beside);
    churn();
    const Trajectory rainAgain = run("rain", &beside);

    expectSame(pyramid, pyramidAgain, "pyramid");
    expectSame(rain, rainAgain, "rain");
    // To compare two builds (compilers, flags, machines): these agree when the runs do.
    std::printf("final state hashes: pyramid %016llx, rain %016llx\n",
                static_cast<unsigned long long>(pyramid.hashes.back()),
                static_cast<unsigned long long>(rain.hashes.back()));
    EXPECT_GT(pyramidAgain.queryAnswers, 0u);
    EXPECT_GT(rainAgain.queryAnswers, 0u);
    // The trajectories are the scenes' physics, not a world that failed to move: the pyramid
    // settles by less than a centimetre and stands (its 0.25 m boxes start resting on each
    // other, the top one at 4.75 m); the rain falls from 1.5-4 m into a pile on the floor.
    EXPECT_LT(pyramid.lowestEndZ, pyramid.lowestStartZ);
    EXPECT_NEAR(pyramid.highestEndZ, pyramid.highestStartZ, 0.01);
    EXPECT_LT(rain.lowestEndZ, 0.2);
    EXPECT_LT(rain.highestEndZ, 2.0);
}

// The net-capture scene: implicit tension-only threads (the direct block solve with its active
// set, post-stabilisation) and colliding nodes wrapping the bin. 1 s: the net has landed on the
// lid (0.35 s) and wrapped the sides (0.6 s).
TEST(Determinism, NetCaptureRepeatsBitwise) {
    const Trajectory first = run("net-capture", nullptr, 1.0);
    churn();
    const cli::Scene stack = cli::loadScene("stack", {}, cli::sceneDirectory());
    cli::BuiltScene beside = cli::buildScene(stack);
    const Trajectory second = run("net-capture", &beside, 1.0);
    expectSame(first, second, "net-capture");
    EXPECT_LT(first.lowestEndZ, first.lowestStartZ - 0.5);  // the edges fell past the lid
}

// Two substeps per step: the pyramid (resting contacts, split impulse every substep) repeats
// bitwise, and differs from the one-substep run (the setting is not ignored).
TEST(Determinism, PyramidWithTwoSubstepsRepeatsBitwise) {
    // The default step's substeps (the soft step takes only one count, softSubsteps).
    const std::vector<std::string> twice = {"world.substeps=2", "world.solver.softSubsteps=0"};
    const Trajectory first = run("pyramid", nullptr, 1.0, twice);
    churn();
    cli::BuiltScene beside = cli::buildScene(cli::loadScene("stack", {}, cli::sceneDirectory()));
    const Trajectory second = run("pyramid", &beside, 1.0, twice);
    expectSame(first, second, "pyramid, 2 substeps");
    const Trajectory single = run("pyramid", nullptr, 1.0);
    EXPECT_NE(first.hashes.back(), single.hashes.back());
    EXPECT_NEAR(first.highestEndZ, first.highestStartZ, 0.01);  // it still stands
}

}  // namespace
}  // namespace tumble
