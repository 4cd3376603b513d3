#pragma once
/// A scene: what a scene file describes (docs/scene-format.md), parsed and checked, and the world
/// built from it. Loading refuses a bad file with an InvalidArgument naming the JSON path, before
/// anything is built or written.

#include <optional>
#include <string>
#include <variant>
#include <vector>

#include "tumble/lumped.h"
#include "tumble/scene/json_reader.h"
#include "tumble/tumble.h"

namespace tumble::cli {

/// One body of a scene, from the "bodies" list or from a generator.
struct BodySpec {
    std::string name;  ///< "ball", or "stack[3]" for a generated body
    std::string path;  ///< JSON path, for messages: "bodies[2]", "generators[0]"
    BodyDef def;       ///< pose, velocities, damping, type
    std::vector<ShapeDef> shapes;
    std::optional<Real> mass;  ///< (kg) scales the shapes' mass and inertia to this
    std::optional<Drag> drag;  ///< aerodynamic drag on the centre of mass
    /// Index in Scene::lumped when a string or net generator makes this body (buildScene creates
    /// it through tumble/lumped.h; def and shapes are unused), else -1.
    int lumped = -1;
};

/// A string or net generator. Its nodes are listed in Scene::bodies (for names, indices and
/// outputs) from firstBody on, in the engine's order: along the string, or row-major over the net.
struct LumpedSpec {
    std::string name;  ///< "net": nodes "net[i][j]", corners selectable as "net.corners"
    std::string path;  ///< "generators[1]"
    std::variant<StringDef, NetDef> def;
    std::size_t firstBody = 0;
    std::size_t nodeCount = 0;
    /// Initial velocities that replace the generator's for single nodes (node index, m/s).
    std::vector<std::pair<int, Vec3>> excite;
};

/// One spring-damper of "springs". Body indices are scene indices; -1 is the world.
struct SpringSpec {
    std::string path;  ///< "springs[2]"
    int bodyA = -1;
    int bodyB = -1;                   ///< -1: def.localAnchorB is a world point
    SpringDef def;                    ///< bodies filled in by buildScene
    bool restLengthFromPose = false;  ///< L0 = the anchors' distance at creation
    /// k from E A / L0 (both > 0) instead of def.stiffness.
    std::optional<std::pair<Real, Real>> youngsModulusAndArea;
};

/// One joint of "joints"; anchors and axis in the world frame at creation, as in JointDef.
struct JointSpec {
    std::string path;  ///< "joints[0]"
    int bodyA = -1;
    int bodyB = -1;                           ///< -1: the world
    JointDef def;                             ///< bodies filled in by buildScene
    std::optional<ControllerDef> controller;  ///< hinges and sliders: a PD/PID controller
};

/// The scene's default outputs (each overridden by the command line).
struct OutputSpec {
    std::string record;              ///< CSV trajectories ("" = none)
    Real recordRate = 0;             ///< samples per second (Hz); 0 = every step
    std::string summary;             ///< JSON summary ("" = none)
    std::string picture;             ///< SVG picture ("" = none)
    std::vector<Real> pictureTimes;  ///< moments drawn (s); empty: start, middle and end
    std::string view = "side";
    std::vector<int> trace;         ///< body indices whose trajectories the picture draws
    std::vector<int> recordBodies;  ///< body indices the CSV holds; empty: every non-static one
};

struct Scene {
    std::string name;  ///< file stem or built-in name
    std::string description;
    std::string source;  ///< the file it came from, for messages
    JsonLines lines;     ///< the line of each value of that file, for messages
    WorldDef world;
    Real duration = 5;  ///< simulated time (s), > 0
    std::vector<BodySpec> bodies;
    std::vector<LumpedSpec> lumped;
    std::vector<SpringSpec> springs;
    std::vector<JointSpec> joints;
    OutputSpec outputs;
    /// What loading found legal but suspect (a mesh file's degenerate triangles, dropped), one
    /// line each, naming the shape; the command prints them with the world's warnings.
    std::vector<std::string> warnings;
};

/// A scene made real: the world and the ids of its bodies and shapes in scene order.
struct BuiltScene {
    World world;
    std::vector<BodyId> bodies;      ///< bodies[i] is scene.bodies[i]
    std::vector<ShapeId> shapes;     ///< every shape, grouped by body
    std::vector<Real> gravityScale;  ///< per body, for the potential energy
    std::vector<SpringId> springs;   ///< "springs", then every generator's threads
    std::vector<JointId> joints;     ///< joints[i] is scene.joints[i]
};

/// Parses a scene document (already overridden). `name` names it in messages; `directory` is
/// where the files it names (meshes, height fields) are found ("": the working directory).
Scene parseScene(const Json& document, const std::string& name, const std::string& directory = "");

/// Body selections for outputs and the command line: each item is a scene index ("3"), a body
/// name ("ball", "net[0][4]") or a net's corners ("net.corners", four bodies). `where` names the
/// list in messages ("outputs.trace[2]", "--trace").
std::vector<int> selectBodies(const Scene& scene, const std::vector<std::string>& items,
                              const std::string& where);

/// Reads a JSON file, recording the line of each value in `lines` when given; a syntax error
/// names the file, line and column, a key given twice in one object its line.
Json readJsonFile(const std::string& path, JsonLines* lines = nullptr);

/// Applies "dotted.path=value" to a document: the value is parsed as JSON when it can be
/// (numbers, true, [1,2,3]) and taken as a string otherwise; numeric segments index arrays;
/// missing objects on the way are created (the strict parser then refuses unknown keys).
void applyOverride(Json& document, const std::string& assignment);

/// The directory of the built-in scenes: $TUMBLE_SCENE_DIR, else scenes/ or ../share/tumble/scenes
/// beside the executable (`argv0`), else the source tree's demos/scenes.
std::string sceneDirectory(const std::string& argv0 = "");
/// Built-in scene names, sorted.
std::vector<std::string> builtinScenes(const std::string& directory);

/// Resolves a built-in name or a file path, reads it, applies the overrides and parses it.
Scene loadScene(const std::string& nameOrFile, const std::vector<std::string>& overrides,
                const std::string& directory);

/// "file:line: path" of a value of the scene's file, for messages after parsing ("file: path"
/// when the line is not known).
std::string located(const Scene& scene, const std::string& path);

/// Creates the world, bodies and shapes. World refusals are re-thrown with the body's path.
BuiltScene buildScene(const Scene& scene);

}  // namespace tumble::cli
