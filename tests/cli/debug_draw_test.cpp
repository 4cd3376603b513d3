// describeWorld reports every shape at its world pose and the touching contacts.

#include "tumble/debug_draw.h"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "tumble/tumble.h"

namespace {

using namespace tumble;

struct Recorder : DebugDraw {
    int bodies = 0, boxes = 0, spheres = 0, planes = 0, contacts = 0, aabbs = 0;
    Vec3 boxCentre = Vec3::Zero(), sphereCentre = Vec3::Zero(), planeNormal = Vec3::Zero();
    Real planeOffset = 0, sphereRadius = 0;

    void beginBody(BodyId, BodyType, bool) override { ++bodies; }
    void drawBox(const Transform& pose, const Vec3&) override {
        ++boxes;
        boxCentre = pose.position;
    }
    void drawSphere(const Transform& pose, Real radius) override {
        ++spheres;
        sphereCentre = pose.position;
        sphereRadius = radius;
    }
    void drawPlane(const Vec3& normal, Real offset) override {
        ++planes;
        planeNormal = normal;
        planeOffset = offset;
    }
    void drawContact(const Vec3&, const Vec3&, Real separation) override {
        ++contacts;
        EXPECT_LE(separation, 0);
    }
    void drawAabb(const Aabb&) override { ++aabbs; }
};

}  // namespace

TEST(DebugDraw, DescribesShapesAtTheirWorldPosesAndTheContacts) {
    World world;
    const BodyId ground =
        world.createBody(BodyDef{.type = BodyType::Static, .position = Vec3(0, 0, 0.5)});
    std::vector<ShapeId> shapes;
    shapes.push_back(world.createShape(ground, ShapeDef{.geometry = HalfSpace{}}));
    const BodyId body = world.createBody(BodyDef{.position = Vec3(1, 2, 1.0)});
    shapes.push_back(world.createShape(body, ShapeDef{.geometry = Box{Vec3::Constant(0.25)}}));
    shapes.push_back(world.createShape(
        body, ShapeDef{.geometry = Sphere{0.1}, .localPose = {Vec3(0, 0, 0.4), Quat::Identity()}}));
    for (int i = 0; i < 60; ++i)
        world.step();  // settle the box on the raised ground

    Recorder r;
    describeWorld(world, shapes, r, kDrawAll);
    EXPECT_EQ(r.bodies, 2);
    EXPECT_EQ(r.boxes, 1);
    EXPECT_EQ(r.spheres, 1);
    EXPECT_EQ(r.planes, 1);
    EXPECT_EQ(r.aabbs, 2);  // the half-space has no finite box
    // The ground body sits at z = 0.5, so its plane z <= 0 in the body frame is z <= 0.5.
    EXPECT_NEAR(r.planeOffset, 0.5, 1e-12);
    EXPECT_NEAR((r.planeNormal - Vec3::UnitZ()).norm(), 0, 1e-12);
    // The box rests on the plane: its centre a half extent above it (within the slop), the
    // sphere 0.4 m above the box's centre.
    EXPECT_NEAR(r.boxCentre.z(), 0.75, 0.01);
    EXPECT_NEAR((r.sphereCentre - r.boxCentre - Vec3(0, 0, 0.4)).norm(), 0, 1e-9);
    EXPECT_EQ(r.sphereRadius, 0.1);
    EXPECT_GE(r.contacts, 3);  // a face on a plane: the box's four corners (or at least three)
}

namespace {

struct LinkRecorder : DebugDraw {
    std::vector<std::pair<Vec3, Vec3>> springs, joints;
    std::vector<Real> tensions;
    std::vector<JointType> types;
    Vec3 axis = Vec3::Zero();

    void drawSpring(const Vec3& a, const Vec3& b, Real tension, bool) override {
        springs.emplace_back(a, b);
        tensions.push_back(tension);
    }
    void drawJoint(JointType type, const Vec3& a, const Vec3& b, const Vec3& jointAxis,
                   bool) override {
        joints.emplace_back(a, b);
        types.push_back(type);
        axis = jointAxis;
    }
};

}  // namespace

TEST(DebugDraw, DescribesSpringsAndJointsAtTheCurrentPoses) {
    World world(WorldDef{.gravity = Vec3(0, 0, -10), .timeStep = 1.0 / 240});
    // A 1 kg weight hanging from the world point (0, 0, 2) on a spring of k = 1000 N/m, L0 = 1 m.
    const BodyId weight = world.createBody(BodyDef{.position = Vec3(0, 0, 1)});
    world.createShape(weight, ShapeDef{.geometry = Sphere{0.05}, .updateBodyMass = false});
    SpringDef springDef;
    springDef.bodyA = weight;
    springDef.localAnchorB = Vec3(0, 0, 2);
    springDef.restLength = 1;
    springDef.stiffness = 1000;
    springDef.damping = 40;
    const SpringId spring = world.createSpring(springDef);
    // A door on a hinge about z at (1, 0, 0), pushed round.
    const BodyId door = world.createBody(
        BodyDef{.position = Vec3(1.5, 0, 0), .angularVelocity = Vec3(0, 0, 1), .gravityScale = 0});
    JointDef hingeDef;
    hingeDef.type = JointType::Hinge;
    hingeDef.bodyA = door;
    hingeDef.anchor = Vec3(1, 0, 0);
    hingeDef.axis = Vec3(0, 0, 2);
    const JointId hinge = world.createJoint(hingeDef);
    for (int i = 0; i < 480; ++i)
        world.step();

    LinkRecorder r;
    const SpringId springs[] = {spring, SpringId{}};  // a null id is skipped
    const JointId joints[] = {hinge};
    describeSprings(world, springs, r);
    describeJoints(world, joints, r);
    ASSERT_EQ(r.springs.size(), 1u);
    // The spring's ends: on the weight's centre, and the world point.
    EXPECT_NEAR((r.springs[0].first - world.position(weight)).norm(), 0, 1e-12);
    EXPECT_NEAR((r.springs[0].second - Vec3(0, 0, 2)).norm(), 0, 1e-12);
    // Settled (zeta = 0.63, 2 s) at m g / k = 1 cm of stretch, carrying the weight: 10 N.
    EXPECT_NEAR(r.springs[0].first.z(), 1 - 0.01, 1e-4);
    EXPECT_NEAR(r.tensions[0], 10, 0.01);
    ASSERT_EQ(r.joints.size(), 1u);
    EXPECT_EQ(r.types[0], JointType::Hinge);
    // The hinge holds: both anchors at (1, 0, 0) while the door has turned; the axis is unit z.
    EXPECT_NEAR((r.joints[0].first - Vec3(1, 0, 0)).norm(), 0, 1e-3);
    EXPECT_NEAR((r.joints[0].second - Vec3(1, 0, 0)).norm(), 0, 1e-3);
    EXPECT_NEAR((r.axis - Vec3::UnitZ()).norm(), 0, 1e-9);
    EXPECT_GT(std::abs(world.jointState(hinge).position), 0.5);
}
