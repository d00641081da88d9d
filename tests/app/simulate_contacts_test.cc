// `flexmbs simulate` with unilateral contacts (docs/scene.md, "Unilateral contacts"): the
// scene of that section, read from the page, runs by Moreau-Jean time stepping into a results
// file whose contact datasets hold the closed-form bounce; a unilateral contact under an ODE
// method is refused with one line and exit 2; a reduced cube lands on its bottom contact surface
// (surface_plane), and a surface contact naming a rigid body or a missing surface is refused.
#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>

#include "core/h5_file.h"
#include "tests/app/flexmbs_process.h"

namespace {

namespace fs = std::filesystem;
using flexmbs::testing::Outcome;

/// The first ```yaml block after `heading` in docs/scene.md.
std::string SceneOfSection(const std::string& heading) {
  std::ifstream in(fs::path(FLEXMBS_SOURCE_DIR) / "docs" / "scene.md");
  std::stringstream text;
  text << in.rdbuf();
  const std::string page = text.str();
  const std::size_t section = page.find(heading);
  if (section == std::string::npos) return "";
  const std::size_t start = page.find("```yaml\n", section);
  const std::size_t end = page.find("```\n", start + 8);
  if (start == std::string::npos || end == std::string::npos) return "";
  return page.substr(start + 8, end - start - 8);
}

class SimulateContactsTest : public ::testing::Test {
 protected:
  void SetUp() override {
    ASSERT_TRUE(fs::exists(flexmbs::testing::kFlexmbsBinary)) << "flexmbs is not built";
    dir_ = fs::temp_directory_path() / ("flexmbs_simulate_contacts_" + std::to_string(::getpid()));
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }
  Outcome Simulate(const std::string& scene, bool json = false) {
    std::ofstream(dir_ / "scene.yaml") << scene;
    results_ = dir_ / "results.h5";
    std::vector<std::string> args{"simulate", (dir_ / "scene.yaml").string(), "-o", results_.string()};
    if (json) args.push_back("--json");
    return flexmbs::testing::RunFlexmbs(args, dir_);
  }
  fs::path dir_, results_;
};

TEST_F(SimulateContactsTest, TheDocumentedBouncingBallRunsAndRecordsItsImpacts) {
  const std::string scene = SceneOfSection("## Unilateral contacts (`contacts:`)");
  ASSERT_NE(scene.find("method: moreau_jean"), std::string::npos) << "the example is gone from docs/scene.md";
  const Outcome run = Simulate(scene, true);
  ASSERT_EQ(run.exit_code, 0) << run.err;
  const nlohmann::json report = nlohmann::json::parse(run.out);
  EXPECT_EQ(report["steps"], 400);  // 2 s / 0.005 s
  EXPECT_EQ(report["max_active_contacts"], 1);
  const flexmbs::h5::File file = flexmbs::h5::File::Open(results_);
  const flexmbs::h5::Group root = file.root();
  EXPECT_EQ(root.GetIntegerAttribute("complete"), 1);
  const flexmbs::h5::Group floor = root.OpenGroup("contacts").OpenGroup("floor");
  EXPECT_EQ(floor.GetStringAttribute("type"), "sphere_plane");
  const Eigen::VectorXd time = root.ReadVector("time"), gap = floor.ReadVector("gap");
  const Eigen::VectorXd impulse = floor.ReadVector("normal_impulse"), active = floor.ReadVector("active");
  ASSERT_EQ(time.size(), 201);
  ASSERT_EQ(gap.size(), 201);
  EXPECT_EQ(floor.ReadMatrix("tangential_impulse").cols(), 2);
  EXPECT_NEAR(gap(0), 1.0, 1e-15);
  // The first impact, at sqrt(2 h0 / g) = 0.4515 s, lies in the step ending at 0.455 s, in the
  // output interval ending at 0.46 s; the ball rebounds with e v_1 = 0.9 sqrt(2 g h0): the
  // interval's impulse is (1 + e) m v_1 up to the weight's impulse over the interval.
  Eigen::Index first = 0;
  while (first < impulse.size() && impulse(first) == 0.0) ++first;
  ASSERT_LT(first, impulse.size());
  EXPECT_EQ(active(first), 1.0);
  EXPECT_NEAR(time(first), std::sqrt(2.0 / 9.81), 0.01);
  EXPECT_NEAR(impulse(first), 1.9 * std::sqrt(2.0 * 9.81), 9.81 * 0.01);
  EXPECT_EQ((impulse.array() > 0.0).count(), 2);  // impacts in the steps ending at 0.455 and 1.270 s (the
                                                  // third ends at 2.005 s, as in Siconos)
  EXPECT_NEAR(impulse.sum(), 1.9 * std::sqrt(2.0 * 9.81) * (1.0 + 0.9), 2.0 * 9.81 * 0.01);
}

TEST_F(SimulateContactsTest, UnilateralContactUnderAnOdeMethodIsRefused) {
  std::string scene = SceneOfSection("## Unilateral contacts (`contacts:`)");
  scene.replace(scene.find("method: moreau_jean"), 19, "method: implicit   ");
  scene.replace(scene.find("  step: 0.005"), 13, "  # step gone");
  scene.replace(scene.find("  theta: 0.5"), 12, "  # no theta");
  flexmbs::testing::ExpectInputError(Simulate(scene), "contacts[0]: contact 'floor' is unilateral");
  EXPECT_FALSE(fs::exists(results_));
}

/// Reduces tests/data/cube.geo (a 0.1 m steel cube, tet4, two free-free modes) with the contact
/// surface "bottom" (its face z = 0) to cube.sid.h5 in `dir`.
void ReduceCubeWithBottomSurface(const fs::path& dir) {
  std::ofstream(dir / "cube.yaml") << "name: cube\ngeometry: {file: "
                                   << (fs::path(FLEXMBS_SOURCE_DIR) / "tests" / "data" / "cube.geo").string()
                                   << ", mesh_size: 0.05, element_order: 1}\n"
                                      "materials: {steel: {youngs_modulus: 2.1e11, poisson_ratio: 0.3, density: 7850}}\n"
                                      "material: steel\nnode_sets: [bottom, top]\n"
                                      "reduction: {method: free_free, modes: 2}\nsid: {contact_surfaces: [bottom]}\n";
  const Outcome reduce = flexmbs::testing::RunFlexmbs(
      {"reduce", (dir / "cube.yaml").string(), "-o", (dir / "cube.sid.h5").string()}, dir);
  ASSERT_EQ(reduce.exit_code, 0) << reduce.err;
}

/// A flexible cube whose bottom face starts 1 mm above the ground, against it by surface_plane.
const char* kDroppedCube = R"(gravity: [0, 0, -9.81]
bodies:
  cube:
    flexible: {file: cube.sid.h5, modes: {kinds: [normal]}}
    initial: {position: [0, 0, 0.001]}
contacts:
  - {name: floor, type: surface_plane, body: cube, surface: bottom, plane: {body: ground}}
simulation: {end_time: 0.05, output_interval: 0.001, method: moreau_jean, step: 1e-4}
)";

