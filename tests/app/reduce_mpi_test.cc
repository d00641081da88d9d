// `mpirun -n 2 flexmbs reduce` on the distributed path (reduction/distributed_reduction.h)
// against the serial spectra reduction of the same body, and what each rank held.
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <Eigen/QR>
#include <Eigen/SVD>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>

#include "sid/sid_file.h"
#include "tests/app/block_body.h"
#include "tests/app/flexmbs_process.h"

namespace {

namespace fs = std::filesystem;
using flexmbs::testing::BlockBody;
using flexmbs::testing::kFlexmbsBinary;
using flexmbs::testing::ReadFile;
using flexmbs::testing::RunFlexmbs;
using flexmbs::testing::ShellQuote;

// The agreement bound between the backends (both reach about 1e-11 alone here).
constexpr double kAgreement = 1e-8;
// The bound on one rank's share of the rows and nonzeros on 2 ranks.
constexpr double kMaxShare = 0.6;

class ReduceMpiTest : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("flexmbs_reduce_mpi_" + std::to_string(::getpid()));
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }

  // Reduces the body serially (spectra) and under `mpirun -n 2` (slepc); returns both files and
  // the MPI run's --json report.
  nlohmann::json ReduceBoth(const std::string& reduction, flexmbs::sid::ReducedBody* serial,
                            flexmbs::sid::ReducedBody* mpi) {
    std::ofstream(dir_ / "serial.yaml") << BlockBody(dir_, "{" + reduction + ", eigensolver: spectra}");
    std::ofstream(dir_ / "mpi.yaml") << BlockBody(dir_, "{" + reduction + ", eigensolver: slepc}");
    const fs::path a = dir_ / "serial.sid.h5", b = dir_ / "mpi.sid.h5", report = dir_ / "mpi.json";
    const auto run = RunFlexmbs({"reduce", (dir_ / "serial.yaml").string(), "-o", a.string()}, dir_);
    EXPECT_EQ(run.exit_code, 0) << run.err;
    const std::string command = "OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 " +
                                std::string(FLEXMBS_MPIEXEC) + " -n 2 " + ShellQuote(kFlexmbsBinary.string()) +
                                " reduce " + ShellQuote((dir_ / "mpi.yaml").string()) + " -o " +
                                ShellQuote(b.string()) + " --json > " + ShellQuote(report.string());
    EXPECT_EQ(std::system(command.c_str()), 0) << command;
    *serial = flexmbs::sid::ReadReducedBody(a);
    *mpi = flexmbs::sid::ReadReducedBody(b);
    return nlohmann::json::parse(ReadFile(report));
  }

  fs::path dir_;
};

// Same frequencies to kAgreement, and the same subspace: every principal angle between the
// column spaces of the two bases has cos >= 1 - kAgreement (Bjorck & Golub 1973: the singular
// values of Q_a^T Q_b for orthonormal bases Q of the two spaces).
void ExpectSameBasis(const flexmbs::sid::ReducedBody& a, const flexmbs::sid::ReducedBody& b) {
  ASSERT_EQ(a.phi.rows(), b.phi.rows());
  ASSERT_EQ(a.phi.cols(), b.phi.cols());
  for (Eigen::Index k = 0; k < a.phi.cols(); ++k) {
    if (a.frequency_hz(k) > 0.0) {
      EXPECT_NEAR(b.frequency_hz(k), a.frequency_hz(k), kAgreement * a.frequency_hz(k)) << "mode " << k;
    }
  }
  const Eigen::MatrixXd Qa = Eigen::HouseholderQR<Eigen::MatrixXd>(a.phi).householderQ() *
                             Eigen::MatrixXd::Identity(a.phi.rows(), a.phi.cols());
  const Eigen::MatrixXd Qb = Eigen::HouseholderQR<Eigen::MatrixXd>(b.phi).householderQ() *
                             Eigen::MatrixXd::Identity(b.phi.rows(), b.phi.cols());
  const Eigen::VectorXd cosines = Eigen::JacobiSVD<Eigen::MatrixXd>(Qa.transpose() * Qb).singularValues();
  EXPECT_GT(cosines.minCoeff(), 1.0 - kAgreement);
  // Mode by mode (distinct frequencies): the modal assurance criterion of each pair is 1.
  for (Eigen::Index k = 0; k < a.phi.cols(); ++k) {
    if (!(a.frequency_hz(k) > 0.0)) continue;  // rigid modes: compared as a subspace above
    const double mac = std::pow(a.phi.col(k).dot(b.phi.col(k)), 2) /
                       (a.phi.col(k).squaredNorm() * b.phi.col(k).squaredNorm());
    EXPECT_GT(mac, 1.0 - kAgreement) << "mode " << k;
  }
}

