// MuJoCo 2.2 (Debian's libmujoco-dev) behind the harness interface. The scene is written as an
// MJCF model (a string, loaded from MuJoCo's in-memory file system) when it is first stepped or
// read: the plane and the walls as world geoms, every body with a free joint and one geom of the
// given mass (MuJoCo computes the inertia from the shape), the harness's h and gravity, and
// MuJoCo's own solver defaults otherwise -- Newton, pyramidal cones, up to 100 iterations to a
// tolerance of 1e-8, soft contacts (solref 0.02 s, clamped to 2 h), semi-implicit Euler. So
// SceneSettings::iterations and ::correction do not apply (its Newton iterations are not
// sweeps). Friction: condim 3 (sliding only), mu on every geom; MuJoCo takes the larger of two.
// MuJoCo 2.2's tendon springs push as well as pull (a two-sided rest length arrived in later
// versions), so it cannot build the net's tension-only threads: its net is point masses that
// collide with nothing, pulled by the harness's thread forces, as in Bullet and ODE.
// Restitution is not matched: MuJoCo has no coefficient, only the contacts' stiffness and
// damping (solref); the scenes use 0, and a requested bounce is refused.

#include <mujoco/mujoco.h>

#include <algorithm>
#include <cstdio>
#include <cstring>
#include <memory>
#include <sstream>
#include <stdexcept>
#include <string>

#include "peer.h"

namespace tumble::bench {
namespace {

// MuJoCo 2.2 sizes its contact list and constraint arrays when the model is compiled, and the
// constraint arrays densely (an njmax x nv Jacobian and its transpose, an njmax x njmax matrix),
// all in one buffer whose size is an int (mjData::nbuffer), so the contacts are budgeted per
// colliding body -- pyramid-20 peaks at 1,790 contacts for 210 cubes (a face on a face gives 4
// or more, each of 4 pyramidal rows) -- and a scene whose arrays would not fit in 2 GiB is
// refused: mj_makeData fails beyond it.
constexpr long kContactsPerBody = 10;
constexpr long kRowsPerContact = 4;
constexpr double kMaxArrays = 2147483647;  // (bytes)

long contactBudget(long collidingBodies) {
    return kContactsPerBody * std::max(collidingBodies, 8L);
}

// Bytes of the dense constraint arrays (values and column indices) for this many bodies.
double arrayBytes(long bodies, long collidingBodies) {
    const auto rows = static_cast<double>(kRowsPerContact * contactBudget(collidingBodies));
    const double dofs = 6.0 * static_cast<double>(bodies);
    return 12 * rows * (2 * dofs + rows);
}

struct ModelDeleter {
    void operator()(mjModel* m) const { mj_deleteModel(m); }
};
struct DataDeleter {
    void operator()(mjData* d) const { mj_deleteData(d); }
};

std::string vec(const Vec3& v) {
    char buffer[96];
    std::snprintf(buffer, sizeof buffer, "%.17g %.17g %.17g", v.x(), v.y(), v.z());
    return buffer;
}

class MujocoWorld final : public PeerWorld {
public:
    explicit MujocoWorld(const SceneSettings& s) : settings_(s) {
        world_.precision(17);
        if (s.restitution != 0)
            throw std::invalid_argument("mujoco peer: restitution is not matched (0 only)");
    }
    void addGround() override { world_ << "<geom type='plane' size='0 0 1'/>\n"; }
    int addCube(const Vec3& position) override {
        BodySpec cube;
        cube.mass = settings_.boxMass;
        cube.position = position;
        return addBody(cube);
    }
    void addStaticBox(const Vec3& center, const Vec3& halfExtents) override {
        world_ << "<geom type='box' pos='" << vec(center) << "' size='" << vec(halfExtents)
               << "'/>\n";
    }
    int addBody(const BodySpec& b) override {
        std::ostringstream geom;
        geom.precision(17);
        if (b.kind == ShapeKind::Box)
            geom << "type='box' size='" << vec(b.halfExtents) << "'";
        else if (b.kind == ShapeKind::Sphere)
            geom << "type='sphere' size='" << b.radius << "'";
        else  // MuJoCo's capsule lies along its local z, as the harness's
            geom << "type='capsule' size='" << b.radius << " " << b.halfLength << "'";
        geom << " mass='" << b.mass << "'";
        if (arrayBytes(bodies() + 1, colliding_ + 1) > kMaxArrays) {
            char why[160];
            std::snprintf(why, sizeof why,
                          "MuJoCo 2.2's dense constraint arrays (njmax x nv, njmax^2) pass its "
                          "2 GiB buffer at body %ld",
                          bodies() + 1);
            refusal_ = why;
            return -1;
        }
        ++colliding_;
        return body(b.position, b.orientation, geom.str(), Vec3::Zero());
    }
    int addPointMass(const Vec3& position, const Vec3& velocity, Real mass, Real radius) override {
        std::ostringstream geom;
        geom.precision(17);
        geom << "type='sphere' size='" << radius << "' mass='" << mass
             << "' contype='0' conaffinity='0'";
        return body(position, Quat::Identity(), geom.str(), velocity);
    }
    void applyForce(int body, const Vec3& force) override {
        compile();
        std::copy(force.data(), force.data() + 3, data_->xfrc_applied + 6 * (body + 1));
    }
    // The applied forces hold for one step, as in the other engines.
    void step() override {
        compile();
        mj_step(model_.get(), data_.get());
        if (data_->warning[mjWARN_CONTACTFULL].number + data_->warning[mjWARN_CNSTRFULL].number >
                0 &&
            !warned_) {
            std::fprintf(stderr, "mujoco: contact budget full, contacts dropped\n");
            warned_ = true;
        }
        std::fill(data_->xfrc_applied, data_->xfrc_applied + 6 * model_->nbody, 0.0);
    }
    // A free joint's qpos is the body's position and quaternion, its qvel the linear velocity
    // in the world frame and the angular one in the body's.
    Vec3 position(int body) const override {
        compile();
        const mjtNum* q = data_->qpos + model_->jnt_qposadr[body];
        return Vec3(q[0], q[1], q[2]);
    }
    Vec3 velocity(int body) const override {
        compile();
        const mjtNum* v = data_->qvel + model_->jnt_dofadr[body];
        return Vec3(v[0], v[1], v[2]);
    }
    Real deepestPenetration() const override {
        compile();
        Real deepest = 0;
        for (int i = 0; i < data_->ncon; ++i)
            deepest = std::max<Real>(deepest, -data_->contact[i].dist);
        return deepest;
    }

