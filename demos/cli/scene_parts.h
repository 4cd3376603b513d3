#pragma once
/// Pieces of the scene parser shared between scene_loader.cpp and generators.cpp.

#include <map>
#include <string>
#include <vector>

#include "json_reader.h"
#include "scene.h"

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

/// One shape of a body: {"type", geometry keys, "position", "orientation", "material"}.
ShapeDef parseShape(const Json& value, const std::string& path, const Materials& materials);

/// Appends the bodies of one generator ("stack", "pyramid", "wall", "grid").
void parseGenerator(const Json& value, const std::string& path, const Materials& materials,
                    std::vector<BodySpec>& bodies);

}  // namespace tumble::cli
