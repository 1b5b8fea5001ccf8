#pragma once

// Time since a steady_clock reading, for the timings the renderer, the batch and the benchmarks
// report.

#include <chrono>
#include <ctime>

namespace encore {

inline double millisecondsSince(std::chrono::steady_clock::time_point start) {
    return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start)
        .count();
}

inline double secondsSince(std::chrono::steady_clock::time_point start) {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

// CPU time the calling thread has used, in seconds: beside a wall time it tells work from
// waiting (for a core, the disk, a lock).
inline double threadCpuSeconds() {
    timespec now{};
    clock_gettime(CLOCK_THREAD_CPUTIME_ID, &now);
    return double(now.tv_sec) + double(now.tv_nsec) * 1e-9;
}

}  // namespace encore
