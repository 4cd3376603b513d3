// The glTF export: the replay's description becomes a node tree (a root turning Tumble's +Z up
// into glTF's +Y up, a node per body, a child per shape with its mesh), the frames become one
// animation (translation and rotation of every moving body, linear interpolation), and the
// threads a line mesh skinned to their two bodies, so they stretch with the animation.

#include <cmath>
#include <cstring>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>

#include "gltf_meshes.h"
#include "tumble/core/error.h"
#include "tumble/core/math.h"
#include "tumble/replay/replay.h"

namespace tumble {
namespace {

using Json = nlohmann::json;
constexpr int kFloat = 5126, kUnsignedShort = 5123, kUnsignedInt = 5125;
constexpr int kArrayBuffer = 34962, kElementBuffer = 34963;

/// The glTF document being built and its binary buffer.
class Document {
public:
    /// Appends `data` as an accessor of `count` elements of `type` ("VEC3"...); `target` 0 for
    /// animation and skin data. With `bounds`, min and max per component (POSITION and
    /// animation inputs need them).
    template <typename T>
    int accessor(const std::vector<T>& data, int component, const char* type, int count, int target,
                 bool bounds = false) {
        while (bin.size() % 4 != 0)
            bin.push_back('\0');
        Json view{
            {"buffer", 0}, {"byteOffset", bin.size()}, {"byteLength", data.size() * sizeof(T)}};
        if (target != 0)
            view["target"] = target;
        bin.append(reinterpret_cast<const char*>(data.data()), data.size() * sizeof(T));
        json["bufferViews"].push_back(view);
        Json a{{"bufferView", json["bufferViews"].size() - 1},
               {"componentType", component},
               {"count", count},
               {"type", type}};
        if (bounds) {
            const std::size_t width = data.size() / static_cast<std::size_t>(count);
            std::vector<double> lo(width, INFINITY), hi(width, -INFINITY);
            for (std::size_t i = 0; i < data.size(); ++i) {
                lo[i % width] = std::min<double>(lo[i % width], data[i]);
                hi[i % width] = std::max<double>(hi[i % width], data[i]);
            }
            a["min"] = lo;
            a["max"] = hi;
        }
        json["accessors"].push_back(a);
        return static_cast<int>(json["accessors"].size()) - 1;
    }

