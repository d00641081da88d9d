// The flexible pendulum (tests/validation/flexible_pendulum_model.h): reduced models with n modes
// against the full FE model (the complete clamped basis) integrated directly, for a few meshes:
// the largest tip-deflection and hinge-angle errors and the CPU time, with the speed-up over the
// full model measured in the same program.
//
// Every model is integrated by the L-stable ESDIRK at the same tolerances (the full model's modes
// reach MHz); the reduced ones also by the explicit Dormand-Prince method, the practical choice
// for a few modes (its speed-up is still against the full model's ESDIRK run). Reduced runs are
// repeated and the smallest CPU time kept; the full model runs once (minutes).
//
// Usage: bench_flexible_pendulum [--cells 3,4] [--end-time 1] [--repeat 3] [--modes 1,2,4,8,16,24,32]
#include <cstdio>
#include <cstdlib>
#include <sstream>
#include <string>
#include <string_view>
#include <vector>

#include "bench/command_line.h"
#include "tests/validation/flexible_pendulum_model.h"

namespace {

using flexmbs::validation::BuildLink;
using flexmbs::validation::Deviation;
using flexmbs::validation::EnergyDriftAfterRelease;
using flexmbs::validation::FeLink;
using flexmbs::validation::FirstModes;
using flexmbs::validation::LargestTipDeflection;
using flexmbs::validation::LinkGeometry;
using flexmbs::validation::RunSwing;
using flexmbs::validation::Swing;
using flexmbs::validation::SwingDeviation;
using flexmbs::validation::SwingEnergyScale;
using flexmbs::validation::SwingOptions;

struct Settings {
  std::vector<int> cells{3, 4};
  double end_time = 1.0;
  int repeat = 3;
  std::vector<int> modes{1, 2, 4, 8, 16, 24, 32};
};

Settings ParseArguments(int argc, char** argv) {
  Settings settings;
  for (int i = 1; i + 1 < argc; i += 2) {
    const std::string_view key = argv[i], value = argv[i + 1];
    if (key == "--cells") {
      settings.cells = flexmbs::bench::ParseIntList(value);
    } else if (key == "--end-time") {
      settings.end_time = std::stod(std::string(value));
    } else if (key == "--repeat") {
      settings.repeat = std::stoi(std::string(value));
    } else if (key == "--modes") {
      settings.modes = flexmbs::bench::ParseIntList(value);
    } else {
      std::fprintf(stderr, "unknown option %s\n", argv[i]);
      std::exit(2);
    }
  }
  return settings;
}

// The run with the smallest CPU time of `repeat` identical runs.
Swing FastestOf(const flexmbs::sid::ReducedBody& body, const SwingOptions& options, int repeat) {
  Swing best = RunSwing(body, options);
  for (int k = 1; k < repeat; ++k) {
    Swing again = RunSwing(body, options);
    if (again.cpu_seconds < best.cpu_seconds) best = std::move(again);
  }
  return best;
}

void BenchMesh(int cells, const Settings& settings) {
  LinkGeometry geometry;
  geometry.cells.x() = cells;
  const FeLink link = BuildLink(geometry);
  const Eigen::Index total = link.body.num_modes();
  SwingOptions implicit;
  implicit.end_time = settings.end_time;
  implicit.output_interval = 1e-3;
  implicit.integrator.method = flexmbs::mbs::OdeMethod::kImplicit;
  implicit.integrator.relative_tolerance = 1e-8;
  implicit.integrator.absolute_tolerance = 1e-8;
  implicit.integrator.max_steps_per_call = 10000000;
  SwingOptions explicit_method = implicit;
  explicit_method.integrator.method = flexmbs::mbs::OdeMethod::kExplicit;

  const Swing full = RunSwing(link.body, implicit);
  const double largest = LargestTipDeflection(full);
  std::printf("\nmesh hex20 %d x 1 x 1, %ld DOF, full model %ld modes (%.3g Hz ... %.3g Hz), %.2f s simulated\n", cells,
              static_cast<long>(link.mesh.num_dofs()), static_cast<long>(total), link.basis.frequency_hz(0),
              link.basis.frequency_hz(total - 1), settings.end_time);
  std::printf("full model (ESDIRK): %ld steps, %ld rhs, %.2f s CPU; largest tip deflection %.3f mm; energy drift "
              "after the release %.1e of m g x_cm\n",
              full.steps, full.rhs_evaluations, full.cpu_seconds, 1e3 * largest,
              EnergyDriftAfterRelease(full, implicit.release_time) / SwingEnergyScale(link.body));
  std::printf("%4s %9s | %11s %9s %11s | %9s %9s | %11s %9s %9s\n", "n", "f_n [Hz]", "tip err [m]", "relative",
              "angle [rad]", "ESDIRK s", "speed-up", "DP5 tip err", "DP5 s", "speed-up");
  for (const int n : settings.modes) {
    if (n >= total) continue;
    const flexmbs::sid::ReducedBody reduced = FirstModes(link.body, n);
    const Swing run = FastestOf(reduced, implicit, settings.repeat);
    const Swing fast = FastestOf(reduced, explicit_method, settings.repeat);
    const SwingDeviation d = Deviation(run, full);
    std::printf("%4d %9.4g | %11.3e %9.2e %11.3e | %9.4f %9.1f | %11.3e %9.4f %9.1f\n", n,
                link.basis.frequency_hz(n - 1), d.tip_deflection, d.tip_deflection / largest, d.hinge_angle,
                run.cpu_seconds, full.cpu_seconds / run.cpu_seconds, Deviation(fast, full).tip_deflection,
                fast.cpu_seconds, full.cpu_seconds / fast.cpu_seconds);
  }
  std::fflush(stdout);
}

}  // namespace

int main(int argc, char** argv) {
  const Settings settings = ParseArguments(argc, argv);
  for (const int cells : settings.cells) BenchMesh(cells, settings);
  return 0;
}