    std::string refusal() const override { return refusal_; }

private:
    long bodies() const { return static_cast<long>(velocities_.size()); }
    int body(const Vec3& position, const Quat& q, const std::string& geom, const Vec3& velocity) {
        world_ << "<body pos='" << vec(position) << "' quat='" << q.w() << " " << vec(q.vec())
               << "'><freejoint/><geom " << geom << "/></body>\n";
        velocities_.push_back(velocity);
        return static_cast<int>(velocities_.size()) - 1;
    }
    std::string mjcf() const {
        const long contacts = contactBudget(colliding_);
        std::ostringstream xml;
        xml.precision(17);
        xml << "<mujoco model='tumble-bench'>\n<option timestep='" << settings_.timeStep
            << "' gravity='" << vec(settings_.gravity) << "'/>\n<size njmax='"
            << kRowsPerContact * contacts << "' nconmax='" << contacts << "'/>\n"
            << "<default><geom friction='" << settings_.friction << " 0.005 0.0001'/></default>\n"
            << "<worldbody>\n"
            << world_.str() << "</worldbody>\n</mujoco>\n";
        return xml.str();
    }
    void compile() const {
        if (model_)
            return;
        const std::string xml = mjcf();
        auto vfs = std::make_unique<mjVFS>();
        mj_defaultVFS(vfs.get());
        if (mj_makeEmptyFileVFS(vfs.get(), "scene.xml", static_cast<int>(xml.size())) != 0)
            throw std::runtime_error("mujoco peer: cannot make the in-memory file");
        std::memcpy(vfs->filedata[mj_findFileVFS(vfs.get(), "scene.xml")], xml.data(), xml.size());
        char error[1000] = "";
        model_.reset(mj_loadXML("scene.xml", vfs.get(), error, sizeof error));
        mj_deleteVFS(vfs.get());
        if (!model_)
            throw std::runtime_error(std::string("mujoco peer: ") + error);
        data_.reset(mj_makeData(model_.get()));
        if (!data_)
            throw std::runtime_error("mujoco peer: mj_makeData failed (its buffer is too large)");
        for (std::size_t i = 0; i < velocities_.size(); ++i) {
            mjtNum* v = data_->qvel + model_->jnt_dofadr[i];
            std::copy(velocities_[i].data(), velocities_[i].data() + 3, v);
        }
    }

    SceneSettings settings_;
    long colliding_ = 0;  // bodies that collide (not the net's point masses)
    std::string refusal_;
    std::ostringstream world_;      // the world body's children, as they were added
    std::vector<Vec3> velocities_;  // each body's initial linear velocity
    mutable std::unique_ptr<mjModel, ModelDeleter> model_;  // compiled at the first use
    mutable std::unique_ptr<mjData, DataDeleter> data_;
    bool warned_ = false;
};

}  // namespace

std::unique_ptr<PeerWorld> createMujoco(const SceneSettings& settings) {
    return std::make_unique<MujocoWorld>(settings);
}

}  // namespace tumble::bench
