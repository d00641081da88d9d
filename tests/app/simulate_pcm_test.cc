// `flexmbs simulate` with a `pcm_contact` force element (docs/scene.md, "Contact elements"): a
// rigid cube (an STL file) dropped on a rigid plate (another) with the Polygonal Contact Model
// settles at the static foundation sinkage m g / (c A), level, under the explicit and the
// implicit method; an unknown body, an unreadable or truncated mesh file, a flipped triangle, a
// hole, and a zero or negative layer modulus or thickness are refused with one line and exit 2.
#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>

#include "core/h5_file.h"
#include "tests/app/flexmbs_process.h"
#include "tests/support/stl_writer.h"

namespace {

namespace fs = std::filesystem;
using flexmbs::testing::Outcome;

constexpr double kMass = 2.0, kG = 9.81, kHalf = 0.05;  // [kg], [m/s^2], the cube's half side [m]
constexpr double kModulus = 1e5, kThickness = 2e-3;     // both layers [Pa], [m]: c = E / (2 h) = 2.5e7 N/m^3

/// The scene: the cube (2 kg, 0.1 m) released 1 mm above the plate's top face (z = 0) with the
/// critical areal damping of its bounce on its footprint (k = c A), explicit to 0.3 s (steps of
/// at most 1 ms: in free fall the error estimate lets a step jump through the plate).
std::string CubeOnPlate() {
  const double c = kModulus / (2.0 * kThickness), area = 4.0 * kHalf * kHalf;
  const double inertia = kMass * (2.0 * kHalf) * (2.0 * kHalf) / 6.0;
  char text[2048];
  std::snprintf(text, sizeof(text),
                "bodies:\n"
                "  cube:\n"
                "    rigid: {mass: %.17g, inertia: [[%.17g, 0, 0], [0, %.17g, 0], [0, 0, %.17g]]}\n"
                "    markers: {centre: {position: [0, 0, 0]}}\n"
                "    initial: {position: [0, 0, %.17g]}\n"
                "forces:\n"
                "  - name: rest\n"
                "    type: pcm_contact\n"
                "    a: {marker: {body: cube, marker: centre}, mesh: cube.stl, layer: {modulus: %g, thickness: %g}}\n"
                "    b: {marker: {body: ground}, mesh: plate.stl, layer: {modulus: %g, thickness: %g}}\n"
                "    max_depth: 0.01\n"
                "    areal_damping: %.17g\n"
                "simulation: {end_time: 0.3, output_interval: 0.01, method: explicit, relative_tolerance: 1e-8, "
                "absolute_tolerance: 1e-11, max_step: 1e-3}\n",
                kMass, inertia, inertia, inertia, kHalf + 1e-3, kModulus, kThickness, kModulus, kThickness,
                2.0 * std::sqrt(c * area * kMass) / area);
  return text;
}

class SimulatePcmTest : public ::testing::Test {
 protected:
  void SetUp() override {
    ASSERT_TRUE(fs::exists(flexmbs::testing::kFlexmbsBinary)) << "flexmbs is not built";
    dir_ = fs::temp_directory_path() / ("flexmbs_simulate_pcm_" + std::to_string(::getpid()));
    fs::create_directories(dir_);
    cube_ = flexmbs::testing::BoxTriangles(Eigen::Vector3d::Constant(kHalf), Eigen::Vector3d::Zero());
    flexmbs::testing::WriteBinaryStl(dir_ / "cube.stl", cube_);
    flexmbs::testing::WriteAsciiStl(dir_ / "plate.stl", flexmbs::testing::BoxTriangles(Eigen::Vector3d(0.2, 0.2, 0.01),
                                                                                       Eigen::Vector3d(0, 0, -0.01)));
  }
  void TearDown() override { fs::remove_all(dir_); }
  Outcome Simulate(const std::string& scene) {
    std::ofstream(dir_ / "scene.yaml") << scene;
    return flexmbs::testing::RunFlexmbs(
        {"simulate", (dir_ / "scene.yaml").string(), "-o", (dir_ / "results.h5").string()}, dir_);
  }
  /// The scene with `from` replaced by `to` (present once).
  static std::string Changed(std::string scene, const std::string& from, const std::string& to) {
    const std::size_t at = scene.find(from);
    EXPECT_NE(at, std::string::npos) << from;
    return scene.replace(at, from.size(), to);
  }
  fs::path dir_;
  std::vector<flexmbs::testing::StlTriangle> cube_;
};

/// Where the run of `scene` left the cube: its depth over m g / (c A) - 1, speed [m/s], tilt [rad]
/// and horizontal drift [m] at the end, and how far below the plate's top it started [m].
struct Rest {
  double depth_error, speed, tilt, drift, start;
};

Rest RestOf(const fs::path& results) {
  const flexmbs::h5::File file = flexmbs::h5::File::Open(results);
  const flexmbs::h5::Group cube = file.root().OpenGroup("bodies").OpenGroup("cube");
  const Eigen::MatrixXd position = cube.ReadMatrix("position"), velocity = cube.ReadMatrix("velocity");
  const Eigen::MatrixXd orientation = cube.ReadMatrix("orientation");
  const Eigen::Index last = position.rows() - 1;
  EXPECT_EQ(last, 30);
  // At rest the layers carry the weight: c A depth = m g, depth = m g / (c A) (flat faces: exact).
  // The binary STL holds the cube's corners as float: its bottom face lies at -float(0.05) =
  // -0.0500000007 m (7.5e-10 m, 9.5e-6 of the depth, below -0.05) and is 3.0e-8 larger.
  const double bottom = static_cast<float>(kHalf);
  const double c = kModulus / (2.0 * kThickness), area = 4.0 * bottom * bottom, rest = kMass * kG / (c * area);
  const Rest r{(bottom - position(last, 2)) / rest - 1.0, velocity.row(last).norm(),
               2.0 * orientation.row(last).tail<2>().norm(), position.row(last).head<2>().norm(),
               bottom - position.col(2).maxCoeff()};
  std::printf("[ numbers  ] depth / (m g / c A) - 1 %.2e, |v| %.2e m/s, tilt %.2e rad, xy drift %.2e m\n",
              r.depth_error, r.speed, r.tilt, r.drift);
  return r;
}

TEST_F(SimulatePcmTest, ACubeDroppedOnAPlateSettlesAtTheFoundationSinkage) {
  const Outcome run = Simulate(CubeOnPlate());
  ASSERT_EQ(run.exit_code, 0) << run.err;
  const Rest rest = RestOf(dir_ / "results.h5");
  EXPECT_LT(rest.start, -0.9e-3) << "it started 1 mm above the plate";
  // Measured: depth 7.6e-14 relative, |v| 1.05e-15 m/s, tilt 5.2e-17 rad, no xy drift.
  EXPECT_LT(std::abs(rest.depth_error), 1e-12);
  EXPECT_LT(rest.speed, 1e-14);
  EXPECT_LT(rest.tilt, 5e-16);
  EXPECT_EQ(rest.drift, 0.0) << "no horizontal force on a centred cube";
}

TEST_F(SimulatePcmTest, UnderTheImplicitMethodTheCubeSettlesAlike) {
  const Outcome run = Simulate(Changed(CubeOnPlate(), "method: explicit", "method: implicit"));
  ASSERT_EQ(run.exit_code, 0) << run.err;
  const Rest rest = RestOf(dir_ / "results.h5");
  // Measured (Newton on the element's Jacobian): depth 2.5e-13, |v| 3.4e-15 m/s, tilt 2.6e-17 rad.
  EXPECT_LT(std::abs(rest.depth_error), 1e-12);
  EXPECT_LT(rest.speed, 1e-14);
  EXPECT_LT(rest.tilt, 5e-16);
  EXPECT_EQ(rest.drift, 0.0);
}

TEST_F(SimulatePcmTest, BadBodiesMeshesAndLayersAreOneLineErrors) {
  using flexmbs::testing::ExpectInputError;
  const std::string scene = CubeOnPlate();
  ExpectInputError(Simulate(Changed(scene, "body: cube", "body: cub")), "cub");
  ExpectInputError(Simulate(Changed(scene, "mesh: cube.stl", "mesh: missing.stl")),
                   "forces[0].a.mesh: force element 'rest': STL file '" + (dir_ / "missing.stl").string() +
                       "': cannot be read");
  fs::copy_file(dir_ / "cube.stl", dir_ / "truncated.stl");
  fs::resize_file(dir_ / "truncated.stl", 84 + 50 * 12 - 1);
  ExpectInputError(Simulate(Changed(scene, "mesh: cube.stl", "mesh: truncated.stl")),
                   "truncated: 12 triangles need 684 bytes, the file has 683");
  std::vector<flexmbs::testing::StlTriangle> flipped = cube_;
  std::swap(flipped[5][1], flipped[5][2]);
  flexmbs::testing::WriteBinaryStl(dir_ / "flipped.stl", flipped);
  ExpectInputError(Simulate(Changed(scene, "mesh: cube.stl", "mesh: flipped.stl")),
                   "force element 'rest': surface 'flipped.stl': triangles");
  ExpectInputError(Simulate(Changed(scene, "mesh: cube.stl", "mesh: flipped.stl")), "inconsistent orientation");
  std::vector<flexmbs::testing::StlTriangle> holed = cube_;
  holed.pop_back();
  flexmbs::testing::WriteBinaryStl(dir_ / "holed.stl", holed);
  ExpectInputError(Simulate(Changed(scene, "mesh: cube.stl", "mesh: holed.stl")),
                   "surface 'holed.stl': edge");
  ExpectInputError(Simulate(Changed(scene, "mesh: cube.stl", "mesh: holed.stl")), "a hole in a surface that must be closed");
  // An open surface may have a rim when the entry says so (here the top's missing triangle).
  EXPECT_EQ(Simulate(Changed(scene, "mesh: cube.stl,", "mesh: holed.stl, closed: false,")).exit_code, 0);
  ExpectInputError(Simulate(Changed(scene, "layer: {modulus: 100000, thickness: 0.002}}\n    b",
                                    "layer: {modulus: 0, thickness: 0.002}}\n    b")),
                   "layer modulus of surface 'cube.stl' 0 must be finite and > 0");
  ExpectInputError(Simulate(Changed(scene, "thickness: 0.002}}\n    max_depth", "thickness: -0.002}}\n    max_depth")),
                   "layer thickness of surface 'plate.stl' -0.002 must be finite and > 0");
}

}  // namespace
