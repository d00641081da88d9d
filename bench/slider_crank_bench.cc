// The flexible slider-crank (tests/validation/slider_crank_model.h): the rod's midpoint
// deflection error against CPU time over the number of in-plane modes (1, 2, 4, 8) and the
// integrator's tolerances, geometric stiffening on. The peer is the most accurate run that
// completes (the most modes at the tightest tolerance; a failed run is reported); errors are max |w_mid(t) - w_peer(t)| over the run relative to the
// peer's peak |w_mid|, times the CPU time of a run relative to the peer's. Run by hand:
//   build/bin/bench_slider_crank [end_time_s]
// Measured (0.4 s, explicit Dormand-Prince; peer 8 modes at rtol 1e-10, 202k steps, peak
// 3.98 mm, which the geometrically exact beam of tests/validation/slider_crank_exact.py puts at
// 3.978 mm): the modal truncation dominates (1, 2, 4 modes: 0.59, 0.11, 0.017 of the peak at
// every tolerance, 0.5-5.8 s); 8 modes: 3.5e-6, 5.5e-9, 1.2e-9 at rtol 1e-4, 1e-6, 1e-8 in
// 0.11, 0.15, 0.34 of the peer's CPU time. (Before the centrifugal stiffening's gyroscopic torque,
// docs/mbs.md "Geometric stiffening", the undamped top mode fluttered at +447 1/s and 8 modes
// failed at rtol 1e-4 and 1e-6.)
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <optional>
#include <vector>

#include "mbs/simulation_error.h"
#include "tests/validation/slider_crank_model.h"

namespace {

using flexmbs::validation::CrankRun;
using flexmbs::validation::CrankRunOptions;

struct Case {
  Eigen::Index modes;
  double relative_tolerance;
};

double Peak(const std::vector<double>& values) {
  double peak = 0.0;
  for (const double v : values) peak = std::max(peak, std::abs(v));
  return peak;
}

}  // namespace

int main(int argc, char** argv) {
  const double end_time = argc > 1 ? std::atof(argv[1]) : 0.4;
  const flexmbs::validation::SliderCrankData data;
  const flexmbs::validation::SliderCrankRod rod = flexmbs::validation::BuildRod(data);
  const std::vector<Eigen::Index> modes = {1, 2, 4, 8};
  const std::vector<double> tolerances = {1e-4, 1e-6, 1e-8};
  const double peer_tolerance = 1e-10;

  // A run may take at most `max_steps` steps per output interval (5e-4 s): the peer (rtol 1e-10)
  // takes ~400 on average; a run that needs 2e4 is failing (measured: 8 modes at rtol 1e-4 took
  // minutes of CPU where the peer took 65 s) and is reported as failed.
  const auto run = [&](Eigen::Index n, double tolerance, long max_steps = 20000) {
    CrankRunOptions options;
    options.end_time = end_time;
    options.integrator.relative_tolerance = tolerance;
    options.integrator.absolute_tolerance = 1e-3 * tolerance;  // [m, rad, q]: deflections are ~1e-3 m
    options.integrator.max_steps_per_call = max_steps;
    return flexmbs::validation::RunSliderCrank(data, flexmbs::validation::RodBody(rod, n, true), options);
  };
  // The peer: the most accurate run that completes (the most modes first).
  std::optional<CrankRun> peer;
  Eigen::Index peer_modes = 0;
  for (auto n = modes.rbegin(); n != modes.rend() && !peer; ++n) {
    try {
      peer = run(*n, peer_tolerance, 10000000);
      peer_modes = *n;
    } catch (const flexmbs::mbs::SimulationError& error) {
      fmt::print("{} modes, rtol {:g}: {}\n", *n, peer_tolerance, error.what());
    }
  }
  if (!peer) return 1;
  const double peak = Peak(peer->mid_deflection);
  fmt::print("slider-crank to t = {} s, stiffening on; peer: {} modes, rtol {:g}: peak |w_mid| {:.4e} m, "
             "{} steps, {:.3f} s CPU\n",
             end_time, peer_modes, peer_tolerance, peak, peer->steps, peer->cpu_seconds);
  fmt::print("{:>5} {:>8} {:>7} {:>9} {:>12} {:>12} {:>10}\n", "modes", "rtol", "steps", "rhs", "error/peak",
             "CPU [s]", "CPU/peer");
  for (const Eigen::Index n : modes) {
    for (const double tolerance : tolerances) {
      try {
        const CrankRun r = run(n, tolerance);
        const double error = flexmbs::validation::LargestDifference(r.time, r.mid_deflection, peer->mid_deflection,
                                                                    0.0, end_time);
        fmt::print("{:>5} {:>8.0e} {:>7} {:>9} {:>12.3e} {:>12.4f} {:>10.3f}\n", n, tolerance, r.steps,
                   r.rhs_evaluations, error / peak, r.cpu_seconds, r.cpu_seconds / peer->cpu_seconds);
      } catch (const flexmbs::mbs::SimulationError& error) {
        fmt::print("{:>5} {:>8.0e} failed: {}\n", n, tolerance, error.what());
      }
      std::fflush(stdout);
    }
  }
  return 0;
}
