// Bullet 3 (Debian's libbullet-dev) behind the harness interface: btDiscreteDynamicsWorld with the
// sequential-impulse solver, as the study used it; fixed steps of h (no sub-stepping), the
// requested iterations, no deactivation (sleeping), the requested restitution (0 in the scenes).
// Penetration: Bullet's default unless asked (SceneSettings::correction) -- split impulse only for
// contacts deeper than 4 cm (m_splitImpulsePenetrationThreshold = -0.04), Baumgarte (ERP 0.2 in
// the velocity) for shallower ones; Baumgarte asks m_splitImpulse = 0; split impulse asks it for
// every penetrating contact (an infinite threshold). SceneSettings::speculativeContacts = false
// drops the contacts that do not touch yet from the solve. Bullet has no spring elements
// to match Tumble's implicit threads, so a net is point-mass spheres that collide with nothing
// (collision mask 0) pulled by the harness's thread forces, applied before each step. Terrain:
// btHeightfieldTerrainShape and btBvhTriangleMeshShape as they come (no internal-edge utility).

#include <BulletCollision/CollisionShapes/btHeightfieldTerrainShape.h>
#include <btBulletDynamicsCommon.h>

#include <algorithm>
#include <cmath>
#include <deque>
#include <memory>

#include "peer.h"

