// Generators: many boxes from one line of a scene file (stack, pyramid, wall, grid), and the
// shared material reader. Strings and nets are in lumped_generators.cpp.

#include <cmath>
#include <limits>
#include <numbers>

#include "scene_parts.h"

namespace tumble::cli {
namespace {

Vec3 readHalfExtents(JsonObject& o) {
    const Vec3 h = o.vec3("halfExtents", Vec3::Constant(0.5));
    if ((h.array() <= 0).any())
        failAt(o.pathOf("halfExtents"), "every half extent must be > 0");
    return h;
}

BodySpec makeBox(const std::string& name, const std::string& path, const Vec3& position,
                 const Vec3& halfExtents, const Material& material) {
    BodySpec b;
    b.name = name;
    b.path = path;
    b.def.position = position;
    b.shapes.push_back(ShapeDef{.geometry = Box{halfExtents}, .material = material});
    return b;
}

/// Unit vector of a row: "x" or "y".
Vec3 rowAxis(JsonObject& o) {
    return o.choice("axis", "x", {"x", "y"}) == "y" ? Vec3::UnitY() : Vec3::UnitX();
}

/// The counts of the box generators are bounded by the bodies they make (checkRoom), which says
/// more than a bound on each count would.
constexpr int kAnyCount = std::numeric_limits<int>::max();

/// Refuses a generator that would take the scene past kMaxSceneBodies, before any is made: a
/// mistyped count (1e8 boxes) must be an error message, not the machine running out of memory.
void checkRoom(const std::vector<BodySpec>& bodies, double more, const std::string& path) {
    if (static_cast<double>(bodies.size()) + more > kMaxSceneBodies)
        failAt(path, "would make ", static_cast<long long>(more),
               " bodies, taking the scene past its limit of ",
               static_cast<long long>(kMaxSceneBodies));
}

/// A 3-D grid of bodies, each carrying the next shape of "shapes" in turn, for piles of mixed
/// shapes ("rain"). With "rotate", body k is turned by k * 37 degrees about a fixed oblique axis
/// so that the shapes do not all land square.
void parseGrid(JsonObject& o, const std::string& path, const std::string& name,
               const Materials& materials, std::vector<BodySpec>& bodies) {
    const Vec3 countReal = o.vec3("count", Vec3(3, 3, 3));
    for (int i = 0; i < 3; ++i) {
        if (countReal[i] < 1 || countReal[i] != std::floor(countReal[i]) || countReal[i] > 1000)
            failAt(o.pathOf("count"), "expected three whole numbers in [1, 1000]");
    }
    const Vec3 spacing = o.vec3("spacing", Vec3::Constant(1));
    if ((spacing.array() <= 0).any())
        failAt(o.pathOf("spacing"), "every spacing must be > 0");
    const Vec3 base = o.vec3("position", Vec3::Zero());  // centre of the lowest layer
    const bool rotate = o.boolean("rotate", false);
    const Json* shapes = o.find("shapes");
    if (shapes == nullptr || !shapes->is_array() || shapes->empty())
        failAt(o.pathOf("shapes"), "expected a non-empty array of shapes");
    std::vector<ShapeDef> defs;
    for (std::size_t i = 0; i < shapes->size(); ++i)
        defs.push_back(parseShape((*shapes)[i], o.pathOf("shapes") + "[" + std::to_string(i) + "]",
                                  materials));
    checkRoom(bodies, countReal.prod(), path);
    const int nx = static_cast<int>(countReal.x()), ny = static_cast<int>(countReal.y()),
              nz = static_cast<int>(countReal.z());
    int k = 0;
    for (int z = 0; z < nz; ++z) {
        for (int y = 0; y < ny; ++y) {
            for (int x = 0; x < nx; ++x, ++k) {
                BodySpec b;
                b.name = name + "[" + std::to_string(bodies.size()) + "]";
                b.path = path;
                b.def.position = base + Vec3((x - 0.5 * (nx - 1)) * spacing.x(),
                                             (y - 0.5 * (ny - 1)) * spacing.y(), z * spacing.z());
                if (rotate)
                    b.def.orientation = Quat(Eigen::AngleAxis<Real>(
                        k * 37.0 * std::numbers::pi / 180, Vec3(1, 0.5, 0.3).normalized()));
                b.shapes.push_back(defs[static_cast<std::size_t>(k) % defs.size()]);
                bodies.push_back(std::move(b));
            }
        }
    }
}

}  // namespace

Material parseMaterial(const Json& value, const std::string& path, const Material& base) {
    JsonObject o(value, path);
    Material m = base;
    m.friction = o.number("friction", m.friction);
    if (m.friction < 0)
        failAt(o.pathOf("friction"), "friction coefficient mu = ", m.friction, " must be >= 0");
    m.restitution = o.number("restitution", m.restitution);
    if (m.restitution < 0 || m.restitution > 1)
        failAt(o.pathOf("restitution"), "restitution e = ", m.restitution, " must be in [0, 1]");
    m.spinningFriction = o.number("spinningFriction", m.spinningFriction);
    if (m.spinningFriction < 0) {
        failAt(o.pathOf("spinningFriction"), "spinning friction length = ", m.spinningFriction,
               " m must be >= 0");
    }
    m.rollingFriction = o.number("rollingFriction", m.rollingFriction);
    if (m.rollingFriction < 0) {
        failAt(o.pathOf("rollingFriction"), "rolling friction length = ", m.rollingFriction,
               " m must be >= 0");
    }
    m.density = o.number("density", m.density);
    if (m.density <= 0)
        failAt(o.pathOf("density"), "density = ", m.density, " kg/m^3 must be > 0");
    o.finish();
    return m;
}

Material materialAt(JsonObject& o, const std::string& key, const Materials& materials) {
    const Json* v = o.find(key);
    const auto fallback = materials.find("default");
    const Material base = fallback == materials.end() ? Material{} : fallback->second;
    if (v == nullptr)
        return base;
    if (v->is_string()) {
        const auto it = materials.find(v->get<std::string>());
        if (it == materials.end())
            failAt(o.pathOf(key), "no material named \"", v->get<std::string>(),
                   "\" in \"materials\"");
        return it->second;
    }
    return parseMaterial(*v, o.pathOf(key), base);
}

void parseGenerator(const Json& value, const std::string& path, const Materials& materials,
                    Scene& scene) {
    std::vector<BodySpec>& bodies = scene.bodies;
    JsonObject o(value, path);
    if (!o.has("type"))
        failAt(o.pathOf("type"), "is required");
    const std::string type =
        o.choice("type", "", {"stack", "pyramid", "wall", "grid", "string", "net"});
    const std::string name = o.string("name", type);
    if (type == "string" || type == "net") {
        parseLumped(o, type, name, materials, scene);
        o.finish();
        return;
    }
    if (type == "grid") {
        parseGrid(o, path, name, materials, bodies);
        o.finish();
        return;
    }
    const Vec3 h = readHalfExtents(o);
    const Vec3 base = o.vec3("position", Vec3::Zero());  // centre of the bottom face
    const Real gap = o.positive("gap", 0, true);
    const Material material = materialAt(o, "material", materials);
    auto add = [&](const Vec3& position) {
        const std::string n = name + "[" + std::to_string(bodies.size()) + "]";
        bodies.push_back(makeBox(n, path, position, h, material));
    };
    if (type == "stack") {
        // A column, bottom first; `gap` (m) of air between blocks drops them onto each other.
        const int count = o.integer("count", 5, 1, kAnyCount);
        checkRoom(bodies, count, path);
        for (int i = 0; i < count; ++i)
            add(base + Vec3(0, 0, h.z() + i * (2 * h.z() + gap)));
    } else if (type == "pyramid") {
        // Row j holds base - j boxes, centred; `gap` (m) between neighbours of a row.
        const int count = o.integer("base", 5, 1, kAnyCount);
        checkRoom(bodies, 0.5 * count * (count + 1.0), path);
        const Vec3 axis = rowAxis(o);
        const Real pitch = 2 * h.dot(axis) + gap;
        for (int row = 0; row < count; ++row) {
            const int n = count - row;
            for (int i = 0; i < n; ++i)
                add(base + axis * ((i - 0.5 * (n - 1)) * pitch) +
                    Vec3(0, 0, h.z() * (1 + 2 * row)));
        }
    } else {
        // Rows of bricks; a "running" bond shifts every other row by half a brick, as masons do.
        const int rows = o.integer("rows", 5, 1, kAnyCount);
        const int columns = o.integer("columns", 8, 1, kAnyCount);
        checkRoom(bodies, static_cast<double>(rows) * columns, path);
        const Vec3 axis = rowAxis(o);
        const bool running = o.choice("bond", "running", {"running", "stack"}) == "running";
        const Real pitch = 2 * h.dot(axis) + gap;
        for (int row = 0; row < rows; ++row) {
            const Real shift = running && row % 2 == 1 ? 0.5 * pitch : 0;
            for (int i = 0; i < columns; ++i)
                add(base +
                    axis * ((i - 0.5 * (columns - 1)) * pitch + shift -
                            0.25 * pitch * (running ? 1 : 0)) +
                    Vec3(0, 0, h.z() * (1 + 2 * row)));
        }
    }
    o.finish();
}

}  // namespace tumble::cli
