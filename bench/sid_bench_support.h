#pragma once

// Helpers of bench_sid_invariants (sid_invariants_bench.cc): option lists, timing, a table of
// times over (size, modes, stage) and its scaling exponents. Not a library: inline, one program.

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <functional>
#include <limits>
#include <sstream>
#include <string>
#include <vector>

namespace flexmbs::bench {

[[noreturn]] inline void Fail(const std::string& message) {
  std::fprintf(stderr, "bench_sid_invariants: %s\n", message.c_str());
  std::exit(1);
}

/// "9,16,23" -> {9, 16, 23}; every entry must be positive.
inline std::vector<int> ParseList(const std::string& text) {
  std::vector<int> values;
  std::stringstream stream(text);
  std::string item;
  while (std::getline(stream, item, ',')) values.push_back(std::atoi(item.c_str()));
  for (int v : values) {
    if (v <= 0) Fail("list entries must be positive: " + text);
  }
  return values;
}

/// A run longer than this is not repeated: its noise is small against its length [s].
constexpr double kSingleRunSeconds = 2.0;

/// The fastest of `repeat` runs of `f` [s] (one run only if the first takes > kSingleRunSeconds).
inline double FastestSeconds(int repeat, const std::function<void()>& f) {
  double best = std::numeric_limits<double>::infinity();
  for (int r = 0; r < repeat && !(r > 0 && best > kSingleRunSeconds); ++r) {
    const auto start = std::chrono::steady_clock::now();
    f();
    best = std::min(best, std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
  }
  return best;
}

/// Least-squares slope of log(y) against log(x) over the points with a finite y (NaN: not measured);
/// NaN with fewer than two such points.
inline double Slope(const std::vector<double>& x, const std::vector<double>& y) {
  double k = 0, sx = 0, sy = 0, sxx = 0, sxy = 0;
  for (std::size_t i = 0; i < x.size(); ++i) {
    if (!std::isfinite(y[i])) continue;
    const double lx = std::log(x[i]), ly = std::log(y[i]);
    k += 1;
    sx += lx;
    sy += ly;
    sxx += lx * lx;
    sxy += lx * ly;
  }
  return k < 2 ? std::numeric_limits<double>::quiet_NaN() : (k * sxy - sx * sy) / (k * sxx - sx * sx);
}

/// Seconds per (body size, number of modes, stage); NaN where a stage was not run.
struct TimeTable {
  std::vector<std::string> stages;
  std::vector<double> dofs;  ///< per size
  std::vector<int> modes;
  std::vector<double> seconds;  ///< [size][modes][stage], row-major

  TimeTable(std::vector<std::string> stage_names, std::vector<int> mode_counts)
      : stages(std::move(stage_names)), modes(std::move(mode_counts)) {}
  /// Appends a size of `dof` DOF with every time NaN.
  void AddSize(double dof) {
    dofs.push_back(dof);
    seconds.resize(seconds.size() + modes.size() * stages.size(), std::numeric_limits<double>::quiet_NaN());
  }
  double& at(std::size_t size, std::size_t mode, std::size_t stage) {
    return seconds[(size * modes.size() + mode) * stages.size() + stage];
  }

  /// Prints the exponents in DOF at fixed n of the stages `in_dof` and in n at fixed DOF of the
  /// stages `in_n`.
  void PrintExponents(const std::vector<std::size_t>& in_dof, const std::vector<std::size_t>& in_n) {
    auto header = [&](const char* label, const std::vector<std::size_t>& which) {
      std::printf("%8s", label);
      for (std::size_t k : which) std::printf(" %9s", stages[k].c_str());
      std::printf("\n");
    };
    if (dofs.size() > 1) {
      std::printf("\nexponent in DOF at fixed n\n");
      header("n", in_dof);
      for (std::size_t m = 0; m < modes.size(); ++m) {
        std::printf("%8d", modes[m]);
        for (std::size_t k : in_dof) {
          std::vector<double> y;
          for (std::size_t s = 0; s < dofs.size(); ++s) y.push_back(at(s, m, k));
          std::printf(" %9.2f", Slope(dofs, y));
        }
        std::printf("\n");
      }
    }
    if (modes.size() > 1) {
      std::printf("\nexponent in n at fixed DOF\n");
      header("DOF", in_n);
      const std::vector<double> n(modes.begin(), modes.end());
      for (std::size_t s = 0; s < dofs.size(); ++s) {
        std::printf("%8.0f", dofs[s]);
        for (std::size_t k : in_n) {
          std::vector<double> y;
          for (std::size_t m = 0; m < modes.size(); ++m) y.push_back(at(s, m, k));
          std::printf(" %9.2f", Slope(n, y));
        }
        std::printf("\n");
      }
    }
  }
};

}  // namespace flexmbs::bench
