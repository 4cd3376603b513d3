// ODE 0.16 (Debian's libode-dev, double precision) behind the harness interface: dWorldQuickStep
// (projected Gauss-Seidel, "SOR-LCP") with the requested iterations, fixed steps of h, no
// auto-disable (sleeping). Matched settings:
// - ERP 0.2 = Tumble's split-impulse factor (the fraction of the depth beyond the slop removed
//   per step); contact surface layer 5 mm = Tumble's slop (the depth left alone);
// - CFM 1e-5, ODE's double-precision default: nearly rigid constraints, as Tumble's;
// - contacts: dContactApprox1 (the friction pyramid scaled by the normal force) with mu, at most
//   4 points per pair (Bullet's and Tumble's manifold size); bounce 0 in the scenes, else the
//   requested restitution (dContactBounce) above Bullet's 0.2 m/s threshold;
// - QuickStep's random constraint order, seeded afresh for every world (deterministic runs).
// Nets: ODE's joints have no tension-only spring, so a net is point masses (bodies without
// geoms) pulled by the harness's thread forces, applied before each step.

#include <ode/ode.h>

#include <algorithm>
#include <array>

#include "peer.h"

namespace tumble::bench {
namespace {

constexpr int kMaxContacts = 4;

// dInitODE2 once per process, before the first world.
void initOde() {
    static const bool done = [] {
        dInitODE2(0);
        return true;
    }();
    (void)done;
}

class OdeWorld final : public PeerWorld {
public:
    explicit OdeWorld(const SceneSettings& s)
        : h_(s.timeStep), friction_(s.friction), restitution_(s.restitution), cubeMass_(s.boxMass) {
        initOde();
        // QuickStep shuffles its constraints with ODE's global generator: reseeding it makes each
        // world's run the same whatever ran before it in the process (every run is then equal).
        dRandSetSeed(0);
        world_ = dWorldCreate();
        space_ = dHashSpaceCreate(nullptr);
        contacts_ = dJointGroupCreate(0);
        dWorldSetGravity(world_, s.gravity.x(), s.gravity.y(), s.gravity.z());
        dWorldSetQuickStepNumIterations(world_, s.iterations);
        dWorldSetERP(world_, 0.2);
        dWorldSetCFM(world_, 1e-5);
        dWorldSetContactSurfaceLayer(world_, 0.005);
        dWorldSetAutoDisableFlag(world_, 0);
    }
    ~OdeWorld() override {
        dJointGroupDestroy(contacts_);
        dSpaceDestroy(space_);  // destroys its geoms
        dWorldDestroy(world_);  // and its bodies
    }
    OdeWorld(const OdeWorld&) = delete;
    OdeWorld& operator=(const OdeWorld&) = delete;

