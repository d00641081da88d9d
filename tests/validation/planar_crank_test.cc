// The flexible slider-crank (tests/validation/slider_crank_model.h: a reduced hex20 rod with its
// four lowest in-plane modes, mirror-symmetric about its xy plane) as a planar scene
// (mbs/planar.h): the rod keeps v_x, v_y, w_z and its modes even under z -> -z, the crank and
// slider v_x, v_y, w_z. Against the spatial run of the same scene and against the independent
// geometrically exact planar beam (slider_crank_exact.json, SciPy), with the solves' sizes and
// the CPU ratio printed; the load check's refusals of a mode that is neither in- nor out-of-plane
// and of a mesh that is not mirror-symmetric, a body without mode shapes, an out-of-plane mode
// started deflected or moving.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <memory>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "mbs/flexible_body.h"
#include "mbs/multibody_system.h"
#include "mbs/planar.h"
#include "tests/input_error.h"
#include "tests/validation/slider_crank_model.h"

namespace flexmbs::validation {
namespace {

constexpr Eigen::Index kModes = 4;

TEST(PlanarSliderCrank, PlanarRunIsTheSpatialRunAndMatchesTheExactBeam) {
  const std::filesystem::path file =
      std::filesystem::path(FLEXMBS_SOURCE_DIR) / "tests/validation/slider_crank_exact.json";
  std::ifstream in(file);
  ASSERT_TRUE(in) << file;
  const nlohmann::json table = nlohmann::json::parse(in);
  const std::vector<double> times = table.at("times").get<std::vector<double>>();
  const std::vector<double> expected = table.at("mid").get<std::vector<double>>();

  const SliderCrankData data;
  const SliderCrankRod rod = BuildRod(data);
  const sid::ReducedBody body = RodBody(rod, kModes, true);
  CrankRunOptions options;
  options.end_time = times.back();
  options.output_interval = times[1] - times[0];
  options.integrator.relative_tolerance = 1e-6;
  options.integrator.absolute_tolerance = 1e-9;
  const CrankRun spatial = RunSliderCrank(data, body, options);
  options.planar = true;
  const CrankRun planar = RunSliderCrank(data, body, options);
  ASSERT_EQ(planar.time.size(), times.size());

  double peak = 0.0;
  for (const double w : expected) peak = std::max(peak, std::abs(w));
  const double to_spatial = LargestDifference(planar.time, planar.mid_deflection, spatial.mid_deflection, 0.0, times.back());
  const double to_exact = LargestDifference(planar.time, planar.mid_deflection, expected, 0.0, times.back());
  const double spatial_to_exact = LargestDifference(spatial.time, spatial.mid_deflection, expected, 0.0, times.back());
  std::printf("planar slider-crank (%ld modes, %.2f s): velocities %ld -> %ld, constraint rows %ld -> %ld (dropped %ld -> "
              "%ld; saddle point %ld -> %ld); steps %ld / %ld, rhs %ld / %ld; midpoint deflection: planar vs spatial "
              "%.2e of the peak, planar vs exact beam %.2e, spatial vs exact beam %.2e; CPU spatial %.3f s, planar "
              "%.3f s (ratio %.2f)\n",
              static_cast<long>(kModes), times.back(), spatial.kept_velocities, planar.kept_velocities, spatial.kept_rows,
              planar.kept_rows, spatial.dropped_rows, planar.dropped_rows, spatial.kept_velocities + spatial.kept_rows,
              planar.kept_velocities + planar.kept_rows, spatial.steps, planar.steps, spatial.rhs_evaluations,
              planar.rhs_evaluations, to_spatial / peak, to_exact / peak, spatial_to_exact / peak, spatial.cpu_seconds,
              planar.cpu_seconds, spatial.cpu_seconds / planar.cpu_seconds);
  // crank 3 + rod 3 + 4 modes + slider 3 columns; the in-plane loop has 9 rows, no redundancy:
  // the other 12 of the 21 are out-of-plane (the revolutes' z translations and x, y alignments,
  // the prismatic joint's z translation and x, y rotations), found by the start-of-run search.
  EXPECT_EQ(planar.kept_velocities, 13);
  EXPECT_EQ(spatial.kept_velocities, 22);
  EXPECT_EQ(planar.kept_rows, 9);
  EXPECT_EQ(planar.dropped_rows, 12);
  // Measured: planar vs spatial 1.8e-8 of the peak (the integrator's tolerance; 13943 against
  // 13952 steps), both 2.07e-2 from the exact beam (slider_crank_test.cc's claim, 0.05).
  EXPECT_LT(to_spatial, 2e-7 * peak);
  EXPECT_LT(to_exact, 0.05 * peak);

  // The load check on the rod: a mode that is neither even nor odd under z -> -z (the first
  // with a uniform z displacement added, odd), and a mesh moved off its mirror symmetry.
  const auto refusal = [&](const sid::ReducedBody& rod_body) {
    CrankRunOptions planar_options = options;
    planar_options.end_time = 1e-3;
    return flexmbs::testing::InputErrorMessage([&] { RunSliderCrank(data, rod_body, planar_options); });
  };
  sid::ReducedBody mixed = body;
  for (Eigen::Index row = 2; row < mixed.phi.rows(); row += 3) mixed.phi(row, 0) += 0.1 * mixed.phi.col(0).cwiseAbs().maxCoeff();
  const std::string mixed_message = refusal(mixed);
  EXPECT_EQ(mixed_message.rfind("body 'rod' mode 1 '", 0), 0u) << mixed_message;
  EXPECT_NE(mixed_message.find("neither in-plane nor out-of-plane: it departs from its reflection z -> -z by"),
            std::string::npos)
      << mixed_message;
  sid::ReducedBody shifted = body;
  shifted.node_positions.row(2).array() += 1e-4;
  const std::string shifted_message = refusal(shifted);
  EXPECT_NE(shifted_message.find("body 'rod': its FE mesh is not mirror-symmetric about its xy plane: node 0 at"),
            std::string::npos)
      << shifted_message;
  sid::ReducedBody no_shapes = body;
  no_shapes.phi.resize(0, body.phi.cols());  // a file with its modes' integrals but no shapes on nodes
  EXPECT_EQ(refusal(no_shapes),
            "body 'rod': its file carries no mode shapes on the FE nodes to tell in-plane from out-of-plane modes");

  // An out-of-plane mode (the first made a uniform z displacement, odd under z -> -z) is dropped;
  // started deflected in it, the rod alone is refused.
  sid::ReducedBody lifted = body;
  for (Eigen::Index row = 0; row < lifted.phi.rows(); ++row) lifted.phi(row, 0) = row % 3 == 2 ? 1e-3 : 0.0;
  mbs::MultibodySystem system(Eigen::Vector3d::Zero());
  system.AddBody(std::make_unique<mbs::FlexibleBody>("rod", lifted, false));
  Eigen::VectorXd y0 = system.NeutralState();
  y0(7) = 2e-3;  // q of mode 1
  EXPECT_EQ(flexmbs::testing::InputErrorMessage([&] { mbs::MakePlanar(system, y0); }),
            "body 'rod': initial q of out-of-plane mode 1 = 0.002 must be 0");
  y0(7) = 0.0;
  y0(system.num_positions() + 6) = 0.5;  // its qdot
  EXPECT_EQ(flexmbs::testing::InputErrorMessage([&] { mbs::MakePlanar(system, y0); }),
            "body 'rod': initial qdot of mode 1 = 0.5 is out of the plane");
}

}  // namespace
}  // namespace flexmbs::validation
