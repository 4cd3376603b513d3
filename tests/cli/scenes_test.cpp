// The built-in scenes that need springs, nets and joints, and a fixture with one of each
// connection, checked against what physics says they must do.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <map>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <vector>

#include "cli_helpers.h"

namespace fs = std::filesystem;
using namespace tumble::cli::test;

namespace {

struct Sample {
    double t = 0, x = 0, y = 0, z = 0, vx = 0, vy = 0, vz = 0;
};

// A cell as a double. Not std::stod: it throws out_of_range on a subnormal, and a resting node's
// velocity decays geometrically under drag until it prints as one (9.88e-324).
double number(const std::string& cell) {
    return std::strtod(cell.c_str(), nullptr);
}

/// The CSV as one time series per body name.
std::map<std::string, std::vector<Sample>> readTrajectories(const fs::path& file) {
    std::istringstream csv(slurp(file));
    std::string line;
    std::getline(csv, line);  // header
    std::map<std::string, std::vector<Sample>> out;
    while (std::getline(csv, line)) {
        std::vector<std::string> cells;
        std::stringstream row(line);
        for (std::string cell; std::getline(row, cell, ',');)
            cells.push_back(cell);
        if (cells.size() != 16)
            continue;
        out[cells[2]].push_back({number(cells[0]), number(cells[3]), number(cells[4]),
                                 number(cells[5]), number(cells[10]), number(cells[11]),
                                 number(cells[12])});
    }
    return out;
}

std::size_t count(const std::string& text, const std::string& what) {
    std::size_t n = 0;
    for (std::size_t at = text.find(what); at != std::string::npos; at = text.find(what, at + 1))
        ++n;
    return n;
}

}  // namespace

TEST(Scenes, NetCaptureWrapsTheDustbinAndRecordsItsCorners) {
    // A 20 x 20 net (mesh 0.1 m, 1.9 m across, corner diagonal 1.34 m) falls centred onto a bin of
    // radius 0.3 m and height 0.8 m. Wrapped: the middle rests on the lid, the edges hang down the
    // side, and the heavy corners end on the ground close to the bin -- a net that fell flat
    // beside it would leave them 1.34 m or more from the axis.
    const fs::path dir = scratch("net_capture");
    const fs::path csv = dir / "corners.csv", summary = dir / "s.json", picture = dir / "p.svg";
    const Outcome o = tumbleRun({"run", "net-capture", "--time", "1.5", "--quiet", "--record",
                                 csv.string(), "--record-bodies", "net.corners,net[10][10]",
                                 "--summary", summary.string(), "--picture", picture.string()});
    ASSERT_EQ(o.status, 0) << o.err;
    const auto paths = readTrajectories(csv);
    ASSERT_EQ(paths.size(), 5u);
    for (const char* corner : {"net[0][0]", "net[0][19]", "net[19][0]", "net[19][19]"}) {
        ASSERT_EQ(paths.count(corner), 1u) << corner;
        const Sample start = paths.at(corner).front(), end = paths.at(corner).back();
        EXPECT_NEAR(std::hypot(start.x, start.y), 0.95 * std::sqrt(2.0), 1e-9) << corner;
        EXPECT_NEAR(end.t, 1.5, 1e-6);
        EXPECT_LT(end.z, 0.02) << corner << " is on the ground (node radius 0.01 m)";
        EXPECT_LT(std::hypot(end.x, end.y), 0.75) << corner << " wrapped in close to the bin";
    }
    const Sample middle = paths.at("net[10][10]").back();
    EXPECT_NEAR(middle.z, 0.81, 0.01) << "the middle rests on the lid";
    EXPECT_LT(std::hypot(middle.x, middle.y), 0.3);
    const nlohmann::json s = nlohmann::json::parse(slurp(summary));
    EXPECT_EQ(s["bodies"], 402);
    EXPECT_LT(s["energy"]["end"]["total"].get<double>(),
              s["energy"]["start"]["total"].get<double>());
    // Each of the four panels (outputs.pictureTimes) draws the 2 x 20 x 19 threads and the 400
    // colliding nodes.
    const std::string svg = slurp(picture);
    EXPECT_EQ(count(svg, "t = "), 4u);
    EXPECT_GE(count(svg, "<line"), 4u * 760u);
    EXPECT_GE(count(svg, "<circle"), 4u * 400u);
}

