// The report: tables as CSV (for the plots) and Markdown (for reading), figures as PNG.

#include "report.h"

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>

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

}  // namespace

bool writeReport(const std::string& dir,
                 const std::vector<std::pair<const ValidationCase*, CaseResult>>& results) {
    std::error_code error;
    std::filesystem::create_directories(dir, error);
    std::ofstream out(dir + "/report.md");
    if (error || !out)
        return false;
    out << "# Validation report\n\nFigures (when python3-matplotlib is installed): "
           "[Fig. 4, oscillator](fig4_oscillator.png), [Fig. 5, bounce](fig5_bounce.png).\n";
    for (const auto& [c, r] : results) {
        out << "\n## " << c->name << ": " << (r.passed() ? "passed" : "FAILED") << "\n\n"
            << c->claim << "\n\n";
        for (const auto& [name, value] : r.metrics)
            out << "- " << name << " = " << value << '\n';
        for (const auto& [name, value] : r.tolerances)
            out << "- tolerance " << name << " = " << value << '\n';
        for (const std::string& failure : r.failures)
            out << "- FAIL: " << failure << '\n';
        if (r.table.empty())
            continue;
        out << '\n';
        writeMarkdownTable(out, r.table);
        writeCsv(dir + "/" + c->name + ".csv", r.table);
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
