#pragma once
// The process's CPU time, for the share of a run its contact solves take
// (MoreauJeanStatistics and EventDrivenStatistics::contact_solve_cpu_seconds, docs/results.md).

#include <time.h>

namespace flexmbs::mbs {

/// The CPU time of this process, all threads [s] (CLOCK_PROCESS_CPUTIME_ID: nanoseconds, where
/// std::clock rounds to microseconds, the size of a small contact solve).
inline double ProcessCpuSeconds() {
  timespec now{};
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &now);
  return static_cast<double>(now.tv_sec) + 1e-9 * static_cast<double>(now.tv_nsec);
}

/// Adds the process CPU time of its scope [s] to `sum` when it ends (also by an exception).
class ScopedCpuTime {
 public:
  explicit ScopedCpuTime(double& sum) : sum_(sum), start_(ProcessCpuSeconds()) {}
  ~ScopedCpuTime() { sum_ += ProcessCpuSeconds() - start_; }
  ScopedCpuTime(const ScopedCpuTime&) = delete;
  ScopedCpuTime& operator=(const ScopedCpuTime&) = delete;

 private:
  double& sum_;
  double start_;
};

}  // namespace flexmbs::mbs
