// Ids carry their world: an id from one World is refused by another at every entry point (it
// used to name whatever lived in the same slot there), a destroyed world's ids do not come back
// to life in a new one, and the tag changes no result: two worlds built alike save alike.

#include <gtest/gtest.h>

#include <cstdint>
#include <vector>

#include "refusal.h"
#include "tumble/checkpoint.h"
#include "tumble/world.h"

namespace tumble {
namespace {

using test::contains;
using test::refusal;

// Two bodies joined by a hinge and a spring, the first with a sphere: every kind of id at slot 0,
// generation 1, whichever world builds it.
struct Pair {
    World world{WorldDef{.gravity = Vec3::Zero()}};
    BodyId a, b;
    ShapeId shape;
    JointId joint;
    SpringId spring;
    Pair() {
        a = world.createBody({});
        b = world.createBody(BodyDef{.position = Vec3(1, 0, 0)});
        shape = world.createShape(a, ShapeDef{.geometry = Sphere{0.2}});
        joint = world.createJoint(JointDef{.type = JointType::Hinge,
                                           .bodyA = a,
                                           .bodyB = b,
                                           .anchor = Vec3(0.5, 0, 0),
                                           .axis = Vec3::UnitZ()});
        spring = world.createSpring(SpringDef{.bodyA = a, .bodyB = b, .stiffness = 10});
    }
};

TEST(WorldIds, AnotherWorldsIdsAreRefusedAtEveryEntryPoint) {
    Pair mine, theirs;
    ASSERT_EQ(mine.a.index, theirs.a.index);
    ASSERT_EQ(mine.a.generation, theirs.a.generation);
    ASSERT_NE(mine.a.world, theirs.a.world);
    World& w = mine.world;
    EXPECT_FALSE(w.isValid(theirs.a));
    EXPECT_FALSE(w.isValid(theirs.shape));
    EXPECT_FALSE(w.isValid(theirs.joint));
    EXPECT_FALSE(w.isValid(theirs.spring));
    const char* foreign = "belongs to another world";
    EXPECT_TRUE(contains(refusal([&] { w.position(theirs.a); }),
                         "BodyId {index 0, generation 1} belongs to another world"));
    EXPECT_TRUE(contains(refusal([&] { w.applyForceToCenter(theirs.b, Vec3(1, 0, 0)); }), foreign));
    EXPECT_TRUE(contains(refusal([&] { w.destroyBody(theirs.a); }), foreign));
    EXPECT_TRUE(contains(refusal([&] { w.createShape(theirs.a, ShapeDef{}); }), foreign));
    EXPECT_TRUE(contains(refusal([&] { w.shapeBody(theirs.shape); }),
                         "ShapeId {index 0, generation 1} belongs to another world"));
    EXPECT_TRUE(contains(refusal([&] { w.destroyShape(theirs.shape); }), foreign));
    EXPECT_TRUE(contains(refusal([&] { w.jointState(theirs.joint); }),
                         "JointId {index 0, generation 1} belongs to another world"));
    EXPECT_TRUE(contains(refusal([&] { w.setJointMotor(theirs.joint, true, 1, 1); }), foreign));
    EXPECT_TRUE(contains(refusal([&] { w.springState(theirs.spring); }),
                         "SpringId {index 0, generation 1} belongs to another world"));
    EXPECT_TRUE(contains(refusal([&] { w.destroySpring(theirs.spring); }), foreign));
    // Definitions that name another world's body.
    EXPECT_TRUE(contains(
        refusal([&] { w.createSpring(SpringDef{.bodyA = mine.a, .bodyB = theirs.b}); }), foreign));
    EXPECT_TRUE(contains(
        refusal([&] { w.createJoint(JointDef{.bodyA = theirs.a, .bodyB = mine.b}); }), foreign));
    EXPECT_EQ(w.bodyCount(), 2);
    EXPECT_EQ(w.jointCount(), 1);
    EXPECT_EQ(w.springCount(), 1);
    EXPECT_TRUE(w.isValid(mine.shape));
}

TEST(WorldIds, IdsTheWorldHandsOutCarryItsTag) {
    Pair pair;
    ASSERT_TRUE(pair.world.step().ok());
    const std::uint32_t tag = pair.a.world;
    EXPECT_NE(tag, 0u);
    for (const BodyId b : pair.world.bodies())
        EXPECT_EQ(b.world, tag);
    EXPECT_EQ(pair.world.bodyShapes(pair.a).front().world, tag);
    EXPECT_EQ(pair.world.jointDef(pair.joint).bodyB.world, tag);
    EXPECT_EQ(BodyId{}.world, 0u) << "null stays all zero";
    EXPECT_TRUE(pair.world.springDef(pair.spring).bodyA == pair.a);
}

TEST(WorldIds, ADestroyedWorldsIdsDoNotNameBodiesOfANewOne) {
    BodyId old;
    {
        World gone;
        old = gone.createBody({});
    }
    World fresh;
    const BodyId body = fresh.createBody({});
    ASSERT_EQ(body.index, old.index);
    ASSERT_EQ(body.generation, old.generation);
    EXPECT_FALSE(fresh.isValid(old));
    EXPECT_TRUE(contains(refusal([&] { fresh.position(old); }), "belongs to another world"));
}

TEST(WorldIds, AMovedWorldKeepsItsIds) {
    World world;
    const BodyId body = world.createBody({});
    World moved = std::move(world);
    EXPECT_TRUE(moved.isValid(body));
}

// The tag is not state: two worlds built and stepped alike save the same bytes, and a world
// loading a checkpoint keeps its own tag, so its own ids work on the loaded state and the
// saving world's do not.
TEST(WorldIds, CheckpointsCarryNoTagAndALoadedWorldKeepsItsOwn) {
    Pair saved, other;
    for (int i = 0; i < 5; ++i) {
        ASSERT_TRUE(saved.world.step().ok());
        ASSERT_TRUE(other.world.step().ok());
    }
    const std::vector<std::uint8_t> bytes = checkpointBytes(saved.world);
    EXPECT_EQ(bytes, checkpointBytes(other.world));

    World loaded;
    const BodyId before = loaded.createBody({});  // slot 0, generation 1, as saved.a
    restoreCheckpoint(loaded, bytes);
    EXPECT_TRUE(loaded.isValid(before)) << "its own id, naming the loaded body in that slot";
    EXPECT_FALSE(loaded.isValid(saved.a));
    const std::vector<BodyId> bodies = loaded.bodies();
    ASSERT_EQ(bodies.size(), 2u);
    EXPECT_EQ(loaded.position(bodies[1]), saved.world.position(saved.b));
    EXPECT_EQ(loaded.jointDef(loaded.bodyJoints(bodies[0]).front()).bodyB, bodies[1]);
    EXPECT_EQ(checkpointBytes(loaded), bytes);

    restoreCheckpoint(saved.world, bytes);  // back to where it was: the ids it gave still work
    EXPECT_TRUE(saved.world.isValid(saved.joint));
    EXPECT_EQ(saved.world.shapeBody(saved.shape), saved.a);
}

}  // namespace
}  // namespace tumble