TEST(Scenes, DustbinMeshCatchesTheNetOnItsRim) {
    // net-capture's net thrown onto an open bin of triangles (radius 0.3 m, 0.8 m tall, thin
    // walls, no lid). Its threads collide (thread.collide): threads caught on the rim between
    // nodes hold the net across the opening -- the middle stays up at the rim, not on the bin's
    // floor or the ground -- and the heavy corners are drawn in as around net-capture's solid
    // bin (< 0.75 m from the axis, on the ground). Without thread contacts the net slid past the
    // rim: corners 1.27 m out, the middle on the ground.
    const fs::path dir = scratch("dustbin_mesh");
    const fs::path csv = dir / "corners.csv";
    const Outcome o = tumbleRun({"run", "dustbin-mesh", "--time", "1.5", "--quiet", "--record",
                                 csv.string(), "--record-bodies", "net.corners,net[10][10]"});
    ASSERT_EQ(o.status, 0) << o.err;
    const auto paths = readTrajectories(csv);
    ASSERT_EQ(paths.size(), 5u);
    for (const char* corner : {"net[0][0]", "net[0][19]", "net[19][0]", "net[19][19]"}) {
        const Sample end = paths.at(corner).back();
        EXPECT_LT(end.z, 0.02) << corner << " is on the ground (node radius 0.01 m)";
        EXPECT_LT(std::hypot(end.x, end.y), 0.75) << corner << " drawn in to the bin";
    }
    const Sample middle = paths.at("net[10][10]").back();
    EXPECT_LT(std::hypot(middle.x, middle.y), 0.3) << "the middle is over the opening";
    EXPECT_GT(middle.z, 0.5) << "held by the rim";
}

TEST(Scenes, DustbinMeshNetComesToRestOnTheBin) {
    // Tolerance, written before measuring (issue 26's target): the net caught on the rim settles,
    // its median node speed below 5 mm/s after 2 s. Measured on main before the thread contacts'
    // push-out was capped (segment_contact_row.cpp): 18.6 mm/s, the skirt on the wall moving.
    const fs::path dir = scratch("dustbin_mesh_rest");
    const fs::path csv = dir / "net.csv";
    std::string nodes;
    for (int i = 0; i < 20; ++i) {
        for (int j = 0; j < 20; ++j) {
            if (!nodes.empty())
                nodes += ',';
            nodes += "net[" + std::to_string(i) + "][" + std::to_string(j) + "]";
        }
    }
    const Outcome o = tumbleRun({"run", "dustbin-mesh", "--time", "2", "--quiet", "--record",
                                 csv.string(), "--record-rate", "2", "--record-bodies", nodes});
    ASSERT_EQ(o.status, 0) << o.err;
    const auto paths = readTrajectories(csv);
    ASSERT_EQ(paths.size(), 400u);
    std::vector<double> speeds;
    for (const auto& [name, samples] : paths) {
        const Sample& end = samples.back();
        EXPECT_NEAR(end.t, 2.0, 1e-9) << name;
        speeds.push_back(std::hypot(end.vx, end.vy, end.vz));
    }
    std::nth_element(speeds.begin(), speeds.begin() + speeds.size() / 2, speeds.end());
    EXPECT_LT(speeds[speeds.size() / 2], 5e-3);
}

TEST(Scenes, StringStrikeReachesTheFreeEndAfterTheWaveTravelTime) {
    // A hanging string carries tension rho g s at height s above its free end, so a transverse
    // wave travels at sqrt(g s) and takes 2 sqrt(s / g) to come down from height s. The 15th of
    // 30 nodes is struck 0.75 m above the last: 0.553 s. Measured: the last node has moved
    // 0.015 mm at 0.32 s, 5.7 mm at 0.44 s and reaches 7.2 cm at 0.64 s.
    const fs::path dir = scratch("string");
    const fs::path csv = dir / "t.csv";
    ASSERT_EQ(tumbleRun({"run", "string", "--time", "1", "--quiet", "--record", csv.string(),
                         "--record-bodies", "string[0],string[14],string[29]"})
                  .status,
              0);
    const auto paths = readTrajectories(csv);
    EXPECT_NEAR(paths.at("string[14]").front().vx, 2.0, 1e-12);
    EXPECT_EQ(paths.at("string[29]").front().vx, 0.0);
    const double travel = 2 * std::sqrt(0.75 / 9.81);
    double quietUntil = 0, peak = 0;
    for (const Sample& p : paths.at("string[29]")) {
        if (std::abs(p.x) < 1e-4)
            quietUntil = p.t;
        peak = std::max(peak, std::abs(p.x));
    }
    EXPECT_GT(quietUntil, 0.5 * travel);
    EXPECT_LT(quietUntil, travel);
    EXPECT_GT(peak, 0.02);
    // The top node, one stiff thread below the fixed point, barely moves sideways.
    for (const Sample& p : paths.at("string[0]"))
        EXPECT_LT(std::abs(p.x), 0.02) << "t = " << p.t;
}

