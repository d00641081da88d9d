#pragma once

// The fastest of several runs in wall-clock and in process CPU time, for bench_sid_file. On a
// machine shared with other jobs the CPU time is the steadier measure.

#include <time.h>

#include <algorithm>
#include <chrono>
#include <functional>
#include <limits>

namespace flexmbs::bench {

/// Wall-clock and CPU time of one run [s].
struct Seconds {
  double wall = std::numeric_limits<double>::infinity();
  double cpu = std::numeric_limits<double>::infinity();
};

/// The CPU time of this process, all threads [s].
inline double ProcessCpuSeconds() {
  timespec t{};
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
  return static_cast<double>(t.tv_sec) + 1e-9 * static_cast<double>(t.tv_nsec);
}

/// The fastest of `repeat` runs of `f`, in wall-clock and in CPU time (each its own minimum).
inline Seconds Fastest(int repeat, const std::function<void()>& f) {
  Seconds best;
  for (int r = 0; r < repeat; ++r) {
    const auto start = std::chrono::steady_clock::now();
    const double cpu_start = ProcessCpuSeconds();
    f();
    best.cpu = std::min(best.cpu, ProcessCpuSeconds() - cpu_start);
    best.wall = std::min(best.wall, std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
  }
  return best;
}

}  // namespace flexmbs::bench
