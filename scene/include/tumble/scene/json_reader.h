#pragma once
/// A strict reader of one JSON object of a scene file. Every accessor names the key it reads, so
/// finish() can refuse any key the file has and the reader never asked for (a typo must not be
/// silently ignored). Every error is an InvalidArgument whose message starts with the JSON path
/// of the offending value, e.g. `bodies[3].shapes[0].halfExtents: ...`.

#include <map>
#include <nlohmann/json.hpp>
#include <set>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include "tumble/core/error.h"
#include "tumble/core/math.h"

namespace tumble::cli {

using Json = nlohmann::json;

/// What failAt throws: an InvalidArgument that also carries the JSON path of the value it refuses,
/// so that the loader can add the line of the file it came from.
class JsonError : public InvalidArgument {
public:
    JsonError(std::string path, const std::string& message)
        : InvalidArgument(message), path_(std::move(path)) {}
    const std::string& path() const { return path_; }

private:
    std::string path_;
};

/// The line (1-based) of each value of a document by its JSON path ("" the root,
/// "bodies[2].position"): the line of its key, or where it starts for an array element or the
/// root.
using JsonLines = std::map<std::string, int>;

/// Parses JSON text and records the line of every value. A key given twice in one object is
/// refused (JsonError at its path, naming both lines): the last one would silently win. Syntax
/// errors are nlohmann's exceptions.
Json parseJson(const std::string& text, JsonLines& lines);

/// The line of `path`, else of the nearest value that holds it; 0 when none is known.
int lineOf(const JsonLines& lines, std::string path);

/// "number", "string", "array"... as a person would say it.
std::string typeName(const Json& value);

/// Throws InvalidArgument "<path>: <parts...>".
template <typename... Parts>
[[noreturn]] void failAt(const std::string& path, Parts&&... parts);

class JsonObject {
public:
    /// Refuses a value that is not an object.
    JsonObject(const Json& value, std::string path);

    const std::string& path() const { return path_; }
    /// The path of a member: "a.b" (or "b" at the root).
    std::string pathOf(const std::string& key) const;
    /// Is the key present? Registers it as known.
    bool has(const std::string& key);
    /// The raw member, or nullptr when absent. Registers the key.
    const Json* find(const std::string& key);

    Real number(const std::string& key, Real fallback);
    Real number(const std::string& key);  ///< required
    /// A number > 0 (or >= 0 when allowZero); the fallback is not checked.
    Real positive(const std::string& key, Real fallback, bool allowZero = false);
    /// An integer in [minimum, maximum].
    int integer(const std::string& key, int fallback, int minimum, int maximum);
    bool boolean(const std::string& key, bool fallback);
    std::string string(const std::string& key, const std::string& fallback);
    /// One of `choices`.
    std::string choice(const std::string& key, const std::string& fallback,
                       const std::vector<std::string>& choices);
    Vec3 vec3(const std::string& key, const Vec3& fallback);
    /// Either [w, x, y, z] (normalised when within 1e-3 of unit length) or
    /// {"axis": [x, y, z], "angle": rad} / {"axis": [...], "degrees": deg}.
    Quat orientation(const std::string& key);
    /// A member object (required to be an object when present).
    JsonObject object(const std::string& key);

    /// Declares keys that a later version will read: present ones are refused as "not yet
    /// supported" rather than as unknown.
    void reserve(const std::vector<std::string>& keys);
    /// Refuses every member that no accessor asked for.
    void finish() const;

private:
    const Json& value_;
    std::string path_;
    std::set<std::string> known_;
    std::set<std::string> reserved_;
};

/// Reads a JSON array of numbers as a Vec3 (path for messages).
Vec3 readVec3(const Json& value, const std::string& path);

template <typename... Parts>
void failAt(const std::string& path, Parts&&... parts) {
    std::ostringstream out;
    out << (path.empty() ? std::string("(top level)") : path) << ": ";
    (out << ... << std::forward<Parts>(parts));
    throw JsonError(path, out.str());
}

}  // namespace tumble::cli
