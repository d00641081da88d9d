// `flexmbs simulate` of a planar scene (docs/scene.md, "A planar scene: a disk rolling down an
// incline"): the scene read from the page runs event-driven into a results file whose disk rolls
// at the closed-form 2/3 g sin a with w_z r = v, its out-of-plane entries exact zeros; a scene that
// does not fit the plane is refused with one line naming the file, the item and the value. The
// page's sphere_segment scene (a frictionless disk sliding off a segment's end) records its one
// separation at the closed-form time; bad segment ends are refused likewise.
#include <gtest/gtest.h>
#include <unistd.h>

#include <Eigen/Core>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <numbers>
#include <string>

#include "core/h5_file.h"
#include "tests/app/contact_scenes.h"
#include "tests/app/flexmbs_process.h"

namespace {

namespace fs = std::filesystem;
using flexmbs::testing::Outcome;

constexpr const char* kSection = "### A planar scene: a disk rolling down an incline";
constexpr double kG = 9.81, kAngle = std::numbers::pi / 6.0, kRadius = 0.1;

class SimulatePlanarTest : public ::testing::Test {
 protected:
  void SetUp() override {
    ASSERT_TRUE(fs::exists(flexmbs::testing::kFlexmbsBinary)) << "flexmbs is not built";
    dir_ = fs::temp_directory_path() / ("flexmbs_simulate_planar_" + std::to_string(::getpid()));
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }
  Outcome Simulate(const std::string& scene) {
    std::ofstream(dir_ / "scene.yaml") << scene;
    results_ = dir_ / "results.h5";
    return flexmbs::testing::RunFlexmbs(
        {"simulate", (dir_ / "scene.yaml").string(), "-o", results_.string()}, dir_);
  }
  fs::path dir_, results_;
};

TEST_F(SimulatePlanarTest, TheDocumentedDiskRollsDownTheInclineAtTwoThirdsGSinA) {
  const std::string scene = flexmbs::testing::SceneOfSection(kSection);
  ASSERT_NE(scene.find("planar: xy"), std::string::npos)
      << "the example is gone from docs/scene.md";
  const Outcome run = Simulate(scene);
  ASSERT_EQ(run.exit_code, 0) << run.err;
  const flexmbs::h5::File file = flexmbs::h5::File::Open(results_);
  const flexmbs::h5::Group root = file.root();
  EXPECT_EQ(root.GetIntegerAttribute("complete"), 1);
  const flexmbs::h5::Group disk = root.OpenGroup("bodies").OpenGroup("disk");
  const Eigen::VectorXd time = root.ReadVector("time");
  const Eigen::MatrixXd position = disk.ReadMatrix("position"),
                        velocity = disk.ReadMatrix("velocity");
  const Eigen::MatrixXd angular_velocity = disk.ReadMatrix("angular_velocity");
  const Eigen::MatrixXd orientation = disk.ReadMatrix("orientation");
  ASSERT_EQ(time.size(), 101);
  ASSERT_NEAR(time(time.size() - 1), 1.0, 1e-12);

  // Down the line (it rises along (cos a, sin a)): s = a_roll t^2 / 2, v = a_roll t, w_z r = v.
  const double a_roll = 2.0 / 3.0 * kG * std::sin(kAngle);
  const Eigen::RowVector3d down(-std::cos(kAngle), -std::sin(kAngle), 0.0),
      normal(-std::sin(kAngle), std::cos(kAngle), 0.0);
  double distance = 0.0, speed = 0.0, rolling = 0.0, off_line = 0.0;
  for (Eigen::Index k = 0; k < time.size(); ++k) {
    const Eigen::RowVector3d moved = position.row(k) - position.row(0);
    const double t = time(k), v = down.dot(velocity.row(k));
    distance = std::max(distance, std::abs(down.dot(moved) - a_roll * t * t / 2.0));
    speed = std::max(speed, std::abs(v - a_roll * t));
    rolling = std::max(rolling, std::abs(angular_velocity(k, 2) * kRadius - v));
    off_line = std::max(off_line, std::abs(normal.dot(moved)));
  }
  const double end_distance = a_roll / 2.0, end_speed = a_roll;  // at t = 1 s
  std::printf(
      "planar disk on the incline, 1 s: distance %.2e, speed %.2e relative to the closed form's at "
      "the end; "
      "w_z r - v %.2e m/s; off the line %.2e m\n",
      distance / end_distance, speed / end_speed, rolling, off_line);
  // Measured: 3.0e-15 (distance), 2.9e-15 (speed), 1.3e-15 m/s, 6.9e-15 m.
  EXPECT_LT(distance / end_distance, 3e-14);
  EXPECT_LT(speed / end_speed, 3e-14);
  EXPECT_LT(rolling, 1.3e-14);
  EXPECT_LT(off_line, 7e-14);
  EXPECT_EQ(root.OpenGroup("contacts").OpenGroup("incline").ReadVector("sliding").maxCoeff(), 0.0);

  // The out-of-plane entries are exact zeros: z, v_z, w_x, w_y, e1, e2.
  EXPECT_EQ(position.col(2).cwiseAbs().maxCoeff(), 0.0);
  EXPECT_EQ(velocity.col(2).cwiseAbs().maxCoeff(), 0.0);
  EXPECT_EQ(angular_velocity.leftCols(2).cwiseAbs().maxCoeff(), 0.0);
  EXPECT_EQ(orientation.middleCols(1, 2).cwiseAbs().maxCoeff(), 0.0);
}

TEST_F(SimulatePlanarTest, ADiskOffThePlaneIsRefusedInOneLine) {
  std::string scene = flexmbs::testing::SceneOfSection(kSection);
  const std::string start = "position: [-0.05, 0.08660254037844388, 0]";
  ASSERT_NE(scene.find(start), std::string::npos) << "the example changed";
  scene.replace(scene.find(start), start.size(), "position: [-0.05, 0.08660254037844388, 0.01]");
  flexmbs::testing::ExpectInputError(Simulate(scene),
                                     "scene.yaml:1:9: planar: body 'disk': initial centre of mass "
                                     "(-0.05, 0.0866025, 0.01) m is off the plane z = 0");
  EXPECT_FALSE(fs::exists(results_));
}

TEST_F(SimulatePlanarTest, APlaneOtherThanXyIsRefusedInOneLine) {
  std::string scene = flexmbs::testing::SceneOfSection(kSection);
  scene.replace(scene.find("planar: xy"), 10, "planar: xz");
  flexmbs::testing::ExpectInputError(
      Simulate(scene), "scene.yaml:1:9: planar: 'xz': the planar scenes' plane is xy");
  EXPECT_FALSE(fs::exists(results_));
}

constexpr const char* kSegmentSection = "### A circle against a finite segment (`sphere_segment`)";

TEST_F(SimulatePlanarTest, TheDocumentedDiskLeavesTheSegmentsEndAtTheClosedFormTime) {
  const std::string scene = flexmbs::testing::SceneOfSection(kSegmentSection);
  ASSERT_NE(scene.find("type: sphere_segment"), std::string::npos)
      << "the example is gone from docs/scene.md";
  const Outcome run = Simulate(scene);
  ASSERT_EQ(run.exit_code, 0) << run.err;
  const flexmbs::h5::File file = flexmbs::h5::File::Open(results_);
  const flexmbs::h5::Group root = file.root();
  EXPECT_EQ(root.OpenGroup("contacts").OpenGroup("edge").GetStringAttribute("type"),
            "sphere_segment");
  const Eigen::VectorXd time = root.OpenGroup("events").ReadVector("time");
  const Eigen::VectorXd kind = root.OpenGroup("events").ReadVector("kind");
  ASSERT_EQ(time.size(), 1);
  EXPECT_EQ(kind(0), 2.0);  // separation
  // At the end (x = 0) after 0.2 m at 0.5 m/s, then pivoting about the corner to the angle where
  // the normal force vanishes: int_0^theta* r dtheta / sqrt(v0^2 + 2 g r (1 - cos theta)) with
  // cos theta* = (2 + v0^2 / (g r)) / 3, SciPy's quad: 0.11681551345886043 s (tests/mbs/
  // planar_segment_test.cc computes it as well).
  const double t_star = 0.4 + 0.11681551345886043;
  std::printf(
      "sphere_segment through the command line: separation at %.15f s, closed form %.15f s (%.2e "
      "s)\n",
      time(0), t_star, time(0) - t_star);
  // Measured: 6.6e-11 s (the root of the contact force).
  EXPECT_NEAR(time(0), t_star, 6e-10);
}

TEST_F(SimulatePlanarTest, BadSegmentEndsAreRefusedInOneLine) {
  const std::string scene = flexmbs::testing::SceneOfSection(kSegmentSection);
  const std::string ends = "ends: [[-1, 0, 0], [0, 0, 0]]";
  ASSERT_NE(scene.find(ends), std::string::npos) << "the example changed";
  const auto with_ends = [&](const std::string& other) {
    std::string changed = scene;
    return changed.replace(changed.find(ends), ends.size(), other);
  };
  flexmbs::testing::ExpectInputError(
      Simulate(with_ends("ends: [[-1, 0, 0]]")),
      "scene.yaml:13:11: contacts[0].ends: contact 'edge': 1 entries, not the segment's two ends");
  flexmbs::testing::ExpectInputError(
      Simulate(with_ends("ends: [[-1, 0, 0], [0, 0, 0.2]]")),
      "scene.yaml:9:5: contacts[0]: contact 'edge': the segment's ends (-1, 0, 0) and (0, "
      "0, 0.2) m must lie at one z of their marker");
  flexmbs::testing::ExpectInputError(
      Simulate(with_ends("ends: [[0, 0, 0], [0, 0, 0]]")),
      "scene.yaml:9:5: contacts[0]: contact 'edge': the segment's ends (0, 0, 0) and (0, 0, "
      "0) m must be finite and apart");
  EXPECT_FALSE(fs::exists(results_));
}

}  // namespace
