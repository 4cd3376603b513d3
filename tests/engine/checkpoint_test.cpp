// Checkpoint and resume: a world restored from a checkpoint continues bitwise-identically to the
// world that was saved (a pile with sleeping bodies and active contacts, joints with motors,
// limits and a controller, a net of threads catching a ball), and a truncated, corrupted,
// wrong-version or missing file is refused, naming the file and the fault, with the world left
// as it was.

#include <gtest/gtest.h>

#include <bit>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <functional>
#include <string>
#include <vector>

#include <unistd.h>

#include "checkpoint_io.h"
#include "engine/checkpoint_resume.h"
#include "refusal.h"
#include "testkit/same_ids.h"
#include "testkit/scenes.h"
#include "tumble/checkpoint.h"
#include "tumble/lumped.h"
#include "tumble/world.h"

namespace tumble {
namespace {

using test::addBody;
using test::contains;
using test::expectBitwiseResume;
using test::readU64;
using test::refusal;
using test::Scene;
using test::writeU64;

// A pile that falls asleep, next to a pyramid that a ball falls onto after the checkpoint; the
// shapes cover every geometry type, and one body has drag.
Scene pileScene(const WorldDef& def = {}) {
    Scene s;
    s.world = World(def);
    const BodyId ground = addBody(s, Vec3::Zero(), BodyType::Static);
    s.world.createShape(ground, ShapeDef{.geometry = HalfSpace{}});
    // Left: a stack of mixed shapes that settles and sleeps.
    const std::vector<Shape> shapes = {
        Box{Vec3(0.5, 0.5, 0.25)}, Cylinder{0.4, 0.25}, Box{Vec3(0.4, 0.3, 0.25)},
        ConvexHull::fromPoints(std::vector<Vec3>{Vec3(-0.4, -0.4, -0.25), Vec3(0.4, -0.4, -0.25),
                                                 Vec3(0.4, 0.4, -0.25), Vec3(-0.4, 0.4, -0.25),
                                                 Vec3(-0.3, -0.3, 0.25), Vec3(0.3, -0.3, 0.25),
                                                 Vec3(0.3, 0.3, 0.25), Vec3(-0.3, 0.3, 0.25)})};
    for (std::size_t i = 0; i < shapes.size(); ++i) {
        const BodyId b = addBody(s, Vec3(-4, 0, 0.26 + 0.52 * static_cast<Real>(i)));
        s.world.createShape(b, ShapeDef{.geometry = shapes[i]});
    }
    // Right: a pyramid of boxes, and a capsule and a sphere dropped on it.
    constexpr int kBase = 5;
    for (int row = 0; row < kBase; ++row) {
        for (int i = 0; i < kBase - row; ++i) {
            const Real x = 1.02 * (i - 0.5 * (kBase - row - 1));
            const BodyId b = addBody(s, Vec3(x, 0, 0.5 + 1.0 * row));
            s.world.createShape(
                b, ShapeDef{.geometry = Box{Vec3::Constant(0.5)}, .material = {.friction = 0.6}});
        }
    }
    const BodyId capsule = addBody(s, Vec3(0.3, 0.1, 12));
    s.world.createShape(capsule, ShapeDef{.geometry = Capsule{0.3, 0.4}});
    s.world.setAngularVelocity(capsule, Vec3(0.5, 1, 0));
    const BodyId ball = addBody(s, Vec3(-0.6, 0, 16));
    s.world.createShape(
        ball, ShapeDef{.geometry = Sphere{0.4}, .material = {.restitution = 0.5, .density = 4000}});
    s.world.setDrag(ball, Drag{.linear = 0.1, .quadratic = 0.05});
    // Far right: a box that lands at 1.4 s and falls asleep after the checkpoint (1.67 s), so
    // the sleep timers it carries decide the step it stops on.
    const BodyId late = addBody(s, Vec3(8, 0, 10));
    s.world.createShape(late, ShapeDef{.geometry = Box{Vec3::Constant(0.25)}});
    return s;
}

// A hinge chain (motor, limit, breakable), a slider under a PD controller, a rope, a fixed
// joint and a ball joint between two bodies that collide with the ground.
Scene jointScene(const SolverSettings& solver = {}, int substeps = 1) {
    Scene s;
    WorldDef def;
    def.enableSleep = false;
    def.solver = solver;
    def.substeps = substeps;
    s.world = World(def);
    const BodyId ground = addBody(s, Vec3::Zero(), BodyType::Static);
    s.world.createShape(ground, ShapeDef{.geometry = HalfSpace{}});
    BodyId previous{};
    for (int i = 0; i < 4; ++i) {
        const BodyId link = addBody(s, Vec3(0.5 + 1.0 * i, 0, 3));
        s.world.createShape(link, ShapeDef{.geometry = Box{Vec3(0.5, 0.1, 0.1)}});
        JointDef j{.type = JointType::Hinge,
                   .bodyA = link,
                   .bodyB = previous,
                   .anchor = Vec3(1.0 * i, 0, 3),
                   .axis = Vec3::UnitY()};
        if (i == 0) {
            j.enableMotor = true;
            j.motorSpeed = 1.5;
            j.maxMotorForce = 40;
        } else {
            j.enableLimit = true;
            j.lower = -0.6;
            j.upper = 0.8;
        }
        if (i == 3)
            j.breakForce = 25;
        s.world.createJoint(j);
        previous = link;
    }
    const BodyId cart = addBody(s, Vec3(-3, 0, 1));
    s.world.createShape(cart, ShapeDef{.geometry = Box{Vec3(0.3, 0.3, 0.3)}});
    const JointId slider = s.world.createJoint(JointDef{.type = JointType::Slider,
                                                        .bodyA = cart,
                                                        .bodyB = {},
                                                        .anchor = Vec3(-3, 0, 1),
                                                        .axis = Vec3::UnitX(),
                                                        .enableLimit = true,
                                                        .lower = -1,
                                                        .upper = 1});
    s.world.setJointController(slider, ControllerDef{.target = 0.7, .kp = 200, .ki = 20, .kd = 5});
    const BodyId weight = addBody(s, Vec3(-3, 0, 0.6));
    s.world.createShape(weight, ShapeDef{.geometry = Sphere{0.2}});
    s.world.createJoint(JointDef{.type = JointType::Distance,
                                 .bodyA = weight,
                                 .bodyB = cart,
                                 .anchor = Vec3(-3, 0, 0.6),
                                 .anchorB = Vec3(-3, 0, 1),
                                 .rope = true});
    const BodyId a = addBody(s, Vec3(3, 2, 0.8));
    const BodyId b = addBody(s, Vec3(3.6, 2, 0.8));
    s.world.createShape(a, ShapeDef{.geometry = Sphere{0.3}});
    s.world.createShape(b, ShapeDef{.geometry = Box{Vec3::Constant(0.25)}});
    s.world.createJoint(
        JointDef{.type = JointType::Fixed, .bodyA = a, .bodyB = b, .anchor = Vec3(3.3, 2, 0.8)});
    const BodyId c = addBody(s, Vec3(3.3, 2, 2));
    s.world.createShape(c, ShapeDef{.geometry = Sphere{0.2}});
    s.world.createJoint(JointDef{.type = JointType::Ball,
                                 .bodyA = c,
                                 .bodyB = b,
                                 .anchor = Vec3(3.3, 2, 1.6),
                                 .collideConnected = true});
    s.world.setAngularVelocity(c, Vec3(2, 0, 1));
    return s;
}

// A net of tension-only threads with colliding nodes catching a ball, plus an explicit spring.
Scene netScene() {
    Scene s;
    const BodyId ground = addBody(s, Vec3::Zero(), BodyType::Static);
    s.world.createShape(ground, ShapeDef{.geometry = HalfSpace{}});
    // The soak's net, lighter and finer, thrown down.
    NetDef net = testkit::captureNet(12, 0.1, Vec3(0, 0, 1.5));
    net.node.mass = 0.01;
    net.node.radius = 0.01;
    net.cornerMass = 0.2;
    net.thread.damping = 0.05;
    net.velocity = Vec3(0, 0, -1);
    net.spreadSpeed = 1;
    const Lumped lumped = createNet(s.world, net);
    s.bodies.insert(s.bodies.end(), lumped.nodes.begin(), lumped.nodes.end());
    s.springs = lumped.threads;
    const BodyId ball = addBody(s, Vec3(0.05, -0.03, 1.9));
    s.world.createShape(ball, ShapeDef{.geometry = Sphere{0.15}, .material = {.density = 300}});
    s.world.setLinearVelocity(ball, Vec3(0, 0, -2));
    const BodyId bob = addBody(s, Vec3(2, 0, 2));
    s.world.createShape(bob, ShapeDef{.geometry = Sphere{0.1}});
    s.world.createSpring(SpringDef{.bodyA = bob,
                                   .bodyB = {},
                                   .localAnchorB = Vec3(2, 0, 3),
                                   .restLength = 0.8,
                                   .stiffness = 50,
                                   .damping = 0.5,
                                   .formulation = SpringFormulation::Explicit});
    return s;
}

int sleepingCount(const World& world, const std::vector<BodyId>& bodies) {
    int n = 0;
    for (const BodyId b : bodies)
        n += world.bodyType(b) == BodyType::Dynamic && !world.isAwake(b);
    return n;
}

int touchingAwakeContacts(const World& world) {
    int n = 0;
    for (const Contact& c : world.contacts())
        n += c.manifold.pointCount > 0 && (world.isAwake(c.bodyA) || world.isAwake(c.bodyB));
    return n;
}

TEST(Checkpoint, PileWithSleepingBodiesAndActiveContactsResumesBitwise) {
    Scene s = pileScene();
    // The left stack is asleep, the pyramid still settling.
    ASSERT_TRUE(testkit::simulate(s.world, 100));
    EXPECT_GE(sleepingCount(s.world, s.bodies), 4);
    EXPECT_GE(touchingAwakeContacts(s.world), 5);
    const BodyId late = s.bodies.back();
    ASSERT_TRUE(s.world.isAwake(late));
    expectBitwiseResume(s, 0, 150);  // the capsule and the ball land on the pyramid
    EXPECT_FALSE(s.world.isAwake(late));
    EXPECT_LT(s.world.position(s.bodies[s.bodies.size() - 2]).z(), 8);  // the ball came down
}

// Destroyed bodies and shapes leave free id slots, dead contacts and broadphase removals that
// the next step completes; a checkpoint taken right after the destruction carries them.
TEST(Checkpoint, PendingRemovalsAndFreeSlotsResumeBitwise) {
    Scene s = pileScene();
    ASSERT_TRUE(testkit::simulate(s.world, 60));
    const std::size_t top = 4 + 1 + 15;  // ground, the left stack, the pyramid's last box
    const BodyId removed = s.bodies[top];
    s.world.destroyBody(removed);
    s.bodies.erase(s.bodies.begin() + static_cast<long>(top));
    s.world.destroyShape(s.world.bodyShapes(s.bodies[0]).front());  // the ground: the pile falls
    const BodyId extra = addBody(s, Vec3(3, 3, 1));  // takes the freed slot, generation 2
    s.world.createShape(extra, ShapeDef{.geometry = Sphere{0.3}});
    EXPECT_EQ(extra.index, removed.index);
    EXPECT_EQ(extra.generation, removed.generation + 1);
    expectBitwiseResume(s, 0, 60);
}

TEST(Checkpoint, JointsWithMotorLimitsControllerAndBreakingResumeBitwise) {
    Scene s = jointScene();
    expectBitwiseResume(s, 45, 200);
    int broken = 0;
    for (const BodyId body : s.world.bodies()) {
        for (const JointId joint : s.world.bodyJoints(body))  // each once, at its body A
            broken += s.world.jointDef(joint).bodyA == body && s.world.jointState(joint).broken;
    }
    EXPECT_EQ(broken, 1);  // the last link's hinge broke after the checkpoint
}

// Friction anchors live in a side table of the solve stage: saved with the contacts, so a
// resumed pile holds its contacts where the original does.
TEST(Checkpoint, PileWithFrictionAnchorsResumesBitwise) {
    WorldDef def;
    def.solver.frictionAnchors = true;
    Scene pile = pileScene(def);
    expectBitwiseResume(pile, 40, 120);
}

// Substeps: the rollback and interpolation state is the step's start, the controllers' state
// is saved once per step; a resumed world must take the substep count from the checkpoint.
TEST(Checkpoint, PileAndJointsWithTwoSubstepsResumeBitwise) {
    // The default step's substeps (the soft step takes only one count, softSubsteps).
    Scene pile = pileScene(WorldDef{.substeps = 2, .solver = SolverSettings{.softSubsteps = 0}});
    ASSERT_TRUE(testkit::simulate(pile.world, 100));
    EXPECT_GE(sleepingCount(pile.world, pile.bodies), 4);
    expectBitwiseResume(pile, 0, 150);
    Scene joints = jointScene(SolverSettings{.softSubsteps = 0}, 2);
    expectBitwiseResume(joints, 45, 200);
}

// The joints' solver choices change every step's numbers: a resumed world that fell back to
// the defaults would diverge at once.
TEST(Checkpoint, JointsUnderNonDefaultSolverSettingsResumeBitwise) {
    SolverSettings solver;
    solver.jointSolve = SpringSolve::Iterative;
    solver.jointGeometricStiffness = false;
    Scene s = jointScene(solver);
    expectBitwiseResume(s, 45, 100);
}

// Every setting differs from its default and from the resuming world's; each must come back.
TEST(Checkpoint, EverySettingRoundTrips) {
    WorldDef def;
    def.gravity = Vec3(0.5, -1, -3);
    def.timeStep = 1.0 / 90;
    def.maxStepsPerAdvance = 3;
    def.substeps = 3;
    def.contactMargin = 0.03;
    def.aabbMargin = 0.07;
    def.enableSleep = false;
    def.linearSleepVelocity = 0.02;
    def.angularSleepVelocity = 0.03;
    def.timeToSleep = 0.9;
    def.impactSpeedThreshold = 0.7;
    SolverSettings& v = def.solver;
    v.iterations = 7;
    v.relaxIterations = 5;
    v.linkIterations = 12;
    v.linkRelaxIterations = 3;
    v.tolerance = 1e-6;
    v.relaxation = 1.2;
    v.friction = FrictionModel::Box;
    v.stabilisation = Stabilisation::Baumgarte;
    v.baumgarte = 0.3;
    v.splitImpulseFactor = 0.4;
    v.slop = 0.002;
    v.restitutionThreshold = 0.6;
    v.warmStart = false;
    v.springSolve = SpringSolve::Iterative;
    v.projectSprings = false;
    v.jointGeometricStiffness = false;
    v.jointSolve = SpringSolve::Iterative;
    v.frictionAnchors = false;
    v.colouredContacts = false;
    // The soft step's count, which a world takes with substeps = 1 only (checked below apart).
    v.softSubsteps = 4;
    v.contactHertz = 60;
    v.contactDampingRatio = 4;
    v.maxPushOutSpeed = 1.5;
    def.substeps = 1;
    const World original(def);
    World resumed;
    restoreCheckpoint(resumed, checkpointBytes(original));
    const WorldDef& r = resumed.settings();
    EXPECT_EQ(r.gravity, def.gravity);
    EXPECT_EQ(r.timeStep, def.timeStep);
    EXPECT_EQ(r.maxStepsPerAdvance, def.maxStepsPerAdvance);
    {
        const World substepped(
            WorldDef{.substeps = 3, .solver = SolverSettings{.softSubsteps = 0}});
        World back;
        restoreCheckpoint(back, checkpointBytes(substepped));
        EXPECT_EQ(back.settings().substeps, 3);
    }
    EXPECT_EQ(r.contactMargin, def.contactMargin);
    EXPECT_EQ(r.aabbMargin, def.aabbMargin);
    EXPECT_EQ(r.enableSleep, def.enableSleep);
    EXPECT_EQ(r.linearSleepVelocity, def.linearSleepVelocity);
    EXPECT_EQ(r.angularSleepVelocity, def.angularSleepVelocity);
    EXPECT_EQ(r.timeToSleep, def.timeToSleep);
    EXPECT_EQ(r.impactSpeedThreshold, def.impactSpeedThreshold);
    const SolverSettings& w = r.solver;
    EXPECT_EQ(w.iterations, v.iterations);
    EXPECT_EQ(w.relaxIterations, v.relaxIterations);
    EXPECT_EQ(w.linkIterations, v.linkIterations);
    EXPECT_EQ(w.linkRelaxIterations, v.linkRelaxIterations);
    EXPECT_EQ(w.tolerance, v.tolerance);
    EXPECT_EQ(w.relaxation, v.relaxation);
    EXPECT_EQ(w.friction, v.friction);
    EXPECT_EQ(w.stabilisation, v.stabilisation);
    EXPECT_EQ(w.baumgarte, v.baumgarte);
    EXPECT_EQ(w.splitImpulseFactor, v.splitImpulseFactor);
    EXPECT_EQ(w.slop, v.slop);
    EXPECT_EQ(w.restitutionThreshold, v.restitutionThreshold);
    EXPECT_EQ(w.warmStart, v.warmStart);
    EXPECT_EQ(w.springSolve, v.springSolve);
    EXPECT_EQ(w.projectSprings, v.projectSprings);
    EXPECT_EQ(w.jointGeometricStiffness, v.jointGeometricStiffness);
    EXPECT_EQ(w.jointSolve, v.jointSolve);
    EXPECT_EQ(w.frictionAnchors, v.frictionAnchors);
    EXPECT_EQ(w.colouredContacts, v.colouredContacts);
    EXPECT_EQ(w.softSubsteps, v.softSubsteps);
    EXPECT_EQ(w.contactHertz, v.contactHertz);
    EXPECT_EQ(w.contactDampingRatio, v.contactDampingRatio);
    EXPECT_EQ(w.maxPushOutSpeed, v.maxPushOutSpeed);
}

// The soft step's settings change every step's numbers (a resumed world that fell back to the
// sweeps would diverge at once), and its impulses are the step's sums in the contact cache.
TEST(Checkpoint, PileUnderTheSoftStepResumesBitwise) {
    WorldDef def;
    def.solver.softSubsteps = 4;
    def.solver.contactHertz = 45;
    def.solver.contactDampingRatio = 5;
    def.solver.maxPushOutSpeed = 2;
    Scene pile = pileScene(def);
    expectBitwiseResume(pile, 40, 120);
}

TEST(Checkpoint, NetCatchingABallResumesBitwise) {
    Scene s = netScene();
    ASSERT_TRUE(testkit::simulate(s.world, 12));  // the ball reaches the net during the resumed run
    expectBitwiseResume(s, 0, 90);
    // The threads' active set changed during the resumed run: some went slack, some taut.
    int slack = 0;
    for (const SpringId thread : s.springs)
        slack += s.world.springState(thread).slack;
    EXPECT_GT(slack, 0);
    EXPECT_LT(slack, static_cast<int>(s.springs.size()));
}

TEST(Checkpoint, FileRoundTripReplacesTheTemporary) {
    Scene s = pileScene();
    ASSERT_TRUE(testkit::simulate(s.world, 30));
    const std::filesystem::path file =
        std::filesystem::temp_directory_path() /
        ("tumble_checkpoint_test_" + std::to_string(::getpid()) + ".ckpt");
    std::filesystem::path tmp = file;
    tmp += ".tmp";
    saveCheckpoint(s.world, file);
    EXPECT_TRUE(std::filesystem::exists(file));
    EXPECT_FALSE(std::filesystem::exists(tmp));
    ASSERT_TRUE(testkit::simulate(s.world, 10));
    saveCheckpoint(s.world, file);  // over the previous one
    World loaded;
    loadCheckpoint(loaded, file);
    EXPECT_EQ(loaded.stepCount(), 40u);
    EXPECT_EQ(checkpointBytes(loaded), checkpointBytes(s.world));
    std::filesystem::remove(file);
}

// --- refusals ------------------------------------------------------------------------------

class CheckpointRefusal : public test::CheckpointRefusalBase {
protected:
    void SetUp() override { prepare(netScene(), 5, jointScene(), 3); }
    std::string refuse(const std::vector<std::uint8_t>& bytes) {
        return CheckpointRefusalBase::refuse(bytes, "run.ckpt");
    }
};

TEST_F(CheckpointRefusal, Truncated) {
    for (const std::size_t size :
         {std::size_t{0}, std::size_t{20}, good.size() / 2, good.size() - 1}) {
        std::vector<std::uint8_t> cut(good.begin(), good.begin() + static_cast<long>(size));
        EXPECT_TRUE(contains(refuse(cut), "truncated")) << size;
    }
}

TEST_F(CheckpointRefusal, BitFlipAnywhereInThePayload) {
    for (const std::size_t at : {std::size_t{40}, good.size() / 3, good.size() - 1}) {
        std::vector<std::uint8_t> flipped = good;
        flipped[at] ^= 0x10;
        EXPECT_TRUE(contains(refuse(flipped), "checksum")) << at;
    }
}

TEST_F(CheckpointRefusal, WrongVersionAndMagic) {
    std::vector<std::uint8_t> version = good;
    version[8] = static_cast<std::uint8_t>(kCheckpointVersion + 1);
    const std::string expected = "version " + std::to_string(kCheckpointVersion + 1) +
                                 ", this build reads version " + std::to_string(kCheckpointVersion);
    EXPECT_TRUE(contains(refuse(version), expected)) << refuse(version);
    std::vector<std::uint8_t> magic = good;
    magic[0] = 'X';
    EXPECT_TRUE(contains(refuse(magic), "not a Tumble checkpoint"));
}

// A payload cut short with a header that agrees (length and checksum recomputed): the reader
// itself must notice, without reading past the end.
TEST_F(CheckpointRefusal, ConsistentHeaderOverABadPayload) {
    std::vector<std::uint8_t> cut(good.begin(), good.begin() + static_cast<long>(good.size() / 2));
    writeU64(cut, 16, cut.size() - 32);
    writeU64(cut, 24, checkpoint_io::fnv1a(std::span<const std::uint8_t>(cut).subspan(32)));
    EXPECT_TRUE(contains(refuse(cut), "corrupt payload"));
    EXPECT_EQ(readU64(good, 16), good.size() - 32);
}

// Payload bytes changed behind a recomputed checksum (what the checksum cannot catch): the
// load either refuses with the file's name or succeeds, and never reads out of bounds.
TEST_F(CheckpointRefusal, CraftedPayloadsAreRefusedOrLoadedNeverCrash) {
    std::uint64_t seed = 12345;
    int refused = 0;
    constexpr int kTrials = 400;
    for (int trial = 0; trial < kTrials; ++trial) {
        std::vector<std::uint8_t> crafted = good;
        for (int flips = 0; flips < 3; ++flips) {
            seed = seed * 6364136223846793005ull + 1442695040888963407ull;
            const std::size_t at = 32 + (seed >> 33) % (crafted.size() - 32);
            crafted[at] ^= static_cast<std::uint8_t>(1u << ((seed >> 20) % 8));
        }
        writeU64(crafted, 24,
                 checkpoint_io::fnv1a(std::span<const std::uint8_t>(crafted).subspan(32)));
        World world;
        const std::string message =
            refusal([&] { restoreCheckpoint(world, crafted, "crafted.ckpt"); });
        if (!message.empty()) {
            ++refused;
            EXPECT_TRUE(contains(message, "checkpoint crafted.ckpt: corrupt payload at byte"));
        }
    }
    EXPECT_GT(refused, 0);
}

TEST(Checkpoint, MissingOrUnwritableFileIsRefused) {
    World world;
    const std::filesystem::path missing = "/nonexistent-dir/none.ckpt";
    EXPECT_TRUE(contains(refusal([&] { loadCheckpoint(world, missing); }), missing.string()));
    EXPECT_TRUE(contains(refusal([&] { saveCheckpoint(world, missing); }), "cannot open"));
}

}  // namespace
}  // namespace tumble