    void addGround() override { dCreatePlane(space_, 0, 0, 1, 0); }
    int addCube(const Vec3& position) override {
        BodySpec cube;
        cube.mass = cubeMass_;
        cube.position = position;
        return addBody(cube);
    }
    void addStaticBox(const Vec3& center, const Vec3& halfExtents) override {
        const dGeomID box =
            dCreateBox(space_, 2 * halfExtents.x(), 2 * halfExtents.y(), 2 * halfExtents.z());
        dGeomSetPosition(box, center.x(), center.y(), center.z());
    }
    int addBody(const BodySpec& b) override {
        dMass mass;
        dGeomID geom = nullptr;
        if (b.kind == ShapeKind::Box) {
            const Vec3 e = 2 * b.halfExtents;
            dMassSetBoxTotal(&mass, b.mass, e.x(), e.y(), e.z());
            geom = dCreateBox(space_, e.x(), e.y(), e.z());
        } else if (b.kind == ShapeKind::Sphere) {
            dMassSetSphereTotal(&mass, b.mass, b.radius);
            geom = dCreateSphere(space_, b.radius);
        } else {
            dMassSetCapsuleTotal(&mass, b.mass, 3, b.radius, 2 * b.halfLength);  // 3: along z
            geom = dCreateCapsule(space_, b.radius, 2 * b.halfLength);
        }
        const dBodyID body = newBody(b.position, mass);
        const dQuaternion q = {b.orientation.w(), b.orientation.x(), b.orientation.y(),
                               b.orientation.z()};
        dBodySetQuaternion(body, q);
        dGeomSetBody(geom, body);
        return static_cast<int>(bodies_.size()) - 1;
    }
    int addPointMass(const Vec3& position, const Vec3& velocity, Real mass, Real radius) override {
        dMass m;
        dMassSetSphereTotal(&m, mass, radius);
        const dBodyID body = newBody(position, m);
        dBodySetLinearVel(body, velocity.x(), velocity.y(), velocity.z());
        return static_cast<int>(bodies_.size()) - 1;
    }
    // ODE zeroes the force accumulators after each step.
    void applyForce(int body, const Vec3& f) override {
        dBodyAddForce(bodies_[body], f.x(), f.y(), f.z());
    }
    void step() override {
        deepest_ = 0;
        dSpaceCollide(space_, this, &nearCallback);
        dWorldQuickStep(world_, h_);
        dJointGroupEmpty(contacts_);
    }
    Vec3 position(int body) const override {
        const dReal* p = dBodyGetPosition(bodies_[body]);
        return Vec3(p[0], p[1], p[2]);
    }
    Vec3 velocity(int body) const override {
        const dReal* v = dBodyGetLinearVel(bodies_[body]);
        return Vec3(v[0], v[1], v[2]);
    }
    /// The deepest contact found by the step's collision pass, before its solve: ODE keeps no
    /// contacts after the step.
    Real deepestPenetration() const override { return deepest_; }

private:
    dBodyID newBody(const Vec3& position, const dMass& mass) {
        const dBodyID body = dBodyCreate(world_);
        dBodySetMass(body, &mass);
        dBodySetPosition(body, position.x(), position.y(), position.z());
        bodies_.push_back(body);
        return body;
    }
    static void nearCallback(void* data, dGeomID a, dGeomID b) {
        auto* self = static_cast<OdeWorld*>(data);
        const dBodyID bodyA = dGeomGetBody(a);
        const dBodyID bodyB = dGeomGetBody(b);
        if (bodyA == nullptr && bodyB == nullptr)
            return;  // the container's walls and floor
        std::array<dContact, kMaxContacts> contact{};
        const int count = dCollide(a, b, kMaxContacts, &contact[0].geom, sizeof(dContact));
        for (int i = 0; i < count; ++i) {
            dContact& c = contact[static_cast<std::size_t>(i)];
            c.surface.mode = dContactApprox1;
            c.surface.mu = self->friction_;  // the pair's mu: ODE has no per-body friction
            c.surface.bounce = 0;
            if (self->restitution_ > 0) {
                c.surface.mode |= dContactBounce;
                c.surface.bounce = self->restitution_;
                c.surface.bounce_vel = 0.2;  // (m/s) Bullet's m_restitutionVelocityThreshold
            }
            self->deepest_ = std::max<Real>(self->deepest_, c.geom.depth);
            const dJointID joint = dJointCreateContact(self->world_, self->contacts_, &c);
            dJointAttach(joint, bodyA, bodyB);
        }
    }

    dWorldID world_ = nullptr;
    dSpaceID space_ = nullptr;
    dJointGroupID contacts_ = nullptr;
    Real h_;
    Real friction_;
    Real restitution_;
    Real cubeMass_;
    Real deepest_ = 0;
    std::vector<dBodyID> bodies_;
};

}  // namespace

std::unique_ptr<PeerWorld> createOde(const SceneSettings& settings) {
    return std::make_unique<OdeWorld>(settings);
}

}  // namespace tumble::bench
