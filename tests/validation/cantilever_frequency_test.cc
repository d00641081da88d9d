// The steel cantilever (1 m x 10 mm x 10 mm, tet10) against Euler-Bernoulli beam theory, and
// the convergence rates of frequencies under mesh refinement.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <string>
#include <vector>
#include <numbers>

#include "fem/assembly.h"
#include "fem/body_spec.h"
#include "fem/mass_properties.h"
#include "reduction/dof_constraints.h"
#include "eigensolvers/eigensolver.h"
#include "tests/fem/test_meshes.h"

namespace flexmbs {
namespace {

namespace fs = std::filesystem;

constexpr double kE = 2.1e11, kRho = 7850.0, kLength = 1.0, kSide = 0.01;
// beta_n L of a clamped-free Euler-Bernoulli beam (roots of cos(x) cosh(x) = -1).
constexpr double kBetaL[] = {1.8751040687, 4.6940911330, 7.8547574382, 10.9955407349};
// The bound for the tet10 beam at its default 5 mm mesh; it covers the
// discretisation error and the beam-theory modelling error (shear and rotary inertia,
// about (beta r)^2 ~ 1e-3 for the fourth mode).
constexpr double kEulerBernoulliTolerance = 0.005;
// Three meshes give one rate estimate; pre-asymptotic terms move it by a few tenths.
constexpr double kRateTolerance = 0.5;
// The clamped cantilever's frequency rate lies between the asymptotic rate its clamped edges
// allow (2 x 0.71: Williams 1952, a clamped-free right angle at nu = 0.3) and the rate of a
// smooth mode under tet10 (Strang & Fix: h^4).
constexpr double kEdgeSingularityRate = 2.0 * 0.71;
constexpr double kSmoothTet10Rate = 4.0;

double EulerBernoulliHz(int n) {
  const double I = std::pow(kSide, 4) / 12.0, A = kSide * kSide;
  const double beta = kBetaL[n] / kLength;
  return beta * beta / (2.0 * std::numbers::pi) * std::sqrt(kE * I / (kRho * A));
}

// The lowest `num_modes` frequencies [Hz] of a mesh, with its node set "clamp" fixed or free.
Eigen::VectorXd Frequencies(const fem::Mesh& mesh, int num_modes, bool clamped) {
  const fem::SystemMatrices system = fem::AssembleSystem(mesh, fem::MassMatrixKind::kConsistent);
  const auto free = clamped ? reduction::FreeDofMap::ClampNodes(mesh.num_nodes(), mesh.node_sets.at("clamp"))
                            : reduction::FreeDofMap(mesh.num_dofs());
  eigensolvers::EigenOptions options;
  options.num_modes = num_modes;
  const eigensolvers::EigenSolution solution = eigensolvers::MakeEigensolver("spectra")->Solve(
      free.Restrict(system.stiffness), free.Restrict(system.mass), options);
  return eigensolvers::FrequenciesHz(solution);
}

// Observed order p of a sequence converging as C h^p on meshes halving h, from the ratio of
// successive differences (needs no reference value).
double ObservedRate(const std::vector<double>& f) {
  return std::log2((f[0] - f[1]) / (f[1] - f[2]));
}

// A structured mesh of the beam: n_length x n_side x n_side cells (six tetrahedra or one
// hexahedron each), node set "clamp" at x = 0.
fem::Mesh StructuredBeam(fem::ElementType type, int n_length, int n_side) {
  fem::Mesh mesh = fem::testing::StructuredBox(type, {n_length, n_side, n_side},
                                               {kLength, kSide, kSide}).mesh;
  for (Eigen::Index n = 0; n < mesh.num_nodes(); ++n) {
    if (mesh.nodes(0, n) == 0.0) mesh.node_sets["clamp"].push_back(static_cast<int>(n));
  }
  return mesh;
}

TEST(CantileverEffectiveMass, BendingPairsCarryTheEulerBernoulliShareOfTheMass) {
  // Euler-Bernoulli: with phi_n = cosh bx - cos bx - s_n (sinh bx - sin bx), int phi_n^2 = L and
  // int phi_n = 2 s_n / b_n, so mode n carries (2 s_n / (b_n L))^2 of the mass (0.613, 0.188,
  // 0.065, 0.033), s_n = (cosh b_n L + cos b_n L) / (sinh b_n L + sin b_n L).
  // Tolerance: the 0.5 % bound for this beam's frequencies (measured: 0.03 %).
  constexpr double kShareTolerance = 0.005;
  const fem::BodySpec spec =
      fem::LoadBodySpec(fs::path(FLEXMBS_SOURCE_DIR) / "cases/01_cantilever/beam.yaml");
  fem::Mesh mesh = fem::BuildBodyMesh(spec);
  const fem::SystemMatrices system = fem::AssembleSystem(mesh, fem::MassMatrixKind::kConsistent);
  const auto free = reduction::FreeDofMap::ClampNodes(mesh.num_nodes(), mesh.node_sets.at("clamp"));
  eigensolvers::EigenOptions options;
  options.num_modes = 8;
  const eigensolvers::EigenSolution solution = eigensolvers::MakeEigensolver("spectra")->Solve(
      free.Restrict(system.stiffness), free.Restrict(system.mass), options);
  const Eigen::MatrixXd phi = free.Expand(solution.modes);  // M-orthonormal
  const Eigen::MatrixXd gamma = phi.transpose() * (system.mass * fem::RigidBodyModes(mesh.nodes));
  const double mass = kRho * kLength * kSide * kSide;
  for (int n = 0; n < 4; ++n) {
    const double bl = kBetaL[n];
    const double s = (std::cosh(bl) + std::cos(bl)) / (std::sinh(bl) + std::sin(bl));
    const double expected = std::pow(2.0 * s / bl, 2);
    // The pair (2n, 2n+1) spans bending in y and z in some rotated basis: sum over the pair.
    for (int axis : {1, 2}) {
      const double share = (gamma(2 * n, axis) * gamma(2 * n, axis) +
                            gamma(2 * n + 1, axis) * gamma(2 * n + 1, axis)) / mass;
      std::printf("bending mode %d, axis %d: effective mass share %.5f, Euler-Bernoulli %.5f\n",
                  n + 1, axis, share, expected);
      EXPECT_NEAR(share, expected, kShareTolerance * expected) << "mode " << n + 1 << " axis " << axis;
    }
  }
}

TEST(CantileverFrequencies, DefaultTet10MeshIsWithinHalfPercentOfEulerBernoulli) {
  const fem::BodySpec spec =
      fem::LoadBodySpec(fs::path(FLEXMBS_SOURCE_DIR) / "cases/01_cantilever/beam.yaml");
  const Eigen::VectorXd f = Frequencies(fem::BuildBodyMesh(spec), 8, true);
  // The square section makes each bending frequency a pair (y and z).
  for (int n = 0; n < 4; ++n) {
    const double expected = EulerBernoulliHz(n);
    for (int k : {2 * n, 2 * n + 1}) {
      const double error = f(k) / expected - 1.0;
      std::printf("bending mode %d (%d): %.4f Hz, Euler-Bernoulli %.4f Hz, error %+.3f %%\n",
                  n + 1, k, f(k), expected, 100.0 * error);
      EXPECT_LT(std::abs(error), kEulerBernoulliTolerance) << "mode " << k;
    }
  }
}

// The lowest frequency [Hz] of an a x b x c steel box whose faces slide (zero normal
// displacement, zero shear traction): the DOF normal to each face are fixed on it.
double SlidingBoxFrequency(fem::ElementType type, int r, const Eigen::Vector3d& size) {
  fem::Mesh mesh = fem::testing::StructuredBox(type, {3 * r, 2 * r, r}, size).mesh;
  for (fem::ElementBlock& block : mesh.blocks) block.material = {"steel", kE, 0.3, kRho};
  std::vector<Eigen::Index> fixed;
  for (Eigen::Index n = 0; n < mesh.num_nodes(); ++n) {
    for (int i = 0; i < 3; ++i) {
      if (mesh.nodes(i, n) == 0.0 || mesh.nodes(i, n) == size(i)) fixed.push_back(3 * n + i);
    }
  }
  const fem::SystemMatrices system = fem::AssembleSystem(mesh, fem::MassMatrixKind::kConsistent);
  const reduction::FreeDofMap free(mesh.num_dofs(), fixed);
  eigensolvers::EigenOptions options;
  options.num_modes = 1;
  const eigensolvers::EigenSolution solution = eigensolvers::MakeEigensolver("spectra")->Solve(
      free.Restrict(system.stiffness), free.Restrict(system.mass), options);
  return eigensolvers::FrequenciesHz(solution)(0);
}

TEST(SlidingBoxFrequency, ConvergesToTheAnalyticModeAtEachElementsTheoreticalRate) {
  // With sliding faces the modes are smooth: u = (A sin k1 x cos k2 y cos k3 z, B cos k1 x
  // sin k2 y cos k3 z, C cos k1 x cos k2 y sin k3 z), k_i = n_i pi / size_i, a plane wave of
  // omega = c |k|. The lowest (a > b > c, and c_s pi |k| below the first P wave c_p pi / a) is
  // the shear wave k = (pi/a, pi/b, 0): omega = c_s pi sqrt(1/a^2 + 1/b^2). Eigenvalue errors
  // then fall as h^(2p) (Strang & Fix): 2 for linear elements, 4 for quadratic ones.
  const Eigen::Vector3d size(0.3, 0.2, 0.1);
  const double shear_speed = std::sqrt(kE / (2.0 * 1.3) / kRho);
  const double exact_hz = shear_speed * std::numbers::pi *
                          std::sqrt(1.0 / (size(0) * size(0)) + 1.0 / (size(1) * size(1))) /
                          (2.0 * std::numbers::pi);
  const struct {
    fem::ElementType type;
    int coarsest;
    double theory;
  } kCases[] = {{fem::ElementType::kTet4, 2, 2.0}, {fem::ElementType::kHex8, 2, 2.0},
                {fem::ElementType::kTet10, 1, 4.0}, {fem::ElementType::kHex20, 1, 4.0}};
  for (const auto& c : kCases) {
    std::vector<double> error;
    for (int r : {c.coarsest, 2 * c.coarsest, 4 * c.coarsest}) {
      error.push_back(SlidingBoxFrequency(c.type, r, size) / exact_hz - 1.0);
      EXPECT_GT(error.back(), 0.0) << "a conforming FE frequency lies above the exact one";
    }
    const double rate = std::log2(error[1] / error[2]);
    std::printf("%-6s sliding box (exact %.3f Hz): relative errors %.2e, %.2e, %.2e; rate %.2f (theory %.0f)\n",
                std::string(fem::Traits(c.type).name).c_str(), exact_hz, error[0], error[1],
                error[2], rate, c.theory);
    EXPECT_NEAR(rate, c.theory, kRateTolerance) << fem::Traits(c.type).name;
  }
}

TEST(CantileverFrequencies, ErrorFallsUnderRefinementAtARateBetweenTheEdgeSingularitysAndTheSmoothOnes) {
  // The clamped face meets the free faces at edges where 3-D elasticity is singular (Williams
  // 1952: displacement ~ r^0.71 for a clamped-free right angle at nu = 0.3), which caps the
  // asymptotic eigenvalue rate near 2 x 0.71 for any element; the slender cells are also far
  // from the asymptotic range, where the smooth part of the mode converges at tet10's 4 (the
  // sliding box above). The conforming frequencies fall towards the solution from above, at an
  // observed rate between the two (measured 2.16 on these meshes).
  const int kFourthBendingMode = 6;
  std::vector<double> f;
  for (int refinement : {1, 2, 4}) {
    const fem::Mesh mesh = StructuredBeam(fem::ElementType::kTet10, 12 * refinement, refinement);
    f.push_back(Frequencies(mesh, 8, true)(kFourthBendingMode));
    std::printf("clamped tet10, cells %d x %d x %d: f4 = %.6f Hz\n", 12 * refinement, refinement,
                refinement, f.back());
  }
  const double rate = ObservedRate(f);
  std::printf("observed convergence rate, clamped 4th bending frequency: %.2f (between %.2f and %.0f)\n", rate,
              kEdgeSingularityRate, kSmoothTet10Rate);
  EXPECT_GT(f[0], f[1]);
  EXPECT_GT(f[1], f[2]);
  EXPECT_GT(rate, kEdgeSingularityRate);
  EXPECT_LT(rate, kSmoothTet10Rate);
}

}  // namespace
}  // namespace flexmbs
