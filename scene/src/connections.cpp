// "springs", "joints" and "drag" of scene files. Bodies are named (or indexed) rather than
// nested, so a spring or joint can join any two bodies, generated ones included; every reference
// is resolved while parsing, so a joint to a missing body is refused before anything is built.

#include <cmath>
#include <numbers>

#include "scene_parts.h"

namespace tumble::cli {
namespace {

std::string indexPath(const std::string& path, std::size_t i) {
    return path + "[" + std::to_string(i) + "]";
}

/// The scene index of the body `o[key]` names: a name, unique in the scene, or an index.
int bodyAt(const Scene& scene, JsonObject& o, const std::string& key) {
    const Json* v = o.find(key);
    const std::size_t count = scene.bodies.size();
    if (v->is_number_integer()) {
        const long long index = v->get<long long>();
        if (index < 0 || index >= static_cast<long long>(count))
            failAt(o.pathOf(key), "no body with index ", index, " (the scene has ", count,
                   count == 1 ? " body)" : " bodies)");
        return static_cast<int>(index);
    }
    if (!v->is_string())
        failAt(o.pathOf(key), "expected a body name or index, got ", typeName(*v));
    const std::string name = v->get<std::string>();
    int found = -1;
    for (std::size_t i = 0; i < count; ++i) {
        if (scene.bodies[i].name != name)
            continue;
        if (found >= 0)
            failAt(o.pathOf(key), "more than one body is named \"", name,
                   "\" (give them distinct names, or use an index)");
        found = static_cast<int>(i);
    }
    if (found < 0)
        failAt(o.pathOf(key), "no body named \"", name, "\"");
    return found;
}

/// bodyA (required) and bodyB (absent: the world), which must differ.
std::pair<int, int> bodiesOf(const Scene& scene, JsonObject& o) {
    if (!o.has("bodyA"))
        failAt(o.pathOf("bodyA"), "is required (a body name or index)");
    const int a = bodyAt(scene, o, "bodyA");
    const int b = o.has("bodyB") ? bodyAt(scene, o, "bodyB") : -1;
    if (a == b)
        failAt(o.pathOf("bodyB"), "is the same body as bodyA (\"", scene.bodies[a].name,
               "\"); leave it out to anchor to the world");
    return {a, b};
}

SpringSpec parseSpring(const Json& value, const std::string& path, const Scene& scene) {
    JsonObject o(value, path);
    SpringSpec s;
    s.path = path;
    std::tie(s.bodyA, s.bodyB) = bodiesOf(scene, o);
    s.def.localAnchorA = o.vec3("anchorA", Vec3::Zero());
    if (s.bodyB < 0 && !o.has("anchorB"))
        failAt(o.pathOf("anchorB"),
               "is required without bodyB: the world point (m) the spring "
               "is anchored at");
    s.def.localAnchorB = o.vec3("anchorB", Vec3::Zero());
    s.restLengthFromPose = !o.has("restLength");
    if (!s.restLengthFromPose)
        s.def.restLength = o.positive("restLength", 1);
    const bool modulus = o.has("youngsModulus") || o.has("area");
    if (modulus == o.has("stiffness"))
        failAt(o.path(),
               "give \"stiffness\" k (N/m) or \"youngsModulus\" (Pa) and \"area\" (m^2), ",
               modulus ? "not both" : "one of them");
    if (modulus) {
        if (!o.has("youngsModulus") || !o.has("area"))
            failAt(o.path(), "\"youngsModulus\" (Pa) and \"area\" (m^2) go together");
        s.youngsModulusAndArea.emplace(o.positive("youngsModulus", 0), o.positive("area", 0));
    } else {
        s.def.stiffness = o.number("stiffness", 0);
        if (s.def.stiffness < 0)
            failAt(o.pathOf("stiffness"), "k = ", s.def.stiffness, " N/m must be >= 0");
    }
    s.def.damping = o.positive("damping", 0, true);
    s.def.tensionOnly = o.boolean("tensionOnly", false);
    s.def.formulation = parseFormulation(o, s.def.formulation);
    s.def.numericalDamping = parseNumericalDamping(o, s.def.numericalDamping);
    o.finish();
    return s;
}

JointType jointType(JsonObject& o) {
    if (!o.has("type"))
        failAt(o.pathOf("type"), "is required");
    const std::string t = o.choice("type", "", {"ball", "hinge", "slider", "fixed", "distance"});
    return t == "ball"     ? JointType::Ball
           : t == "hinge"  ? JointType::Hinge
           : t == "slider" ? JointType::Slider
           : t == "fixed"  ? JointType::Fixed
                           : JointType::Distance;
}

Vec3 requiredVec3(JsonObject& o, const std::string& key, const char* what) {
    if (!o.has(key))
        failAt(o.pathOf(key), "is required: ", what);
    return o.vec3(key, Vec3::Zero());
}

/// A hinge's (rad, N m) or slider's (m, N) PD/PID controller; see tumble/control.h.
ControllerDef parseController(const Json& value, const std::string& path) {
    JsonObject o(value, path);
    ControllerDef c;
    c.mode = o.choice("mode", "position", {"position", "velocity"}) == "position"
                 ? ControlMode::Position
                 : ControlMode::Velocity;
    c.target = o.number("target", 0);
    c.targetVelocity = o.number("targetVelocity", 0);
    c.kp = o.positive("kp", 0, true);
    c.ki = o.positive("ki", 0, true);
    c.kd = o.positive("kd", 0, true);
    if (o.has("maxForce"))
        c.maxForce = o.positive("maxForce", 0);
    o.finish();
    return c;
}

/// Axis, limits, motor and controller of a hinge (angles in rad) or slider (m).
void parseAxial(JsonObject& o, JointSpec& spec) {
    JointDef& def = spec.def;
    const bool hinge = def.type == JointType::Hinge;
    def.axis = o.vec3("axis", def.axis);
    if (def.axis.norm() < 1e-9)
        failAt(o.pathOf("axis"), "a ", hinge ? "hinge" : "slider", "'s axis must not be zero");
    if (o.has("limits")) {
        JsonObject limits = o.object("limits");
        def.enableLimit = true;
        def.lower = limits.number("lower");
        def.upper = limits.number("upper");
        limits.finish();
        if (def.lower > def.upper)
            failAt(limits.path(), "lower = ", def.lower, " > upper = ", def.upper,
                   ": lower must be <= upper (equal locks the joint)");
        const Real pi = std::numbers::pi_v<Real>;
        if (hinge && (def.lower < -pi || def.upper > pi))
            failAt(limits.path(), "a hinge's limits (rad) must lie in [-pi, pi] (got [", def.lower,
                   ", ", def.upper, "])");
    }
    if (o.has("motor")) {
        JsonObject motor = o.object("motor");
        def.enableMotor = true;
        def.motorSpeed = motor.number("speed", 0);
        def.maxMotorForce = motor.positive("maxForce", 0, true);
        motor.finish();
    }
    if (const Json* controller = o.find("controller"))
        spec.controller = parseController(*controller, o.pathOf("controller"));
}

JointSpec parseJoint(const Json& value, const std::string& path, const Scene& scene) {
    JsonObject o(value, path);
    JointSpec j;
    j.path = path;
    JointDef& def = j.def;
    def.type = jointType(o);
    std::tie(j.bodyA, j.bodyB) = bodiesOf(scene, o);
    if (def.type == JointType::Distance) {
        def.anchor = requiredVec3(o, "anchor", "A's end of the rod or rope (m, world)");
        def.anchorB = requiredVec3(o, "anchorB", "B's end of the rod or rope (m, world)");
        if (o.has("length"))
            def.length = o.positive("length", 0);
        else if ((def.anchorB - def.anchor).norm() <= 0)
            failAt(o.pathOf("anchorB"),
                   "coincides with anchor: a distance joint needs a length "
                   "> 0 (use a ball joint to join two points)");
        def.rope = o.boolean("rope", false);
    } else {
        def.anchor = requiredVec3(o, "anchor", "where the bodies are joined (m, world)");
    }
    if (def.type == JointType::Hinge || def.type == JointType::Slider)
        parseAxial(o, j);
    def.breakForce = o.positive("breakForce", def.breakForce);
    def.breakTorque = o.positive("breakTorque", def.breakTorque);
    def.collideConnected = o.boolean("collideConnected", false);
    o.finish();
    return j;
}

template <typename Spec, typename Parse>
void parseList(const Json& value, const std::string& key, std::vector<Spec>& out, Parse parse) {
    if (!value.is_array())
        failAt(key, "expected an array, got ", typeName(value));
    for (std::size_t i = 0; i < value.size(); ++i)
        out.push_back(parse(value[i], indexPath(key, i)));
}

}  // namespace

SpringFormulation parseFormulation(JsonObject& o, SpringFormulation fallback) {
    const char* names[] = {"explicit", "implicit", "backward-euler"};
    const std::string f =
        o.choice("formulation", names[static_cast<int>(fallback)], {names[0], names[1], names[2]});
    return f == names[0]   ? SpringFormulation::Explicit
           : f == names[1] ? SpringFormulation::Implicit
                           : SpringFormulation::BackwardEuler;
}

Real parseNumericalDamping(JsonObject& o, Real fallback) {
    const Real value = o.positive("numericalDamping", fallback, true);
    if (value > 1)
        failAt(o.pathOf("numericalDamping"), value, " must be in [0, 1]");
    return value;
}

Drag parseDrag(const Json& value, const std::string& path) {
    JsonObject o(value, path);
    Drag drag;
    drag.linear = o.positive("linear", 0, true);
    drag.quadratic = o.positive("quadratic", 0, true);
    if (const Json* p = o.find("projection")) {
        const std::string at = o.pathOf("projection");
        if (p->is_array() && p->size() == 3 && (*p)[0].is_array()) {
            for (int r = 0; r < 3; ++r)
                drag.projection.row(r) = readVec3((*p)[r], indexPath(at, r)).transpose();
        } else if (p->is_array() && p->size() == 3) {
            drag.projection = readVec3(*p, at).asDiagonal();
        } else {
            failAt(at, "expected [a, b, c] (a diagonal) or three rows [[...], [...], [...]]");
        }
    }
    o.finish();
    return drag;
}

void parseSprings(const Json& value, Scene& scene) {
    parseList(value, "springs", scene.springs,
              [&](const Json& v, const std::string& path) { return parseSpring(v, path, scene); });
}

void parseJoints(const Json& value, Scene& scene) {
    parseList(value, "joints", scene.joints,
              [&](const Json& v, const std::string& path) { return parseJoint(v, path, scene); });
}

void buildConnections(const Scene& scene, BuiltScene& built) {
    World& world = built.world;
    const auto idOf = [&](int index) { return index < 0 ? BodyId{} : built.bodies[index]; };
    std::vector<SpringId> springs;
    for (const SpringSpec& spec : scene.springs) {
        try {
            SpringDef def = spec.def;
            def.bodyA = idOf(spec.bodyA);
            def.bodyB = idOf(spec.bodyB);
            if (spec.restLengthFromPose) {
                const Vec3 a = world.transform(def.bodyA).apply(def.localAnchorA);
                const Vec3 b = def.bodyB.isNull()
                                   ? def.localAnchorB
                                   : Vec3(world.transform(def.bodyB).apply(def.localAnchorB));
                def.restLength = (b - a).norm();
                if (!(def.restLength > 0))
                    fail("restLength: the anchors coincide at creation; give a restLength > 0");
            }
            if (spec.youngsModulusAndArea)
                def.stiffness = axialStiffness(spec.youngsModulusAndArea->first,
                                               spec.youngsModulusAndArea->second, def.restLength);
            springs.push_back(world.createSpring(def));
        } catch (const InvalidArgument& e) {
            fail(located(scene, spec.path), ": ", e.what());
        }
    }
    // "springs" first, then the threads the generators made.
    built.springs.insert(built.springs.begin(), springs.begin(), springs.end());
    for (const JointSpec& spec : scene.joints) {
        try {
            JointDef def = spec.def;
            def.bodyA = idOf(spec.bodyA);
            def.bodyB = idOf(spec.bodyB);
            built.joints.push_back(world.createJoint(def));
            if (spec.controller)
                world.setJointController(built.joints.back(), *spec.controller);
        } catch (const InvalidArgument& e) {
            fail(located(scene, spec.path), ": ", e.what());
        }
    }
}

}  // namespace tumble::cli
