// `tumble run --checkpoint FILE [--checkpoint-every T]` and `tumble run --resume FILE`: a run
// stopped and resumed ends in the very state of the run that was not stopped, and a bad
// checkpoint is refused with status 2 and a message naming the file and the fault. Scenes with
// a height field or a triangle mesh resume as well.

#include <gtest/gtest.h>

#include <filesystem>
#include <string>
#include <vector>

#include "cli_helpers.h"

namespace fs = std::filesystem;
using namespace tumble::cli::test;

namespace {

/// The CSV's rows (after the header) whose time column is at least `from`.
std::vector<std::string> rowsFrom(const std::string& csv, double from) {
    std::vector<std::string> rows;
    std::size_t start = csv.find('\n') + 1;
    while (start < csv.size()) {
        const std::size_t end = csv.find('\n', start);
        const std::string row = csv.substr(start, end - start);
        if (std::stod(row.substr(0, row.find(','))) >= from - 1e-9)
            rows.push_back(row);
        start = end + 1;
    }
    return rows;
}

}  // namespace

// net-capture: threads, colliding nodes and a bin; stopped at 0.25 s and resumed to 0.5 s.
TEST(CheckpointCommand, ResumedRunEndsBitwiseWhereTheUninterruptedRunEnds) {
    const fs::path dir = scratch("checkpoint_resume");
    const std::string whole = (dir / "whole.ckpt").string();
    const std::string half = (dir / "half.ckpt").string();
    const std::string resumed = (dir / "resumed.ckpt").string();
    const std::string periodic = (dir / "periodic.ckpt").string();
    const Outcome a = tumbleRun({"run", "net-capture", "--time", "0.5", "--quiet", "--checkpoint",
                                 whole, "--record", (dir / "whole.csv").string()});
    ASSERT_EQ(a.status, 0) << a.err;
    const Outcome b = tumbleRun({"run", "net-capture", "--time", "0.25", "--quiet", "--checkpoint",
                                 half, "--checkpoint-every", "0.1"});
    ASSERT_EQ(b.status, 0) << b.err;
    const Outcome c =
        tumbleRun({"run", "net-capture", "--time", "0.5", "--quiet", "--resume", half,
                   "--checkpoint", resumed, "--record", (dir / "resumed.csv").string(), "--summary",
                   (dir / "s.json").string()});
    ASSERT_EQ(c.status, 0) << c.err;
    EXPECT_EQ(slurp(resumed), slurp(whole));
    // The trajectory from 0.25 s on, row for row.
    const std::vector<std::string> resumedRows = rowsFrom(slurp(dir / "resumed.csv"), 0);
    ASSERT_FALSE(resumedRows.empty());
    EXPECT_EQ(resumedRows.front().substr(0, 9), "0.250000,");
    EXPECT_EQ(resumedRows, rowsFrom(slurp(dir / "whole.csv"), 0.25));
    EXPECT_NE(slurp(dir / "s.json").find("\"steps\": 60"), std::string::npos);  // h = 1/120
    // Checkpoints every 0.1 s do not change the run; no temporary is left behind.
    const Outcome d = tumbleRun({"run", "net-capture", "--time", "0.5", "--quiet", "--checkpoint",
                                 periodic, "--checkpoint-every", "0.1"});
    ASSERT_EQ(d.status, 0) << d.err;
    EXPECT_EQ(slurp(periodic), slurp(whole));
    EXPECT_FALSE(fs::exists(periodic + ".tmp"));
}

// The mesh scenes: the checkpoint carries the height field (terrain) and the triangle mesh
// (mesh-level), so a run resumed from it ends where the uninterrupted run ends.
TEST(CheckpointCommand, MeshScenesResumeBitwise) {
    for (const std::string scene : {"terrain", "mesh-level"}) {
        const fs::path dir = scratch("checkpoint_mesh_" + scene);
        const std::string whole = (dir / "whole.ckpt").string();
        const std::string half = (dir / "half.ckpt").string();
        const std::string resumed = (dir / "resumed.ckpt").string();
        for (const auto& args : std::vector<std::vector<std::string>>{
                 {"run", scene, "--time", "0.5", "--quiet", "--checkpoint", whole},
                 {"run", scene, "--time", "0.25", "--quiet", "--checkpoint", half},
                 {"run", scene, "--time", "0.5", "--quiet", "--resume", half, "--checkpoint",
                  resumed}}) {
            const Outcome run = tumbleRun(args);
            ASSERT_EQ(run.status, 0) << scene << ": " << run.err;
        }
        EXPECT_EQ(slurp(resumed), slurp(whole)) << scene;
        EXPECT_NE(slurp(half), slurp(whole)) << scene << ": the bodies moved in between";
    }
}

TEST(CheckpointCommand, BadCheckpointIsRefusedWithStatusTwo) {
    const fs::path dir = scratch("checkpoint_bad");
    const std::string good = (dir / "good.ckpt").string();
    ASSERT_EQ(tumbleRun({"run", "stack", "--time", "0.2", "--quiet", "--checkpoint", good}).status,
              0);
    const std::string bytes = slurp(good);
    const auto write = [&](const std::string& name, const std::string& content) {
        const std::string path = (dir / name).string();
        std::ofstream(path, std::ios::binary) << content;
        return path;
    };
    const auto refused = [&](const std::vector<std::string>& extra, const std::string& part) {
        std::vector<std::string> args{"run", "stack", "--time", "0.5", "--quiet"};
        args.insert(args.end(), extra.begin(), extra.end());
        const Outcome o = tumbleRun(args);
        EXPECT_EQ(o.status, 2) << o.err;
        EXPECT_NE(o.err.find(part), std::string::npos) << o.err;
    };
    const std::string cut = write("cut.ckpt", bytes.substr(0, bytes.size() / 2));
    refused({"--resume", cut}, "checkpoint " + cut + ": truncated");
    std::string flipped = bytes;
    flipped[flipped.size() / 2] ^= 4;
    const std::string flip = write("flip.ckpt", flipped);
    refused({"--resume", flip}, "checkpoint " + flip + ": corrupted");
    refused({"--resume", write("text.ckpt", "not a checkpoint at all, but long enough\n")},
            "not a Tumble checkpoint");
    refused({"--resume", (dir / "missing.ckpt").string()}, "cannot open");
    // A checkpoint of another scene.
    const std::string other = (dir / "other.ckpt").string();
    ASSERT_EQ(
        tumbleRun({"run", "bounce", "--time", "0.1", "--quiet", "--checkpoint", other}).status, 0);
    refused({"--resume", other}, "written from another scene");
    refused({"--resume", good, "--dt", "0.01"}, "time step");
    refused({"--checkpoint-every", "0.1"}, "--checkpoint-every needs --checkpoint");
    refused({"--checkpoint", (dir / "x.ckpt").string(), "--checkpoint-every", "0"}, "> 0");
    refused({"--checkpoint", (dir / "no-dir" / "x.ckpt").string()}, "cannot open");
}
