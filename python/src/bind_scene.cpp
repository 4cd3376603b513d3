// Scene files (docs/scene-format.md) loaded into a World, and scenes run as `tumble run` runs them.
#include <sstream>

#include "bindings.h"
#include "command.h"
#include "tumble/scene/scene.h"

namespace tumble::python {
namespace {

/// A scene made real, for Python: the world and its ids in scene order.
struct PyBuilt {
    py::object world;
    std::vector<BodyId> bodies;
    std::vector<ShapeId> shapes;
    std::vector<SpringId> springs;
    std::vector<JointId> joints;
};

struct RunResult {
    int status = 0;
    std::string out;
    std::string err;
};

std::string directoryOr(const std::string& directory) {
    return directory.empty() ? cli::sceneDirectory() : directory;
}

// The arguments of `tumble run` from keywords: None leaves an option out, lists repeat it.
std::vector<std::string> runArguments(const std::string& scene, const py::kwargs& options) {
    std::vector<std::string> args{"tumble", "run", scene};
    for (const auto& [key, value] : options) {
        if (value.is_none())
            continue;
        std::string flag = "--" + key.cast<std::string>();
        for (char& ch : flag)
            ch = ch == '_' ? '-' : ch;
        if (py::isinstance<py::bool_>(value)) {
            if (value.cast<bool>())
                args.push_back(flag);
            continue;
        }
        const bool many = py::isinstance<py::list>(value) || py::isinstance<py::tuple>(value);
        for (const py::handle item :
             many ? value.cast<py::list>() : py::list(py::make_tuple(value))) {
            args.push_back(flag);
            args.push_back(py::str(item).cast<std::string>());
        }
    }
    return args;
}

}  // namespace

void bindScene(py::module_& m) {
    py::class_<cli::Scene>(m, "Scene", "A parsed, checked scene file (docs/scene-format.md).")
        .def_readonly("name", &cli::Scene::name)
        .def_readonly("description", &cli::Scene::description)
        .def_readonly("source", &cli::Scene::source)
        .def_readonly("world", &cli::Scene::world, "WorldDef")
        .def_readonly("duration", &cli::Scene::duration, "(s)")
        .def_property_readonly("body_names",
                               [](const cli::Scene& s) {
                                   std::vector<std::string> names;
                                   for (const cli::BodySpec& b : s.bodies)
                                       names.push_back(b.name);
                                   return names;
                               })
        .def(
            "select",
            [](const cli::Scene& s, const std::vector<std::string>& items) {
                return cli::selectBodies(s, items, "select");
            },
            py::arg("items"), "Scene indices of names (\"ball\", \"net[0][4]\", \"net.corners\").");
    py::class_<PyBuilt>(m, "BuiltScene", "A scene's world and its ids in scene order.")
        .def_readonly("world", &PyBuilt::world)
        .def_readonly("bodies", &PyBuilt::bodies)
        .def_readonly("shapes", &PyBuilt::shapes)
        .def_readonly("springs", &PyBuilt::springs)
        .def_readonly("joints", &PyBuilt::joints);
    py::class_<RunResult>(m, "RunResult", "What `tumble run` did.")
        .def_readonly("status", &RunResult::status, "0 ok, 1 a step failed")
        .def_readonly("out", &RunResult::out, "what it printed")
        .def_readonly("err", &RunResult::err, "its warnings and errors");

    m.def(
        "scene_directory", [] { return cli::sceneDirectory(); },
        "The built-in scenes' directory ($TUMBLE_SCENE_DIR first).");
    m.def(
        "builtin_scenes", [](const std::string& d) { return cli::builtinScenes(directoryOr(d)); },
        py::arg("directory") = "");
    m.def(
        "load_scene",
        [](const std::string& nameOrFile, const std::vector<std::string>& overrides,
           const std::string& directory) {
            return cli::loadScene(nameOrFile, overrides, directoryOr(directory));
        },
        py::arg("name_or_file"), py::arg("overrides") = std::vector<std::string>{},
        py::arg("directory") = "",
        "Reads and checks a scene: a built-in name or a JSON file; overrides are "
        "\"dotted.path=value\" as `tumble run --set`.");
    m.def(
        "build_scene",
        [](const cli::Scene& scene) {
            cli::BuiltScene b = cli::buildScene(scene);
            PyBuilt out{
                py::cast(new PyWorld(std::move(b.world)), py::return_value_policy::take_ownership),
                b.bodies, b.shapes, b.springs, b.joints};
            return out;
        },
        py::arg("scene"), "Creates the scene's World (BuiltScene.world) and its bodies.");
    m.def(
        "run",
        [](const std::string& scene, const py::kwargs& options) {
            const std::vector<std::string> args = runArguments(scene, options);
            std::ostringstream out, err;
            int status = 0;
            {
                py::gil_scoped_release release;
                status = cli::runCommand(args, out, err);
            }
            if (status == 2)
                throw InvalidArgument(err.str());
            return RunResult{status, out.str(), err.str()};
        },
        py::arg("scene"),
        "Runs a scene as `tumble run SCENE` does, the keywords being its options: time, dt, "
        "iterations, set (list), record, record_rate, record_bodies (list), summary, picture, "
        "view, trace (list), quiet (bool), checkpoint, checkpoint_every, resume. Bad input "
        "raises InvalidArgument with the command's message; returns a RunResult.");
}

}  // namespace tumble::python
