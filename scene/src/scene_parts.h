#pragma once
/// Pieces of the scene parser shared between scene_loader.cpp and generators.cpp.

#include <map>
#include <string>
#include <vector>

#include "tumble/collision/mesh_data.h"
#include "tumble/scene/json_reader.h"
#include "tumble/scene/scene.h"

namespace tumble::cli {

using Materials = std::map<std::string, Material>;

/// Most bodies a scene file may make (bodies plus generators): far above any scene the engine
/// steps at a useful rate, far below what exhausts memory (~0.5 kB per body while loading).
inline constexpr double kMaxSceneBodies = 1'000'000;

/// {"friction", "restitution", "density"}, checked: friction >= 0, restitution in [0, 1],
/// density > 0. Missing keys take `base`'s values.
Material parseMaterial(const Json& value, const std::string& path, const Material& base = {});

/// The member `key` of `o`: a material name from `materials`, or an inline material object.
/// Absent: the scene's "default" material when it has one, else the engine's defaults.
Material materialAt(JsonObject& o, const std::string& key, const Materials& materials);

/// The member "filter": {"category": bits, "mask": bits}, each an integer in [0, 2^32).
CollisionFilter parseFilter(JsonObject& o);

/// Where a shape's files are found (relative names: beside the scene file) and where its load
/// warnings go (Scene::warnings).
struct ShapeSource {
    std::string directory;                         ///< "" : the working directory
    std::vector<std::string>* warnings = nullptr;  ///< null: dropped
};

/// One shape of a body: {"type", geometry keys, "position", "orientation", "material",
/// "filter"}.
ShapeDef parseShape(const Json& value, const std::string& path, const Materials& materials,
                    const ShapeSource& source = {});

/// A "mesh" shape's geometry (mesh_shapes.cpp): "vertices" and "triangles", or "file" (.obj,
/// .stl). Checked (mesh_io.h); refusals name the key or element.
TriangleMeshData parseMeshData(JsonObject& o, const ShapeSource& source);
/// A "heightField" shape's geometry: "heights" (rows) and "spacing", or "file" (a PNG),
/// "spacing", "heightScale", "heightOffset".
HeightFieldData parseHeightFieldData(JsonObject& o, const ShapeSource& source);
/// The Shape of checked mesh data; a refusal is re-thrown at `path`, dropped degenerate triangles
/// go to `source.warnings`.
Shape meshShape(const TriangleMeshData& mesh, const ShapeSource& source, const std::string& path);
Shape heightFieldShape(const HeightFieldData& field, const std::string& path);

/// Appends the bodies of one generator ("stack", "pyramid", "wall", "grid", "string", "net")
/// to scene.bodies (and a string's or net's description to scene.lumped).
void parseGenerator(const Json& value, const std::string& path, const Materials& materials,
                    Scene& scene);

/// A string or net generator (lumped_generators.cpp); `o` has had "type" and "name" read.
void parseLumped(JsonObject& o, const std::string& type, const std::string& name,
                 const Materials& materials, Scene& scene);

/// The member "formulation": "implicit", "backward-euler" or "explicit".
SpringFormulation parseFormulation(JsonObject& o, SpringFormulation fallback);
/// The member "numericalDamping", in [0, 1] (SpringDef::numericalDamping).
Real parseNumericalDamping(JsonObject& o, Real fallback);

/// {"linear": N s/m, "quadratic": N s^2/m^2, "projection": [a, b, c] (diagonal) or 3 rows}.
Drag parseDrag(const Json& value, const std::string& path);

/// "springs" and "joints" (connections.cpp), read after every body so they can name any.
void parseSprings(const Json& value, Scene& scene);
void parseJoints(const Json& value, Scene& scene);

/// Creates a string's or net's nodes and threads, appending them to built.bodies (and its
/// colliding nodes' spheres to built.shapes, its threads to built.springs).
void buildLumped(const Scene& scene, const LumpedSpec& spec, BuiltScene& built);
/// Creates the springs and joints once every body exists.
void buildConnections(const Scene& scene, BuiltScene& built);

}  // namespace tumble::cli