namespace tumble::bench {
namespace {

// Debian's Bullet is built in single precision: btScalar is float.
btScalar narrow(Real x) {
    return static_cast<btScalar>(x);
}
btVector3 narrow(const Vec3& v) {
    return btVector3(narrow(v.x()), narrow(v.y()), narrow(v.z()));
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
          // It multiplies the restitutions too (btManifoldResult::calculateCombinedRestitution):
          // sqrt(e) on each body gives e for every pair -- for the ball on the ground the same as
          // 1 on the ground and e on the ball.
          restitution_(std::sqrt(s.restitution)),
          speculative_(s.speculativeContacts),
          cube_(btVector3(0.5, 0.5, 0.5)) {
        world_.setGravity(narrow(s.gravity));
        btContactSolverInfo& solver = world_.getSolverInfo();
        solver.m_numIterations = s.iterations;
        if (s.correction == SceneSettings::Correction::Baumgarte) {
            solver.m_splitImpulse = 0;
        } else if (s.correction == SceneSettings::Correction::SplitImpulse) {
            solver.m_splitImpulse = 1;
            solver.m_splitImpulsePenetrationThreshold = BT_LARGE_FLOAT;
        }
    }
    ~BulletWorld() override {
        for (int i = world_.getNumCollisionObjects() - 1; i >= 0; --i) {
            btCollisionObject* object = world_.getCollisionObjectArray()[i];
            world_.removeCollisionObject(object);
            delete static_cast<btRigidBody*>(object)->getMotionState();
            delete object;
        }
    }
    void addGround() override { add(&plane_, 0, Vec3::Zero(), Quat::Identity()); }
    int addCube(const Vec3& position) override {
        return index(add(&cube_, mass_, position, Quat::Identity()));
    }
    void addStaticBox(const Vec3& center, const Vec3& halfExtents) override {
        add(own(std::make_unique<btBoxShape>(narrow(halfExtents))), 0, center, Quat::Identity());
    }
    int addBody(const BodySpec& b) override {
        btCollisionShape* shape = nullptr;
        if (b.kind == ShapeKind::Box)
            shape = own(std::make_unique<btBoxShape>(narrow(b.halfExtents)));
        else if (b.kind == ShapeKind::Sphere)
            shape = own(std::make_unique<btSphereShape>(narrow(b.radius)));
        else
            shape =
                own(std::make_unique<btCapsuleShapeZ>(narrow(b.radius), narrow(2 * b.halfLength)));
        return index(add(shape, b.mass, b.position, b.orientation));
    }
    // Bullet puts a height field's origin at the middle of its box and spaces samples 1 apart
    // before its local scaling: the body sits at the middle so sample (i, j) lands on
    // (i dx, j dy, h). flipQuadEdges splits cells along (i, j)-(i+1, j+1), as terrainMesh does.
    bool addHeightField(const HeightFieldData& field) override {
        std::vector<float>& heights =
            heightData_.emplace_back(field.heights.begin(), field.heights.end());
        const auto [low, high] = std::minmax_element(field.heights.begin(), field.heights.end());
        auto shape = std::make_unique<btHeightfieldTerrainShape>(
            static_cast<int>(field.columns), static_cast<int>(field.rows), heights.data(),
            narrow(*low), narrow(*high), 2, true);
        shape->setLocalScaling(btVector3(narrow(field.spacingX), narrow(field.spacingY), 1));
        const Vec3 middle(0.5 * (field.columns - 1) * field.spacingX,
                          0.5 * (field.rows - 1) * field.spacingY, 0.5 * (*low + *high));
        add(own(std::move(shape)), 0, middle, Quat::Identity());
        return true;
    }
    bool addTriangleMesh(const TriangleMeshData& mesh) override {
        MeshArrays& arrays = meshData_.emplace_back();
        for (const Vec3& v : mesh.vertices)
            arrays.vertices.insert(arrays.vertices.end(),
                                   {narrow(v.x()), narrow(v.y()), narrow(v.z())});
        for (const auto& t : mesh.triangles)
            arrays.indices.insert(arrays.indices.end(), t.begin(), t.end());
        arrays.mesh = std::make_unique<btTriangleIndexVertexArray>(
            static_cast<int>(mesh.triangles.size()), arrays.indices.data(), 3 * sizeof(int),
            static_cast<int>(mesh.vertices.size()), arrays.vertices.data(), 3 * sizeof(btScalar));
        add(own(std::make_unique<btBvhTriangleMeshShape>(arrays.mesh.get(), true)), 0, Vec3::Zero(),
            Quat::Identity());
        return true;
    }
    int addPointMass(const Vec3& position, const Vec3& velocity, Real mass, Real radius) override {
        btCollisionShape* shape = own(std::make_unique<btSphereShape>(narrow(radius)));
        btRigidBody* body = add(shape, mass, position, Quat::Identity(), 0);
        body->setLinearVelocity(narrow(velocity));
        return index(body);
    }
    void applyForce(int body, const Vec3& force) override {
        bodies_[body]->applyCentralForce(narrow(force));
    }
    // stepSimulation clears the applied forces after the step.
    void step() override { world_.stepSimulation(static_cast<btScalar>(h_), 0); }
    Vec3 position(int body) const override {
        const btVector3& p = bodies_[body]->getCenterOfMassPosition();
        return Vec3(p.x(), p.y(), p.z());
    }
    Vec3 velocity(int body) const override {
        const btVector3& v = bodies_[body]->getLinearVelocity();
        return Vec3(v.x(), v.y(), v.z());
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
    btCollisionShape* own(std::unique_ptr<btCollisionShape> shape) {
        shapes_.push_back(std::move(shape));
        return shapes_.back().get();
    }
    int index(btRigidBody* body) {
        bodies_.push_back(body);
        return static_cast<int>(bodies_.size()) - 1;
    }
    btRigidBody* add(btCollisionShape* shape, Real mass, const Vec3& position,
                     const Quat& orientation, int mask = -1) {
        btVector3 inertia(0, 0, 0);
        if (mass > 0)
            shape->calculateLocalInertia(static_cast<btScalar>(mass), inertia);
        btTransform pose;
        pose.setIdentity();
        pose.setOrigin(narrow(position));
        pose.setRotation(btQuaternion(narrow(orientation.x()), narrow(orientation.y()),
                                      narrow(orientation.z()), narrow(orientation.w())));
        auto* motion = new btDefaultMotionState(pose);
        btRigidBody::btRigidBodyConstructionInfo info(static_cast<btScalar>(mass), motion, shape,
                                                      inertia);
        info.m_friction = static_cast<btScalar>(friction_);
        info.m_restitution = static_cast<btScalar>(restitution_);
        auto* body = new btRigidBody(info);
        body->setActivationState(DISABLE_DEACTIVATION);
        if (!speculative_)
            body->setContactProcessingThreshold(0);
        if (mask == -1) {
            world_.addRigidBody(body);
        } else {
            world_.addRigidBody(body, btBroadphaseProxy::DefaultFilter, mask);
        }
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
    Real restitution_;
    bool speculative_;
    btStaticPlaneShape plane_{btVector3(0, 0, 1), 0};
    btBoxShape cube_;
    // Static meshes' arrays: Bullet reads them in place, so they outlive the shapes.
    struct MeshArrays {
        std::vector<int> indices;
        std::vector<btScalar> vertices;
        std::unique_ptr<btTriangleIndexVertexArray> mesh;
    };
    std::deque<MeshArrays> meshData_;
    std::deque<std::vector<float>> heightData_;
    std::vector<std::unique_ptr<btCollisionShape>> shapes_;  // outlive the bodies (destroyed after)
    std::vector<btRigidBody*> bodies_;
};

}  // namespace

std::unique_ptr<PeerWorld> createBullet(const SceneSettings& settings) {
    return std::make_unique<BulletWorld>(settings);
}

}  // namespace tumble::bench
