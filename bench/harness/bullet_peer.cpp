// Bullet 3 (Debian's libbullet-dev) behind the harness interface: btDiscreteDynamicsWorld with the
// sequential-impulse solver, as the study used it; fixed steps of h (no sub-stepping), the
// requested iterations, no deactivation (sleeping), restitution 0.

#include <btBulletDynamicsCommon.h>

#include <algorithm>
#include <cmath>

#include "peer.h"

namespace tumble::bench {
namespace {

// Debian's Bullet is built in single precision: btScalar is float.
btScalar narrow(Real x) {
    return static_cast<btScalar>(x);
}

class BulletWorld final : public PeerWorld {
public:
    explicit BulletWorld(const SceneSettings& s)
        : dispatcher_(&configuration_),
          world_(&dispatcher_, &broadphase_, &solver_, &configuration_),
          h_(s.timeStep),
          mass_(s.boxMass),
          // Bullet multiplies the two friction coefficients: sqrt(mu) on each gives mu.
          friction_(std::sqrt(s.friction)),
          cube_(btVector3(0.5, 0.5, 0.5)) {
        world_.setGravity(btVector3(0, 0, narrow(-9.81)));
        world_.getSolverInfo().m_numIterations = s.iterations;
    }
    ~BulletWorld() override {
        for (int i = world_.getNumCollisionObjects() - 1; i >= 0; --i) {
            btCollisionObject* object = world_.getCollisionObjectArray()[i];
            world_.removeCollisionObject(object);
            delete static_cast<btRigidBody*>(object)->getMotionState();
            delete object;
        }
    }
    void addGround() override { add(&plane_, 0, Vec3::Zero()); }
    int addCube(const Vec3& position) override {
        cubes_.push_back(add(&cube_, mass_, position));
        return static_cast<int>(cubes_.size()) - 1;
    }
    void step() override { world_.stepSimulation(static_cast<btScalar>(h_), 0); }
    Vec3 position(int cube) const override {
        const btVector3& p = cubes_[cube]->getCenterOfMassPosition();
        return Vec3(p.x(), p.y(), p.z());
    }
    Real deepestPenetration() const override {
        Real deepest = 0;
        for (int m = 0; m < dispatcher_.getNumManifolds(); ++m) {
            const btPersistentManifold* manifold = dispatcher_.getManifoldByIndexInternal(m);
            for (int i = 0; i < manifold->getNumContacts(); ++i) {
                deepest = std::max<Real>(deepest, -manifold->getContactPoint(i).getDistance());
            }
        }
        return deepest;
    }

private:
    btRigidBody* add(btCollisionShape* shape, Real mass, const Vec3& position) {
        btVector3 inertia(0, 0, 0);
        if (mass > 0)
            shape->calculateLocalInertia(static_cast<btScalar>(mass), inertia);
        btTransform pose;
        pose.setIdentity();
        pose.setOrigin(btVector3(narrow(position.x()), narrow(position.y()), narrow(position.z())));
        auto* motion = new btDefaultMotionState(pose);
        btRigidBody::btRigidBodyConstructionInfo info(static_cast<btScalar>(mass), motion, shape,
                                                      inertia);
        info.m_friction = static_cast<btScalar>(friction_);
        info.m_restitution = 0;
        auto* body = new btRigidBody(info);
        body->setActivationState(DISABLE_DEACTIVATION);
        world_.addRigidBody(body);
        return body;
    }

    btDefaultCollisionConfiguration configuration_;
    mutable btCollisionDispatcher dispatcher_;  // its manifold accessors are not const
    btDbvtBroadphase broadphase_;
    btSequentialImpulseConstraintSolver solver_;
    btDiscreteDynamicsWorld world_;
    Real h_;
    Real mass_;
    Real friction_;
    btStaticPlaneShape plane_{btVector3(0, 0, 1), 0};
    btBoxShape cube_;
    std::vector<btRigidBody*> cubes_;
};

}  // namespace

std::unique_ptr<PeerWorld> createBullet(const SceneSettings& settings) {
    return std::make_unique<BulletWorld>(settings);
}

}  // namespace tumble::bench
