// `tumble sweep`: study files read strictly, run i the same whatever the workers and shards, an
// interrupted study resumed without redoing a run, and the measures checked against physics.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include "cli_helpers.h"
#include "refusal.h"

namespace fs = std::filesystem;
using namespace tumble::cli::test;
using tumble::test::contains;

namespace {

const std::string kDrop = kFixtures + "/studies/drop.json";

/// The table without its last column (wall_s, the one measurement that differs between runs).
std::string withoutWallTime(const std::string& table) {
    std::istringstream in(table);
    std::string out, line;
    while (std::getline(in, line))
        out += line.substr(0, line.rfind(',')) + "\n";
    return out;
}

/// The rows of a CSV as maps from column to cell.
std::vector<std::map<std::string, std::string>> rowsOf(const std::string& table) {
    std::istringstream in(table);
    std::string line, cell;
    std::getline(in, line);
    std::vector<std::string> header;
    for (std::istringstream h(line); std::getline(h, cell, ',');)
        header.push_back(cell);
    std::vector<std::map<std::string, std::string>> rows;
    while (std::getline(in, line)) {
        std::istringstream r(line);
        rows.emplace_back();
        for (std::size_t k = 0; std::getline(r, cell, ','); ++k)
            rows.back()[header.at(k)] = cell;
    }
    return rows;
}

Outcome sweep(const std::string& study, const fs::path& out, std::vector<std::string> extra = {}) {
    std::vector<std::string> args{"sweep", study, "--out", out.string()};
    args.insert(args.end(), extra.begin(), extra.end());
    return tumbleRun(args);
}

}  // namespace

// A ball dropped from rest falls to z = 0.1 m in sqrt(2 (z0 - 0.1) / g); symplectic Euler is
// early by h/2 at most, and the crossing is interpolated within a step: within h = 1 ms.
TEST(SweepCommand, DroppedBallFallTimeMatchesFreeFallPerRow) {
    const fs::path dir = scratch("sweep_drop");
    const Outcome o = sweep(kDrop, dir / "out", {"--jobs", "2"});
    ASSERT_EQ(o.status, 0) << o.err;
    const auto rows = rowsOf(slurp(dir / "out" / "results.csv"));
    ASSERT_EQ(rows.size(), 20u);  // 5 heights x 4 sideways speeds
    for (std::size_t i = 0; i < rows.size(); ++i) {
        const auto& row = rows[i];
        EXPECT_EQ(row.at("run"), std::to_string(i));
        EXPECT_EQ(row.at("status"), "ok");
        const double z0 = std::stod(row.at("z0"));
        EXPECT_NEAR(std::stod(row.at("fall")), std::sqrt(2 * (z0 - 0.1) / 9.81), 1e-3) << i;
        EXPECT_DOUBLE_EQ(std::stod(row.at("zmax")), z0);
        const double vx = std::stod(row.at("vx"));
        EXPECT_GE(vx, -1);
        EXPECT_LE(vx, 1);
    }
    EXPECT_DOUBLE_EQ(std::stod(rows[0].at("z0")), 0.2335);
    EXPECT_DOUBLE_EQ(std::stod(rows[19].at("z0")), 2.0335);
    EXPECT_NE(rows[0].at("vx"), rows[1].at("vx"));  // drawn per run
}

TEST(SweepCommand, TableIsTheSameWhateverTheWorkersAndShards) {
    const fs::path dir = scratch("sweep_workers");
    ASSERT_EQ(sweep(kDrop, dir / "one", {"--jobs", "1"}).status, 0);
    ASSERT_EQ(sweep(kDrop, dir / "three", {"--jobs", "3"}).status, 0);
    // Two shards of a job array into one directory, then a plain run that finds all done.
    ASSERT_EQ(sweep(kDrop, dir / "shards", {"--shard", "1/2"}).status, 0);
    EXPECT_FALSE(fs::exists(dir / "shards" / "results.csv"));
    ASSERT_EQ(sweep(kDrop, dir / "shards", {"--shard", "0/2"}).status, 0);
    const Outcome merge = sweep(kDrop, dir / "shards");
    ASSERT_EQ(merge.status, 0) << merge.err;
    EXPECT_TRUE(contains(merge.err, "sweep: 0/0 runs"));
    EXPECT_FALSE(fs::exists(dir / "shards" / "results.shard-0-of-2.csv"));
    const std::string one = withoutWallTime(slurp(dir / "one" / "results.csv"));
    EXPECT_EQ(std::count(one.begin(), one.end(), '\n'), 21);
    EXPECT_EQ(withoutWallTime(slurp(dir / "three" / "results.csv")), one);
    EXPECT_EQ(withoutWallTime(slurp(dir / "shards" / "results.csv")), one);
}

// Stopped after 5 runs, with a sixth row cut short as a kill leaves it, then resumed.
TEST(SweepCommand, InterruptedStudyResumesWithoutRedoingRuns) {
    const fs::path dir = scratch("sweep_resume");
    ASSERT_EQ(sweep(kDrop, dir / "whole").status, 0);
    const Outcome first = sweep(kDrop, dir / "cut", {"--max-runs", "5", "--jobs", "2"});
    ASSERT_EQ(first.status, 0) << first.err;
    EXPECT_TRUE(contains(first.out, "5 of 20 runs done"));
    const std::string partial = slurp(dir / "cut" / "results.csv");
    EXPECT_EQ(std::count(partial.begin(), partial.end(), '\n'), 6);
    std::ofstream(dir / "cut" / "results.csv", std::ios::app) << "7,1234,0.2";
    const Outcome second = sweep(kDrop, dir / "cut", {"--jobs", "2"});
    ASSERT_EQ(second.status, 0) << second.err;
    EXPECT_TRUE(contains(second.err, "sweep: 15/15 runs"));  // 20 - 5: none twice
    EXPECT_EQ(withoutWallTime(slurp(dir / "cut" / "results.csv")),
              withoutWallTime(slurp(dir / "whole" / "results.csv")));
}

