// Scene values that cannot give a meaningful run (docs/scene.md, "Limits"): an output interval
// asking for more than 10^7 samples, and a step below the round-off of the time at the end
// time, are refused by LoadScene (before any output file is opened) with one line naming the
// scene file, the item and the value; the values at the limits are accepted.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <limits>
#include <string>

#include "mbs/scene.h"
#include "tests/input_error.h"

namespace flexmbs::testing {
namespace {

namespace fs = std::filesystem;

/// A scene of one rigid box with `simulation_lines` (each "  key: value\n") as its simulation section.
class SceneLimitsTest : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("flexmbs_scene_limits_" + std::to_string(::getpid()));
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }

  mbs::SimulationOptions Load(const std::string& simulation_lines) {
    std::ofstream(file()) << "bodies:\n  box:\n    rigid: {mass: 1.0, inertia: [[1, 0, 0], [0, 1, 0], [0, 0, 1]]}\n"
                          << "simulation:\n" << simulation_lines;
    return mbs::LoadScene(file()).options;
  }
  std::string Refusal(const std::string& simulation_lines) {
    return InputErrorMessage([&] { Load(simulation_lines); });
  }
  fs::path file() const { return dir_ / "scene.yaml"; }
  fs::path dir_;
};

TEST_F(SceneLimitsTest, OutputIntervalAskingForMoreThanTenMillionSamplesIsRefused) {
  // The value of issue 21, which failed inside ARKODE with exit 1 before.
  EXPECT_EQ(Refusal("  end_time: 1.0\n  output_interval: 1e-300\n"),
            file().string() + ":6:20: simulation.output_interval: 1e-300 s asks for 1e+300 samples up to end_time 1 s, "
                              "more than the limit of 1e+07");
  EXPECT_NE(Refusal("  end_time: 2.0\n  output_interval: 1e-7\n").find("2e+07 samples"), std::string::npos);
  EXPECT_EQ(Load("  end_time: 2.0\n  output_interval: 2e-7\n").output_interval, 2e-7);
}

TEST_F(SceneLimitsTest, StepBelowTheRoundOffOfTheEndTimeIsRefused) {
  const double end_time = 100.0, limit = 64 * std::numeric_limits<double>::epsilon() * end_time;  // 1.42e-12 s
  for (const std::string key : {"max_step", "fixed_step"}) {
    const std::string message = Refusal("  end_time: 100\n  " + key + ": 1e-13\n");
    EXPECT_TRUE(message.starts_with(file().string() + ":6:")) << message;
    EXPECT_NE(message.find("simulation." + key + ": 1e-13 s is below the round-off of the time up to end_time 100 s "
                           "(at least 64 epsilon x end_time = 1.42e-12 s)"),
              std::string::npos)
        << message;
  }
  EXPECT_EQ(Load("  end_time: 100\n  max_step: 1.5e-12\n").integrator.max_step, 1.5e-12);
  EXPECT_GT(1.5e-12, limit);
}

}  // namespace
}  // namespace flexmbs::testing
