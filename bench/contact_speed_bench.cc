// Speed against error of compliant contact on a reduced body (issue 16; docs/contact.md, "Which
// modes a contact needs"): a steel sphere striking the end of a steel rod, the reduced rod
// (loaded modes, with and without the contact load's static correction mode) against the full
// FE model of the same mesh with the same Hertz spring, in one run: peak-force and force-history
// errors and the CPU ratio full / reduced (tests/mbs/sphere_rod_scenario.h).
//
//   bench_contact_speed [--cells 100,1,1] [--modes 2,4,8,16] [--substeps 20] [--rtol 1e-8]
//
// The reduced model's one-time cost (the eigen-solve of the rod's modes) is printed apart.

#include <fmt/format.h>

#include <chrono>
#include <cstring>
#include <string>
#include <vector>

#include "bench/command_line.h"
#include "tests/mbs/sphere_rod_scenario.h"

namespace {

using namespace flexmbs::mbs::testing;

/// The value after `flag` in argv, or `fallback`.
std::string Option(int argc, char** argv, const char* flag, const char* fallback) {
  for (int i = 1; i + 1 < argc; ++i) {
    if (std::strcmp(argv[i], flag) == 0) return argv[i + 1];
  }
  return fallback;
}

}  // namespace

int main(int argc, char** argv) {
  const std::vector<int> cells = flexmbs::bench::ParseIntList(Option(argc, argv, "--cells", "100,1,1"));
  const std::vector<int> mode_counts = flexmbs::bench::ParseIntList(Option(argc, argv, "--modes", "2,4,8,16"));
  const int substeps = std::stoi(Option(argc, argv, "--substeps", "20"));
  const double rtol = std::stod(Option(argc, argv, "--rtol", "1e-8"));
  if (cells.size() != 3) {
    fmt::print(stderr, "--cells takes three counts (x, y, z)\n");
    return 2;
  }
  SphereRodSetup setup;
  setup.cells = Eigen::Vector3i(cells[0], cells[1], cells[2]);
  const auto start = std::chrono::steady_clock::now();
  const SphereRod scenario = MakeSphereRod(setup);
  const double preprocessing = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  fmt::print("rod {} x {} x {} hex8 cells, {} DOF, {} free-free modes in the band; meshing, assembly and eigen-solve "
             "{:.2f} s (once per body)\n",
             cells[0], cells[1], cells[2], scenario.rod.K.rows(), scenario.rod.basis.num_modes(), preprocessing);
  const ForceHistory full = FullSphereRod(scenario, substeps);
  const double t_c = HertzContactTime(scenario);
  fmt::print("full FE model: peak {:.6g} N, contact {:.4g} us, {:.3f} s (Newmark, step output / {})\n", Peak(full),
             1e6 * Duration(full, setup.output), full.seconds, substeps);
  fmt::print("{:>8} {:>10} {:>12} {:>12} {:>10} {:>10}\n", "modes", "f_max t_c", "peak error", "history err",
             "cpu [s]", "full/red");
  for (const bool correction : {false, true}) {
    for (const int modes : mode_counts) {
      const ForceHistory reduced = ReducedSphereRod(scenario, modes, correction, rtol);
      fmt::print("{:>6}{:2} {:10.3f} {:+12.3e} {:12.3e} {:10.3f} {:10.1f}\n", modes, correction ? "+c" : "",
                 reduced.highest_mode_hz * t_c, Peak(reduced) / Peak(full) - 1.0, HistoryError(reduced, full),
                 reduced.seconds, full.seconds / reduced.seconds);
    }
  }
  return 0;
}