// The capture criterion on a small net: over the bin it closes round it; 1.5 m off it misses.
TEST(SweepCommand, CaptureCriterionTellsACaptureFromAClearMiss) {
    const fs::path dir = scratch("sweep_capture");
    const Outcome o = sweep(kFixtures + "/studies/capture.json", dir / "out", {"--jobs", "2"});
    ASSERT_EQ(o.status, 0) << o.err;
    const auto rows = rowsOf(slurp(dir / "out" / "results.csv"));
    ASSERT_EQ(rows.size(), 2u);
    EXPECT_EQ(rows[0].at("captured"), "1");
    EXPECT_EQ(rows[1].at("captured"), "0");
}

TEST(SweepCommand, BadStudiesAreRefusedWithFileLineAndKeyAndNothingWritten) {
    const fs::path dir = scratch("sweep_bad");
    const std::string head = "{\n  \"scene\": \"bounce\",\n  \"outputs\": [\"steps\"],\n";
    const auto refused = [&](const std::string& name, const std::string& body,
                             const std::string& part) {
        const std::string path = (dir / (name + ".json")).string();
        std::ofstream(path) << head << body << "\n}\n";
        const Outcome o = sweep(path, dir / ("out-" + name));
        EXPECT_EQ(o.status, 2) << name;
        EXPECT_TRUE(contains(o.err, part)) << name;
        EXPECT_FALSE(fs::exists(dir / ("out-" + name))) << name;
    };
    refused("unknown_key", "  \"sed\": 3", "unknown_key.json:4: sed");
    refused("bad_path",
            "  \"parameters\": [\n    {\"path\": \"bodies.0.positon.2\", \"values\": [1]}\n  ]",
            "bad_path.json:5: parameters[0].path: \"bodies.0.positon.2\" does not apply");
    refused("negative_count",
            "  \"parameters\": [{\"path\": \"duration\", \"grid\": [1, 2], \"count\": -3}]",
            "negative_count.json:4: parameters[0].count: must be >= 1");
    refused("bad_bounds",
            "  \"parameters\": [{\"path\": \"duration\", \"distribution\": \"uniform\",\n"
            "    \"min\": 2, \"max\": 1, \"count\": 3}]",
            "bad_bounds.json:5: parameters[0].max: = 1 must be > min = 2");
    refused("log_bounds",
            "  \"parameters\": [{\"path\": \"duration\", \"distribution\": \"log-uniform\",\n"
            "    \"min\": 0, \"max\": 1, \"count\": 3}]",
            "log_bounds.json:5: parameters[0].min: = 0 must be > 0");
    const std::string badOutput = (dir / "bad_output.json").string();
    std::ofstream(badOutput) << "{\"scene\": \"bounce\", \"outputs\": [\n  {\"name\": \"z\", "
                                "\"measure\": \"final\", \"body\": \"bal\"}]}\n";
    const Outcome o = sweep(badOutput, dir / "out-output");
    EXPECT_EQ(o.status, 2);
    EXPECT_TRUE(contains(o.err, "bad_output.json:2: outputs[0].body"));
    EXPECT_TRUE(contains(o.err, "no body named \"bal\""));
    const Outcome shard = sweep(kDrop, dir / "out-shard", {"--shard", "2/2"});
    EXPECT_EQ(shard.status, 2);
    EXPECT_TRUE(contains(shard.err, "--shard 2/2"));
    EXPECT_FALSE(fs::exists(dir / "out-shard"));
}

// A directory holds one study's results: another study's rows are never mixed in.
TEST(SweepCommand, DirectoryOfAnotherStudyIsRefused) {
    const fs::path dir = scratch("sweep_other");
    ASSERT_EQ(sweep(kFixtures + "/studies/capture.json", dir / "out", {"--max-runs", "0"}).status,
              0);
    const Outcome o = sweep(kDrop, dir / "out");
    EXPECT_EQ(o.status, 2);
    EXPECT_TRUE(contains(o.err, "holds the results of another study"));
}

// A run whose values the scene refuses is a row with status "error", not the end of the study.
TEST(SweepCommand, RunThatFailsIsRecordedAndTheStudyGoesOn) {
    const fs::path dir = scratch("sweep_error");
    const std::string study = (dir / "mass.json").string();
    std::ofstream(study) << R"({"scene": "bounce", "duration": 0.05,
  "parameters": [{"path": "bodies.0.mass", "values": [0.057, -1, 0.1]}],
  "outputs": ["steps"]})";
    const Outcome o = sweep(study, dir / "out");
    ASSERT_EQ(o.status, 0) << o.err;
    EXPECT_TRUE(contains(o.err, "run 1: "));
    EXPECT_TRUE(contains(o.err, "bodies[0].mass"));
    const auto rows = rowsOf(slurp(dir / "out" / "results.csv"));
    ASSERT_EQ(rows.size(), 3u);
    EXPECT_EQ(rows[0].at("status"), "ok");
    EXPECT_EQ(rows[1].at("status"), "error");
    EXPECT_EQ(rows[1].at("steps"), "nan");
    EXPECT_EQ(rows[2].at("status"), "ok");
    EXPECT_EQ(rows[2].at("steps"), "12");  // 0.05 s at h = 1/240
}
