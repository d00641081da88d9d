// The rotating cantilever (Southwell): a steel beam clamped at the hub axis spins about an axis
// through the clamp perpendicular to it; centrifugal tension stiffens its bending. The reduced
// 3-D model (tet10, fixed-interface modes, SID centrifugal stiffening K0omega) must follow the
// 1-D rotating Euler-Bernoulli beam.
//
// B: x along the beam (clamp at x = 0), spin w = Omega e_z, so omega_q = [0, 0, Omega^2, 0, 0, 0]
// and only W_3 = diag(-1, -1, 0) enters. About q = 0 the reduced equations in the rotating frame
// (docs/sid.md: Oe with its order-1 terms) are
//
//     Me q'' + (Ke + Omega^2 [K0omega_3 + Kw_3]) q = 0,   Kw_3 = int Phi^T W_3 Phi dm,
//
// with Coriolis coupling left out (it couples lead-lag with the stiff axial motion only; the
// 1-D reference leaves it out too). Kw_3 (centrifugal softening) vanishes for flapping (along
// z) and is -Omega^2 Me for lead-lag (along y): flapping follows omega^2 = omega0^2 + K_s
// Omega^2, lead-lag omega0^2 + (K_s - 1) Omega^2 (Southwell's form; the exact curves bend
// slightly below it at higher spin).
//
// The frequencies are computed from the reduced body as written to and read back from its
// `.sid.h5` file (Ke, Me and the order-1 block of Oe, as a solver would use them); the direct
// sum K0omega_3 + Kw_3 formed in the test must equal the file's block.
#include <gtest/gtest.h>
#include <unistd.h>

#include <Eigen/Eigenvalues>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <sstream>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "fem/assembly.h"
#include "reduction/geometric_stiffening.h"
#include "reduction/modal_basis.h"
#include "reduction/sid_body_builder.h"
#include "sid/sid_file.h"
#include "tests/fem/test_meshes.h"