    Json json{{"asset", {{"version", "2.0"}, {"generator", "tumble run --gltf"}}},
              {"scene", 0},
              {"accessors", Json::array()},
              {"bufferViews", Json::array()},
              {"nodes", Json::array()},
              {"meshes", Json::array()},
              {"materials", Json::array()}};
    std::string bin;
    std::map<std::string, std::array<int, 3>> geometries;  ///< position, normal, index accessors
};

/// The body colour the viewer uses too (docs/replay.md): golden-angle hues, static grey.
std::array<double, 3> colourOf(int index, const std::string& type) {
    if (type != "dynamic")
        return type == "static" ? std::array{0.55, 0.55, 0.55} : std::array{0.45, 0.7, 0.45};
    const double h = std::fmod(index * 137.508, 360.0) / 60, s = 0.65, l = 0.6;
    const double c = (1 - std::abs(2 * l - 1)) * s, x = c * (1 - std::abs(std::fmod(h, 2) - 1));
    const int sector = static_cast<int>(h);
    const std::array<std::array<double, 3>, 6> rgb{
        {{c, x, 0}, {x, c, 0}, {0, c, x}, {0, x, c}, {x, 0, c}, {c, 0, x}}};
    std::array<double, 3> out{};
    for (int k = 0; k < 3; ++k)  // glTF colours are linear: undo the sRGB curve
        out[k] = std::pow(rgb[sector % 6][k] + l - c / 2, 2.2);
    return out;
}

/// A mesh of the shape in the material; shapes of the same geometry (a net's nodes) share
/// their vertex and index accessors.
int meshOf(Document& doc, const Json& shape, int material) {
    Json geometry = shape;
    geometry.erase("position");
    geometry.erase("orientation");
    auto [at, added] = doc.geometries.try_emplace(geometry.dump());
    std::array<int, 3>& cached = at->second;
    if (added) {
        const gltf::Mesh m = gltf::shapeMesh(shape, 20.0F);
        const int count = static_cast<int>(m.positions.size() / 3);
        cached = {doc.accessor(m.positions, kFloat, "VEC3", count, kArrayBuffer, true),
                  doc.accessor(m.normals, kFloat, "VEC3", count, kArrayBuffer),
                  doc.accessor(m.indices, kUnsignedInt, "SCALAR",
                               static_cast<int>(m.indices.size()), kElementBuffer)};
    }
    doc.json["meshes"].push_back(
        {{"primitives",
          {{{"attributes", {{"POSITION", cached[0]}, {"NORMAL", cached[1]}}},
            {"indices", cached[2]},
            {"material", material}}}}});
    return static_cast<int>(doc.json["meshes"].size()) - 1;
}

Transform poseOf(const ReplayPose& p) {
    return {
        Vec3(p.position[0], p.position[1], p.position[2]),
        Quat(p.orientation[3], p.orientation[0], p.orientation[1], p.orientation[2]).normalized()};
}

/// The body nodes (children of the root, node 0) with their shapes; returns the nodes' indices.
std::vector<int> addBodies(Document& doc, const Json& bodies, const ReplayFrame& first) {
    std::vector<int> nodes;
    for (std::size_t i = 0; i < bodies.size(); ++i) {
        const Json& body = bodies[i];
        const auto c = colourOf(static_cast<int>(i), body["type"]);
        doc.json["materials"].push_back(
            {{"pbrMetallicRoughness",
              {{"baseColorFactor", {c[0], c[1], c[2], 1.0}}, {"metallicFactor", 0.0}}}});
        const int material = static_cast<int>(doc.json["materials"].size()) - 1;
        Json children = Json::array();
        for (const Json& shape : body["shapes"]) {
            Json node{{"mesh", meshOf(doc, shape, material)}};
            if (shape["type"] != "plane") {  // a plane's mesh is already in the body frame
                node["translation"] = shape["position"];
                node["rotation"] = shape["orientation"];
            }
            doc.json["nodes"].push_back(node);
            children.push_back(doc.json["nodes"].size() - 1);
        }
        const ReplayPose& p = first.poses[i];
        const std::string name = body["name"];
        Json node{{"name", name.empty() ? "body " + std::to_string(i) : name},
                  {"translation", Json(p.position)},
                  {"rotation", Json(p.orientation)}};
        if (!children.empty())
            node["children"] = children;
        doc.json["nodes"].push_back(node);
        nodes.push_back(static_cast<int>(doc.json["nodes"].size()) - 1);
    }
    return nodes;
}

/// One animation: translation and rotation of every non-static body at every frame.
void addAnimation(Document& doc, const Replay& r, const Json& bodies,
                  const std::vector<int>& nodes) {
    std::vector<float> times;
    for (const ReplayFrame& f : r.frames)
        times.push_back(static_cast<float>(f.time - r.frames.front().time));
    const int count = static_cast<int>(times.size());
    const int input = doc.accessor(times, kFloat, "SCALAR", count, 0, true);
    Json samplers = Json::array(), channels = Json::array();
    for (std::size_t i = 0; i < nodes.size(); ++i) {
        if (bodies[i]["type"] == "static")
            continue;
        std::vector<float> translation, rotation;
        for (const ReplayFrame& f : r.frames) {
            const ReplayPose& p = f.poses[i];
            translation.insert(translation.end(), p.position.begin(), p.position.end());
            const Quat q = poseOf(p).rotation;  // unit to float precision, as glTF checks
            for (const double x : {q.x(), q.y(), q.z(), q.w()})
                rotation.push_back(static_cast<float>(x));
        }
        for (const auto& [path, data, type] :
             {std::tuple{"translation", &translation, "VEC3"}, {"rotation", &rotation, "VEC4"}}) {
            samplers.push_back({{"input", input},
                                {"output", doc.accessor(*data, kFloat, type, count, 0)},
                                {"interpolation", "LINEAR"}});
            channels.push_back({{"sampler", samplers.size() - 1},
                                {"target", {{"node", nodes[i]}, {"path", path}}}});
        }
    }
    if (!channels.empty())
        doc.json["animations"] = {
            {{"name", "run"}, {"samplers", samplers}, {"channels", channels}}};
}

/// The threads and springs as one line mesh skinned to their bodies (the root, a joint with the
/// identity bind, holds world anchors). Returns the mesh node, or -1 when there are none.
int addThreads(Document& doc, const Json& springs, const ReplayFrame& first,
               const std::vector<int>& nodes) {
    if (springs.empty())
        return -1;
    std::vector<int> joints{0};
    std::vector<int> jointOf(nodes.size() + 1, -1);  // by body index + 1 (0 = the world)
    jointOf[0] = 0;
    std::vector<float> positions, weights, binds;
    std::vector<std::uint16_t> jointIndices;
    const Eigen::Matrix4f identity = Eigen::Matrix4f::Identity();
    binds.insert(binds.end(), identity.data(), identity.data() + 16);
    for (const Json& s : springs) {
        for (const char* end : {"A", "B"}) {
            const int body = s[std::string("body") + end];
            const auto& a = s[std::string("anchor") + end];
            Vec3 p(a[0].get<double>(), a[1].get<double>(), a[2].get<double>());
            Transform pose;
            if (body >= 0)
                p = (pose = poseOf(first.poses[body])).apply(p);
            if (jointOf[body + 1] < 0) {
                if (joints.size() >= 65535)
                    fail("glTF export: more than 65534 bodies carry threads");
                jointOf[body + 1] = static_cast<int>(joints.size());
                joints.push_back(nodes[body]);
                Eigen::Matrix4d m = Eigen::Matrix4d::Identity();  // the body's pose, inverted
                m.topLeftCorner<3, 3>() = pose.rotation.toRotationMatrix().transpose();
                m.topRightCorner<3, 1>() = -(pose.rotation.conjugate() * pose.position);
                const Eigen::Matrix4f f = m.cast<float>();
                binds.insert(binds.end(), f.data(), f.data() + 16);  // column-major, as glTF
            }
            for (int k = 0; k < 3; ++k)
                positions.push_back(static_cast<float>(p[k]));
            jointIndices.insert(jointIndices.end(),
                                {static_cast<std::uint16_t>(jointOf[body + 1]), 0, 0, 0});
            weights.insert(weights.end(), {1, 0, 0, 0});
        }
    }
    const int count = static_cast<int>(positions.size() / 3);
    doc.json["materials"].push_back(
        {{"pbrMetallicRoughness",
          {{"baseColorFactor", {0.9, 0.75, 0.2, 1.0}}, {"metallicFactor", 0.0}}}});
    Json attributes{
        {"POSITION", doc.accessor(positions, kFloat, "VEC3", count, kArrayBuffer, true)},
        {"JOINTS_0", doc.accessor(jointIndices, kUnsignedShort, "VEC4", count, kArrayBuffer)},
        {"WEIGHTS_0", doc.accessor(weights, kFloat, "VEC4", count, kArrayBuffer)}};
    doc.json["meshes"].push_back({{"name", "threads"},
                                  {"primitives",
                                   {{{"attributes", attributes},
                                     {"mode", 1},  // LINES
                                     {"material", doc.json["materials"].size() - 1}}}}});
    doc.json["skins"] = {
        {{"joints", joints},
         {"inverseBindMatrices",
          doc.accessor(binds, kFloat, "MAT4", static_cast<int>(joints.size()), 0)}}};
    doc.json["nodes"].push_back(
        {{"name", "threads"}, {"mesh", doc.json["meshes"].size() - 1}, {"skin", 0}});
    return static_cast<int>(doc.json["nodes"].size()) - 1;
}

void writeGlb(const Document& doc, const std::string& path) {
    std::string text = doc.json.dump();
    text.append((4 - text.size() % 4) % 4, ' ');
    std::string bin = doc.bin;
    bin.append((4 - bin.size() % 4) % 4, '\0');
    std::ofstream out(path, std::ios::binary);
    if (!out)
        fail("glTF file \"", path, "\" cannot be written");
    auto word = [&](std::uint32_t w) { out.write(reinterpret_cast<const char*>(&w), 4); };
    word(0x46546C67);  // "glTF"
    word(2);
    word(static_cast<std::uint32_t>(12 + 8 + text.size() + 8 + bin.size()));
    word(static_cast<std::uint32_t>(text.size()));
    word(0x4E4F534A);  // "JSON"
    out << text;
    word(static_cast<std::uint32_t>(bin.size()));
    word(0x004E4942);  // "BIN\0"
    out << bin;
    if (!out)
        fail("glTF file \"", path, "\" could not be written");
}

}  // namespace

void writeGltf(const Replay& replay, const std::string& path) {
    if (replay.frames.empty())
        fail("glTF export: the replay has no frames");
    const Json description = Json::parse(replay.description);
    Document doc;
    // The root turns +Z up into +Y up: a quarter turn about x (x, y, z, w).
    const double s = std::sqrt(0.5);
    doc.json["nodes"].push_back(
        {{"name", description.value("title", "tumble")}, {"rotation", {-s, 0.0, 0.0, s}}});
    const std::vector<int> nodes = addBodies(doc, description["bodies"], replay.frames.front());
    if (!nodes.empty())
        doc.json["nodes"][0]["children"] = nodes;
    addAnimation(doc, replay, description["bodies"], nodes);
    Json roots = Json::array({0});
    const int threads = addThreads(doc, description["springs"], replay.frames.front(), nodes);
    if (threads >= 0)
        roots.push_back(threads);
    doc.json["scenes"] = {{{"nodes", roots}}};
    doc.json["buffers"] = {{{"byteLength", (doc.bin.size() + 3) / 4 * 4}}};
    writeGlb(doc, path);
}

}  // namespace tumble
