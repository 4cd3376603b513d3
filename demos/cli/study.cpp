// Study files -> Study. Everything a run needs is checked here, before a directory is made or a
// run started: the keys, the parameter ranges, and each parameter path and output tried on the
// base scene, so that a typo is a refusal naming the study's line, not a table of failed runs.

#include "study.h"

#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <numbers>
#include <set>
#include <sstream>

#include "measures.h"

namespace tumble::cli {
namespace {

/// More runs than any study needs; a product above it is a typo (or would overflow).
constexpr std::uint64_t kMaxRuns = 100'000'000;

/// splitmix64's finaliser: a bijective 64-bit mix (Steele, Lea, Flood 2014).
std::uint64_t mix(std::uint64_t x) {
    x += 0x9E3779B97F4A7C15ull;
    x = (x ^ (x >> 30)) * 0xBF58476D1CE4E5B9ull;
    x = (x ^ (x >> 27)) * 0x94D049BB133111EBull;
    return x ^ (x >> 31);
}

/// A uniform number in (0, 1) keyed by (run seed, parameter, draw): counter-based, so no state.
double uniform01(std::uint64_t seed, std::size_t parameter, int draw) {
    const std::uint64_t bits = mix(seed ^ mix(2 * parameter + static_cast<std::uint64_t>(draw)));
    return (static_cast<double>(bits >> 11) + 0.5) * 0x1p-53;
}

std::uint64_t fnv1a(const std::string& text, std::uint64_t hash = 0xcbf29ce484222325ull) {
    for (const unsigned char c : text)
        hash = (hash ^ c) * 0x100000001b3ull;
    return hash;
}

std::string readText(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    std::stringstream text;
    text << in.rdbuf();
    return text.str();
}

/// `count` evenly spaced values from `from` to `to`, both included; integers when both ends are
/// integers and so is every step (an iteration count must stay an integer).
std::vector<Json> gridValues(const Json& from, const Json& to, std::uint64_t count) {
    const Real a = from.get<Real>(), b = to.get<Real>();
    const bool integral = from.is_number_integer() && to.is_number_integer() &&
                          (count == 1 || std::fmod(b - a, Real(count - 1)) == 0);
    std::vector<Json> values;
    for (std::uint64_t j = 0; j < count; ++j) {
        const Real x = count == 1       ? a
                       : j + 1 == count ? b
                                        : a + (b - a) * Real(j) / Real(count - 1);
        values.push_back(integral ? Json(static_cast<long long>(std::llround(x))) : Json(x));
    }
    return values;
}

StudyParameter parseParameter(JsonObject o) {
    StudyParameter p;
    if (!o.has("path"))
        failAt(o.pathOf("path"), "is required (a --set path such as bodies.0.position.2)");
    p.path = o.string("path", "");
    if (p.path.empty() || p.path.find('=') != std::string::npos)
        failAt(o.pathOf("path"), "\"", p.path, "\" is no --set path (dotted keys, no '=')");
    p.column = o.string("name", p.path);
    const int ways = int(o.has("values")) + int(o.has("grid")) + int(o.has("distribution"));
    if (ways != 1)
        failAt(o.path(), "give exactly one of \"values\", \"grid\" or \"distribution\"");
    if (const Json* values = o.find("values")) {
        if (!values->is_array() || values->empty())
            failAt(o.pathOf("values"), "expected a non-empty array of values");
        p.values.assign(values->begin(), values->end());
        p.count = p.values.size();
        o.finish();
        return p;
    }
    p.count = static_cast<std::uint64_t>(o.integer("count", 1, 1, 10'000'000));
    if (const Json* grid = o.find("grid")) {
        if (!grid->is_array() || grid->size() != 2 || !(*grid)[0].is_number() ||
            !(*grid)[1].is_number())
            failAt(o.pathOf("grid"), "expected [from, to] (two numbers)");
        p.values = gridValues((*grid)[0], (*grid)[1], p.count);
        o.finish();
        return p;
    }
    const std::string kind = o.choice("distribution", "", {"uniform", "normal", "log-uniform"});
    p.kind = kind == "uniform"  ? StudyParameter::Kind::Uniform
             : kind == "normal" ? StudyParameter::Kind::Normal
                                : StudyParameter::Kind::LogUniform;
    if (p.kind == StudyParameter::Kind::Normal) {
        p.a = o.number("mean");
        p.b = o.positive("stddev", 1);
        if (!o.has("stddev"))
            failAt(o.pathOf("stddev"), "is required for a normal distribution");
    } else {
        p.a = o.number("min");
        p.b = o.number("max");
        if (!(p.a < p.b))
            failAt(o.pathOf("max"), "= ", p.b, " must be > min = ", p.a);
        if (p.kind == StudyParameter::Kind::LogUniform && !(p.a > 0))
            failAt(o.pathOf("min"), "= ", p.a, " must be > 0 for a log-uniform distribution");
    }
    o.finish();
    return p;
}

/// The value tried on the base scene when the study is read.
Json sampleValue(const StudyParameter& p) {
    return p.values.empty() ? Json(p.a) : p.values.front();
}

StudyOutput parseOutput(const Json& value, const std::string& path, const Scene& scene) {
    StudyOutput out;
    if (value.is_string()) {
        out.name = out.summaryKey = value.get<std::string>();
        Real unused = 0;
        if (!summaryValue(Summary{}, out.summaryKey, unused))
            failAt(path, "\"", out.summaryKey, "\" is no summary figure (", summaryKeys(), ")");
        return out;
    }
    JsonObject o(value, path);
    if (!o.has("name"))
        failAt(o.pathOf("name"), "is required (the CSV column)");
    out.name = o.string("name", "");
    const std::string measure =
        o.choice("measure", "", {"final", "min", "max", "first-below", "first-above", "captured"});
    using Kind = StudyOutput::Kind;
    out.kind = measure == "final"         ? Kind::Final
               : measure == "min"         ? Kind::Min
               : measure == "max"         ? Kind::Max
               : measure == "first-below" ? Kind::FirstBelow
               : measure == "first-above" ? Kind::FirstAbove
                                          : Kind::Captured;
    // Bodies are named as in the run's scene and looked up per run (a parameter may move them).
    auto body = [&](const std::string& key) {
        if (!o.has(key))
            failAt(o.pathOf(key), "is required (a body name or index)");
        const Json* b = o.find(key);
        const std::string item = b->is_string() ? b->get<std::string>() : b->dump();
        if (selectBodies(scene, {item}, o.pathOf(key)).size() != 1)
            failAt(o.pathOf(key), "\"", item, "\" names several bodies; one is measured");
        return item;
    };
    if (out.kind == Kind::Captured) {
        out.net = o.string("net", "net");
        selectBodies(scene, {out.net + ".corners"}, o.pathOf("net"));
        out.target = body("target");
    } else {
        out.body = body("body");
        out.quantity = o.choice("quantity", "z", quantityNames());
        if (out.kind == Kind::FirstBelow || out.kind == Kind::FirstAbove)
            out.threshold = o.number("value");
    }
    o.finish();
    return out;
}

/// Tries every parameter path on the base scene: a path that does not exist is refused here.
void checkParameters(const Study& study, const std::string& directory) {
    for (std::size_t k = 0; k < study.parameters.size(); ++k) {
        const StudyParameter& p = study.parameters[k];
        std::vector<std::string> sets = study.sets;
        sets.push_back(p.path + "=" + sampleValue(p).dump());
        try {
            loadScene(study.scenePath, sets, directory);
        } catch (const InvalidArgument& e) {
            failAt("parameters[" + std::to_string(k) + "].path", "\"", p.path,
                   "\" does not apply to the scene: ", e.what());
        }
    }
}

void checkColumns(const Study& study) {
    std::set<std::string> seen{"run", "seed", "status", "wall_s"};
    auto add = [&](const std::string& column, const std::string& path) {
        if (column.empty() || column.find_first_of(",\"\n") != std::string::npos)
            failAt(path, "the column name \"", column,
                   "\" must be non-empty, without , \" or newline");
        if (!seen.insert(column).second)
            failAt(path, "the column \"", column,
                   "\" is given twice (or is run, seed, status, wall_s)");
    };
    for (std::size_t k = 0; k < study.parameters.size(); ++k)
        add(study.parameters[k].column, "parameters[" + std::to_string(k) + "].name");
    for (std::size_t k = 0; k < study.outputs.size(); ++k)
        add(study.outputs[k].name, "outputs[" + std::to_string(k) + "]");
}

Study parseStudy(const Json& document, const std::string& path, const std::string& directory) {
    namespace fs = std::filesystem;
    JsonObject o(document, "");
    Study study;
    study.source = path;
    if (!o.has("scene"))
        failAt("scene", "is required (a built-in scene name or a FILE.json)");
    const std::string scene = o.string("scene", "");
    const bool isFile =
        scene.find('/') != std::string::npos || fs::path(scene).extension() == ".json";
    // A file is relative to the study; a built-in name is resolved now, so every worker agrees.
    study.scenePath = isFile ? (fs::path(path).parent_path() / scene).string()
                             : (fs::path(directory) / (scene + ".json")).string();
    if (!fs::exists(study.scenePath))
        failAt("scene", "\"", scene, "\": no such ", isFile ? "file" : "built-in scene");
    if (const Json* seed = o.find("seed")) {
        if (!seed->is_number_unsigned())
            failAt("seed", "expected an integer >= 0, got ", seed->dump());
        study.seed = seed->get<std::uint64_t>();
    }
    if (o.has("duration"))
        study.sets.push_back("duration=" + Json(o.positive("duration", 1)).dump());
    if (const Json* sets = o.find("set")) {
        if (!sets->is_object())
            failAt("set", "expected an object of --set paths and values");
        for (const auto& [key, value] : sets->items())
            study.sets.push_back(key + "=" + value.dump());
    }
    Scene base;
    try {
        base = loadScene(study.scenePath, study.sets, directory);
    } catch (const InvalidArgument& e) {
        failAt(o.has("set") ? "set" : "scene", e.what());
    }
    const Json* parameters = o.find("parameters");
    if (parameters != nullptr && !parameters->is_array())
        failAt("parameters", "expected an array");
    for (std::size_t k = 0; parameters != nullptr && k < parameters->size(); ++k) {
        study.parameters.push_back(
            parseParameter(JsonObject((*parameters)[k], "parameters[" + std::to_string(k) + "]")));
        study.runs *= study.parameters.back().count;
        if (study.runs > kMaxRuns)
            failAt("parameters[" + std::to_string(k) + "].count", "the study would have more than ",
                   kMaxRuns, " runs");
    }
    const Json* outputs = o.find("outputs");
    if (outputs == nullptr || !outputs->is_array() || outputs->empty())
        failAt("outputs", "expected a non-empty array of summary figures and measures");
    for (std::size_t k = 0; k < outputs->size(); ++k)
        study.outputs.push_back(
            parseOutput((*outputs)[k], "outputs[" + std::to_string(k) + "]", base));
    o.finish();
    checkColumns(study);
    checkParameters(study, directory);
    study.fingerprint = std::to_string(fnv1a(readText(study.scenePath), fnv1a(document.dump())));
    return study;
}

}  // namespace

Study loadStudy(const std::string& path, const std::string& sceneDirectory) {
    JsonLines lines;
    const Json document = readJsonFile(path, &lines);
    if (!document.is_object())
        fail(path, ":", lineOf(lines, ""), ": (top level): a study is a JSON object {...}");
    try {
        return parseStudy(document, path, sceneDirectory);
    } catch (const JsonError& e) {
        fail(path, ":", lineOf(lines, e.path()), ": ", e.what());
    }
}

std::uint64_t runSeed(const Study& study, std::uint64_t index) {
    return mix(mix(study.seed) ^ index);
}

std::vector<Json> runValues(const Study& study, std::uint64_t index) {
    // Mixed radix, the first parameter varying slowest: run i's grid point without a table.
    std::vector<std::uint64_t> digit(study.parameters.size());
    std::uint64_t rest = index;
    for (std::size_t k = study.parameters.size(); k-- > 0;) {
        digit[k] = rest % study.parameters[k].count;
        rest /= study.parameters[k].count;
    }
    const std::uint64_t seed = runSeed(study, index);
    std::vector<Json> values;
    for (std::size_t k = 0; k < study.parameters.size(); ++k) {
        const StudyParameter& p = study.parameters[k];
        const double u = uniform01(seed, k, 0);
        switch (p.kind) {
            case StudyParameter::Kind::Values:
                values.push_back(p.values[digit[k]]);
                break;
            case StudyParameter::Kind::Uniform:
                values.emplace_back(p.a + u * (p.b - p.a));
                break;
            case StudyParameter::Kind::LogUniform:
                values.emplace_back(p.a * std::exp(u * std::log(p.b / p.a)));
                break;
            case StudyParameter::Kind::Normal: {
                // Box-Muller on two keyed uniforms: the same numbers on every standard library.
                const double r = std::sqrt(-2 * std::log(u));
                values.emplace_back(
                    p.a + p.b * r * std::cos(2 * std::numbers::pi * uniform01(seed, k, 1)));
                break;
            }
        }
    }
    return values;
}

std::vector<std::string> runOverrides(const Study& study, std::uint64_t index) {
    std::vector<std::string> sets = study.sets;
    const std::vector<Json> values = runValues(study, index);
    for (std::size_t k = 0; k < values.size(); ++k)
        sets.push_back(study.parameters[k].path + "=" + values[k].dump());
    return sets;
}

}  // namespace tumble::cli