namespace flexmbs {
namespace {

namespace fs = std::filesystem;
using Index = Eigen::Index;

// The beam: L = 1 m, thickness h = 10 mm along z (flapping), width b = 30 mm along y
// (lead-lag, three times stiffer so that the modes stay apart), steel.
constexpr double kLength = 1.0, kWidth = 0.03, kThickness = 0.01;
const fem::IsotropicMaterial kSteel{"steel", 2.1e11, 0.3, 7850.0};
// Mesh 40 x 3 x 1 structured cells of six straight-sided tet10 each; ten fixed-interface modes
// (flapping 1-5, lead-lag 1-4, torsion 1 or axial above).
constexpr int kModes = 10;

// Southwell coefficient of the first flapping mode of a uniform cantilever with zero hub radius
// (Wright, Smith, Thresher & Wang, J. Appl. Mech. 49, 1982, table of Southwell coefficients).
constexpr double kSouthwellFlap = 1.193;
// The requested agreement of the 3-D reduced model's frequency ratios omega(Omega)/omega0 with
// the 1-D references. Measured: flap within 0.11 %, lead-lag within 0.39 % up to Omega =
// 2 omega0. Its parts: (1) the mesh: the clamped root's Poisson edge singularity converges
// slowly (first order) and raises K_s: 1.1990, 1.1965, 1.1953 on 20, 40, 80 cells along the
// beam (1.1937 with nu = 0 on 20 cells, the 1-D value is 1.1933); (2) the modal truncation
// (Ritz, ten modes): 0.24 % of the lead-lag ratio at Omega = 2 omega0 (against twenty modes),
// 0.01 % of the flap ratio; (3) beam theory's neglect of shear, rotary inertia and the
// section's Poisson effects, of order (h / L)^2 = 1e-4.
constexpr double kRatioTolerance = 0.01;
// Southwell's linear form holds to within this up to Omega = omega0 (the exact 1-D curves fall
// 0.3 % (flap) and 0.5 % (lead-lag) below it there; 1.4 % and 4.6 % at Omega = 2 omega0).
constexpr double kSouthwellRange = 1.0;
constexpr double kSpinRatios[] = {0.5, 1.0, 1.5, 2.0};

constexpr const char* kPython = "/usr/bin/python3";

// K0omega_3 + Kw_3 formed in the test and the file's Oe.m1 agree to the round-off of sums over
// the mesh (measured 1e-15 relative).
constexpr double kRoundOff = 1e-12;

// The reduced rotating beam.
struct ReducedBeam {
  fem::Mesh mesh;
  Eigen::SparseMatrix<double> K, M;
  reduction::ReducedBasis basis;
  Eigen::MatrixXd spin_stiffness;  // K0omega_3 + Kw_3 [per (rad/s)^2], formed directly
  sid::ReducedBody file;           // the body read back from its .sid.h5 file
  /// From the file: column j of Oe.m1[j](:, 2) (l = 3: omega_3^2), [per (rad/s)^2].
  Eigen::MatrixXd file_spin_stiffness;
};

const ReducedBeam& Beam() {
  static const ReducedBeam beam = [] {
    ReducedBeam b;
    b.mesh = fem::testing::StructuredBox(fem::ElementType::kTet10, {40, 3, 1}, {kLength, kWidth, kThickness}).mesh;
    for (fem::ElementBlock& block : b.mesh.blocks) block.material = kSteel;
    fem::SystemMatrices system = fem::AssembleSystem(b.mesh, fem::MassMatrixKind::kConsistent);
    b.K = std::move(system.stiffness);
    b.M = std::move(system.mass);
    const reduction::FeModel model{b.K, b.M, b.mesh.nodes};
    reduction::BoundaryConditions clamp;
    clamp.supports.push_back({"hub", {}});
    for (Index n = 0; n < b.mesh.num_nodes(); ++n) {
      if (b.mesh.nodes(0, n) == 0.0) clamp.supports[0].nodes.push_back(static_cast<int>(n));
    }
    eigensolvers::EigenOptions eigen;
    eigen.num_modes = kModes;
    b.basis = reduction::FixedInterfaceModalBasis(model, clamp, eigen, *eigensolvers::MakeEigensolver("spectra"));
    const reduction::StiffeningResult stiffening =
        reduction::ComputeGeometricStiffening(b.mesh, model, clamp, b.basis.Phi);
    // Kw_3 = Phi^T M (W_3 Phi), W_3 = diag(-1, -1, 0) on every node.
    Eigen::MatrixXd W3Phi = -b.basis.Phi;
    for (Index n = 0; n < b.mesh.num_nodes(); ++n) W3Phi.row(3 * n + 2).setZero();
    b.spin_stiffness = stiffening.body.K0omega[2] + b.basis.Phi.transpose() * (b.M * W3Phi);
    b.spin_stiffness = (0.5 * (b.spin_stiffness + b.spin_stiffness.transpose())).eval();

    const reduction::SidSpec sid;  // defaults: stiffening on
    const fem::SystemMatrices views{b.K, b.M};
    const fs::path path = fs::temp_directory_path() / ("flexmbs_rotating_cantilever_" + std::to_string(getpid()) + ".sid.h5");
    sid::WriteReducedBody(path, reduction::BuildReducedBody({b.mesh, views, fem::MassMatrixKind::kConsistent, sid}, b.basis));
    b.file = sid::ReadReducedBody(path);
    fs::remove(path);
    b.file_spin_stiffness.resize(kModes, kModes);
    for (Index j = 0; j < kModes; ++j) b.file_spin_stiffness.col(j) = b.file.Oe.m1[static_cast<std::size_t>(j)].col(2);
    return b;
  }();
  return beam;
}

// The lowest frequency [rad/s] at spin Omega [rad/s] of a mode moving mostly along `axis` (1:
// lead-lag along y, 2: flapping along z): the fraction of its displacement along that axis is
// asserted to exceed 90 %.
double Frequency(const ReducedBeam& b, double spin, int axis) {
  const Eigen::MatrixXd A = b.file.Ke.m0 + spin * spin * b.file_spin_stiffness;
  const Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd> solver(A, b.file.Me.m0);
  for (Index k = 0; k < A.rows(); ++k) {
    const Eigen::VectorXd u = b.basis.Phi * solver.eigenvectors().col(k);
    double along = 0.0;
    for (Index n = 0; n < b.mesh.num_nodes(); ++n) along += u(3 * n + axis) * u(3 * n + axis);
    if (along > 0.9 * u.squaredNorm()) return std::sqrt(solver.eigenvalues()(k));
  }
  ADD_FAILURE() << "no mode along axis " << axis << " at spin " << spin;
  return 0.0;
}

TEST(RotatingCantilever, FileOrderOneOeIsTheStiffeningPlusTheCentrifugalSoftening) {
  const ReducedBeam& b = Beam();
  EXPECT_LE((b.file_spin_stiffness - b.spin_stiffness).norm(), kRoundOff * b.spin_stiffness.norm());
  EXPECT_LE((b.file.Ke.m0 - b.basis.K_reduced).norm(), kRoundOff * b.basis.K_reduced.norm());
}

TEST(RotatingCantilever, FlappingAndLeadLagFollowSouthwellAtModerateSpin) {
  const ReducedBeam& b = Beam();
  const double flap0 = Frequency(b, 0.0, 2), lag0 = Frequency(b, 0.0, 1);
  // The Southwell coefficient of the reduced model, from a small spin (the curve's slope at 0).
  const double small = 1e-3 * flap0;
  const double k_flap = (std::pow(Frequency(b, small, 2), 2) - flap0 * flap0) / (small * small);
  const double k_lag = (std::pow(Frequency(b, small * lag0 / flap0, 1), 2) - lag0 * lag0) /
                       std::pow(small * lag0 / flap0, 2);
  std::printf("[ numbers  ] flap0 %.4f rad/s, lag0 %.4f rad/s; Southwell coefficients: flap %.5f (K_s %.3f, "
              "error %+.2e), lead-lag %.5f (K_s - 1 = %.3f)\n",
              flap0, lag0, k_flap, kSouthwellFlap, k_flap / kSouthwellFlap - 1.0, k_lag, kSouthwellFlap - 1.0);
  EXPECT_NEAR(k_flap / kSouthwellFlap, 1.0, kRatioTolerance);
  // Lead-lag: K_s - 1 is small; its error is that of K_s (the softening -Omega^2 Me is exact).
  EXPECT_NEAR((k_lag + 1.0) / kSouthwellFlap, 1.0, kRatioTolerance);
  for (const double s : kSpinRatios) {
    if (s > kSouthwellRange) continue;
    const double flap = Frequency(b, s * flap0, 2) / flap0, lag = Frequency(b, s * lag0, 1) / lag0;
    const double flap_southwell = std::sqrt(1.0 + kSouthwellFlap * s * s);
    const double lag_southwell = std::sqrt(1.0 + (kSouthwellFlap - 1.0) * s * s);
    std::printf("[ numbers  ] Omega/omega0 %.2f: flap ratio %.5f, Southwell %.5f (%+.2e); lead-lag %.5f, "
                "Southwell %.5f (%+.2e)\n",
                s, flap, flap_southwell, flap / flap_southwell - 1.0, lag, lag_southwell, lag / lag_southwell - 1.0);
    EXPECT_NEAR(flap / flap_southwell, 1.0, kRatioTolerance) << "s " << s;
    EXPECT_NEAR(lag / lag_southwell, 1.0, kRatioTolerance) << "s " << s;
  }
}

TEST(RotatingCantilever, FrequencyRatiosMatchTheOneDimensionalRotatingBeam) {
  if (!fs::exists(kPython)) GTEST_SKIP() << kPython << " not found";
  const fs::path script = fs::path(FLEXMBS_SOURCE_DIR) / "tests/validation/rotating_beam_reference.py";
  std::ostringstream command;
  command << kPython << " '" << script.string() << "'";
  for (const double s : kSpinRatios) command << ' ' << s;
  FILE* pipe = popen(command.str().c_str(), "r");
  ASSERT_NE(pipe, nullptr);
  std::string out;
  char buffer[4096];
  std::size_t n;
  while ((n = fread(buffer, 1, sizeof buffer, pipe)) > 0) out.append(buffer, n);
  ASSERT_EQ(pclose(pipe), 0) << command.str() << " failed (needs numpy and scipy)";
  const nlohmann::json reference = nlohmann::json::parse(out);
  EXPECT_NEAR(reference.at("southwell_flap").get<double>(), kSouthwellFlap, 5e-4)
      << "the 1-D reference against Wright et al.'s coefficient (given to 3 decimals)";

  const ReducedBeam& b = Beam();
  const double flap0 = Frequency(b, 0.0, 2), lag0 = Frequency(b, 0.0, 1);
  std::size_t k = 0;
  for (const double s : kSpinRatios) {
    const double flap = Frequency(b, s * flap0, 2) / flap0, lag = Frequency(b, s * lag0, 1) / lag0;
    const double flap_1d = reference.at("flap").at(k).get<double>(), lag_1d = reference.at("lag").at(k).get<double>();
    ++k;
    std::printf("[ numbers  ] Omega/omega0 %.2f: flap ratio %.5f, 1-D %.5f (%+.2e); lead-lag %.5f, 1-D %.5f "
                "(%+.2e)\n",
                s, flap, flap_1d, flap / flap_1d - 1.0, lag, lag_1d, lag / lag_1d - 1.0);
    EXPECT_NEAR(flap / flap_1d, 1.0, kRatioTolerance) << "s " << s;
    EXPECT_NEAR(lag / lag_1d, 1.0, kRatioTolerance) << "s " << s;
  }
}

}  // namespace
}  // namespace flexmbs
