// `flexmbs compare A.sid.h5 body.yaml` end to end (docs/cli.md): a reduced tet10 block's system
// modes against its full FE model, the JSON report, and bad input.
#include <gtest/gtest.h>
#include <unistd.h>

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <numbers>
#include <string>
#include <vector>

#include "sid/sid_file.h"
#include "tests/app/block_body.h"
#include "tests/app/flexmbs_process.h"

namespace {

namespace fs = std::filesystem;
using flexmbs::testing::BlockBody;
using flexmbs::testing::ExpectInputError;
using flexmbs::testing::Outcome;

constexpr int kExitOk = 0;
// The system frequencies recomputed here from the file's Ke and Me against the report's: the
// same small dense problem solved twice (round-off), the report printing 17 digits.
constexpr double kSameSolve = 1e-9;
// Rayleigh-Ritz bound f_j(system) >= f_j(full), up to the dense solve's round-off.
constexpr double kRitzRoundOff = 1e-10;
// A free-free modal body's kept modes are the full model's modes: the same Lanczos solve twice
// (measured: errors 6.7e-16, 1 - MAC 1.1e-15; was 1e-8).
constexpr double kSameModes = 1e-14;
// The lowest three elastic modes of the Craig-Bampton block (tet4, rigid root interface, 12
// normal modes) pair with MAC near 1 (measured 0.99764, 0.99841, 0.99835; errors 0.9 %, 0.9 %,
// 0.7 %: a stubby block converges slowly in fixed-interface modes).
constexpr double kLowModeMac = 0.99;
constexpr int kRigidModes = 6;
constexpr int kLowElasticModes = 3;

class CompareTest : public ::testing::Test {
 protected:
  void SetUp() override {
    ASSERT_TRUE(fs::exists(flexmbs::testing::kFlexmbsBinary)) << "flexmbs is not built";
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    dir_ = fs::temp_directory_path() / (std::string("flexmbs_compare_") + info->name() + "_" + std::to_string(::getpid()));
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override {
    std::error_code ec;
    fs::remove_all(dir_, ec);
  }

  Outcome Flexmbs(const std::vector<std::string>& args) const { return flexmbs::testing::RunFlexmbs(args, dir_); }

  // The block body with `reduction`, meshed with tet4 (918 DOF: fast) or tet10 (5544 DOF).
  std::string Block(const std::string& reduction, int element_order = 1) const {
    std::string text = BlockBody(dir_, reduction);
    text.replace(text.find("element_order: 2"), 16, "element_order: " + std::to_string(element_order));
    return text;
  }

  // Writes the tet4 block body with `reduction` as `name`.yaml and reduces it to `name`.sid.h5.
  std::pair<fs::path, fs::path> Reduce(const std::string& name, const std::string& reduction) const {
    const fs::path body = dir_ / (name + ".yaml"), file = dir_ / (name + ".sid.h5");
    std::ofstream(body) << Block(reduction);
    const Outcome run = Flexmbs({"reduce", body.string(), "-o", file.string()});
    EXPECT_EQ(run.exit_code, kExitOk) << run.err;
    return {file, body};
  }

  nlohmann::json CompareJson(const fs::path& a, const fs::path& b) const {
    const Outcome run = Flexmbs({"compare", a.string(), b.string(), "--json"});
    EXPECT_EQ(run.exit_code, kExitOk) << run.err;
    return nlohmann::json::parse(run.out);
  }

  fs::path dir_;
};

// The frequencies [Hz] of Ke x = lambda Me x of a reduced body, ascending (round-off negative
// eigenvalues as 0).
std::vector<double> SystemFrequencies(const flexmbs::sid::ReducedBody& body) {
  const Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd> eigen(body.Ke.m0, body.Me.m0);
  std::vector<double> f;
  for (double lambda : eigen.eigenvalues()) f.push_back(std::sqrt(std::max(lambda, 0.0)) / (2.0 * std::numbers::pi));
  return f;
}

TEST_F(CompareTest, CraigBamptonSystemModesLieAboveTheirFullModelPartners) {
  // A free block with a rigid (RBE2) interface on its root face: the full model keeps that face
  // rigid, its marker free.
  const auto [file, body] =
      Reduce("cb", "{method: craig_bampton, modes: 12, interfaces: [{node_set: root, coupling: rigid}]}");
  const flexmbs::sid::ReducedBody a = flexmbs::sid::ReadReducedBody(file);
  const nlohmann::json j = CompareJson(file, body);
  for (const char* key : {"a", "b", "error_reference", "pairs", "mac", "effective_mass_kg", "effective_mass_fraction",
                          "full_model"}) {
    EXPECT_TRUE(j.contains(key)) << key;
  }
  EXPECT_EQ(j["error_reference"], "b");
  const nlohmann::json& full = j["full_model"];
  for (const char* key : {"method", "method_from", "held_by", "dofs", "modes", "frequency_hz", "eigensolver"}) {
    EXPECT_TRUE(full.contains(key)) << key;
  }
  EXPECT_EQ(full["method"], "craig_bampton");
  EXPECT_EQ(full["method_from"], "provenance");
  EXPECT_EQ(full["held_by"], "free (no supports), interface 'root' rigid (marker free)");
  EXPECT_EQ(full["eigensolver"], "spectra");
  EXPECT_EQ(full["dofs"].get<Eigen::Index>(), a.phi.rows());
  const int n = static_cast<int>(a.num_modes());  // 6 constraint + 12 normal
  ASSERT_EQ(n, 18);
  EXPECT_EQ(full["modes"].get<int>(), n + 9);  // the default margin: max(6, n / 2)
  const std::vector<double> f_full = full["frequency_hz"];
  ASSERT_EQ(f_full.size(), static_cast<std::size_t>(n + 9));
  EXPECT_EQ(j["mac"].size(), static_cast<std::size_t>(n));
  EXPECT_EQ(j["mac"][0].size(), static_cast<std::size_t>(n + 9));

  const std::vector<double> f_system = SystemFrequencies(a);
  const nlohmann::json& pairs = j["pairs"];
  ASSERT_EQ(pairs.size(), static_cast<std::size_t>(n));
  std::printf("[ numbers  ] CB block (rigid root, 12 normal modes) against its full model, f_A / f_B - 1 (MAC):");
  for (int k = 0; k < n; ++k) {
    const nlohmann::json& p = pairs[static_cast<std::size_t>(k)];
    const double f_a = p["frequency_a_hz"], f_b = p["frequency_b_hz"], error = p["relative_error"];
    if (k < kRigidModes) {  // the constraint modes span the rigid motions: six at 0 Hz on both sides
      EXPECT_EQ(f_a, 0.0) << k;
      EXPECT_EQ(f_b, 0.0) << k;
      EXPECT_EQ(error, 0.0) << k;
      continue;
    }
    EXPECT_NEAR(f_a / f_system[static_cast<std::size_t>(k)], 1.0, kSameSolve) << k;
    // Rayleigh-Ritz: at or above the full model's frequency of the same rank.
    EXPECT_GE(f_a, f_full[static_cast<std::size_t>(k)] * (1.0 - kRitzRoundOff)) << k;
    EXPECT_EQ(p["mode_a"], "reduced_normal_" + std::to_string(k - kRigidModes + 1));
    EXPECT_NEAR(error, f_a / f_b - 1.0, 1e-15) << k;
    if (k < kRigidModes + kLowElasticModes) {
      EXPECT_EQ(p["mode_b"], "normal_" + std::to_string(k - kRigidModes + 1));
      EXPECT_GE(p["mac"].get<double>(), kLowModeMac) << k;
      EXPECT_GE(error, -kRitzRoundOff) << k;
      std::printf(" %.2e (%.5f)", error, p["mac"].get<double>());
    }
  }
  std::printf("\n");
  // The free body's rigid translations carry its whole mass, on both sides.
  for (const char* side : {"a", "b"}) {
    for (int d = 0; d < 3; ++d) EXPECT_NEAR(j["effective_mass_fraction"][side][d].get<double>(), 1.0, 1e-9) << side;
  }
}

TEST_F(CompareTest, FreeFreeModalBodyAgreesWithItsFullModel) {
  const auto [file, body] = Reduce("modal", "{method: free_free, modes: 6}");
  const flexmbs::sid::ReducedBody a = flexmbs::sid::ReadReducedBody(file);
  const nlohmann::json j = CompareJson(file, body);
  ASSERT_EQ(j["pairs"].size(), 12u);
  for (std::size_t k = 0; k < 12; ++k) {
    const nlohmann::json& p = j["pairs"][k];
    const double f_b = p["frequency_b_hz"];
    if (k < kRigidModes) {
      EXPECT_EQ(p["relative_error"].get<double>(), 0.0);
      continue;
    }
    // The file's own modes are the full model's: the frequencies `reduce` wrote and the MAC.
    EXPECT_NEAR(f_b / a.frequency_hz(static_cast<Eigen::Index>(k)), 1.0, kSameModes) << k;
    EXPECT_LE(std::abs(p["relative_error"].get<double>()), kSameModes) << k;
    EXPECT_GE(p["mac"].get<double>(), 1.0 - kSameModes) << k;
  }
  // The text report names the error's definition.
  const Outcome text = Flexmbs({"compare", file.string(), body.string()});
  ASSERT_EQ(text.exit_code, kExitOk) << text.err;
  EXPECT_NE(text.out.find("error = f_A / f_B - 1"), std::string::npos) << text.out;
  EXPECT_NE(text.out.find("full FE model"), std::string::npos) << text.out;
}

TEST_F(CompareTest, ModesSetsTheFullModelsModeCount) {
  const auto [file, body] = Reduce("modal", "{method: free_free, modes: 3}");
  const Outcome run = Flexmbs({"compare", file.string(), body.string(), "--json", "--modes", "20"});
  ASSERT_EQ(run.exit_code, kExitOk) << run.err;
  const nlohmann::json j = nlohmann::json::parse(run.out);
  EXPECT_EQ(j["full_model"]["modes"].get<int>(), 20);
  EXPECT_EQ(j["mac"][0].size(), 20u);
}

TEST_F(CompareTest, ABodyFileOfAnotherMeshIsAnInputErrorNamingBothFiles) {
  const auto [file, body] = Reduce("modal", "{method: free_free, modes: 3}");
  std::ofstream(dir_ / "tet10.yaml") << Block("{method: free_free, modes: 3}", 2);
  ExpectInputError(Flexmbs({"compare", file.string(), (dir_ / "tet10.yaml").string()}),
                   file.string() + " and " + (dir_ / "tet10.yaml").string() + ": the meshes differ (");
}

TEST_F(CompareTest, ABodyFileAskingForAnotherMethodIsAnInputError) {
  const auto [file, body] = Reduce("modal", "{method: free_free, modes: 3}");
  std::ofstream(dir_ / "cb.yaml") << Block("{method: craig_bampton, modes: 3, interfaces: [{node_set: root, coupling: rigid}]}");
  ExpectInputError(Flexmbs({"compare", file.string(), (dir_ / "cb.yaml").string()}),
                   "A was reduced by free_free (its provenance), the body file's reduction section asks for "
                   "craig_bampton");
}

TEST_F(CompareTest, MissingFilesAndMisplacedOptionsAreInputErrors) {
  const auto [file, body] = Reduce("modal", "{method: free_free, modes: 3}");
  const fs::path absent = dir_ / "absent.sid.h5";
  ExpectInputError(Flexmbs({"compare", absent.string(), body.string()}), absent.string() + ": no such file");
  const fs::path no_body = dir_ / "absent.yaml";
  ExpectInputError(Flexmbs({"compare", file.string(), no_body.string()}), no_body.string() + ": cannot open the file");
  ExpectInputError(Flexmbs({"compare", file.string(), file.string(), "--modes", "20"}),
                   "--modes 20: only when B is a body file");
  ExpectInputError(Flexmbs({"compare", file.string(), body.string(), "--modes", "0"}),
                   "--modes: 0 is not a whole number >= 1");
}

}  // namespace
