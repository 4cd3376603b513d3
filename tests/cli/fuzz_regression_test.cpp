// Inputs that fuzz/scene_loader_fuzz (or review of what it exercises) found to break the scene
// loader, kept as regression tests. Every file in fuzz_regressions/ must load or be refused with
// an InvalidArgument that has a message -- the fuzz target's own contract.

#include <gtest/gtest.h>

#include <filesystem>
#include <sstream>
#include <string>
#include <vector>

#include "command.h"
#include "tumble/scene/scene.h"

namespace fs = std::filesystem;

namespace tumble::cli {
namespace {

const fs::path kRegressions = fs::path(TUMBLE_CLI_TEST_DIR) / "fuzz_regressions";

/// The message of the InvalidArgument thrown by loading `file` ("" when it loads).
std::string loadRefusal(const fs::path& file) {
    try {
        loadScene(file.string(), {}, ".");
    } catch (const InvalidArgument& e) {
        return e.what();
    }
    return "";
}

TEST(FuzzRegression, EveryFoundInputLoadsOrIsRefusedWithAMessage) {
    int files = 0;
    for (const auto& entry : fs::directory_iterator(kRegressions)) {
        ++files;
        try {
            const Scene scene = loadScene(entry.path().string(), {}, ".");
            BuiltScene built = buildScene(scene);
            built.world.step();
        } catch (const InvalidArgument& e) {
            EXPECT_NE(std::string(e.what()), "") << entry.path();
        }  // anything else escapes and fails the test
    }
    EXPECT_GE(files, 1);
}

// nlohmann reports a number beyond a double's range as out_of_range, not as a parse error; it
// escaped the loader and ended `tumble run` with std::terminate.
TEST(FuzzRegression, NumberBeyondADoubleIsRefusedNamingTheFileAndTheNumber) {
    const std::string message = loadRefusal(kRegressions / "number_overflow.json");
    EXPECT_NE(message.find("number_overflow.json: JSON value out of range: number overflow "
                           "parsing '1e200202'"),
              std::string::npos)
        << message;
    std::ostringstream out, err;
    EXPECT_EQ(
        runCommand({"tumble", "run", (kRegressions / "number_overflow.json").string()}, out, err),
        2);
    EXPECT_NE(err.str().find("out of range"), std::string::npos) << err.str();
}

// Found by review of the same path: an array index too long for std::stoul threw
// std::out_of_range out of --set.
TEST(FuzzRegression, OverrideWithAHugeArrayIndexIsRefused) {
    Json document = Json::parse(R"({"bodies": [{"name": "a"}]})");
    try {
        applyOverride(document, "bodies.123456789012345678901234567890.name=b");
        FAIL() << "accepted";
    } catch (const InvalidArgument& e) {
        EXPECT_NE(std::string(e.what()).find("is not an index of an array of 1"), std::string::npos)
            << e.what();
    }
    EXPECT_NO_THROW(applyOverride(document, "bodies.0.name=b"));
    EXPECT_EQ(document["bodies"][0]["name"], "b");
}

// A mistyped count used to make every body before anything was checked: 1e8 boxes ran the
// process out of memory instead of giving a message.
TEST(FuzzRegression, GeneratorsPastAMillionBodiesAreRefusedBeforeMakingThem) {
    for (const char* generator :
         {R"({"type": "stack", "count": 100000000})", R"({"type": "pyramid", "base": 1000000000})",
          R"({"type": "wall", "rows": 100000, "columns": 100000})",
          R"({"type": "grid", "count": [1000, 1000, 2], "shapes": [{"type": "sphere"}]})"}) {
        const Json document =
            Json::parse(std::string(R"({"bodies": [], "generators": [)") + generator + "]}");
        try {
            parseScene(document, "big");
            ADD_FAILURE() << "accepted " << generator;
        } catch (const InvalidArgument& e) {
            EXPECT_NE(std::string(e.what()).find("generators[0]: would make "), std::string::npos)
                << e.what();
            EXPECT_NE(std::string(e.what()).find("past its limit of 1000000"), std::string::npos)
                << e.what();
        }
    }
    // The limit counts the listed bodies too (making a million bodies to show the limit itself
    // is allowed takes 0.5 GB and seconds).
    const Json oneTooMany = Json::parse(R"({"bodies": [{"shapes": [{"type": "sphere"}]}],
        "generators": [{"type": "grid", "count": [1000, 1000, 1],
                        "shapes": [{"type": "sphere"}]}]})");
    try {
        parseScene(oneTooMany, "big");
        ADD_FAILURE() << "accepted 1,000,001 bodies";
    } catch (const InvalidArgument& e) {
        EXPECT_NE(std::string(e.what()).find("past its limit"), std::string::npos) << e.what();
    }
    const Json fine = Json::parse(R"({"generators": [{"type": "grid", "count": [100, 100, 2],
        "shapes": [{"type": "sphere"}]}]})");
    EXPECT_EQ(parseScene(fine, "fine").bodies.size(), 20'000u);
}

}  // namespace
}  // namespace tumble::cli
