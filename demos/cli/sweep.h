#pragma once
/// `tumble sweep` and `tumble-sweep` (docs/sweeps.md): the runs of a study, the results table on
/// disk that makes a study resumable, and the local driver. The MPI driver (sweep_mpi.cpp) shares
/// all of it but the hand-out of runs, so both write the same table.

#include <chrono>
#include <cstdint>
#include <filesystem>
#include <iosfwd>
#include <limits>
#include <map>
#include <mutex>
#include <string>
#include <vector>

#include "study.h"

namespace CLI {
class App;
}

namespace tumble::cli {

struct SweepOptions {
    std::string study;  ///< the study file
    std::string out;    ///< the results directory (made when missing)
    std::string shard;  ///< "i/N": only the runs with index % N == i ("" = all)
    int jobs = 0;       ///< local worker threads; 0 = one per core
    /// New runs this invocation at most (then it stops as if interrupted); for budgets and tests.
    std::uint64_t maxRuns = std::numeric_limits<std::uint64_t>::max();
    bool terminal = false;  ///< stderr is a terminal: the progress line is redrawn in place
};

/// Declares the options both commands take (`local` adds --jobs) on `app`.
void addSweepOptions(CLI::App& app, SweepOptions& options, bool local);

/// One finished run: its CSV row (with its newline) and, when it failed, why.
struct RunResult {
    std::uint64_t index = 0;
    std::string row;
    std::string message;
};

/// Runs run `index` of the study through the same runScene as `tumble run`. Never throws: a run
/// whose scene is refused or that throws is a row with status "error".
RunResult runStudy(const Study& study, std::uint64_t index);

/// The results table's header line (with its newline).
std::string resultsHeader(const Study& study);

/// The results directory: what is done (every results*.csv in it, so shards and interrupted
/// runs count), what is left for this invocation, and the rows as they come. A row is appended
/// whole as its run ends (synced to disk at least once a second), so a killed sweep loses at
/// most the runs in flight.
class SweepTable {
public:
    /// Refuses (InvalidArgument) a directory made by another study or a table of other columns.
    SweepTable(const Study& study, const SweepOptions& options, std::ostream& err);
    SweepTable(const SweepTable&) = delete;
    SweepTable& operator=(const SweepTable&) = delete;
    ~SweepTable();

    /// This invocation's runs, in index order.
    const std::vector<std::uint64_t>& todo() const { return todo_; }
    /// Appends a finished run; thread-safe. Prints progress and a failed run's message.
    void record(const RunResult& result);
    /// Once every run of the study is done, writes DIR/results.csv sorted by run (atomically)
    /// and removes the shard files; says where the table is or what is left. Returns 0.
    int finish(std::ostream& out);

private:
    void readExisting(const std::filesystem::path& file, bool own);
    void progress(bool last);

    const Study& study_;
    std::filesystem::path dir_, own_;
    std::string header_;
    std::map<std::uint64_t, std::string> done_;
    std::vector<std::uint64_t> todo_;
    int fd_ = -1;
    std::mutex mutex_;
    std::ostream& err_;
    bool terminal_ = false;
    std::uint64_t finished_ = 0;
    std::chrono::steady_clock::time_point begin_ = std::chrono::steady_clock::now();
    double lastPrint_ = 0;
    double lastSync_ = 0;  ///< (s since begin_) of the last fsync
};

/// `tumble sweep`: the study on local threads. Returns 0, or 2 for bad input (nothing written).
int runSweep(const SweepOptions& options, const std::string& sceneDirectory, std::ostream& out,
             std::ostream& err);

}  // namespace tumble::cli