TEST_F(SimulateContactsTest, FlexibleCubeLandsOnItsBottomSurfaceAndRests) {
  ReduceCubeWithBottomSurface(dir_);
  if (HasFatalFailure()) return;
  const Outcome run = Simulate(kDroppedCube, true);
  ASSERT_EQ(run.exit_code, 0) << run.err;
  const nlohmann::json report = nlohmann::json::parse(run.out);
  EXPECT_GT(report["max_active_contacts"].get<int>(), 2);  // the face's vertices, not one point
  const flexmbs::h5::File file = flexmbs::h5::File::Open(results_);
  const flexmbs::h5::Group root = file.root();
  EXPECT_EQ(root.GetIntegerAttribute("complete"), 1);
  const flexmbs::h5::Group floor = root.OpenGroup("contacts").OpenGroup("floor");
  EXPECT_EQ(floor.GetStringAttribute("type"), "surface_plane");
  const Eigen::VectorXd time = root.ReadVector("time"), gap = floor.ReadVector("gap");
  const Eigen::VectorXd impulse = floor.ReadVector("normal_impulse");
  EXPECT_NEAR(gap(0), 0.001, 1e-15);
  // Free fall to the touch at sqrt(2 g0 / g) = 14.3 ms: no impulse in the intervals before it.
  for (Eigen::Index k = 0; k < time.size() && time(k) < 0.014; ++k) EXPECT_EQ(impulse(k), 0.0) << time(k);
  // From rest to rest (e = 0; the two modes' vibration carries no momentum): the floor's impulse
  // over the run is the weight's, m g T, up to the cube's final speed.
  const double mass = 7850.0 * 1e-3;
  const Eigen::MatrixXd velocity = root.OpenGroup("bodies").OpenGroup("cube").ReadMatrix("velocity");
  EXPECT_NEAR(impulse.sum() + mass * velocity(velocity.rows() - 1, 2), mass * 9.81 * time(time.size() - 1), 1e-9);
  EXPECT_LT(std::abs(velocity(velocity.rows() - 1, 2)), 1e-3);
  EXPECT_LT(std::abs(gap(gap.size() - 1)), 1e-4);  // resting on the floor
}

TEST_F(SimulateContactsTest, SurfaceContactOnARigidBodyOrAMissingSurfaceIsRefused) {
  ReduceCubeWithBottomSurface(dir_);
  if (HasFatalFailure()) return;
  std::string scene = kDroppedCube;
  scene.replace(scene.find("surface: bottom"), 15, "surface: top   ");
  flexmbs::testing::ExpectInputError(Simulate(scene),
                                     "contacts[0].surface: contact 'floor': body 'cube' carries no contact surface "
                                     "'top' (it has: bottom)");
  EXPECT_FALSE(fs::exists(results_));
  scene = kDroppedCube;
  scene.replace(scene.find("body: cube,"), 11, "body: cubes,");
  flexmbs::testing::ExpectInputError(Simulate(scene), "contacts[0].body: contact 'floor': no body 'cubes'");
  const std::string rigid = std::string(kDroppedCube).replace(
      std::string(kDroppedCube).find("    flexible: {file: cube.sid.h5, modes: {kinds: [normal]}}"), 59,
      "    rigid: {mass: 1, inertia: [[1, 0, 0], [0, 1, 0], [0, 0, 1]]}");
  flexmbs::testing::ExpectInputError(Simulate(rigid),
                                     "contacts[0].body: contact 'floor': body 'cube' is rigid; surfaces are a flexible "
                                     "body's");
}

}  // namespace
