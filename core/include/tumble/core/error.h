#pragma once
/// The one exception type of Tumble. Setup-time input (definitions, settings, ids, scene files) is
/// checked where it enters and refused with InvalidArgument; its message names the field, the value
/// and the rule it broke. Nothing is changed by a refused call. `World::step` never throws: it
/// reports problems through its status.

#include <sstream>
#include <stdexcept>
#include <string>
#include <utility>

namespace tumble {

class InvalidArgument : public std::invalid_argument {
public:
    explicit InvalidArgument(const std::string& message) : std::invalid_argument(message) {}
};

/// Builds an InvalidArgument message from streamable parts: fail("BodyDef.mass = ", m, " must be >
/// 0").
template <typename... Parts>
[[noreturn]] void fail(Parts&&... parts) {
    std::ostringstream out;
    (out << ... << std::forward<Parts>(parts));
    throw InvalidArgument(out.str());
}

}  // namespace tumble
