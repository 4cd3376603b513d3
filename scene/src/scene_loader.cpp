// Scene files -> Scene. The parse is complete before anything is built: every value is read
// through JsonObject, which names the JSON path of whatever it refuses.

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <optional>
#include <sstream>

#include "scene_parts.h"
#include "tumble/solver/contact_solver.h"  // checkSolverSettings

namespace tumble::cli {
namespace {

/// Upper bounds of the solver's counts (docs/scene-format.md): far above any useful value, low
/// enough that a typo is refused rather than run for days (10^9 iterations was).
constexpr int kMaxIterations = 10'000;
constexpr int kMaxSubsteps = 1'000;

std::string indexPath(const std::string& path, std::size_t i) {
    return path + "[" + std::to_string(i) + "]";
}

SolverSettings parseSolver(JsonObject o) {
    SolverSettings s;
    s.iterations = o.integer("iterations", s.iterations, 1, kMaxIterations);
    s.relaxIterations = o.integer("relaxIterations", s.relaxIterations, 0, kMaxIterations);
    s.linkIterations = o.integer("linkIterations", s.linkIterations, 1, kMaxIterations);
    s.linkRelaxIterations =
        o.integer("linkRelaxIterations", s.linkRelaxIterations, 0, kMaxIterations);
    s.tolerance = o.positive("tolerance", s.tolerance, true);
    s.relaxation = o.number("relaxation", s.relaxation);
    const std::string friction = o.choice("friction", "coupled", {"coupled", "box"});
    s.friction = friction == "box" ? FrictionModel::Box : FrictionModel::Coupled;
    const std::string stab =
        o.choice("stabilisation", "split-impulse", {"split-impulse", "baumgarte"});
    s.stabilisation = stab == "baumgarte" ? Stabilisation::Baumgarte : Stabilisation::SplitImpulse;
    s.baumgarte = o.number("baumgarte", s.baumgarte);
    s.splitImpulseFactor = o.number("splitImpulseFactor", s.splitImpulseFactor);
    s.slop = o.positive("slop", s.slop, true);
    s.restitutionThreshold = o.positive("restitutionThreshold", s.restitutionThreshold, true);
    s.warmStart = o.boolean("warmStart", s.warmStart);
    s.frictionAnchors = o.boolean("frictionAnchors", s.frictionAnchors);
    s.softSubsteps = o.integer("softSubsteps", s.softSubsteps, 0, kMaxSubsteps);
    s.contactHertz = o.number("contactHertz", s.contactHertz);
    s.contactDampingRatio = o.number("contactDampingRatio", s.contactDampingRatio);
    s.maxPushOutSpeed = o.number("maxPushOutSpeed", s.maxPushOutSpeed);
    o.finish();
    try {
        checkSolverSettings(s);
    } catch (const InvalidArgument& e) {
        failAt(o.path(), e.what());
    }
    return s;
}

WorldDef parseWorld(JsonObject o) {
    WorldDef w;
    w.timeStep = o.positive("timeStep", w.timeStep);
    w.substeps = o.integer("substeps", w.substeps, 1, kMaxSubsteps);
    w.gravity = o.vec3("gravity", w.gravity);
    w.contactMargin = o.positive("contactMargin", w.contactMargin, true);
    w.aabbMargin = o.positive("aabbMargin", w.aabbMargin, true);
    w.solver = parseSolver(o.object("solver"));
    JsonObject sleep = o.object("sleep");
    w.enableSleep = sleep.boolean("enabled", w.enableSleep);
    w.linearSleepVelocity = sleep.positive("linearVelocity", w.linearSleepVelocity, true);
    w.angularSleepVelocity = sleep.positive("angularVelocity", w.angularSleepVelocity, true);
    w.timeToSleep = sleep.positive("timeToSleep", w.timeToSleep);
    sleep.finish();
    o.finish();
    return w;
}

Shape parseGeometry(JsonObject& o, const std::string& type, const ShapeSource& source) {
    if (type == "mesh")
        return meshShape(parseMeshData(o, source), source, o.path());
    if (type == "heightField")
        return heightFieldShape(parseHeightFieldData(o, source), o.path());
    if (type == "sphere")
        return Sphere{o.positive("radius", Sphere{}.radius)};
    if (type == "box") {
        const Vec3 h = o.vec3("halfExtents", Box{}.halfExtents);
        if ((h.array() <= 0).any())
            failAt(o.pathOf("halfExtents"), "every half extent must be > 0 (got [", h.x(), ", ",
                   h.y(), ", ", h.z(), "])");
        return Box{h};
    }
    if (type == "capsule")
        return Capsule{o.positive("radius", Capsule{}.radius),
                       o.positive("halfLength", Capsule{}.halfLength, true)};
    if (type == "cylinder")
        return Cylinder{o.positive("radius", Cylinder{}.radius),
                        o.positive("halfLength", Cylinder{}.halfLength)};
    if (type == "half-space") {
        const Vec3 n = o.vec3("normal", Vec3::UnitZ());
        if (n.norm() < 1e-12)
            failAt(o.pathOf("normal"), "must not be zero");
        return HalfSpace{n.normalized(), o.number("offset", 0)};
    }
    // hull
    const Json* points = o.find("points");
    if (points == nullptr || !points->is_array())
        failAt(o.pathOf("points"), "expected an array of [x, y, z] points");
    std::vector<Vec3> cloud;
    for (std::size_t i = 0; i < points->size(); ++i)
        cloud.push_back(readVec3((*points)[i], indexPath(o.pathOf("points"), i)));
    try {
        return ConvexHull::fromPoints(cloud);
    } catch (const InvalidArgument& e) {
        failAt(o.pathOf("points"), e.what());
    }
}

}  // namespace

ShapeDef parseShape(const Json& value, const std::string& path, const Materials& materials,
                    const ShapeSource& source) {
    JsonObject o(value, path);
    if (!o.has("type"))
        failAt(o.pathOf("type"), "is required");
    const std::string type = o.choice(
        "type", "",
        {"sphere", "box", "capsule", "cylinder", "half-space", "hull", "mesh", "heightField"});
    ShapeDef def;
    def.geometry = parseGeometry(o, type, source);
    def.localPose.position = o.vec3("position", Vec3::Zero());
    def.localPose.rotation = o.orientation("orientation");
    def.material = materialAt(o, "material", materials);
    def.filter = parseFilter(o);
    o.finish();
    return def;
}

CollisionFilter parseFilter(JsonObject& o) {
    CollisionFilter filter;
    if (!o.has("filter"))
        return filter;
    JsonObject f = o.object("filter");
    for (const auto& [key, bits] :
         {std::pair{"category", &filter.category}, {"mask", &filter.mask}}) {
        const Json* v = f.find(key);
        if (v == nullptr)
            continue;
        if (!v->is_number_integer() || v->get<long long>() < 0 ||
            v->get<long long>() > 0xFFFFFFFFll)
            failAt(f.pathOf(key), "expected an integer in [0, 4294967295] (a bit mask)");
        *bits = static_cast<std::uint32_t>(v->get<long long>());
    }
    f.finish();
    return filter;
}

namespace {

BodySpec parseBody(const Json& value, const std::string& path, std::size_t index,
                   const Materials& materials, const ShapeSource& source) {
    JsonObject o(value, path);
    BodySpec b;
    b.path = path;
    b.name = o.string("name", "body" + std::to_string(index));
    const std::string type = o.choice("type", "dynamic", {"dynamic", "static", "kinematic"});
    b.def.type = type == "static"      ? BodyType::Static
                 : type == "kinematic" ? BodyType::Kinematic
                                       : BodyType::Dynamic;
    b.def.position = o.vec3("position", Vec3::Zero());
    b.def.orientation = o.orientation("orientation");
    b.def.linearVelocity = o.vec3("linearVelocity", Vec3::Zero());
    b.def.angularVelocity = o.vec3("angularVelocity", Vec3::Zero());
    b.def.linearDamping = o.positive("linearDamping", 0, true);
    b.def.angularDamping = o.positive("angularDamping", 0, true);
    b.def.gravityScale = o.number("gravityScale", 1);
    b.def.allowSleep = o.boolean("allowSleep", true);
    b.def.awake = o.boolean("awake", true);
    b.def.fixedRotation = o.boolean("fixedRotation", false);
    if (o.has("mass")) {
        b.mass = o.positive("mass", 1);
        if (b.def.type != BodyType::Dynamic)
            failAt(o.pathOf("mass"), "only a dynamic body has a mass");
    }
    if (const Json* shapes = o.find("shapes")) {
        if (!shapes->is_array())
            failAt(o.pathOf("shapes"), "expected an array, got ", typeName(*shapes));
        for (std::size_t i = 0; i < shapes->size(); ++i)
            b.shapes.push_back(
                parseShape((*shapes)[i], indexPath(o.pathOf("shapes"), i), materials, source));
    }
    if (b.mass && b.shapes.empty())
        failAt(o.pathOf("mass"), "needs shapes to take its inertia from");
    if (const Json* drag = o.find("drag")) {
        if (b.def.type != BodyType::Dynamic)
            failAt(o.pathOf("drag"), "only a dynamic body feels drag");
        b.drag = parseDrag(*drag, o.pathOf("drag"));
    }
    o.finish();
    return b;
}

/// A list of body selections (see selectBodies): indices or strings.
std::vector<int> parseSelection(JsonObject& o, const std::string& key, const Scene& scene) {
    const Json* list = o.find(key);
    if (list == nullptr)
        return {};
    if (!list->is_array())
        failAt(o.pathOf(key), "expected an array of body indices, names or \"<net>.corners\"");
    std::vector<int> out;
    for (std::size_t i = 0; i < list->size(); ++i) {
        const Json& item = (*list)[i];
        if (!item.is_string() && !item.is_number_integer())
            failAt(indexPath(o.pathOf(key), i), "expected a body index or name, got ",
                   typeName(item));
        const std::string text =
            item.is_string() ? item.get<std::string>() : std::to_string(item.get<long long>());
        for (const int b : selectBodies(scene, {text}, indexPath(o.pathOf(key), i)))
            out.push_back(b);
    }
    return out;
}

OutputSpec parseOutputs(JsonObject o, const Scene& scene) {
    OutputSpec out;
    out.record = o.string("record", "");
    out.recordRate = o.positive("recordRate", 0, true);
    out.recordBodies = parseSelection(o, "recordBodies", scene);
    out.summary = o.string("summary", "");
    out.picture = o.string("picture", "");
    if (const Json* times = o.find("pictureTimes")) {
        if (!times->is_array() || times->empty() || times->size() > 12)
            failAt(o.pathOf("pictureTimes"), "expected an array of 1 to 12 times (s)");
        for (std::size_t i = 0; i < times->size(); ++i) {
            const Json& t = (*times)[i];
            // Times past the end draw the end, so --time can shorten a run that names them.
            if (!t.is_number() || !(t.get<Real>() >= 0))
                failAt(indexPath(o.pathOf("pictureTimes"), i), "expected a time >= 0 (s)");
            out.pictureTimes.push_back(t.get<Real>());
        }
    }
    out.view = o.choice("view", "side", {"side", "top", "front"});
    out.trace = parseSelection(o, "trace", scene);
    o.finish();
    return out;
}

Materials parseMaterials(JsonObject o, const Json& document) {
    Materials materials;
    if (const auto it = document.find("materials"); it != document.end()) {
        for (const auto& [name, value] : it->items())
            materials[name] = parseMaterial(value, o.pathOf(name));
        for (const auto& [name, value] : it->items())
            o.has(name);
    }
    o.finish();
    return materials;
}

}  // namespace

Scene parseScene(const Json& document, const std::string& name, const std::string& directory) {
    JsonObject root(document, "");
    Scene scene;
    scene.name = name;
    const ShapeSource source{directory, &scene.warnings};
    scene.description = root.string("description", "");
    scene.duration = root.positive("duration", scene.duration);
    scene.world = parseWorld(root.object("world"));
    const Materials materials = parseMaterials(root.object("materials"), document);
    if (const Json* bodies = root.find("bodies")) {
        if (!bodies->is_array())
            failAt("bodies", "expected an array, got ", typeName(*bodies));
        for (std::size_t i = 0; i < bodies->size(); ++i)
            scene.bodies.push_back(parseBody((*bodies)[i], indexPath("bodies", i),
                                             scene.bodies.size(), materials, source));
    }
    if (const Json* generators = root.find("generators")) {
        if (!generators->is_array())
            failAt("generators", "expected an array, got ", typeName(*generators));
        for (std::size_t i = 0; i < generators->size(); ++i)
            parseGenerator((*generators)[i], indexPath("generators", i), materials, scene);
    }
    if (const Json* springs = root.find("springs"))
        parseSprings(*springs, scene);
    if (const Json* joints = root.find("joints"))
        parseJoints(*joints, scene);
    scene.outputs = parseOutputs(root.object("outputs"), scene);
    root.finish();
    return scene;
}

std::vector<int> selectBodies(const Scene& scene, const std::vector<std::string>& items,
                              const std::string& where) {
    const auto count = static_cast<long long>(scene.bodies.size());
    std::vector<int> out;
    for (const std::string& item : items) {
        if (!item.empty() && std::all_of(item.begin(), item.end(), ::isdigit)) {
            const long long index = item.size() > 12 ? count : std::stoll(item);
            if (index >= count)
                failAt(where, "no body with index ", item, " (the scene has bodies 0 to ",
                       count - 1, ")");
            out.push_back(static_cast<int>(index));
            continue;
        }
        const std::string corners = ".corners";
        if (item.size() > corners.size() &&
            item.compare(item.size() - corners.size(), corners.size(), corners) == 0) {
            const std::string net = item.substr(0, item.size() - corners.size());
            const auto it =
                std::find_if(scene.lumped.begin(), scene.lumped.end(), [&](const LumpedSpec& l) {
                    return l.name == net && std::holds_alternative<NetDef>(l.def);
                });
            if (it == scene.lumped.end())
                failAt(where, "\"", item, "\": no net generator named \"", net, "\"");
            const NetDef& def = std::get<NetDef>(it->def);
            const int first = static_cast<int>(it->firstBody), m = def.columns;
            const int last = def.rows * m - 1;
            // Lumped::corners' order: (0,0), (0,m-1), (n-1,0), (n-1,m-1).
            for (const int k : {0, m - 1, last - (m - 1), last})
                out.push_back(first + k);
            continue;
        }
        const std::size_t before = out.size();
        for (std::size_t i = 0; i < scene.bodies.size(); ++i) {
            if (scene.bodies[i].name == item)
                out.push_back(static_cast<int>(i));
        }
        if (out.size() == before)
            failAt(where, "no body named \"", item, "\" (give an index, a name, or ",
                   "\"<net>.corners\")");
    }
    return out;
}

namespace {

/// The assignment of `overrides` that set the value at `path` (loader notation,
/// "bodies[0].position"), or null.
const std::string* overrideOf(const std::vector<std::string>& overrides, const std::string& path) {
    for (const std::string& assignment : overrides) {
        std::string key;  // "bodies.0.position" -> "bodies[0].position"
        std::stringstream segments(assignment.substr(0, assignment.find('=')));
        for (std::string part; std::getline(segments, part, '.');) {
            const bool index = !part.empty() && part.find_first_not_of("0123456789") == part.npos;
            key += index ? "[" + part + "]" : (key.empty() ? "" : ".") + part;
        }
        if (path.rfind(key, 0) == 0 &&
            (path.size() == key.size() || path[key.size()] == '.' || path[key.size()] == '['))
            return &assignment;
    }
    return nullptr;
}

/// The path of the file's key that an API refusal names: the engine's messages start with the
/// definition's field ("BodyDef.linearVelocity = ..."), and the file's keys are named after those
/// fields. `path` itself when the message names none the file has.
std::string fieldPath(const Scene& scene, const std::string& path, const std::string& message,
                      const std::string& definition) {
    if (message.rfind(definition, 0) != 0)
        return path;
    const std::size_t end = message.find_first_of(" =:.", definition.size());
    const std::string key = path + "." + message.substr(definition.size(), end - definition.size());
    return scene.lines.count(key) != 0 ? key : path;
}

}  // namespace

Json readJsonFile(const std::string& path, JsonLines* lines) {
    std::ifstream in(path, std::ios::binary);
    if (!in)
        fail(path, ": cannot open the file");
    std::stringstream buffer;
    buffer << in.rdbuf();
    const std::string text = buffer.str();
    JsonLines scratch;
    JsonLines& where = lines != nullptr ? *lines : scratch;
    try {
        return parseJson(text, where);
    } catch (const JsonError& e) {  // a duplicate key
        fail(path, ":", lineOf(where, e.path()), ": ", e.what());
    } catch (const Json::parse_error& e) {
        // nlohmann gives a byte offset (1-based, one past the offending byte); people want lines.
        const std::size_t end = std::min<std::size_t>(e.byte == 0 ? 0 : e.byte - 1, text.size());
        const auto line = 1 + std::count(text.begin(), text.begin() + end, '\n');
        const std::size_t lineStart = text.rfind('\n', end == 0 ? 0 : end - 1);
        const std::size_t column = lineStart == std::string::npos ? end + 1 : end - lineStart;
        // Drop nlohmann's "[json.exception...] parse error at line L, column C: " prefix.
        std::string what = e.what();
        if (const std::size_t at = what.find("parse error"); at != std::string::npos) {
            const std::size_t colon = what.find(": ", at);
            what = what.substr(colon == std::string::npos ? at : colon + 2);
        }
        fail(path, ":", line, ":", column, ": JSON syntax error: ", what);
    } catch (const Json::exception& e) {
        // A number beyond a double's range ("1e400") is no syntax error to nlohmann but an
        // out_of_range (406) without a position; its message quotes the number. Found by
        // fuzz/scene_loader_fuzz: it used to escape as a foreign exception and end the process.
        std::string what = e.what();
        if (const std::size_t at = what.find("] "); at != std::string::npos)
            what = what.substr(at + 2);
        fail(path, ": JSON value out of range: ", what);
    }
}

void applyOverride(Json& document, const std::string& assignment) {
    const std::size_t eq = assignment.find('=');
    if (eq == std::string::npos || eq == 0)
        fail("--set ", assignment, ": expected key=value (e.g. world.solver.iterations=20)");
    const std::string key = assignment.substr(0, eq);
    const std::string text = assignment.substr(eq + 1);
    Json value = Json::parse(text, nullptr, false);
    if (value.is_discarded())
        value = text;
    Json* at = &document;
    std::stringstream segments(key);
    std::string segment;
    std::vector<std::string> parts;
    while (std::getline(segments, segment, '.'))
        parts.push_back(segment);
    for (std::size_t i = 0; i < parts.size(); ++i) {
        const std::string& part = parts[i];
        const bool numeric = !part.empty() && std::all_of(part.begin(), part.end(), [](char c) {
            return c >= '0' && c <= '9';  // not ::isdigit: a negative char is undefined there
        });
        if (at->is_array()) {
            // At most 18 digits: std::stoul would throw std::out_of_range beyond unsigned long.
            if (!numeric || part.size() > 18 || std::stoul(part) >= at->size())
                fail("--set ", key, ": \"", part, "\" is not an index of an array of ", at->size());
            at = &(*at)[std::stoul(part)];
        } else {
            if (part.empty())
                fail("--set ", key, ": empty key segment");
            if (at->is_null())
                *at = Json::object();
            if (!at->is_object())
                fail("--set ", key, ": \"", part, "\" is inside ", typeName(*at));
            at = &(*at)[part];
        }
        if (i + 1 == parts.size())
            *at = value;
    }
}

std::string sceneDirectory(const std::string& argv0) {
    namespace fs = std::filesystem;
    if (const char* env = std::getenv("TUMBLE_SCENE_DIR"))
        return env;
    if (!argv0.empty()) {
        std::error_code ec;
        const fs::path exe = fs::canonical(fs::path(argv0), ec);
        if (!ec) {
            for (const fs::path& p : {exe.parent_path() / "scenes",
                                      exe.parent_path() / ".." / "share" / "tumble" / "scenes"})
                if (fs::is_directory(p))
                    return p.string();
        }
    }
    return TUMBLE_SOURCE_SCENE_DIR;
}

std::vector<std::string> builtinScenes(const std::string& directory) {
    namespace fs = std::filesystem;
    std::vector<std::string> names;
    std::error_code ec;
    for (const auto& entry : fs::directory_iterator(directory, ec)) {
        if (entry.path().extension() == ".json")
            names.push_back(entry.path().stem().string());
    }
    std::sort(names.begin(), names.end());
    return names;
}

Scene loadScene(const std::string& nameOrFile, const std::vector<std::string>& overrides,
                const std::string& directory) {
    namespace fs = std::filesystem;
    const bool isFile =
        nameOrFile.find('/') != std::string::npos || fs::path(nameOrFile).extension() == ".json";
    std::string path = nameOrFile;
    if (!isFile) {
        path = (fs::path(directory) / (nameOrFile + ".json")).string();
        if (!fs::exists(path)) {
            std::string list;
            for (const std::string& n : builtinScenes(directory))
                list += (list.empty() ? "" : ", ") + n;
            fail("unknown scene \"", nameOrFile, "\" (built-in scenes: ", list,
                 "; a file must end in .json)");
        }
    }
    JsonLines lines;
    Json document = readJsonFile(path, &lines);
    // Before any option is applied: an option given to a document that is no scene would be
    // blamed for it.
    if (!document.is_object())
        fail(path, ":", lineOf(lines, ""), ": (top level): a scene is a JSON object {...}, got ",
             typeName(document));
    for (const std::string& o : overrides)
        applyOverride(document, o);
    try {
        Scene scene = parseScene(document, fs::path(path).stem().string(),
                                 fs::path(path).parent_path().string());
        scene.source = path;
        scene.lines = std::move(lines);
        return scene;
    } catch (const JsonError& e) {
        if (const std::string* set = overrideOf(overrides, e.path()))
            fail(path, ": ", e.what(), " (the value of --set ", *set, ")");
        fail(path, ":", lineOf(lines, e.path()), ": ", e.what());
    } catch (const InvalidArgument& e) {
        fail(path, ": ", e.what());
    }
}

std::string located(const Scene& scene, const std::string& path) {
    std::string out = scene.source;
    if (const int line = lineOf(scene.lines, path); line > 0)
        out.append(":").append(std::to_string(line));
    return out.append(": ").append(path);
}

BuiltScene buildScene(const Scene& scene) {
    std::optional<World> made;
    try {
        made.emplace(scene.world);
    } catch (const InvalidArgument& e) {
        fail(scene.source, ": world: ", e.what());
    }
    BuiltScene built{std::move(*made), {}, {}, {}, {}, {}};
    World& world = built.world;
    for (const BodySpec& spec : scene.bodies) {
        if (spec.lumped >= 0) {
            // The engine's generator makes all of a string's or net's nodes at its first one.
            const LumpedSpec& lumped = scene.lumped[static_cast<std::size_t>(spec.lumped)];
            if (built.bodies.size() == lumped.firstBody)
                buildLumped(scene, lumped, built);
            continue;
        }
        try {
            const BodyId body = world.createBody(spec.def);
            for (const ShapeDef& shape : spec.shapes)
                built.shapes.push_back(world.createShape(body, shape));
            if (spec.mass) {
                MassProperties mass = world.massProperties(body);
                const Real scale = *spec.mass / mass.mass;
                mass.mass = *spec.mass;
                mass.inertia *= scale;
                world.setMassProperties(body, mass);
            }
            if (spec.drag)
                world.setDrag(body, *spec.drag);
            built.bodies.push_back(body);
            built.gravityScale.push_back(spec.def.gravityScale);
        } catch (const InvalidArgument& e) {
            fail(located(scene, fieldPath(scene, spec.path, e.what(), "BodyDef.")), " (\"",
                 spec.name, "\"): ", e.what());
        }
    }
    buildConnections(scene, built);
    return built;
}

}  // namespace tumble::cli
