// The replay writer: a JSON description, then one fixed-layout binary record per frame
// (docs/replay.md). Frames are float32: a body's position to ~1e-7 of its size, which no screen
// shows; time stays float64 so long runs keep their step boundaries.

#include <algorithm>
#include <cstring>
#include <fstream>
#include <nlohmann/json.hpp>

#include "replay_format.h"
#include "tumble/collision/mesh_shape.h"
#include "tumble/core/error.h"
#include "tumble/replay/replay.h"

namespace tumble {
namespace {

using Json = nlohmann::ordered_json;

Json vec(const Vec3& v) {
    return Json::array({v.x(), v.y(), v.z()});
}
Json quat(const Quat& q) {
    return Json::array({q.x(), q.y(), q.z(), q.w()});
}

// Names in the enums' order (tumble/body.h, tumble/core/solver_types.h).
constexpr const char* kBodyTypes[] = {"static", "kinematic", "dynamic"};
constexpr const char* kJointTypes[] = {"ball", "hinge", "slider", "fixed", "distance"};
static_assert(static_cast<int>(BodyType::Dynamic) == 2 &&
              static_cast<int>(JointType::Distance) == 4);

const char* typeName(BodyType type) {
    return kBodyTypes[static_cast<int>(type)];
}
const char* jointName(JointType type) {
    return kJointTypes[static_cast<int>(type)];
}

/// The geometry's type and sizes, in its own frame.
Json geometryJson(const Shape& shape) {
    Json j;
    std::visit(
        [&](const auto& g) {
            using T = std::decay_t<decltype(g)>;
            if constexpr (std::is_same_v<T, Sphere>) {
                j = {{"type", "sphere"}, {"radius", g.radius}};
            } else if constexpr (std::is_same_v<T, Capsule>) {
                j = {{"type", "capsule"}, {"radius", g.radius}, {"halfLength", g.halfLength}};
            } else if constexpr (std::is_same_v<T, Box>) {
                j = {{"type", "box"}, {"halfExtents", vec(g.halfExtents)}};
            } else if constexpr (std::is_same_v<T, Cylinder>) {
                j = {{"type", "cylinder"}, {"radius", g.radius}, {"halfLength", g.halfLength}};
            } else if constexpr (std::is_same_v<T, HalfSpace>) {
                j = {{"type", "plane"}, {"normal", vec(g.normal)}, {"offset", g.offset}};
            } else if constexpr (std::is_same_v<T, TriangleMesh>) {
                Json vertices = Json::array(), triangles = Json::array();
                for (const Vec3& v : g.data->vertices)
                    vertices.push_back(vec(v));
                for (const auto& t : g.data->triangles)
                    triangles.push_back(Json::array({t[0], t[1], t[2]}));
                j = {{"type", "mesh"}, {"vertices", vertices}, {"triangles", triangles}};
            } else if constexpr (std::is_same_v<T, HeightField>) {
                const HeightFieldData& grid = g.data->grid;
                j = {{"type", "heightfield"},
                     {"columns", grid.columns},
                     {"rows", grid.rows},
                     {"spacing", Json::array({grid.spacingX, grid.spacingY})},
                     {"heights", grid.heights}};
            } else {
                Json vertices = Json::array(), faces = Json::array();
                for (const Vec3& v : g.data->vertices)
                    vertices.push_back(vec(v));
                for (const HullFace& f : g.data->faces) {
                    Json face = Json::array();
                    for (std::uint32_t k = 0; k < f.count; ++k)
                        face.push_back(g.data->faceVertices[f.first + k]);
                    faces.push_back(face);
                }
                j = {{"type", "hull"}, {"vertices", vertices}, {"faces", faces}};
            }
        },
        shape);
    return j;
}

/// The index of `body` in `bodies`, -1 for the null body; refuses a body not listed.
int indexOf(const std::vector<BodyId>& bodies, BodyId body, const char* what) {
    if (body.isNull())
        return -1;
    const auto it = std::find(bodies.begin(), bodies.end(), body);
    if (it == bodies.end())
        fail("ReplayContent: a ", what, " attached to body ", body.index,
             " which is not in ReplayContent.bodies");
    return static_cast<int>(it - bodies.begin());
}

bool listed(const std::vector<BodyId>& bodies, BodyId body) {
    return body.isNull() || std::find(bodies.begin(), bodies.end(), body) != bodies.end();
}

/// Completes the content's defaults from the world and checks its lists.
void complete(ReplayContent& c, const World& world) {
    if (c.bodies.empty())
        c.bodies = world.bodies();
    for (const BodyId b : c.bodies) {
        if (!world.isValid(b))
            fail("ReplayContent.bodies: body ", b.index, " is not a valid body of this world");
    }
    if (!c.names.empty() && c.names.size() != c.bodies.size())
        fail("ReplayContent.names has ", c.names.size(), " names for ", c.bodies.size(),
             " bodies: give one per body or none");
    if (!c.gravityScale.empty() && c.gravityScale.size() != c.bodies.size())
        fail("ReplayContent.gravityScale has ", c.gravityScale.size(), " values for ",
             c.bodies.size(), " bodies: give one per body or none");
    auto gather = [&](auto& list, auto attached, auto def) {
        if (!list.empty())
            return;
        for (const BodyId b : c.bodies) {
            for (const auto id : (world.*attached)(b)) {
                const auto& d = (world.*def)(id);
                if (listed(c.bodies, d.bodyA) && listed(c.bodies, d.bodyB) &&
                    std::find(list.begin(), list.end(), id) == list.end())
                    list.push_back(id);
            }
        }
    };
    gather(c.springs, &World::bodySprings, &World::springDef);
    gather(c.joints, &World::bodyJoints, &World::jointDef);
}

Json bodiesJson(const World& world, const ReplayContent& c) {
    Json bodies = Json::array();
    for (std::size_t i = 0; i < c.bodies.size(); ++i) {
        const BodyId b = c.bodies[i];
        const MassProperties m = world.massProperties(b);
        Json shapes = Json::array();
        for (const ShapeId s : world.bodyShapes(b)) {
            const ShapeDef& def = world.shapeDef(s);
            Json shape = geometryJson(def.geometry);
            shape["position"] = vec(def.localPose.position);
            shape["orientation"] = quat(def.localPose.rotation);
            shapes.push_back(shape);
        }
        const bool dynamic = world.bodyType(b) == BodyType::Dynamic;
        bodies.push_back({{"name", c.names.empty() ? "" : c.names[i]},
                          {"type", typeName(world.bodyType(b))},
                          {"mass", dynamic ? m.mass : 0.0},
                          {"localCenter", vec(m.localCenter)},
                          {"shapes", shapes}});
    }
    return bodies;
}

Json springsJson(const World& world, const ReplayContent& c) {
    Json springs = Json::array();
    for (const SpringId s : c.springs) {
        const SpringDef& d = world.springDef(s);
        springs.push_back({{"bodyA", indexOf(c.bodies, d.bodyA, "spring")},
                           {"bodyB", indexOf(c.bodies, d.bodyB, "spring")},
                           {"anchorA", vec(d.localAnchorA)},
                           {"anchorB", vec(d.localAnchorB)},
                           {"restLength", d.restLength},
                           {"thread", d.tensionOnly}});
    }
    return springs;
}

Json jointsJson(const World& world, const ReplayContent& c) {
    Json joints = Json::array();
    for (const JointId id : c.joints) {
        const JointDef& d = world.jointDef(id);
        const Vec3 anchorB = d.type == JointType::Distance ? d.anchorB : d.anchor;
        // Anchors in each body's frame, so a viewer draws them at any frame's poses.
        joints.push_back(
            {{"type", jointName(d.type)},
             {"bodyA", indexOf(c.bodies, d.bodyA, "joint")},
             {"bodyB", indexOf(c.bodies, d.bodyB, "joint")},
             {"anchorA", vec(world.transform(d.bodyA).applyInverse(d.anchor))},
             {"anchorB",
              vec(d.bodyB.isNull() ? anchorB : world.transform(d.bodyB).applyInverse(anchorB))}});
    }
    return joints;
}

}  // namespace

ReplayWriter::ReplayWriter(const std::string& path, const World& world, ReplayContent content)
    : content_(std::move(content)) {
    auto file = std::make_unique<std::ofstream>(path, std::ios::binary);
    if (!*file)
        fail("replay file \"", path, "\" cannot be written");
    file_ = std::move(file);
    out_ = file_.get();
    writeDescription(world);
}

ReplayWriter::ReplayWriter(std::ostream& out, const World& world, ReplayContent content)
    : out_(&out), content_(std::move(content)) {
    writeDescription(world);
}

ReplayWriter::~ReplayWriter() {
    if (!finished_)
        finish();
}

void ReplayWriter::writeDescription(const World& world) {
    complete(content_, world);
    const ReplayContent& c = content_;
    const Json description{{"format", "tumble-replay"},
                           {"version", kReplayVersion},
                           {"title", c.title},
                           {"timeStep", world.settings().timeStep},
                           {"gravity", vec(world.settings().gravity)},
                           {"frame", {{"tensions", c.tensions}, {"contacts", c.contacts}}},
                           {"bodies", bodiesJson(world, c)},
                           {"springs", springsJson(world, c)},
                           {"joints", jointsJson(world, c)}};
    std::string text = description.dump();
    text.append((4 - text.size() % 4) % 4, ' ');  // frames start 4-byte aligned
    out_->write(replay::kMagic, sizeof replay::kMagic);
    replay::writeWord(*out_, kReplayVersion);
    replay::writeWord(*out_, static_cast<std::uint32_t>(text.size()));
    out_->write(text.data(), static_cast<std::streamsize>(text.size()));
}

void ReplayWriter::addFrame(const World& world) {
    const ReplayContent& c = content_;
    buffer_.clear();
    Real kinetic = 0, potential = 0;
    const Vec3 g = world.settings().gravity;
    for (std::size_t i = 0; i < c.bodies.size(); ++i) {
        const BodyId b = c.bodies[i];
        const Transform t = world.transform(b);
        const Vec3 v = world.linearVelocity(b);
        const bool dynamic = world.bodyType(b) == BodyType::Dynamic;
        const Real energy = dynamic ? world.kineticEnergy(b) : 0;
        const Real scale = c.gravityScale.empty() ? 1 : c.gravityScale[i];
        kinetic += energy;
        if (dynamic)
            potential -= world.massProperties(b).mass * scale * g.dot(world.centerOfMass(b));
        for (const Real x :
             {t.position.x(), t.position.y(), t.position.z(), t.rotation.x(), t.rotation.y(),
              t.rotation.z(), t.rotation.w(), v.x(), v.y(), v.z(), energy})
            buffer_.push_back(static_cast<float>(x));
    }
    if (c.tensions) {
        for (const SpringId s : c.springs)
            buffer_.push_back(static_cast<float>(world.springState(s).tension));
    }
    std::uint32_t contactCount = 0;
    if (c.contacts) {
        const Real h = world.settings().timeStep;
        for (const Contact& contact : world.contacts()) {
            const Manifold& m = contact.manifold;
            for (int k = 0; k < m.pointCount; ++k) {
                if (!(contact.normalImpulse[k] > 0))  // speculative: not touching
                    continue;
                const Vec3& p = m.points[k].position;
                for (const Real x : {p.x(), p.y(), p.z(), m.normal.x(), m.normal.y(), m.normal.z(),
                                     contact.normalImpulse[k] / h})
                    buffer_.push_back(static_cast<float>(x));
                ++contactCount;
            }
        }
    }
    replay::writeWord(*out_, replay::kFrameTag);
    const double time = world.time();
    out_->write(reinterpret_cast<const char*>(&time), sizeof time);
    const float energy[3] = {static_cast<float>(kinetic), static_cast<float>(potential),
                             static_cast<float>(world.springPotentialEnergy())};
    out_->write(reinterpret_cast<const char*>(energy), sizeof energy);
    replay::writeWord(*out_, contactCount);
    out_->write(reinterpret_cast<const char*>(buffer_.data()),
                static_cast<std::streamsize>(buffer_.size() * sizeof(float)));
    ++frames_;
}

void ReplayWriter::finish() {
    finished_ = true;
    replay::writeWord(*out_, replay::kEndTag);
    replay::writeWord(*out_, static_cast<std::uint32_t>(frames_));
    out_->flush();
}

}  // namespace tumble