TEST(Scenes, ArmMotorsDriveBothHingesToTheirUpperLimits) {
    // Shoulder at (0, 0, 1) turning up at 0.8 rad/s to its limit 1.2 rad, elbow 0.6 m out turning
    // at 1.2 rad/s to 2.0 rad: the hand's centre (0.55 m beyond the elbow, welded) ends at
    // shoulder + 0.6 (cos 1.2, sin 1.2) + 0.55 (cos 3.2, sin 3.2) in x-z, held there against
    // gravity by the limits.
    const fs::path dir = scratch("arm");
    const fs::path csv = dir / "t.csv";
    ASSERT_EQ(tumbleRun({"run", "arm", "--quiet", "--record", csv.string(), "--record-bodies",
                         "hand", "--record-rate", "10"})
                  .status,
              0);
    const Sample hand = readTrajectories(csv).at("hand").back();
    const double x = 0.6 * std::cos(1.2) + 0.55 * std::cos(3.2);
    const double z = 1 + 0.6 * std::sin(1.2) + 0.55 * std::sin(3.2);
    EXPECT_NEAR(hand.x, x, 0.01);
    EXPECT_NEAR(hand.z, z, 0.01);
    EXPECT_NEAR(hand.y, 0, 1e-6);
    EXPECT_LT(std::hypot(hand.vx, hand.vz), 1e-3);
}

TEST(Scenes, PidArmHoldsItsSetPointsAgainstGravity) {
    // The arm of `arm` with PID controllers from the scene file instead of motors: shoulder to
    // 0.8 rad, elbow to 1.2 rad. The integral takes up the gravity load, so the hand ends where
    // the set-points put it, at rest (a PD alone would sag by torque / kp).
    const fs::path dir = scratch("pd-arm");
    const fs::path csv = dir / "t.csv";
    ASSERT_EQ(tumbleRun({"run", "pd-arm", "--quiet", "--record", csv.string(), "--record-bodies",
                         "hand", "--record-rate", "10"})
                  .status,
              0);
    const Sample hand = readTrajectories(csv).at("hand").back();
    const double x = 0.6 * std::cos(0.8) + 0.55 * std::cos(2.0);
    const double z = 1 + 0.6 * std::sin(0.8) + 0.55 * std::sin(2.0);
    EXPECT_NEAR(hand.x, x, 1e-4);
    EXPECT_NEAR(hand.z, z, 1e-4);
    EXPECT_LT(std::hypot(hand.vx, hand.vz), 1e-4);
}

TEST(Scenes, SliderRopeSpringAndDragDoWhatTheirDefinitionsSay) {
    const fs::path dir = scratch("connections");
    const fs::path csv = dir / "t.csv", summary = dir / "s.json";
    ASSERT_EQ(tumbleRun({"run", kFixtures + "/connections.json", "--quiet", "--record",
                         csv.string(), "--summary", summary.string()})
                  .status,
              0);
    const auto paths = readTrajectories(csv);
    ASSERT_EQ(paths.size(), 4u);  // outputs.recordBodies
    // Slider: its motor moves the cart along x at 0.5 m/s (0.25 m by 0.5 s, to a step), the
    // upper limit stops it at 0.4 m, and it stays at the rail's height against gravity.
    const auto& cart = paths.at("cart");
    EXPECT_NEAR(cart[5].t, 0.5, 1e-6);
    EXPECT_NEAR(cart[5].x, 0.25, 0.5 / 240 + 1e-9);
    EXPECT_NEAR(cart.back().x, 0.4, 1e-3);
    for (const Sample& p : cart)
        EXPECT_NEAR(p.z, 3, 1e-3);
    // Rope of 1 m from (2, 0, 3), 0.5 m slack at the start: never longer than 1 m; hangs at 1 m.
    for (const Sample& p : paths.at("bob"))
        EXPECT_LT(std::hypot(p.x - 2, 3 - p.z), 1.0 + 2e-3) << "t = " << p.t;
    EXPECT_NEAR(paths.at("bob").back().z, 2, 1e-3);
    // Spring k = E A / L0 = 2e5 * 1e-3 / 1 = 200 N/m under 2 kg, damped at zeta = 0.5: settles
    // m g / k = 0.0981 m below its unstretched length.
    EXPECT_NEAR(paths.at("weight").back().z, 2 - 2 * 9.81 / 200, 1e-5);
    // Linear drag b = 0.5 N s/m on 0.1 kg: terminal speed m g / b after 25 time constants.
    EXPECT_NEAR(paths.at("feather").back().vz, -0.1 * 9.81 / 0.5, 1e-6);
    // The spring's energy is counted: k x^2 / 2 at rest.
    const nlohmann::json s = nlohmann::json::parse(slurp(summary));
    EXPECT_NEAR(s["energy"]["end"]["elastic"].get<double>(), 0.5 * 200 * std::pow(0.0981, 2), 1e-3);
}
