// A steel sphere striking the end of an elastic steel rod (issue 16; the classical test of Hertz
// contact with wave propagation: Goldsmith, "Impact", 1960, §4.6; Seifried, Schiehlen & Eberhard,
// "Numerical and experimental evaluation of the coefficient of restitution for repeated impacts",
// IJIE 2005): the rod a reduced flexible body, the contact the compliant sphere_surface element
// with Hertz's law on the rod's end face, integrated by the implicit ODE method — against the full
// FE model of the same mesh with the same Hertz spring, integrated without any multibody code
// (tests/mbs/hertz_rod_model.h) at a step far below the contact's time scales.

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstdio>
#include <vector>

#include "tests/mbs/sphere_rod_scenario.h"

namespace flexmbs::mbs {
namespace {

using testing::Duration;
using testing::ForceHistory;
using testing::HistoryError;
using testing::Peak;
using testing::SphereRod;
using testing::SphereRodSetup;

TEST(SphereRodImpact, ReducedRodMatchesTheFullFeModelOnceTheContactsModesAreKept) {
  const SphereRod scenario = testing::MakeSphereRod(SphereRodSetup{});
  const SphereRodSetup& setup = scenario.setup;
  const ForceHistory full = testing::FullSphereRod(scenario, 20);
  const double t_hertz = testing::HertzContactTime(scenario);
  std::printf("sphere r = %g m, m = %.4g kg on a %g m rod at %g m/s: full FE peak %.5g N over %.4g us (Hertz on a "
              "half-space: %.4g us), %.3f s\n",
              setup.radius, scenario.sphere_mass, setup.length, setup.speed, Peak(full),
              1e6 * Duration(full, setup.output), 1e6 * t_hertz, full.seconds);
  std::printf("%6s %12s %12s %12s %12s %10s %9s\n", "modes", "f_max t_c", "peak", "duration", "history", "cpu [s]",
              "speed-up");
  const std::vector<int> mode_counts{2, 4, 8, 16};
  // peak_error[c][i], history_error[c][i]: without (c = 0) and with (c = 1) the correction mode.
  std::array<std::vector<double>, 2> peak_error, history_error;
  std::array<int, 2> enough{0, 0};  // the fewest modes for a peak force within 1 %
  for (const bool correction : {false, true}) {
    for (int modes : mode_counts) {
      const ForceHistory reduced = testing::ReducedSphereRod(scenario, modes, correction, 1e-8);
      peak_error[correction].push_back(std::abs(Peak(reduced) / Peak(full) - 1.0));
      history_error[correction].push_back(HistoryError(reduced, full));
      if (enough[correction] == 0 && peak_error[correction].back() <= 0.01) enough[correction] = modes;
      std::printf("%4d%2s %12.3f %+12.3e %+12.3e %12.3e %10.3f %9.1f\n", modes, correction ? "+c" : "",
                  reduced.highest_mode_hz * t_hertz, Peak(reduced) / Peak(full) - 1.0,
                  Duration(reduced, setup.output) / Duration(full, setup.output) - 1.0, history_error[correction].back(), reduced.seconds,
                  full.seconds / reduced.seconds);
    }
  }
  std::printf("modes for a peak force within 1 %%: %d, with the end face's correction mode %d\n", enough[0], enough[1]);
  // The rule of docs/contact.md ("Which modes a contact needs") rests on these counts: the
  // loaded modes up to f_max = 3 / t_c alone, up to 1.5 / t_c with the correction mode.
  EXPECT_EQ(enough[0], 8);
  EXPECT_EQ(enough[1], 4);
  for (std::size_t i = 0; i < mode_counts.size(); ++i) {
    SCOPED_TRACE(mode_counts[i]);
    // The correction mode always helps (measured: 4.1e-2 -> 1.4e-2 at 2 modes, 3.5e-3 ->
    // 1.3e-5 at 16).
    EXPECT_LT(peak_error[1][i], peak_error[0][i]);
    EXPECT_LT(history_error[1][i], history_error[0][i]);
    if (i == 0) continue;
    // Without it the peak error halves per doubling of the modes (measured ratios 0.42-0.47).
    EXPECT_LT(peak_error[0][i], 0.6 * peak_error[0][i - 1]);
  }
  // Converged with 16 loaded modes and the correction mode (measured: peak 1.3e-5, history
  // 1.4e-4 of the peak force).
  EXPECT_LT(peak_error[1].back(), 1.3e-4);
  EXPECT_LT(history_error[1].back(), 1.4e-3);
}

}  // namespace
}  // namespace flexmbs::mbs
