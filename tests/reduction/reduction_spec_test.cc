// The `reduction:` section of a body file: what it accepts and the one-line errors.
#include "reduction/reduction_spec.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <unistd.h>

#include "tests/input_error.h"

namespace flexmbs::reduction {
namespace {

namespace fs = std::filesystem;

const std::vector<std::string> kNodeSets = {"clamp", "tip"};

fs::path WriteBody(const std::string& reduction_yaml) {
  // One folder per test and process: CTest runs the tests of this file concurrently.
  const auto* test = ::testing::UnitTest::GetInstance()->current_test_info();
  const fs::path dir = fs::temp_directory_path() /
                       (std::string("flexmbs_reduction_spec_") + test->name() + "_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  const fs::path path = dir / "body.yaml";
  std::ofstream(path) << "name: b\n" << reduction_yaml;
  return path;
}

std::string ErrorOf(const std::string& reduction_yaml) {
  return testing::InputErrorMessage([&] { LoadReductionSpec(WriteBody(reduction_yaml), kNodeSets); });
}

TEST(ReductionSpec, ReadsACraigBamptonSection) {
  const ReductionSpec spec = LoadReductionSpec(WriteBody(R"(reduction:
  method: craig_bampton
  modes: 12
  supports: [clamp]
  eigensolver: slepc
  orthonormalize: true
  interfaces:
    - {node_set: clamp}
    - {node_set: tip, coupling: averaging, marker: [1, 0.005, 0.005]}
  correction_modes:
    - {node_set: tip, direction: [0, 1, 0]}
    - {node_set: clamp, distribution: per_node}
)"), kNodeSets);
  EXPECT_EQ(spec.method, ReductionMethod::kCraigBampton);
  EXPECT_EQ(spec.num_modes, 12);
  EXPECT_EQ(spec.eigensolver, "slepc");
  EXPECT_TRUE(spec.orthonormalize);
  ASSERT_EQ(spec.supports.size(), 1u);
  EXPECT_EQ(spec.supports[0].node_set, "clamp");
  EXPECT_EQ(spec.supports[0].components, (std::array<bool, 3>{true, true, true}));
  ASSERT_EQ(spec.interfaces.size(), 2u);
  EXPECT_EQ(spec.interfaces[0].coupling, Coupling::kNodes);
  EXPECT_FALSE(spec.interfaces[0].p_BoMarker_B.has_value());
  EXPECT_EQ(spec.interfaces[1].coupling, Coupling::kAveraging);
  EXPECT_EQ(*spec.interfaces[1].p_BoMarker_B, Eigen::Vector3d(1, 0.005, 0.005));
  ASSERT_EQ(spec.corrections.size(), 2u);
  EXPECT_EQ(*spec.corrections[0].direction, Eigen::Vector3d(0, 1, 0));
  EXPECT_EQ(spec.corrections[0].distribution, LoadDistribution::kResultant);
  EXPECT_FALSE(spec.corrections[1].direction.has_value());
  EXPECT_EQ(spec.corrections[1].distribution, LoadDistribution::kPerNode);
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
  EXPECT_EQ(ErrorOf("reduction: {method: fixed_interface, modes: 5}\n"),
            file + ":2:12: reduction: method 'fixed_interface' needs 'supports' or 'interfaces' to hold the body");
  EXPECT_EQ(ErrorOf("reduction: {modes: 5, supports: [clamp]}\n"),
            file + ":2:12: reduction: method 'free_free' takes no 'supports' or 'interfaces' (use fixed_interface or craig_bampton)");
  EXPECT_EQ(ErrorOf("reduction: {method: fixed_interface, modes: 5, supports: [root]}\n"),
            file + ":2:59: reduction.supports[0]: 'root' is not one of the body's node_sets (clamp, tip)");
  EXPECT_EQ(ErrorOf("reduction: {method: craig_bampton, modes: 5, interfaces: [{node_set: hub}]}\n"),
            file + ":2:70: reduction.interfaces[0].node_set: 'hub' is not one of the body's node_sets (clamp, tip)");
  EXPECT_EQ(ErrorOf("reduction: {modes: 5, correction_modes: [{node_set: tip, distribution: lumped}]}\n"),
            file + ":2:72: reduction.correction_modes[0].distribution: 'lumped' must be one of: resultant, per_node");
  EXPECT_EQ(ErrorOf("reduction: {modes: 5, correction_modes: [{node_set: tip, direction: [0, 0, 0]}]}\n"),
            file + ":2:69: reduction.correction_modes[0].direction: a load direction must not be zero");
}

}  // namespace
}  // namespace flexmbs::reduction
