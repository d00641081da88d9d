// The `reduction:` section of a body file: what it accepts and the one-line errors.
#include "reduction/reduction_spec.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "core/error.h"

namespace flexmbs::reduction {
namespace {

namespace fs = std::filesystem;

const std::vector<std::string> kNodeSets = {"clamp", "tip"};

fs::path WriteBody(const std::string& reduction_yaml) {
  const fs::path dir = fs::temp_directory_path() / "flexmbs_reduction_spec_test";
  fs::create_directories(dir);
  const fs::path path = dir / "body.yaml";
  std::ofstream(path) << "name: b\n" << reduction_yaml;
  return path;
}

std::string ErrorOf(const std::string& reduction_yaml) {
  try {
    LoadReductionSpec(WriteBody(reduction_yaml), kNodeSets);
  } catch (const InputError& e) {
    return e.what();
  }
  return "no error";
}

TEST(ReductionSpec, ReadsACraigBamptonSection) {
  const ReductionSpec spec = LoadReductionSpec(WriteBody(R"(reduction:
  method: craig_bampton
  modes: 12
  eigensolver: slepc
  orthonormalize: true
  interfaces:
    - {node_set: clamp}
    - {node_set: tip, coupling: average, marker: [1, 0.005, 0.005]}
  correction_modes:
    - {node_set: tip, axes: [y, z]}
)"), kNodeSets);
  EXPECT_EQ(spec.method, ReductionMethod::kCraigBampton);
  EXPECT_EQ(spec.num_modes, 12);
  EXPECT_EQ(spec.eigensolver, "slepc");
  EXPECT_TRUE(spec.orthonormalize);
  ASSERT_EQ(spec.interfaces.size(), 2u);
  EXPECT_EQ(spec.interfaces[0].coupling, InterfaceCoupling::kNodes);
  EXPECT_FALSE(spec.interfaces[0].p_BoMarker_B.has_value());
  EXPECT_EQ(spec.interfaces[1].coupling, InterfaceCoupling::kAverage);
  EXPECT_EQ(*spec.interfaces[1].p_BoMarker_B, Eigen::Vector3d(1, 0.005, 0.005));
  ASSERT_EQ(spec.corrections.size(), 1u);
  EXPECT_EQ(spec.corrections[0].axes, (std::vector<int>{1, 2}));
}

TEST(ReductionSpec, DefaultsToFreeFreeWithExactRigidModesOnSpectra) {
  const ReductionSpec spec = LoadReductionSpec(WriteBody("reduction: {max_frequency_hz: 500}\n"), kNodeSets);
  EXPECT_EQ(spec.method, ReductionMethod::kFreeFree);
  EXPECT_EQ(spec.max_frequency_hz, 500.0);
  EXPECT_EQ(spec.eigensolver, "spectra");
  EXPECT_TRUE(spec.exact_rigid_body_modes);
}

TEST(ReductionSpec, BadInputGivesOneLineErrorsNamingFileItemAndValue) {
  const std::string file = WriteBody("").string();
  EXPECT_EQ(ErrorOf(""), file + ":1:1: missing key 'reduction'");
  EXPECT_EQ(ErrorOf("reduction: {method: guyan, modes: 3}\n"),
            file + ":2:21: reduction.method: 'guyan' must be one of: free_free, fixed_interface, craig_bampton");
  EXPECT_EQ(ErrorOf("reduction: {method: free_free}\n"),
            file + ":2:12: reduction: give the number of normal modes ('modes') or a band ('max_frequency_hz')");
  EXPECT_EQ(ErrorOf("reduction: {modes: 0}\n"), file + ":2:20: reduction.modes: mode count 0 must be > 0");
  EXPECT_EQ(ErrorOf("reduction: {modes: 5, eigensolver: arpack}\n"),
            file + ":2:36: reduction.eigensolver: unknown eigensolver 'arpack' (available: spectra, slepc)");
  EXPECT_EQ(ErrorOf("reduction: {method: craig_bampton, modes: 5}\n"),
            file + ":2:12: reduction: method 'craig_bampton' needs at least one entry in 'interfaces'");
  EXPECT_EQ(ErrorOf("reduction: {method: craig_bampton, modes: 5, interfaces: [{node_set: hub}]}\n"),
            file + ":2:70: reduction.interfaces[0].node_set: 'hub' is not one of the body's node_sets (clamp, tip)");
  EXPECT_EQ(ErrorOf("reduction: {modes: 5, correction_modes: [{node_set: tip, axes: [w]}]}\n"),
            file + ":2:65: reduction.correction_modes[0].axes[0]: 'w' must be one of: x, y, z");
}

}  // namespace
}  // namespace flexmbs::reduction
