// A nearly redundant loop through a flexible body (docs/mbs.md, "Redundant constraints"): the
// slider-crank of cases/02_slider_crank with revolute joints at both ends of its gmsh tet10 rod.
// The rod's kept modes (four bending pairs, no torsion) carry an end twist of ~1e-4 of their
// rotation from the unstructured mesh, so the wrist pin's last axis alignment repeats the crank
// pin's up to that trace. Dropped as nearly redundant (the default), the run must move like the
// same mechanism with a spherical wrist pin, which does not have that row at all; enforced
// (redundant_pivot at the singular pivot), the row over-constrains the rod: the pin's torque is
// amplified by 1/pivot and the motion departs from the spherical wrist's.
#include <gtest/gtest.h>
#include <unistd.h>

#include <Eigen/Core>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <regex>
#include <string>

#include "core/h5_file.h"
#include "tests/app/flexmbs_process.h"

namespace {

namespace fs = std::filesystem;
using flexmbs::testing::Outcome;
using flexmbs::testing::RunFlexmbs;

const fs::path kCase = fs::path(FLEXMBS_SOURCE_DIR) / "cases" / "02_slider_crank";
// Past the first deflection peak (3.95 mm at 0.164 s), within the spin-up and after it.
constexpr double kEndTime = 0.2;
// Both models hold the rod's ends alike in the plane; they differ by the wrist pin's two
// out-of-plane rows (kept in the revolute run, absent in the spherical one), whose loads act on
// the in-plane motion only at second order. Both are integrated to rtol 1e-6 (the case's
// settings); measured: 2.1e-8 of the peak (was 1e-5).
constexpr double kSameDeflection = 2e-7;
// Enforcing the twist row: the row's multiplier is its load over a pivot of 2e-8, so the wrist
// pin carries ~1 kN m of torque on a 6 mm rod (measured 991 N m; dropped: 8.3e-4 N m, the
// in-plane loads' second-order share), and the motion departs from the spherical wrist's
// (measured 1.45 % of the peak; until the nodes' rotations carried their second-order part the
// row locked the bending, 2.35 vs 3.95 mm). The dropped run's torque is bounded near its
// measurement (was 10 N m); the enforced run's torque and departure are shown above a tenth of
// theirs.
constexpr double kDroppedTorque = 1e-2;           // N m
constexpr double kOverConstrainedTorque = 100.0;  // N m
constexpr double kOverConstrainedShare = 1e-3;

// The largest torque component [N m] the wrist pin carries over the run.
double LargestWristTorque(const fs::path& results) {
  const flexmbs::h5::File file = flexmbs::h5::File::Open(results);
  return file.root().OpenGroup("joints").OpenGroup("wrist_pin").ReadMatrix("torque").cwiseAbs().maxCoeff();
}

// The rod's midpoint deflection over time: the distance of marker `mid` from the chord through
// the rod's frame origin and marker `end_b`, in the W x-y plane (cases/02_slider_crank/compare.py).
Eigen::VectorXd MidpointDeflection(const fs::path& results) {
  const flexmbs::h5::File file = flexmbs::h5::File::Open(results);
  const flexmbs::h5::Group rod = file.root().OpenGroup("bodies").OpenGroup("rod");
  const Eigen::MatrixXd a = rod.ReadMatrix("position");
  const flexmbs::h5::Group markers = rod.OpenGroup("markers");
  const Eigen::MatrixXd b = markers.ReadMatrix("end_b"), mid = markers.ReadMatrix("mid");
  Eigen::VectorXd w(a.rows());
  for (Eigen::Index k = 0; k < a.rows(); ++k) {
    const Eigen::Vector2d chord = (b.row(k) - a.row(k)).head<2>().transpose();
    const Eigen::Vector2d normal = Eigen::Vector2d(-chord.y(), chord.x()) / chord.norm();
    w(k) = normal.dot((mid.row(k) - a.row(k)).head<2>().transpose());
  }
  return w;
}

class NearRedundantLoop : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    dir_ = fs::temp_directory_path() / ("flexmbs_near_redundant_" + std::to_string(getpid()));
    fs::remove_all(dir_);
    fs::create_directories(dir_);
    const Outcome reduce =
        RunFlexmbs({"reduce", (kCase / "rod.yaml").string(), "-o", (dir_ / "rod.sid.h5").string()}, dir_);
    ASSERT_EQ(reduce.exit_code, 0) << reduce.err;
  }
  static void TearDownTestSuite() { fs::remove_all(dir_); }

  // Runs the case's scene for kEndTime with the wrist pin of `wrist_type` and the extra
  // simulation `settings`; returns the --json report, the midpoint deflection and the largest
  // wrist-pin torque component [N m].
  static nlohmann::json Run(const std::string& name, const std::string& wrist_type, const std::string& settings,
                            Eigen::VectorXd* deflection, double* wrist_torque) {
    std::string scene = flexmbs::testing::ReadFile(kCase / "scene.yaml");
    scene = std::regex_replace(scene, std::regex("file: out/rod.sid.h5"), "file: " + (dir_ / "rod.sid.h5").string());
    scene = std::regex_replace(scene, std::regex("(name: wrist_pin\\n\\s+type:) \\w+"), "$1 " + wrist_type);
    scene = std::regex_replace(scene, std::regex("end_time: [0-9.]+"),
                               "end_time: " + std::to_string(kEndTime) + settings);
    scene = std::regex_replace(scene, std::regex("\\n\\s+paraview:[^\\n]*"), "");
    const fs::path scene_file = dir_ / (name + ".yaml"), results = dir_ / (name + ".h5");
    std::ofstream(scene_file) << scene;
    const Outcome run = RunFlexmbs({"simulate", scene_file.string(), "-o", results.string(), "--json"}, dir_);
    EXPECT_EQ(run.exit_code, 0) << run.err;
    if (run.exit_code != 0) return {};
    *deflection = MidpointDeflection(results);
    *wrist_torque = LargestWristTorque(results);
    return nlohmann::json::parse(run.out);
  }

  static fs::path dir_;
};

