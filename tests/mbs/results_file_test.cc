// The results file: every recorded series round-trips, units are set, and a writer killed
// between flushes leaves a readable file with every flushed sample and `complete` = 0.
#include "mbs/results_file.h"

#include <gtest/gtest.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <filesystem>
#include <fmt/format.h>

#include "core/error.h"
#include "core/h5_file.h"
#include "tests/input_error.h"

namespace flexmbs::mbs {
namespace {

namespace fs = std::filesystem;

fs::path TempPath(const std::string& name) {
  const fs::path dir = fs::temp_directory_path() / fmt::format("flexmbs_results_test_{}", getpid());
  fs::create_directories(dir);
  return dir / name;
}

// A rigid crank and a flexible rod with two modes and one recorded marker, joined by one joint.
ResultsLayout Layout() {
  ResultsLayout layout;
  layout.bodies = {{"crank", "rigid", {}, {}}, {"rod", "flexible", {"normal_1", "normal_2"}, {"mid"}}};
  layout.joints = {{"pin", "revolute"}};
  layout.provenance = {{"scene", "slider_crank.yaml"}};
  return layout;
}

ResultsSample Sample(double t) {
  ResultsSample sample;
  sample.time = t;
  Eigen::VectorXd x_crank(7), u_crank(6), x_rod(9), u_rod(8);
  x_crank << t, 0, 0, 1, 0, 0, 0;
  u_crank << 1, 2, 3, 4, 5, 6;
  x_rod << 1, 2, 3, 0, 1, 0, 0, t, -t;
  u_rod << 0, 0, 1, 0, 0, 2, 0.5, -0.5;
  sample.positions = {x_crank, x_rod};
  sample.velocities = {u_crank, u_rod};
  sample.marker_positions = {{}, {Eigen::Vector3d(t, 2 * t, 3 * t)}};
  sample.joint_forces = {Eigen::Vector3d(10 * t, 0, -1)};
  sample.joint_torques = {Eigen::Vector3d(0, t, 0)};
  sample.kinetic_energy = 2 * t;
  sample.potential_energy = -t;
  return sample;
}

TEST(ResultsFile, EverySeriesRoundTripsWithUnits) {
  const fs::path path = TempPath("complete.h5");
  {
    ResultsWriter writer(path, Layout());
    for (int k = 0; k < 3; ++k) writer.Append(Sample(0.1 * k));
    EXPECT_EQ(writer.samples(), 3);
    writer.Finish("end time reached");
  }
  const h5::File file = h5::File::Open(path);
  const h5::Group root = file.root();
  EXPECT_EQ(root.GetStringAttribute("format"), kResultsFormat);
  EXPECT_EQ(root.GetIntegerAttribute("complete"), 1);
  EXPECT_EQ(root.GetStringAttribute("termination"), "end time reached");
  EXPECT_EQ(root.ReadUnits("time"), "s");
  EXPECT_EQ(root.ReadVector("time"), Eigen::Vector3d(0.0, 0.1, 0.2));
  const h5::Group rod = root.OpenGroup("bodies").OpenGroup("rod");
  EXPECT_EQ(rod.GetStringAttribute("kind"), "flexible");
  const Eigen::MatrixXd q = rod.ReadMatrix("modal_coordinates");
  ASSERT_EQ(q.rows(), 3);
  EXPECT_EQ(q(2, 0), 0.2);
  EXPECT_EQ(q(2, 1), -0.2);
  EXPECT_EQ(rod.ReadUnits("modal_velocities"), "q/s");
  EXPECT_EQ(rod.ReadMatrix("orientation").row(1), Eigen::RowVector4d(0, 1, 0, 0));
  EXPECT_EQ(rod.OpenGroup("markers").ReadMatrix("mid").row(2), Eigen::RowVector3d(0.2, 0.4, 0.2 * 3));
  EXPECT_FALSE(root.OpenGroup("bodies").OpenGroup("crank").Has("modal_coordinates"));
  const h5::Group pin = root.OpenGroup("joints").OpenGroup("pin");
  EXPECT_EQ(pin.ReadMatrix("force")(1, 0), 1.0);
  EXPECT_EQ(pin.ReadUnits("torque"), "N m");
  EXPECT_EQ(root.OpenGroup("energy").ReadVector("total")(2), 0.2);
}

// Element series (ResultsLayout::ElementSeries): two elements in one folder, a scalar and a
// row channel each, written as <folder>/<name>/ with type and units; a row of the wrong width is
// refused.
TEST(ResultsFile, ElementSeriesRoundTripUnderTheirFolder) {
  const fs::path path = TempPath("elements.h5");
  ResultsLayout layout = Layout();
  for (const char* name : {"mesh_a", "mesh_b"}) {
    layout.element_series.push_back({"gears", name, "spur_gear_contact", {{"force", 0, "N"}, {"torque", 2, "N m"}}});
  }
  const auto with_rows = [](double t, Eigen::Index torque_width) {
    ResultsSample sample = Sample(t);
    for (double scale : {1.0, -1.0}) {
      sample.element_rows.push_back(
          {Eigen::VectorXd::Constant(1, scale * t), Eigen::VectorXd::LinSpaced(torque_width, scale * t, 2 * scale * t)});
    }
    return sample;
  };
  {
    ResultsWriter writer(path, layout);
    for (int k = 0; k < 3; ++k) writer.Append(with_rows(0.1 * k, 2));
    EXPECT_THROW(writer.Append(with_rows(0.3, 3)), InternalError);
    writer.Finish("end time reached");
  }
  const h5::File file = h5::File::Open(path);
  const h5::Group gears = file.root().OpenGroup("gears");
  const h5::Group b = gears.OpenGroup("mesh_b");
  EXPECT_EQ(b.GetStringAttribute("type"), "spur_gear_contact");
  EXPECT_EQ(b.ReadUnits("torque"), "N m");
  EXPECT_EQ(gears.OpenGroup("mesh_a").ReadVector("force"), Eigen::Vector3d(0.0, 0.1, 0.2));
  const Eigen::MatrixXd torque = b.ReadMatrix("torque");
  ASSERT_EQ(torque.rows(), 3);
  EXPECT_EQ(torque.row(2), Eigen::RowVector2d(-0.2, -0.4));
  // The refused sample left no rows, in the bodies' series either.
  EXPECT_EQ(file.root().OpenGroup("bodies").OpenGroup("crank").ReadMatrix("position").rows(), 3);
  EXPECT_GT(VerifyResultsFile(path).datasets, 0);
}

// The constraints' drift per sample and the run's statistics/ (parts, wall and CPU seconds, the
// total their sum, the contact solves' CPU seconds); statistics are written once.
TEST(ResultsFile, ConstraintResidualsAndStatisticsRoundTrip) {
  const fs::path path = TempPath("statistics.h5");
  {
    ResultsWriter writer(path, Layout());
    for (int k = 0; k < 3; ++k) {
      ResultsSample sample = Sample(0.1 * k);
      sample.constraint_position = 1e-12 * k;
      sample.constraint_velocity = 2e-9 * k;
      writer.Append(sample);
    }
    writer.WriteStatistics({{1.5, 1.25}, {4.0, 3.5}, {0.5, 0.25}, 0.75});
    EXPECT_THROW(writer.WriteStatistics({}), InternalError);
    writer.Finish("end time reached");
  }
  const h5::File file = h5::File::Open(path);
  const h5::Group constraints = file.root().OpenGroup("constraints");
  EXPECT_EQ(constraints.ReadVector("position_residual"), Eigen::Vector3d(0.0, 1e-12, 2e-12));
  EXPECT_EQ(constraints.ReadVector("velocity_residual")(2), 4e-9);
  EXPECT_EQ(constraints.ReadUnits("position_residual"), "m or rad");
  const h5::Group statistics = file.root().OpenGroup("statistics");
  EXPECT_EQ(statistics.ReadStrings("parts"), (std::vector<std::string>{"setup", "integration", "output", "total"}));
  EXPECT_EQ(statistics.ReadVector("wall_seconds"), Eigen::Vector4d(1.5, 4.0, 0.5, 6.0));
  EXPECT_EQ(statistics.ReadVector("cpu_seconds"), Eigen::Vector4d(1.25, 3.5, 0.25, 5.0));
  EXPECT_EQ(statistics.ReadUnits("cpu_seconds"), "s");
  EXPECT_EQ(statistics.ReadScalar("contact_solve_cpu_seconds"), 0.75);
  EXPECT_EQ(statistics.ReadUnits("contact_solve_cpu_seconds"), "s");
  EXPECT_GT(VerifyResultsFile(path).datasets, 0);
}

TEST(ResultsFile, KilledWriterLeavesEveryFlushedSampleReadable) {
  const fs::path path = TempPath("killed.h5");
  constexpr int kFlushedSamples = 10;
  const pid_t child = fork();
  ASSERT_GE(child, 0);
  if (child == 0) {
    ResultsWriter writer(path, Layout(), /*flush_interval_seconds=*/0.0);
    for (int k = 0; k < kFlushedSamples; ++k) writer.Append(Sample(0.01 * k));
    raise(SIGKILL);
  }
  int status = 0;
  ASSERT_EQ(waitpid(child, &status, 0), child);
  ASSERT_TRUE(WIFSIGNALED(status));
  const h5::File file = h5::File::Open(path);
  const h5::Group root = file.root();
  EXPECT_EQ(root.GetIntegerAttribute("complete"), 0);
  EXPECT_EQ(root.GetStringAttribute("termination"), "interrupted");
  EXPECT_EQ(root.ReadVector("time").size(), kFlushedSamples);
  EXPECT_EQ(root.OpenGroup("bodies").OpenGroup("rod").ReadMatrix("modal_coordinates").rows(), kFlushedSamples);
}

TEST(ResultsFile, UnwritablePathIsAnInputErrorNamingIt) {
  const std::string message =
      testing::InputErrorMessage([] { ResultsWriter("/nonexistent/folder/results.h5", Layout()); });
  EXPECT_NE(message.find("/nonexistent/folder/results.h5"), std::string::npos) << message;
}

}  // namespace
}  // namespace flexmbs::mbs
