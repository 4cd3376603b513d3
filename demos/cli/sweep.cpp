// The study's runs and its results table. The table is the only shared state: runs are pure
// functions of (study, index), rows are appended whole with O_APPEND, and the final
// table is the rows sorted by index, so any number of workers in any order writes the same file
// (but for the wall_s column, which is a measurement).

#include "sweep.h"

#include <fcntl.h>
#include <unistd.h>

#include <CLI/CLI.hpp>
#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <sstream>
#include <thread>

#include "measures.h"
#include "run.h"

namespace tumble::cli {
namespace {

using Clock = std::chrono::steady_clock;

std::string number(double x) {
    char text[32];
    std::snprintf(text, sizeof text, "%.17g", x);
    return text;
}

/// A parameter value as a CSV cell: numbers round-trip, anything else is its JSON text quoted.
std::string cell(const Json& value) {
    if (value.is_number_float())
        return number(value.get<double>());
    if (value.is_number())
        return value.dump();
    std::string text = value.is_string() ? value.get<std::string>() : value.dump();
    if (text.find_first_of(",\"\n") == std::string::npos)
        return text;
    std::string quoted = "\"";
    for (const char c : text)
        quoted += c == '"' ? std::string("\"\"") : std::string(1, c);
    return quoted + "\"";
}

std::pair<std::uint64_t, std::uint64_t> parseShard(const std::string& text) {
    unsigned long long i = 0, n = 0;
    char slash = 0, extra = 0;
    if (std::sscanf(text.c_str(), "%llu%c%llu%c", &i, &slash, &n, &extra) != 3 || slash != '/' ||
        n == 0 || i >= n || text.find('-') != std::string::npos)
        fail("--shard ", text, ": expected i/N with 0 <= i < N (e.g. 0/4)");
    return {i, n};
}

/// Writes all of `text` (a row is never left half-written by a short write).
void writeAll(int fd, const std::string& text, const std::filesystem::path& file) {
    for (std::size_t at = 0; at < text.size();) {
        const ssize_t n = ::write(fd, text.data() + at, text.size() - at);
        if (n < 0)
            fail(file.string(), ": cannot be written");
        at += static_cast<std::size_t>(n);
    }
}

}  // namespace

void addSweepOptions(CLI::App& app, SweepOptions& o, bool local) {
    app.add_option("study", o.study, "The study file (docs/sweeps.md)")->required();
    app.add_option("--out", o.out, "Results directory (made when missing)")->required();
    app.add_option("--shard", o.shard, "Run only runs i, i+N, i+2N... (i/N): for job arrays");
    app.add_option("--max-runs", o.maxRuns, "Stop after this many new runs (resume later)");
    if (local)
        app.add_option("--jobs,-j", o.jobs, "Worker threads (default: one per core)");
}

std::string resultsHeader(const Study& study) {
    std::string header = "run,seed";
    for (const StudyParameter& p : study.parameters)
        header += "," + p.column;
    for (const StudyOutput& o : study.outputs)
        header += "," + o.name;
    return header + ",status,wall_s\n";
}

RunResult runStudy(const Study& study, std::uint64_t index) {
    const auto begin = Clock::now();
    RunResult result{index, std::to_string(index) + "," + std::to_string(runSeed(study, index)),
                     ""};
    for (const Json& value : runValues(study, index))
        result.row += "," + cell(value);
    std::vector<Real> values(study.outputs.size(), std::numeric_limits<Real>::quiet_NaN());
    std::string status = "error";
    try {
        const Scene scene = loadScene(study.scenePath, runOverrides(study, index), "");
        RunMeasures measures(study, scene);
        RunOptions options;
        options.quiet = true;
        options.observe = [&](const BuiltScene& built, bool end) { measures.observe(built, end); };
        Summary summary;
        std::ostringstream discard;
        const int code = runScene(scene, options, discard, discard, &summary);
        status = code != 0 ? "non-finite" : summary.warnings.empty() ? "ok" : "warned";
        values = measures.values(summary);
    } catch (const std::exception& e) {
        result.message = e.what();
    }
    for (const Real v : values)
        result.row += "," + number(v);
    char wall[32];
    std::snprintf(wall, sizeof wall, "%.3f",
                  std::chrono::duration<double>(Clock::now() - begin).count());
    result.row += "," + status + "," + wall + "\n";
    return result;
}

SweepTable::SweepTable(const Study& study, const SweepOptions& options, std::ostream& err)
    : study_(study),
      dir_(options.out),
      header_(resultsHeader(study)),
      err_(err),
      terminal_(options.terminal) {
    namespace fs = std::filesystem;
    const auto [shard, shards] = options.shard.empty()
                                     ? std::pair<std::uint64_t, std::uint64_t>{0, 1}
                                     : parseShard(options.shard);
    own_ = dir_ / (shards == 1 ? "results.csv"
                               : "results.shard-" + std::to_string(shard) + "-of-" +
                                     std::to_string(shards) + ".csv");
    std::error_code ec;
    fs::create_directories(dir_, ec);
    if (!fs::is_directory(dir_))
        fail("--out ", dir_.string(), ": cannot make the directory");
    // The results belong to one study and scene: mixing two would be a silent corruption.
    const fs::path stamp = dir_ / "study.fingerprint";
    std::ifstream in(stamp);
    std::string previous;
    if (in >> previous && previous != study.fingerprint)
        fail(dir_.string(), ": holds the results of another study (or its scene has changed); ",
             "give another --out");
    if (previous.empty())
        std::ofstream(stamp) << study.fingerprint << "\n";
    for (const auto& entry : fs::directory_iterator(dir_)) {
        const std::string name = entry.path().filename().string();
        if (name.rfind("results", 0) == 0 && entry.path().extension() == ".csv")
            readExisting(entry.path(), entry.path() == own_);
    }
    fd_ = ::open(own_.c_str(), O_WRONLY | O_CREAT | O_APPEND, 0644);
    if (fd_ < 0)
        fail(own_.string(), ": cannot be written");
    if (fs::file_size(own_) == 0) {
        writeAll(fd_, header_, own_);
        ::fsync(fd_);
    }
    for (std::uint64_t i = shard; i < study.runs && todo_.size() < options.maxRuns; i += shards) {
        if (done_.count(i) == 0)
            todo_.push_back(i);
    }
}

SweepTable::~SweepTable() {
    if (fd_ >= 0) {
        ::fsync(fd_);
        ::close(fd_);
    }
}

void SweepTable::readExisting(const std::filesystem::path& file, bool own) {
    std::ifstream in(file, std::ios::binary);
    std::stringstream buffer;
    buffer << in.rdbuf();
    const std::string text = buffer.str();
    if (text.empty())
        return;
    if (text.compare(0, header_.size(), header_) != 0)
        fail(file.string(), ": its columns are not this study's (", header_.substr(0, 60),
             "...); give another --out");
    std::size_t at = header_.size(), end = 0;
    for (; (end = text.find('\n', at)) != std::string::npos; at = end + 1) {
        const std::string row = text.substr(at, end + 1 - at);
        unsigned long long index = 0;
        if (std::sscanf(row.c_str(), "%llu,", &index) == 1 && index < study_.runs)
            done_.emplace(index, row);
    }
    // A row cut short by a kill is dropped, and its run redone.
    if (own && at < text.size())
        std::filesystem::resize_file(file, at);
}

void SweepTable::record(const RunResult& result) {
    const std::lock_guard<std::mutex> lock(mutex_);
    // A written row survives the process being killed (it is in the kernel's cache); fsync
    // guards against the machine going down, and costs ~6 ms here: at most once a second, or
    // it alone would cap rank 0 at ~180 rows/s.
    writeAll(fd_, result.row, own_);
    const double now = std::chrono::duration<double>(Clock::now() - begin_).count();
    if (now > lastSync_ + 1) {
        ::fsync(fd_);
        lastSync_ = now;
    }
    done_.emplace(result.index, result.row);
    ++finished_;
    if (!result.message.empty())
        err_ << "tumble sweep: run " << result.index << ": " << result.message << "\n";
    progress(false);
}

void SweepTable::progress(bool last) {
    const double elapsed = std::chrono::duration<double>(Clock::now() - begin_).count();
    if (!last && elapsed < lastPrint_ + 1)
        return;
    lastPrint_ = elapsed;
    const double left =
        finished_ > 0 ? elapsed / double(finished_) * double(todo_.size() - finished_) : 0;
    char line[160];
    std::snprintf(line, sizeof line, "sweep: %llu/%zu runs (%3.0f%%), %.1f s, ~%.0f s left",
                  static_cast<unsigned long long>(finished_), todo_.size(),
                  todo_.empty() ? 100.0 : 100.0 * double(finished_) / double(todo_.size()), elapsed,
                  left);
    err_ << (terminal_ ? "\r" : "") << line << (terminal_ && !last ? "" : "\n") << std::flush;
}

int SweepTable::finish(std::ostream& out) {
    namespace fs = std::filesystem;
    progress(true);
    if (done_.size() < study_.runs) {
        out << "sweep: " << done_.size() << " of " << study_.runs << " runs done in "
            << dir_.string() << "; run again (or the other shards) to continue\n";
        return 0;
    }
    std::string table = header_;
    for (const auto& [index, row] : done_)
        table += row;
    const fs::path final = dir_ / "results.csv", temporary = dir_ / "results.csv.tmp";
    const int fd = ::open(temporary.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    if (fd < 0)
        fail(temporary.string(), ": cannot be written");
    writeAll(fd, table, temporary);
    ::fsync(fd);
    ::close(fd);
    fs::rename(temporary, final);
    for (const auto& entry : fs::directory_iterator(dir_)) {
        if (entry.path().filename().string().rfind("results.shard-", 0) == 0)
            fs::remove(entry.path());
    }
    out << "sweep: " << study_.runs << " runs in " << final.string() << "\n";
    return 0;
}

int runSweep(const SweepOptions& options, const std::string& sceneDirectory, std::ostream& out,
             std::ostream& err) {
    const Study study = loadStudy(options.study, sceneDirectory);
    SweepTable table(study, options, err);
    const std::vector<std::uint64_t>& todo = table.todo();
    const unsigned cores = std::max(1u, std::thread::hardware_concurrency());
    const std::size_t jobs =
        std::min<std::size_t>(options.jobs > 0 ? std::size_t(options.jobs) : cores, todo.size());
    std::atomic<std::size_t> next{0};
    auto work = [&] {
        for (std::size_t k; (k = next++) < todo.size();)
            table.record(runStudy(study, todo[k]));
    };
    std::vector<std::thread> workers;
    for (std::size_t j = 1; j < jobs; ++j)
        workers.emplace_back(work);
    work();
    for (std::thread& w : workers)
        w.join();
    return table.finish(out);
}

}  // namespace tumble::cli
