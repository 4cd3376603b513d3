// describeWorld reports every shape at its world pose and the touching contacts.

#include "tumble/debug_draw.h"

#include <gtest/gtest.h>

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
