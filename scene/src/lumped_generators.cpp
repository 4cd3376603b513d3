// The string and net generators of scene files: parsed into StringDef / NetDef (tumble/lumped.h)
// and built by the engine's own generators, so a scene file gets exactly what an embedding
// application gets. Each node is also listed as a scene body, so outputs can name it.

#include <cmath>
#include <type_traits>
#include <variant>

#include "scene_parts.h"

namespace tumble::cli {
namespace {

constexpr int kMaxNodes = 1'000'000;  ///< a larger net is surely a typo

NodeDef parseNode(JsonObject o, const Materials& materials) {
    NodeDef node;
    node.mass = o.positive("mass", node.mass);
    node.radius = o.positive("radius", node.radius);
    node.collide = o.boolean("collide", node.collide);
    node.fixedRotation = o.boolean("fixedRotation", node.fixedRotation);
    node.material = materialAt(o, "material", materials);
    node.filter = parseFilter(o);
    o.finish();
    return node;
}

ThreadDef parseThread(JsonObject o) {
    ThreadDef thread;
    const bool fromModulus = o.has("youngsModulus") || o.has("area");
    if (fromModulus && o.has("axialRigidity"))
        failAt(o.path(),
               "give \"axialRigidity\" (E A, N) or \"youngsModulus\" and \"area\", "
               "not both");
    if (fromModulus) {
        if (!o.has("youngsModulus") || !o.has("area"))
            failAt(o.path(), "\"youngsModulus\" (Pa) and \"area\" (m^2) go together");
        thread.axialRigidity = o.positive("youngsModulus", 0) * o.positive("area", 0);
    } else {
        thread.axialRigidity = o.positive("axialRigidity", thread.axialRigidity);
    }
    thread.damping = o.positive("damping", thread.damping, true);
    thread.tensionOnly = o.boolean("tensionOnly", thread.tensionOnly);
    thread.formulation = parseFormulation(o, thread.formulation);
    thread.numericalDamping = parseNumericalDamping(o, thread.numericalDamping);
    thread.collide = o.boolean("collide", thread.collide);
    o.finish();
    return thread;
}

StringDef parseString(JsonObject& o, const Materials& materials) {
    StringDef d;
    d.start = o.vec3("start", d.start);
    d.end = o.vec3("end", d.end);
    if ((d.end - d.start).norm() < 1e-12)
        failAt(o.pathOf("end"), "must differ from \"start\": the segments would have no length");
    d.fixedStart = o.boolean("fixedStart", d.fixedStart);
    d.fixedEnd = o.boolean("fixedEnd", d.fixedEnd);
    d.count = o.integer("count", d.count, d.fixedStart || d.fixedEnd ? 1 : 2, kMaxNodes);
    d.restLengthRatio = o.positive("restLengthRatio", d.restLengthRatio);
    d.velocity = o.vec3("velocity", d.velocity);
    d.node = parseNode(o.object("node"), materials);
    d.thread = parseThread(o.object("thread"));
    return d;
}

NetDef parseNet(JsonObject& o, const Materials& materials) {
    NetDef d;
    d.rows = o.integer("rows", d.rows, 0, kMaxNodes);
    d.columns = o.integer("columns", d.columns, 0, kMaxNodes);
    if (d.rows < 2 || d.columns < 2)
        failAt(o.path(), "a net needs at least 2 x 2 nodes (got rows x columns = ", d.rows, " x ",
               d.columns, ")");
    if (static_cast<long long>(d.rows) * d.columns > kMaxNodes)
        failAt(o.path(), "at most ", kMaxNodes, " nodes");
    d.meshSize = o.positive("meshSize", d.meshSize);
    d.center = o.vec3("center", d.center);
    d.orientation = o.orientation("orientation");
    d.node = parseNode(o.object("node"), materials);
    d.cornerMass = o.positive("cornerMass", d.cornerMass, true);
    d.thread = parseThread(o.object("thread"));
    d.velocity = o.vec3("velocity", d.velocity);
    d.spreadSpeed = o.number("spreadSpeed", d.spreadSpeed);
    return d;
}

/// "excite": [{"node": k or [i, j], "velocity": [x, y, z]}]: initial velocities of single nodes.
void parseExcite(JsonObject& o, LumpedSpec& spec, int columns) {
    const Json* list = o.find("excite");
    if (list == nullptr)
        return;
    if (!list->is_array())
        failAt(o.pathOf("excite"), "expected an array of {\"node\", \"velocity\"}");
    for (std::size_t i = 0; i < list->size(); ++i) {
        JsonObject e((*list)[i], o.pathOf("excite") + "[" + std::to_string(i) + "]");
        const Json* node = e.find("node");
        long long index = -1;
        if (node != nullptr && node->is_number_integer()) {
            index = node->get<long long>();
        } else if (node != nullptr && columns > 0 && node->is_array() && node->size() == 2 &&
                   (*node)[0].is_number_integer() && (*node)[1].is_number_integer()) {
            const long long row = (*node)[0].get<long long>(), column = (*node)[1].get<long long>();
            if (column >= 0 && column < columns && row >= 0)
                index = row * columns + column;
        } else {
            failAt(e.pathOf("node"), columns > 0 ? "expected a node index or [row, column]"
                                                 : "expected a node index");
        }
        if (index < 0 || index >= static_cast<long long>(spec.nodeCount))
            failAt(e.pathOf("node"), "no such node (the generator has ", spec.nodeCount, ")");
        if (!e.has("velocity"))
            failAt(e.pathOf("velocity"), "is required");
        spec.excite.emplace_back(static_cast<int>(index), e.vec3("velocity", Vec3::Zero()));
        e.finish();
    }
}

}  // namespace

void parseLumped(JsonObject& o, const std::string& type, const std::string& name,
                 const Materials& materials, Scene& scene) {
    LumpedSpec spec;
    spec.name = name;
    spec.path = o.path();
    spec.firstBody = scene.bodies.size();
    int columns = 0;
    if (type == "string") {
        const StringDef d = parseString(o, materials);
        spec.nodeCount = static_cast<std::size_t>(d.count);
        spec.def = d;
    } else {
        const NetDef d = parseNet(o, materials);
        spec.nodeCount = static_cast<std::size_t>(d.rows) * d.columns;
        columns = d.columns;
        spec.def = d;
    }
    std::optional<Drag> drag;
    if (const Json* v = o.find("drag"))
        drag = parseDrag(*v, o.pathOf("drag"));
    parseExcite(o, spec, columns);
    const int index = static_cast<int>(scene.lumped.size());
    for (std::size_t k = 0; k < spec.nodeCount; ++k) {
        BodySpec b;
        b.name = columns > 0 ? name + "[" + std::to_string(k / columns) + "][" +
                                   std::to_string(k % columns) + "]"
                             : name + "[" + std::to_string(k) + "]";
        b.path = spec.path;
        b.drag = drag;
        b.lumped = index;
        scene.bodies.push_back(std::move(b));
    }
    scene.lumped.push_back(std::move(spec));
}

void buildLumped(const Scene& scene, const LumpedSpec& spec, BuiltScene& built) {
    World& world = built.world;
    // The picture needs the ids of the nodes' spheres, and the World has no public way to list a
    // body's shapes (nor do its queries see shapes added since the last step). So the generator
    // is asked for bare nodes and each gets here the very sphere NodeDef::collide would give it.
    auto bare = spec.def;
    NodeDef node;
    std::visit(
        [&](auto& d) {
            node = d.node;
            d.node.collide = false;
        },
        bare);
    Lumped made;
    try {
        made = std::visit(
            [&](const auto& d) {
                if constexpr (std::is_same_v<std::decay_t<decltype(d)>, StringDef>)
                    return createString(world, d);
                else
                    return createNet(world, d);
            },
            bare);
        for (std::size_t k = 0; k < made.nodes.size(); ++k) {
            const BodyId id = made.nodes[k];
            if (node.collide) {
                // Built whole (GCC 12 -Wmaybe-uninitialized false positive on assigning the
                // variant); the node's mass and inertia are the generator's.
                const ShapeDef sphere{.geometry = Sphere{node.radius},
                                      .material = node.material,
                                      .filter = node.filter,
                                      .updateBodyMass = false};
                built.shapes.push_back(world.createShape(id, sphere));
            }
            const BodySpec& body = scene.bodies[spec.firstBody + k];
            if (body.drag)
                world.setDrag(id, *body.drag);
            built.bodies.push_back(id);
            built.gravityScale.push_back(1);
        }
        for (const auto& [k, velocity] : spec.excite)
            world.setLinearVelocity(made.nodes[static_cast<std::size_t>(k)], velocity);
    } catch (const InvalidArgument& e) {
        fail(located(scene, spec.path), " (\"", spec.name, "\"): ", e.what());
    }
    built.springs.insert(built.springs.end(), made.threads.begin(), made.threads.end());
}

}  // namespace tumble::cli
