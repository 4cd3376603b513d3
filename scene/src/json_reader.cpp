#include "tumble/scene/json_reader.h"

#include <algorithm>
#include <cmath>
#include <iterator>
#include <numbers>

#include "tumble/core/error.h"

namespace tumble::cli {
namespace {

/// An input iterator over the text that remembers how far the parser has read: nlohmann's parser
/// callbacks carry no position, and a line is what a person looks for in a file.
class TrackingIterator {
public:
    using iterator_category = std::input_iterator_tag;
    using value_type = char;
    using difference_type = std::ptrdiff_t;
    using pointer = const char*;
    using reference = const char&;

    TrackingIterator(const char* at, const char** read) : at_(at), read_(read) {}
    reference operator*() const { return *at_; }
    TrackingIterator& operator++() {
        *read_ = ++at_;
        return *this;
    }
    TrackingIterator operator++(int) {
        TrackingIterator before = *this;
        ++*this;
        return before;
    }
    bool operator==(const TrackingIterator& other) const { return at_ == other.at_; }

private:
    const char* at_;
    const char** read_;
};

/// An object or array the parser is inside.
struct OpenValue {
    std::string path;
    bool array = false;
    std::size_t elements = 0;         ///< finished elements (arrays)
    std::map<std::string, int> keys;  ///< key -> its line (objects)
    std::string key;                  ///< the key whose value comes next (objects)
};

}  // namespace

Json parseJson(const std::string& text, JsonLines& lines) {
    const char* read = text.data();
    const char* counted = text.data();
    int line = 1;
    // The line of the token just read. Every token ends at the last character read except a
    // number, which the lexer knows has ended only by reading one more: so read - 1.
    const auto lineNow = [&] {
        const char* upTo = std::max(counted, read - 1);
        line += static_cast<int>(std::count(counted, upTo, '\n'));
        counted = upTo;
        return line;
    };
    std::vector<OpenValue> open;
    const auto startValue = [&](int at) {  // the path of the value that starts here
        if (open.empty()) {
            lines[""] = at;
            return std::string();
        }
        const OpenValue& parent = open.back();
        if (!parent.array)
            return parent.path.empty() ? parent.key : parent.path + "." + parent.key;
        std::string path = parent.path + "[" + std::to_string(parent.elements) + "]";
        lines[path] = at;
        return path;
    };
    const auto endValue = [&] {
        if (!open.empty() && open.back().array)
            ++open.back().elements;
    };
    const Json::parser_callback_t track = [&](int, Json::parse_event_t event, Json& parsed) {
        using Event = Json::parse_event_t;
        if (event == Event::object_start || event == Event::array_start) {
            std::string path = startValue(lineNow());
            open.push_back({std::move(path), event == Event::array_start, 0, {}, {}});
        } else if (event == Event::object_end || event == Event::array_end) {
            open.pop_back();
            endValue();
        } else if (event == Event::key) {
            OpenValue& object = open.back();
            object.key = parsed.get<std::string>();
            const int at = lineNow();
            const std::string path =
                object.path.empty() ? object.key : object.path + "." + object.key;
            const auto [first, added] = object.keys.emplace(object.key, at);
            lines[path] = at;  // a duplicate is refused at its own line
            if (!added)
                failAt(path, "key given twice in one object (lines ", first->second, " and ", at,
                       "): the last value would silently replace the first");
            lines[path] = at;
        } else {  // a number, string, boolean or null
            startValue(lineNow());
            endValue();
        }
        return true;
    };
    const char* end = text.data() + text.size();
    return Json::parse(TrackingIterator(text.data(), &read), TrackingIterator(end, &read), track);
}

int lineOf(const JsonLines& lines, std::string path) {
    for (;;) {
        if (const auto it = lines.find(path); it != lines.end())
            return it->second;
        if (path.empty())
            return 0;
        const std::size_t cut = path.back() == ']' ? path.rfind('[') : path.rfind('.');
        path.erase(cut == std::string::npos ? 0 : cut);
    }
}

std::string typeName(const Json& value) {
    switch (value.type()) {
        case Json::value_t::null:
            return "null";
        case Json::value_t::object:
            return "an object";
        case Json::value_t::array:
            return "an array";
        case Json::value_t::string:
            return "a string";
        case Json::value_t::boolean:
            return "a boolean";
        case Json::value_t::number_integer:
        case Json::value_t::number_unsigned:
        case Json::value_t::number_float:
            return "a number";
        default:
            return "an unsupported value";
    }
}

JsonObject::JsonObject(const Json& value, std::string path)
    : value_(value), path_(std::move(path)) {
    if (!value_.is_object())
        failAt(path_, "expected an object, got ", typeName(value_));
}

std::string JsonObject::pathOf(const std::string& key) const {
    return path_.empty() ? key : path_ + "." + key;
}

bool JsonObject::has(const std::string& key) {
    known_.insert(key);
    return value_.contains(key);
}

const Json* JsonObject::find(const std::string& key) {
    known_.insert(key);
    const auto it = value_.find(key);
    return it == value_.end() ? nullptr : &*it;
}

Real JsonObject::number(const std::string& key, Real fallback) {
    const Json* v = find(key);
    if (v == nullptr)
        return fallback;
    if (!v->is_number())
        failAt(pathOf(key), "expected a number, got ", typeName(*v));
    const Real x = v->get<Real>();
    if (!std::isfinite(x))
        failAt(pathOf(key), "must be finite");
    return x;
}

Real JsonObject::number(const std::string& key) {
    if (!has(key))
        failAt(pathOf(key), "is required");
    return number(key, 0);
}

Real JsonObject::positive(const std::string& key, Real fallback, bool allowZero) {
    if (!has(key))
        return fallback;
    const Real x = number(key, fallback);
    if (allowZero ? x < 0 : x <= 0)
        failAt(pathOf(key), "must be ", allowZero ? ">= 0" : "> 0", " (got ", x, ")");
    return x;
}

int JsonObject::integer(const std::string& key, int fallback, int minimum, int maximum) {
    const Json* v = find(key);
    if (v == nullptr)
        return fallback;
    if (!v->is_number_integer())
        failAt(pathOf(key), "expected an integer, got ", typeName(*v), " ", v->dump());
    const long long x = v->get<long long>();
    if (x < minimum || x > maximum) {
        failAt(pathOf(key), "must be >= ", minimum, x > maximum ? " and <= " : "",
               x > maximum ? std::to_string(maximum) : "", " (got ", x, ")");
    }
    return static_cast<int>(x);
}

bool JsonObject::boolean(const std::string& key, bool fallback) {
    const Json* v = find(key);
    if (v == nullptr)
        return fallback;
    if (!v->is_boolean())
        failAt(pathOf(key), "expected true or false, got ", typeName(*v));
    return v->get<bool>();
}

std::string JsonObject::string(const std::string& key, const std::string& fallback) {
    const Json* v = find(key);
    if (v == nullptr)
        return fallback;
    if (!v->is_string())
        failAt(pathOf(key), "expected a string, got ", typeName(*v));
    return v->get<std::string>();
}

std::string JsonObject::choice(const std::string& key, const std::string& fallback,
                               const std::vector<std::string>& choices) {
    const std::string s = string(key, fallback);
    for (const std::string& c : choices) {
        if (c == s)
            return s;
    }
    std::string list;
    for (const std::string& c : choices)
        list += (list.empty() ? "\"" : ", \"") + c + "\"";
    failAt(pathOf(key), "\"", s, "\" is not one of ", list);
}

Vec3 readVec3(const Json& v, const std::string& path) {
    if (!v.is_array() || v.size() != 3)
        failAt(path, "expected an array of 3 numbers, got ", typeName(v));
    Vec3 out;
    for (int i = 0; i < 3; ++i) {
        if (!v[i].is_number())
            failAt(path + "[" + std::to_string(i) + "]", "expected a number, got ", typeName(v[i]));
        out[i] = v[i].get<Real>();
    }
    if (!out.allFinite())
        failAt(path, "must be finite");
    return out;
}

Vec3 JsonObject::vec3(const std::string& key, const Vec3& fallback) {
    const Json* v = find(key);
    return v == nullptr ? fallback : readVec3(*v, pathOf(key));
}

Quat JsonObject::orientation(const std::string& key) {
    const Json* v = find(key);
    if (v == nullptr)
        return Quat::Identity();
    const std::string path = pathOf(key);
    if (v->is_array()) {
        if (v->size() != 4)
            failAt(path, "expected [w, x, y, z] or {\"axis\", \"angle\"}, got ", v->size(),
                   " numbers");
        Real q[4];
        for (int i = 0; i < 4; ++i) {
            if (!(*v)[i].is_number())
                failAt(path + "[" + std::to_string(i) + "]", "expected a number");
            q[i] = (*v)[i].get<Real>();
        }
        const Quat out(q[0], q[1], q[2], q[3]);
        if (!isFinite(out) || std::abs(out.norm() - 1) > 1e-3)
            failAt(path, "quaternion [w, x, y, z] must have unit length (got ", out.norm(), ")");
        return out.normalized();
    }
    JsonObject o(*v, path);
    const Vec3 axis = o.vec3("axis", Vec3::UnitZ());
    if (axis.norm() < 1e-12)
        failAt(o.pathOf("axis"), "must not be zero");
    if (o.has("angle") && o.has("degrees"))
        failAt(path, "give \"angle\" (rad) or \"degrees\", not both");
    const Real angle =
        o.has("degrees") ? o.number("degrees") * std::numbers::pi / 180 : o.number("angle", 0);
    o.finish();
    return Quat(Eigen::AngleAxis<Real>(angle, axis.normalized()));
}

JsonObject JsonObject::object(const std::string& key) {
    static const Json empty = Json::object();
    const Json* v = find(key);
    return JsonObject(v == nullptr ? empty : *v, pathOf(key));
}

void JsonObject::reserve(const std::vector<std::string>& keys) {
    reserved_.insert(keys.begin(), keys.end());
}

void JsonObject::finish() const {
    for (const auto& [key, member] : value_.items()) {
        if (known_.count(key) != 0)
            continue;
        if (reserved_.count(key) != 0)
            failAt(pathOf(key), "not yet supported (reserved for a later version)");
        std::string list;
        for (const std::string& k : known_)
            list += (list.empty() ? "" : ", ") + k;
        failAt(pathOf(key), "unknown key (expected one of: ", list, ")");
    }
}

}  // namespace tumble::cli
