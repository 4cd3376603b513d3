// tumble-sweep: a study across MPI ranks (docs/sweeps.md). Rank 0 owns the results directory and
// hands out run indices one at a time, so a rank that drew cheap runs asks again sooner; every
// rank runs them, rank 0 on a second thread beside its dispatch loop (which alone calls MPI).
// Rows come back as text and go through the same SweepTable as `tumble sweep`: the same table.

#include <mpi.h>

#include <CLI/CLI.hpp>
#include <atomic>
#include <chrono>
#include <iostream>
#include <memory>
#include <optional>
#include <thread>

#include "sweep.h"

namespace {

using namespace tumble::cli;

constexpr int kRequest = 1;  // worker -> 0: the last run's row (empty at first), asks for a run
constexpr int kAssign = 2;   // 0 -> worker: a run index, or kStop
constexpr int kGone = 3;     // worker -> 0: this rank cannot run the study and leaves
constexpr std::uint64_t kStop = ~std::uint64_t{0};

std::string encode(const RunResult& r) {
    return r.message.empty() ? r.row : r.row + '\0' + r.message;
}

RunResult decode(const std::string& payload) {
    const std::size_t cut = payload.find('\0');
    RunResult r{std::stoull(payload), payload.substr(0, cut), ""};
    if (cut != std::string::npos)
        r.message = payload.substr(cut + 1);
    return r;
}

/// Rank 0: runs on a thread of its own while this loop answers the other ranks. Polls with a
/// short sleep rather than a blocking receive: Open MPI's spins, and would take a core.
int coordinate(const Study& study, SweepTable& table, int ranks) {
    const std::vector<std::uint64_t>& todo = table.todo();
    std::atomic<std::size_t> next{0};
    auto take = [&] {
        const std::size_t k = next++;
        return k < todo.size() ? todo[k] : kStop;
    };
    std::thread local([&] {
        for (std::uint64_t i; (i = take()) != kStop;)
            table.record(runStudy(study, i));
    });
    for (int active = ranks - 1; active > 0;) {
        int arrived = 0;
        MPI_Status status;
        MPI_Iprobe(MPI_ANY_SOURCE, MPI_ANY_TAG, MPI_COMM_WORLD, &arrived, &status);
        if (arrived == 0) {
            std::this_thread::sleep_for(std::chrono::milliseconds(1));
            continue;
        }
        int size = 0;
        MPI_Get_count(&status, MPI_CHAR, &size);
        std::string payload(static_cast<std::size_t>(size), '\0');
        MPI_Recv(payload.data(), size, MPI_CHAR, status.MPI_SOURCE, status.MPI_TAG, MPI_COMM_WORLD,
                 MPI_STATUS_IGNORE);
        if (status.MPI_TAG == kGone) {
            --active;
            continue;
        }
        if (!payload.empty())
            table.record(decode(payload));
        const std::uint64_t index = take();
        MPI_Send(&index, 1, MPI_UINT64_T, status.MPI_SOURCE, kAssign, MPI_COMM_WORLD);
        if (index == kStop)
            --active;
    }
    local.join();
    return table.finish(std::cout);
}

void work(const Study& study) {
    std::string payload;
    for (;;) {
        MPI_Send(payload.data(), static_cast<int>(payload.size()), MPI_CHAR, 0, kRequest,
                 MPI_COMM_WORLD);
        std::uint64_t index = kStop;
        MPI_Recv(&index, 1, MPI_UINT64_T, 0, kAssign, MPI_COMM_WORLD, MPI_STATUS_IGNORE);
        if (index == kStop)
            return;
        payload = encode(runStudy(study, index));
    }
}

}  // namespace

int main(int argc, char** argv) {
    int provided = 0, rank = 0, ranks = 1;
    MPI_Init_thread(&argc, &argv, MPI_THREAD_FUNNELED, &provided);
    MPI_Comm_rank(MPI_COMM_WORLD, &rank);
    MPI_Comm_size(MPI_COMM_WORLD, &ranks);
    CLI::App app{"tumble-sweep: run a study across MPI ranks (docs/sweeps.md)", "tumble-sweep"};
    SweepOptions options;
    addSweepOptions(app, options, false);
    int code = 0;
    try {
        app.parse(argc, argv);
    } catch (const CLI::ParseError& e) {
        // Every rank parses the same command line; one speaks.
        code = rank == 0 ? app.exit(e) : (e.get_exit_code() == 0 ? 0 : 2);
        MPI_Finalize();
        return code == 0 ? 0 : 2;
    }
    const std::string directory = sceneDirectory(argv[0]);
    std::optional<Study> study;
    std::unique_ptr<SweepTable> table;
    if (rank == 0) {
        try {
            study.emplace(loadStudy(options.study, directory));
            table = std::make_unique<SweepTable>(*study, options, std::cerr);
        } catch (const tumble::InvalidArgument& e) {
            std::cerr << "tumble-sweep: error: " << e.what() << "\n";
            code = 2;
        }
    }
    MPI_Bcast(&code, 1, MPI_INT, 0, MPI_COMM_WORLD);
    if (code == 0 && rank == 0) {
        code = coordinate(*study, *table, ranks);
    } else if (code == 0) {
        try {
            study.emplace(loadStudy(options.study, directory));
        } catch (const tumble::InvalidArgument& e) {
            // The study is unreadable on this node: its runs go to the other ranks.
            std::cerr << "tumble-sweep: rank " << rank << " leaves: " << e.what() << "\n";
            MPI_Send(nullptr, 0, MPI_CHAR, 0, kGone, MPI_COMM_WORLD);
        }
        if (study)
            work(*study);
    }
    table.reset();
    MPI_Finalize();
    return code;
}