fs::path NearRedundantLoop::dir_;

TEST_F(NearRedundantLoop, DroppedTwistRowMovesLikeTheSphericalWristAndEnforcedItOverConstrains) {
  Eigen::VectorXd revolute, spherical, enforced;
  double revolute_torque = 0.0, spherical_torque = 0.0, enforced_torque = 0.0;
  const nlohmann::json dropped = Run("revolute", "revolute", "", &revolute, &revolute_torque);
  const nlohmann::json peer = Run("spherical", "spherical", "", &spherical, &spherical_torque);
  const nlohmann::json locked =
      Run("enforced", "revolute", "\n  redundant_pivot: 1e-10", &enforced, &enforced_torque);
  ASSERT_FALSE(dropped.is_null() || peer.is_null() || locked.is_null());

  // The one nearly redundant row: the wrist pin's second axis alignment.
  ASSERT_EQ(dropped["redundant_constraints"].size(), 1u) << dropped.dump();
  const std::string row = dropped["redundant_constraints"][0];
  EXPECT_EQ(row.rfind("'wrist_pin' row 5 of 5 (nearly redundant: pivot ", 0), 0u) << row;
  EXPECT_GT(dropped["dropped_row_violation"].get<double>(), 0.0);
  EXPECT_LT(dropped["dropped_row_limit_share"].get<double>(), 1.0);
  EXPECT_TRUE(peer["redundant_constraints"].empty());
  EXPECT_TRUE(locked["redundant_constraints"].empty());

  ASSERT_EQ(revolute.size(), spherical.size());
  ASSERT_EQ(revolute.size(), enforced.size());
  const double peak = spherical.cwiseAbs().maxCoeff();
  const double difference = (revolute - spherical).cwiseAbs().maxCoeff();
  const double enforced_difference = (enforced - spherical).cwiseAbs().maxCoeff();
  std::printf("midpoint deflection peak: spherical wrist %.4g mm, revolute (twist row dropped) %.4g mm, "
              "revolute enforced %.4g mm; dropped vs spherical %.3g of the peak, enforced %.3g; dropped-row "
              "violation %.3g (%.3g of its limit); largest wrist-pin torque: dropped %.3g N m, enforced %.3g N m\n",
              1e3 * peak, 1e3 * revolute.cwiseAbs().maxCoeff(), 1e3 * enforced.cwiseAbs().maxCoeff(),
              difference / peak, enforced_difference / peak, dropped["dropped_row_violation"].get<double>(),
              dropped["dropped_row_limit_share"].get<double>(), revolute_torque, enforced_torque);
  EXPECT_GT(peak, 3e-3);  // the rod deflects (3.95 mm in cases/02_slider_crank/README.md)
  EXPECT_LT(difference, kSameDeflection * peak);
  EXPECT_EQ(spherical_torque, 0.0);
  EXPECT_LT(revolute_torque, kDroppedTorque);
  EXPECT_GT(enforced_torque, kOverConstrainedTorque);
  EXPECT_GT(enforced_difference, kOverConstrainedShare * peak);
}

}  // namespace
