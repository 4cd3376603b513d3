// Box2D 2.4 (Debian's libbox2d-dev, single precision) behind the harness interface, for the
// planar scenes only (stack, pyramid): the scene's x-z plane is Box2D's x-y plane, a unit cube
// is a 1 m square of the same mass (density = mass / 1 m^2), the ground is an edge along y = 0.
// Matched settings: h, velocity iterations = the requested iterations, and as many position
// iterations (Box2D's non-linear Gauss-Seidel position pass plays the part of Tumble's
// split-impulse sweeps, which run as many times); friction mu on each fixture (Box2D mixes
// sqrt(muA muB)), restitution 0, sleeping off. Box2D's linear slop is 5 mm, as Tumble's; its
// polygons carry a 1 cm skin (b2_polygonRadius), so a column stands 1 cm taller per cube.

#include <box2d/box2d.h>

#include <algorithm>

#include "peer.h"

namespace tumble::bench {
namespace {

class Box2dWorld final : public PeerWorld {
public:
    explicit Box2dWorld(const SceneSettings& s)
        : world_(b2Vec2(static_cast<float>(s.gravity.x()), static_cast<float>(s.gravity.z()))),
          h_(static_cast<float>(s.timeStep)),
          iterations_(s.iterations),
          friction_(static_cast<float>(s.friction)),
          density_(static_cast<float>(s.boxMass)) {
        world_.SetAllowSleeping(false);
    }
    void addGround() override {
        b2BodyDef def;
        b2Body* ground = world_.CreateBody(&def);
        b2EdgeShape edge;
        edge.SetTwoSided(b2Vec2(-1000, 0), b2Vec2(1000, 0));
        b2FixtureDef fixture;
        fixture.shape = &edge;
        fixture.friction = friction_;
        fixture.restitution = 0;
        ground->CreateFixture(&fixture);
    }
    int addCube(const Vec3& position) override {
        b2BodyDef def;
        def.type = b2_dynamicBody;
        def.position.Set(static_cast<float>(position.x()), static_cast<float>(position.z()));
        b2Body* body = world_.CreateBody(&def);
        b2PolygonShape square;
        square.SetAsBox(0.5f, 0.5f);
        b2FixtureDef fixture;
        fixture.shape = &square;
        fixture.density = density_;
        fixture.friction = friction_;
        fixture.restitution = 0;
        body->CreateFixture(&fixture);
        bodies_.push_back(body);
        return static_cast<int>(bodies_.size()) - 1;
    }
    bool planar() const override { return true; }
    void step() override { world_.Step(h_, iterations_, iterations_); }
    Vec3 position(int body) const override {
        const b2Vec2 p = bodies_[body]->GetPosition();
        return Vec3(p.x, 0, p.y);
    }
    Vec3 velocity(int body) const override {
        const b2Vec2 v = bodies_[body]->GetLinearVelocity();
        return Vec3(v.x, 0, v.y);
    }
    Real deepestPenetration() const override {
        Real deepest = 0;
        // GetContactList is not const in Box2D 2.4.
        for (b2Contact* c = const_cast<b2World&>(world_).GetContactList(); c != nullptr;
             c = c->GetNext()) {
            if (!c->IsTouching())
                continue;
            b2WorldManifold manifold;
            c->GetWorldManifold(&manifold);
            for (int i = 0; i < c->GetManifold()->pointCount; ++i)
                deepest = std::max<Real>(deepest, -manifold.separations[i]);
        }
        return deepest;
    }

private:
    b2World world_;
    float h_;
    int iterations_;
    float friction_;
    float density_;
    std::vector<b2Body*> bodies_;
};

}  // namespace

std::unique_ptr<PeerWorld> createBox2d(const SceneSettings& settings) {
    return std::make_unique<Box2dWorld>(settings);
}

}  // namespace tumble::bench
