#pragma once
/// The harness's clocks and its one statistic, shared by the scene table and the string runs.

#include <time.h>

#include <algorithm>
#include <vector>

namespace tumble::bench {

/// This thread's CPU time (s): beside the wall time, because the machine may be shared.
inline double cpuNow() {
    timespec t{};
    clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
    return static_cast<double>(t.tv_sec) + 1e-9 * static_cast<double>(t.tv_nsec);
}

/// The median of `v` (non-empty).
inline double median(std::vector<double> v) {
    std::sort(v.begin(), v.end());
    const std::size_t n = v.size();
    return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

}  // namespace tumble::bench
