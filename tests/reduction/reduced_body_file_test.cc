// The `.sid.h5` v1 file: exact round trip, and one-line errors for foreign, truncated and
// wrong-version files.
#include "reduction/reduced_body_file.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fmt/format.h>
#include <fstream>

#include "core/error.h"
#include "core/h5_file.h"
#include "tests/input_error.h"

namespace flexmbs::reduction {
namespace {

namespace fs = std::filesystem;

fs::path TempPath(const std::string& name) {
  const fs::path dir = fs::temp_directory_path() / "flexmbs_reduced_body_file_test";
  fs::create_directories(dir);
  return dir / name;
}

ReducedBody SampleBody() {
  ReducedBody body;
  body.name = "bracket";
  body.mass_properties.mass_kg = 1.25;
  body.mass_properties.p_BoCm_B = Eigen::Vector3d(0.1, -0.2, 0.3);
  body.mass_properties.I_Cm_B << 1, 0.1, 0.2, 0.1, 2, 0.3, 0.2, 0.3, 3;
  body.node_positions = Eigen::Matrix3Xd::Random(3, 4);
  body.node_sets = {{"clamp", {0, 1}}, {"tip", {3}}};
  body.phi = Eigen::MatrixXd::Random(12, 3);
  body.mode_names = {"constraint_1", "normal_1", "normal_2"};
  body.mode_kinds = {"constraint", "normal", "normal"};
  body.frequency_hz = Eigen::Vector3d(std::nan(""), 12.5, 80.25);
  body.relative_residuals = Eigen::Vector3d(std::nan(""), 1e-12, 3e-11);
  body.stiffness_reduced = Eigen::MatrixXd::Random(3, 3);
  body.mass_reduced = Eigen::MatrixXd::Identity(3, 3);
  body.participation = Eigen::MatrixXd::Random(3, 6);
  body.provenance = {{"mesh", "bracket.msh"}, {"eigensolver", "spectra"}};
  return body;
}

// Equal matrices, NaN where the other has NaN (HDF5 stores doubles unchanged).
void ExpectSame(const Eigen::MatrixXd& a, const Eigen::MatrixXd& b) {
  ASSERT_EQ(a.rows(), b.rows());
  ASSERT_EQ(a.cols(), b.cols());
  EXPECT_TRUE(((a.array() == b.array()) || (a.array().isNaN() && b.array().isNaN())).all());
}

TEST(ReducedBodyFile, RoundTripIsExact) {
  const fs::path path = TempPath("round_trip.sid.h5");
  const ReducedBody written = SampleBody();
  WriteReducedBody(path, written);
  const ReducedBody read = ReadReducedBody(path);
  EXPECT_EQ(read.name, written.name);
  EXPECT_EQ(read.mass_properties.mass_kg, written.mass_properties.mass_kg);
  ExpectSame(read.mass_properties.p_BoCm_B, written.mass_properties.p_BoCm_B);
  ExpectSame(read.mass_properties.I_Cm_B, written.mass_properties.I_Cm_B);
  ExpectSame(read.node_positions, written.node_positions);
  EXPECT_EQ(read.node_sets, written.node_sets);
  ExpectSame(read.phi, written.phi);
  EXPECT_EQ(read.mode_names, written.mode_names);
  EXPECT_EQ(read.mode_kinds, written.mode_kinds);
  ExpectSame(read.frequency_hz, written.frequency_hz);
  ExpectSame(read.relative_residuals, written.relative_residuals);
  ExpectSame(read.stiffness_reduced, written.stiffness_reduced);
  ExpectSame(read.mass_reduced, written.mass_reduced);
  ExpectSame(read.participation, written.participation);
  EXPECT_EQ(read.provenance.at("mesh"), "bracket.msh");
  EXPECT_TRUE(read.provenance.contains("tool_version"));
}

// The message of the InputError that reading `path` throws.
std::string ReadError(const fs::path& path) {
  return testing::InputErrorMessage([&] { ReadReducedBody(path); });
}

TEST(ReducedBodyFile, ForeignHdf5FileIsRefusedByName) {
  const fs::path path = TempPath("foreign.h5");
  h5::File file = h5::File::Create(path);
  file.root().WriteScalar("x", 1.0, "1");
  file.Commit();
  EXPECT_EQ(ReadError(path), path.string() + ": not a flexmbs reduced body (no format 'flexmbs-sid')");
}

TEST(ReducedBodyFile, WrongSchemaVersionIsRefusedByName) {
  const fs::path path = TempPath("future.sid.h5");
  h5::File file = h5::File::Create(path);
  file.root().SetStringAttribute("format", "flexmbs-sid");
  file.root().SetIntegerAttribute("schema_version", kSidSchemaVersion + 1);
  file.Commit();
  EXPECT_EQ(ReadError(path), fmt::format("{}: schema_version {} is not supported (this flexmbs reads {})",
                                         path.string(), kSidSchemaVersion + 1, kSidSchemaVersion));
}

TEST(ReducedBodyFile, TruncatedFileIsOneLineError) {
  const fs::path path = TempPath("truncated.sid.h5");
  WriteReducedBody(path, SampleBody());
  fs::resize_file(path, fs::file_size(path) / 2);
  const std::string error = ReadError(path);
  EXPECT_EQ(error.rfind(path.string() + ": ", 0), 0u) << error;
  EXPECT_EQ(error.find('\n'), std::string::npos) << error;
}

}  // namespace
}  // namespace flexmbs::reduction
