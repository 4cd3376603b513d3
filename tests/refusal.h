#pragma once
/// Test helpers for refused input: the message of the InvalidArgument a call throws, and a
/// check that shows the whole message when it lacks the expected part.

#include <gtest/gtest.h>

#include <string>

#include "tumble/core/error.h"

namespace tumble::test {

/// Passes when `text` contains `part`, and shows the whole text when it does not.
inline ::testing::AssertionResult contains(const std::string& text, const std::string& part) {
    if (text.find(part) != std::string::npos)
        return ::testing::AssertionSuccess();
    return ::testing::AssertionFailure() << "\"" << text << "\" lacks \"" << part << "\"";
}

/// The message of the InvalidArgument that `call` throws ("" if it throws none).
template <typename Call>
std::string refusal(Call&& call) {
    try {
        call();
    } catch (const InvalidArgument& e) {
        return e.what();
    }
    return "";
}

}  // namespace tumble::test