// Each rank assembled only its share: the rows and the nonzeros of K over the ranks add up to
// the whole (rows: 3 x nodes of the serial body; nonzeros: each row is owned by one rank, so
// the sum is nnz(K), which must exceed every share), and no rank holds more than kMaxShare.
// `static_factorizations`: the MUMPS factorisations the static solves made of their own.
void ExpectSplitAssembly(const nlohmann::json& report, Eigen::Index dofs, int static_factorizations) {
  const auto& ranks = report.at("mpi").at("ranks");
  ASSERT_EQ(ranks.size(), 2u);
  long long rows = 0, nonzeros = 0, elements = 0;
  for (const auto& r : ranks) {
    rows += r.at("rows").get<long long>();
    nonzeros += r.at("nonzeros").get<long long>();
    elements += r.at("elements").get<long long>();
  }
  EXPECT_EQ(rows, dofs);
  EXPECT_EQ(report.at("dofs").get<long long>(), dofs);
  for (const auto& r : ranks) {
    EXPECT_GT(r.at("rows").get<long long>(), 0);
    EXPECT_LT(static_cast<double>(r.at("rows").get<long long>()), kMaxShare * static_cast<double>(rows));
    EXPECT_LT(static_cast<double>(r.at("nonzeros").get<long long>()), kMaxShare * static_cast<double>(nonzeros));
    EXPECT_LT(static_cast<double>(r.at("elements").get<long long>()), kMaxShare * static_cast<double>(elements));
    EXPECT_GT(r.at("peak_rss_mb_after_solve").get<double>(), 0.0);
    EXPECT_GE(r.at("peak_rss_mb").get<double>(), r.at("peak_rss_mb_after_solve").get<double>());
  }
  // After the solve rank 0 used the distributed matrices: products, and static solves for the
  // geometric stiffening (on by default), with the eigen-solve's factorisation of the held body's
  // K_oo or one of their own. The eigen-solve factorised twice (its shift, the Sturm count).
  EXPECT_GT(report.at("mpi").at("products").at("columns").get<int>(), 0);
  EXPECT_EQ(report.at("mpi").at("static_solves").at("factorizations").get<int>(), static_factorizations);
  EXPECT_EQ(report.at("seconds").at("eigensolver").at("factorizations").get<int>(), 2);
  EXPECT_EQ(report.at("seconds").at("eigensolver").at("missed_mode_check").get<std::string>(), "sturm_count");
  EXPECT_GE(report.at("mpi").at("static_solves").at("solves").get<int>(), 12);
  for (const char* stage : {"partition_scatter", "assembly", "factorisation_solve", "gather", "basis_rank0"}) {
    EXPECT_GE(report.at("mpi").at("seconds").at(stage).get<double>(), 0.0) << stage;
  }
}

TEST_F(ReduceMpiTest, FixedInterfaceOnTwoRanksGivesTheSerialBasisFromSplitAssembly) {
  flexmbs::sid::ReducedBody serial, mpi;
  const nlohmann::json report = ReduceBoth("method: fixed_interface, supports: [root], modes: 6", &serial, &mpi);
  ExpectSameBasis(serial, mpi);
  ExpectSplitAssembly(report, serial.phi.rows(), 0);
}

TEST_F(ReduceMpiTest, FreeFreeOnTwoRanksGivesTheSerialBasisFromSplitAssembly) {
  flexmbs::sid::ReducedBody serial, mpi;
  const nlohmann::json report = ReduceBoth("method: free_free, modes: 6", &serial, &mpi);
  ExpectSameBasis(serial, mpi);
  ExpectSplitAssembly(report, serial.phi.rows(), 1);
}

// A frequency band (all modes below 30 kHz: 6 rigid and 8 elastic). The free body's rigid modes
// used to fail their residual bound (3.4e-5 against 1e-8) because SLEPc's spectrum slicing ran at
// the band's upper end; the held body's band keeps its factorisation of K_oo for the stiffening.
TEST_F(ReduceMpiTest, FrequencyBandsOnTwoRanksGiveTheSerialBasis) {
  for (const std::string reduction : {"method: free_free, max_frequency_hz: 30000",
                                      "method: fixed_interface, supports: [root], max_frequency_hz: 30000"}) {
    SCOPED_TRACE(reduction);
    flexmbs::sid::ReducedBody serial, mpi;
    const nlohmann::json report = ReduceBoth(reduction, &serial, &mpi);
    EXPECT_GT(serial.phi.cols(), 6);
    ExpectSameBasis(serial, mpi);
    ExpectSplitAssembly(report, serial.phi.rows(), reduction.find("free_free") != std::string::npos ? 1 : 0);
  }
}

TEST_F(ReduceMpiTest, AMeshingErrorOnRankZeroStopsEveryRankWithItsMessage) {
  // Only rank 0 meshes: the other rank must hear of the error instead of waiting for its part.
  std::ofstream(dir_ / "broken.geo") << "SetFactory(\"OpenCASCADE\");\nBox(1) = {0, 0, 0, 0.1, 0.07;\n";
  std::ofstream(dir_ / "broken.yaml")
      << "geometry: {file: broken.geo, mesh_size: 0.02, element_order: 2}\n"
         "materials: {steel: {youngs_modulus: 2.1e11, poisson_ratio: 0.3, density: 7850}}\n"
         "reduction: {method: free_free, modes: 6, eigensolver: slepc}\n";
  const fs::path err = dir_ / "stderr.txt";
  const std::string command = "OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 timeout 120 " +
                              std::string(FLEXMBS_MPIEXEC) + " -n 2 " + ShellQuote(kFlexmbsBinary.string()) +
                              " reduce " + ShellQuote((dir_ / "broken.yaml").string()) + " -o " +
                              ShellQuote((dir_ / "broken.sid.h5").string()) + " > /dev/null 2> " +
                              ShellQuote(err.string());
  const int status = std::system(command.c_str());
  ASSERT_TRUE(WIFEXITED(status));
  EXPECT_EQ(WEXITSTATUS(status), flexmbs::testing::kExitInputError);  // not timeout's 124
  const std::string message = "flexmbs: error: " + (dir_ / "broken.yaml").string() + ": ";
  const std::string text = ReadFile(err);
  std::size_t count = 0;
  for (std::size_t at = text.find(message); at != std::string::npos; at = text.find(message, at + 1)) ++count;
  EXPECT_EQ(count, 2u) << text;  // one line from each rank
}

}  // namespace
