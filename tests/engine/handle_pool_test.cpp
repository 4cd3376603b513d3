// HandlePool, the id table of every store: slots taken and reused last-in first-out with their
// generation bumped, stale, null and foreign ids refused by name, and a dense order that follows
// swap-with-last removal exactly (the solver sweeps the stores in that order, so it must be a
// function of the call sequence alone).

#include "handle_pool.h"

#include <gtest/gtest.h>

#include <cstdint>
#include <string>
#include <vector>

#include "refusal.h"

namespace tumble {
namespace {

using test::contains;
using test::refusal;

struct TestId {
    std::uint32_t index = 0;
    std::uint32_t generation = 0;
    std::uint32_t world = 0;
    friend bool operator==(TestId, TestId) = default;
};

using Pool = HandlePool<TestId>;

Pool makePool(std::uint32_t world = 7) {
    Pool pool("TestId", "thing");
    pool.setWorld(world);
    return pool;
}

TEST(HandlePool, AddTakesNewSlotsInOrderAtGenerationOne) {
    Pool pool = makePool();
    for (std::uint32_t i = 0; i < 3; ++i) {
        const TestId id = pool.add();
        EXPECT_EQ(id, (TestId{i, 1, 7}));
        EXPECT_EQ(pool.indexOf(id), i);
        EXPECT_EQ(pool.idAt(i), id);
    }
    EXPECT_EQ(pool.size(), 3u);
    EXPECT_EQ(pool.slotCount(), 3u);
}

TEST(HandlePool, RemoveMovesTheLastIntoTheFreedIndex) {
    Pool pool = makePool();
    const TestId a = pool.add(), b = pool.add(), c = pool.add();
    EXPECT_EQ(pool.remove(a), 0u);  // the freed dense index
    EXPECT_FALSE(pool.isValid(a));
    EXPECT_EQ(pool.idAt(0), c);  // the last took a's place
    EXPECT_EQ(pool.indexOf(c), 0u);
    EXPECT_EQ(pool.indexOf(b), 1u);
    EXPECT_EQ(pool.remove(b), 1u);  // the last one: nothing moves
    EXPECT_EQ(pool.size(), 1u);
    EXPECT_EQ(pool.idAt(0), c);
}

TEST(HandlePool, FreedSlotsAreReusedLastInFirstOutWithTheirGenerationBumped) {
    Pool pool = makePool();
    const TestId a = pool.add(), b = pool.add();
    pool.add();
    pool.remove(a);
    pool.remove(b);
    EXPECT_EQ(pool.add(), (TestId{1, 2, 7}));  // b's slot, freed last
    EXPECT_EQ(pool.add(), (TestId{0, 2, 7}));
    EXPECT_EQ(pool.add(), (TestId{3, 1, 7}));  // no free slot left: a new one
    EXPECT_EQ(pool.slotCount(), 4u);
}

TEST(HandlePool, NullStaleUnknownAndForeignIdsAreRefusedByName) {
    Pool pool = makePool();
    const TestId old = pool.add();
    pool.remove(old);
    const TestId reused = pool.add();
    ASSERT_EQ(reused.index, old.index);
    EXPECT_FALSE(pool.isValid(old));
    EXPECT_TRUE(contains(refusal([&] { pool.indexOf(old); }),
                         "TestId {index 0, generation 1} does not name a live thing"));
    EXPECT_TRUE(contains(refusal([&] { pool.indexOf(TestId{}); }), "TestId is null"));
    EXPECT_TRUE(contains(refusal([&] { pool.indexOf(TestId{5, 1, 7}); }), "does not name"));
    // The same slot and generation from another world's pool.
    const TestId foreign{reused.index, reused.generation, 8};
    EXPECT_FALSE(pool.isValid(foreign));
    EXPECT_TRUE(contains(refusal([&] { pool.indexOf(foreign); }),
                         "TestId {index 0, generation 2} belongs to another world"));
    EXPECT_EQ(refusal([&] { pool.indexOf(reused); }), "");
}

// A reference model of the dense order: a list of slots where removal moves the last entry into
// the hole. Over a long random sequence of adds and removes the pool agrees with it at every
// step, and two pools fed the same sequence agree with each other bit for bit.
TEST(HandlePool, DenseOrderIsSwapWithLastOfTheCallSequence) {
    Pool pool = makePool();
    Pool twin = makePool(9);  // another world: the tag changes nothing but the ids' tag
    std::vector<std::uint32_t> model;
    std::uint64_t seed = 99;
    for (int step = 0; step < 2000; ++step) {
        seed = seed * 6364136223846793005ull + 1442695040888963407ull;
        const bool add = model.empty() || (seed >> 60) < 9;  // grows on average
        if (add) {
            const TestId id = pool.add();
            EXPECT_EQ(twin.add().index, id.index);
            model.push_back(id.index);
        } else {
            const std::uint32_t index = static_cast<std::uint32_t>((seed >> 20) % model.size());
            const TestId id = pool.idAt(index);
            EXPECT_EQ(pool.remove(id), index);
            twin.remove(twin.idAt(index));
            model[index] = model.back();
            model.pop_back();
        }
        ASSERT_EQ(pool.size(), model.size());
        for (std::uint32_t i = 0; i < model.size(); ++i) {
            ASSERT_EQ(pool.idAt(i).index, model[i]) << "step " << step;
            ASSERT_EQ(twin.idAt(i).index, model[i]);
            ASSERT_EQ(twin.idAt(i).generation, pool.idAt(i).generation);
        }
    }
}

TEST(HandlePool, MoveLastIntoKeepsParallelArraysInStep) {
    Pool pool = makePool();
    std::vector<int> numbers;
    std::vector<std::string> names;
    std::vector<TestId> ids;
    for (int i = 0; i < 4; ++i) {
        ids.push_back(pool.add());
        numbers.push_back(i);
        names.push_back(std::to_string(i));
    }
    moveLastInto(pool.remove(ids[1]), numbers, names);
    EXPECT_EQ(numbers, (std::vector<int>{0, 3, 2}));
    EXPECT_EQ(names, (std::vector<std::string>{"0", "3", "2"}));
    EXPECT_EQ(numbers[pool.indexOf(ids[3])], 3);
    moveLastInto(pool.remove(ids[2]), numbers, names);  // the last: only shrinks
    EXPECT_EQ(numbers, (std::vector<int>{0, 3}));
    EXPECT_EQ(names[pool.indexOf(ids[0])], "0");
}

}  // namespace
}  // namespace tumble
