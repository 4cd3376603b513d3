// The report: tables as CSV (for the plots) and Markdown (for reading), figures as PNG.

#include "report.h"

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>

namespace tumble::validation {
namespace {

void writeCsv(const std::string& path, const std::vector<TableRow>& table) {
    std::ofstream out(path);
    out.precision(10);
    for (std::size_t i = 0; i < table.front().values.size(); ++i)
        out << (i ? "," : "") << table.front().values[i].first;
    out << '\n';
    for (const TableRow& row : table) {
        for (std::size_t i = 0; i < row.values.size(); ++i)
            out << (i ? "," : "") << row.values[i].second;
        out << '\n';
    }
}

void writeMarkdownTable(std::ofstream& out, const std::vector<TableRow>& table) {
    out << '|';
    for (const auto& [name, value] : table.front().values)
        out << ' ' << name << " |";
    out << "\n|";
    for (std::size_t i = 0; i < table.front().values.size(); ++i)
        out << "---|";
    out << '\n';
    for (const TableRow& row : table) {
        out << '|';
        for (const auto& [name, value] : row.values) {
            char cell[32];
            std::snprintf(cell, sizeof cell, " %.4g |", value);
            out << cell;
        }
        out << '\n';
    }
}

// One engine's stack row in tumble-bench's CSV.
struct BenchStack {
    double wall = 0;        ///< median wall s per simulated s
    double collapsed = -1;  ///< when the stack collapsed (s), -1 never
};

// Fig. 11's peers: the stack rows ("stack-N", engine, "ran", median wall s per sim s, ...,
// collapsed_at_s in column 11) of tumble-bench's CSV, as cubes -> engine -> row. Empty when the
// file is not there.
std::map<int, std::map<std::string, BenchStack>> benchStacks(const std::string& path) {
    std::map<int, std::map<std::string, BenchStack>> rows;
    std::ifstream in(path);
    std::string line;
    std::getline(in, line);  // header
    while (std::getline(in, line)) {
        std::vector<std::string> cells;
        std::stringstream fields(line);
        for (std::string cell; std::getline(fields, cell, ',');)
            cells.push_back(cell);
        if (cells.size() < 11 || cells[0].rfind("stack-", 0) != 0 || cells[2] != "ran")
            continue;
        rows[std::atoi(cells[0].c_str() + 6)][cells[1]] = {std::atof(cells[3].c_str()),
                                                           std::atof(cells[10].c_str())};
    }
    return rows;
}

// Fig. 11 beside the peers: this run's Tumble column and tumble-bench's committed rows, as
// Markdown in the report and as DIR/fig11_peers.csv (cubes, engine, wall s per sim s) for the plot.
void writeStackPeers(std::ofstream& out, const std::string& dir, const CaseResult& r) {
#ifdef TUMBLE_VALIDATE_BENCH_CSV
    const auto bench = benchStacks(TUMBLE_VALIDATE_BENCH_CSV);
    if (bench.empty())
        return;
    out << "\nBeside the peers: the engines' columns are tumble-bench's (median wall s per "
           "simulated s, same scene, 5 s x 5 runs) from `bench/results/harness/tumble-bench.csv`, "
           "a separate run, committed with its machine in bench/README.md; its Tumble column "
           "shows how far the two runs' machine load differed. A stack that fell was timed "
           "falling.\n\n"
           "| cubes | tumble (this run) | tumble (bench) | bullet | ode | box2d |\n"
           "|---|---|---|---|---|---|\n";
    std::ofstream csv(dir + "/fig11_peers.csv");
    csv.precision(10);
    csv << "cubes,engine,wall_s_per_s,collapsed_at_s\n";
    for (const auto& [cubes, engines] : bench) {
        double here = -1;
        for (const TableRow& row : r.table) {
            if (row.values[0].second == cubes)
                here = row.values[1].second;
        }
        char cell[32];
        std::snprintf(cell, sizeof cell, "| %d |", cubes);
        out << cell;
        if (here >= 0) {
            std::snprintf(cell, sizeof cell, " %.4g |", here);
            out << cell;
        } else {
            out << " - |";
        }
        for (const char* engine : {"tumble", "bullet", "ode", "box2d"}) {
            const auto found = engines.find(engine);
            if (found == engines.end()) {
                out << " not run |";
                continue;
            }
            const BenchStack& b = found->second;
            char text[64];
            if (b.collapsed >= 0)
                std::snprintf(text, sizeof text, " %.4g (fell at %.2g s) |", b.wall, b.collapsed);
            else
                std::snprintf(text, sizeof text, " %.4g |", b.wall);
            out << text;
            csv << cubes << ',' << engine << ',' << b.wall << ',' << b.collapsed << '\n';
        }
        out << '\n';
    }
#else
    (void)out;
    (void)dir;
    (void)r;
#endif
}

#ifdef TUMBLE_VALIDATE_BENCH_CSV
// The peers' runs of a case's scene, from tumble-bench's committed CSVs (bench/results/harness):
// which file goes with which case, the harness mode that wrote it and what it ran.
struct PeerCsv {
    const char* caseName;
    const char* file;
    const char* mode;
    const char* what;
};

constexpr const char* kStringPeers =
    "the same string in Bullet and ODE as point masses under the harness's tension-only thread "
    "forces (Tumble's explicit law)";

constexpr PeerCsv kPeerCsvs[] = {
    {"oscillator", "study-peers-oscillator.csv", "--study",
     "the same mass on the same explicit spring (-k x applied before each step) in Bullet and ODE, "
     "measured by the same code (validation/cases/fig45.h)"},
    {"bounce", "study-peers-bounce.csv", "--study",
     "the same drop in Bullet (its default correction: split impulse only for penetrations "
     "deeper than 4 cm, Baumgarte for shallower; Baumgarte alone; split impulse everywhere; the "
     "last two also without its speculative contacts) and ODE (Baumgarte, ERP 0.2), measured by "
     "the same code (validation/cases/fig45.h)"},
    {"string", "string-peers-transient.csv", "--string", kStringPeers},
    {"string-cost", "string-peers-cost.csv", "--string", kStringPeers},
};
#endif

// Fig. 4, 5, 7 and 10 beside the peers: the case's tumble-bench CSV (kPeerCsvs), copied into DIR
// for the plot and named in the report. Nothing for other cases or when the file is not there.
void copyPeerCsv(std::ofstream& out, const std::string& dir, const std::string& name) {
#ifdef TUMBLE_VALIDATE_BENCH_CSV
    for (const PeerCsv& peer : kPeerCsvs) {
        if (name != peer.caseName)
            continue;
        const std::filesystem::path from =
            std::filesystem::path(TUMBLE_VALIDATE_BENCH_CSV).parent_path() / peer.file;
        std::error_code error;
        if (!std::filesystem::exists(from, error))
            continue;
        std::filesystem::copy_file(from, std::filesystem::path(dir) / peer.file,
                                   std::filesystem::copy_options::overwrite_existing, error);
        if (error)
            continue;
        out << "\nBeside the peers: `" << peer.file << "` (plotted) is `tumble-bench " << peer.mode
            << "`'s committed run (bench/results/harness): " << peer.what
            << ", a separate run; see bench/README.md.\n";
    }
#else
    (void)out;
    (void)dir;
    (void)name;
#endif
}

}  // namespace

bool writeReport(const std::string& dir,
                 const std::vector<std::pair<const ValidationCase*, CaseResult>>& results) {
    std::error_code error;
    std::filesystem::create_directories(dir, error);
    std::ofstream out(dir + "/report.md");
    if (error || !out)
        return false;
    out << "# Validation report\n\nFigures (when python3-matplotlib is installed): "
           "[Fig. 4, oscillator](fig4_oscillator.png), [Fig. 5, bounce](fig5_bounce.png), "
           "[Fig. 7, string transient and spectrum](fig7_string.png), [Fig. 10, string cost "
           "against stiffness](fig10_string_cost.png), [Fig. 11, stack cost against "
           "cubes](fig11_stack_cost.png). Timings are one machine's, at its load then: "
           "benchmarks, not claims.\n";
    for (const auto& [c, r] : results) {
        out << "\n## " << c->name << ": " << (r.passed() ? "passed" : "FAILED") << "\n\n"
            << c->claim << "\n\n";
        for (const auto& [name, value] : r.metrics)
            out << "- " << name << " = " << value << '\n';
        for (const auto& [name, value] : r.tolerances)
            out << "- tolerance " << name << " = " << value << '\n';
        for (const std::string& failure : r.failures)
            out << "- FAIL: " << failure << '\n';
        for (const auto& [name, rows] : r.series) {
            if (!rows.empty())
                writeCsv(dir + "/" + c->name + "-" + name + ".csv", rows);
        }
        if (r.table.empty())
            continue;
        out << '\n';
        writeMarkdownTable(out, r.table);
        writeCsv(dir + "/" + c->name + ".csv", r.table);
        if (c->name == "stack-cost")
            writeStackPeers(out, dir, r);
        copyPeerCsv(out, dir, c->name);
    }
    out.close();
    std::printf("wrote %s/report.md\n", dir.c_str());
#ifdef TUMBLE_VALIDATE_PLOT_SCRIPT
    const std::string command =
        std::string("/usr/bin/python3 ") + TUMBLE_VALIDATE_PLOT_SCRIPT + " " + dir;
    if (!std::filesystem::exists("/usr/bin/python3") || std::system(command.c_str()) != 0)
        std::printf("no plots (python3-matplotlib missing?): %s\n", command.c_str());
#endif
    return true;
}

}  // namespace tumble::validation
