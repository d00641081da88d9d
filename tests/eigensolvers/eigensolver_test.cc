#include "eigensolvers/eigensolver.h"

#include <fmt/format.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <cstdio>
#include <numbers>
#include <string>
#include <vector>

#include "core/error.h"
#include "fem/assembly.h"
#include "fem/mass_properties.h"
#include "reduction/dof_constraints.h"
#include "eigensolvers/shifted_factorization.h"
#include "tests/support/eigen_contract.h"
#include "tests/support/test_problems.h"

namespace flexmbs::eigensolvers {
namespace {

using testing::HexBox;
using testing::kClusterTolerance;
using testing::kOrthonormalityBound;
using testing::kResidualBound;
using testing::LargestPrincipalAngleSine;
using testing::NodesOnPlane;
using testing::SolveDense;
using testing::Steel;
using SparseMatrix = Eigen::SparseMatrix<double>;

// The solver's round-off floors against the test's (other summation orders), relative: measured
// 6.5e-12.
constexpr double kFloorRoundOff = 5e-11;
// Eigenvalue agreement with the dense solver, relative to max(|lambda|, first elastic
// lambda). The dense reference is in shift-invert form, accurate relative to each low
// eigenvalue (test_problems.h); measured deviations are 1e-12 .. 3e-11, this is the
// contract's 1e-8.
constexpr double kDenseAgreement = 1e-8;
// Subspace agreement (sine of the largest principal angle) of a cluster of eigenvalues with
// the dense one. Davis-Kahan: sin theta <= residual / relative gap to the rest of the
// spectrum; residuals <= 1e-8 and the gaps here are >= 1e-2.
constexpr double kSubspaceAgreement = 1e-6;

const std::unique_ptr<Eigensolver>& Spectra() {
  static const std::unique_ptr<Eigensolver> solver = MakeEigensolver("spectra");
  return solver;
}

struct Problem {
  fem::Mesh mesh;
  SparseMatrix K;
  SparseMatrix M;
};

// A shift for the dense reference of a free-free body: -1e-6 of the mesh's stiffness-to-mass
// scale, far below the first elastic eigenvalue and far above round-off.
double FreeFreeShift(const Problem& p) { return FreeBodyShift(p.K, p.M); }

Problem Assemble(fem::Mesh mesh) {
  fem::SystemMatrices system = fem::AssembleSystem(mesh, fem::MassMatrixKind::kConsistent);
  return {std::move(mesh), std::move(system.stiffness), std::move(system.mass)};
}

// The residuals and round-off floors of EigenSolution's definition (eigensolver.h), computed
// here from K and M with Eigen's own sparse products, not with the solver's functions
// (ComputeResiduals, MOrthonormalityError), so that a wrong definition there cannot hide a bad pair.
struct TestResiduals {
  Eigen::VectorXd relative, floor;
};
TestResiduals ResidualsFromKAndM(const SparseMatrix& K, const SparseMatrix& M, const EigenSolution& s) {
  const SparseMatrix K_abs = K.cwiseAbs(), M_abs = M.cwiseAbs();
  const double zero_eigenvalue = kZeroEigenvalue * K.diagonal().sum() / M.diagonal().sum();
  TestResiduals r{Eigen::VectorXd(s.eigenvalues.size()), Eigen::VectorXd(s.eigenvalues.size())};
  for (Eigen::Index j = 0; j < s.eigenvalues.size(); ++j) {
    const double lambda = s.eigenvalues(j);
    const Eigen::VectorXd phi = s.modes.col(j), K_phi = K * phi, M_phi = M * phi;
    const Eigen::VectorXd abs_phi = phi.cwiseAbs();
    const double rigid_scale = std::abs(lambda) <= zero_eigenvalue ? std::abs(s.shift) * M_phi.norm() : 0.0;
    const double d = std::max({K_phi.norm(), std::abs(lambda) * M_phi.norm(), rigid_scale,
                               std::numeric_limits<double>::min()});
    r.relative(j) = (K_phi - lambda * M_phi).norm() / d;
    r.floor(j) = std::numeric_limits<double>::epsilon() *
                 (K_abs * abs_phi + std::abs(lambda) * (M_abs * abs_phi)).norm() / d;
  }
  return r;
}

// Every returned pair meets the contract, computed here from K and M (ResidualsFromKAndM).
// `strict`: the residual bound itself, not relaxed to the round-off floor (the floors of these
// compact meshes are far below it, which is checked too).
void ExpectContract(const SparseMatrix& K, const SparseMatrix& M, const EigenSolution& s, bool strict = true) {
  ASSERT_EQ(s.modes.cols(), s.eigenvalues.size());
  ASSERT_EQ(s.relative_residuals.size(), s.eigenvalues.size());
  ASSERT_EQ(s.residual_floors.size(), s.eigenvalues.size());
  for (Eigen::Index j = 1; j < s.eigenvalues.size(); ++j) EXPECT_LE(s.eigenvalues(j - 1), s.eigenvalues(j));
  const TestResiduals residuals = ResidualsFromKAndM(K, M, s);
  for (Eigen::Index j = 0; j < residuals.relative.size(); ++j) {
    if (strict) {
      EXPECT_LE(residuals.relative(j), kResidualBound) << "mode " << j;
      EXPECT_LE(residuals.floor(j), kResidualBound) << "mode " << j;  // the bound is attainable
    } else {
      EXPECT_LE(residuals.relative(j), std::max(kResidualBound, kResidualFloorFactor * residuals.floor(j)))
          << "mode " << j;
    }
    // The backend multiplies M through M_s (eigensolvers/mass_operator.h), a summation order of its
    // own: the two residuals of one pair may differ by the round-off of computing them.
    EXPECT_NEAR(residuals.relative(j), s.relative_residuals(j), residuals.floor(j)) << "mode " << j;
    EXPECT_NEAR(residuals.floor(j), s.residual_floors(j), kFloorRoundOff * residuals.floor(j)) << "mode " << j;
  }
  const Eigen::MatrixXd gram = s.modes.transpose() * (M * s.modes);
  const double orthonormality = (gram - Eigen::MatrixXd::Identity(gram.rows(), gram.cols())).cwiseAbs().maxCoeff();
  EXPECT_LE(orthonormality, kOrthonormalityBound);
  // The same Gram matrix summed in another order (M_s): equal to round-off.
  EXPECT_NEAR(s.orthonormality_error, orthonormality, 1e-14);
}

// The returned eigenvalues match the dense ones, and each complete cluster of (numerically)
// repeated eigenvalues spans the dense cluster's subspace.
void ExpectMatchesDense(const SparseMatrix& M, const EigenSolution& s, const testing::DenseEigen& dense,
                        double lambda_ref) {
  const Eigen::Index n = s.eigenvalues.size();
  ASSERT_LE(n, dense.values.size());
  double max_deviation = 0.0;
  double max_sine = 0.0;
  for (Eigen::Index j = 0; j < n; ++j) {
    const double deviation =
        std::abs(s.eigenvalues(j) - dense.values(j)) / std::max(std::abs(dense.values(j)), lambda_ref);
    max_deviation = std::max(max_deviation, deviation);
    EXPECT_LE(deviation, kDenseAgreement)
        << "mode " << j << ": " << s.eigenvalues(j) << " vs dense " << dense.values(j);
  }
  const auto same = [&](double a, double b) {
    return std::abs(a - b) <= kClusterTolerance * std::max({std::abs(a), std::abs(b), lambda_ref});
  };
  for (Eigen::Index begin = 0; begin < n;) {
    Eigen::Index end = begin + 1;
    while (end < dense.values.size() && same(dense.values(end - 1), dense.values(end))) ++end;
    if (end > n) break;  // a cluster cut by the last returned mode: its subspace is not unique
    const double sine = LargestPrincipalAngleSine(M, s.modes.middleCols(begin, end - begin),
                                                  dense.vectors.middleCols(begin, end - begin));
    EXPECT_LE(sine, kSubspaceAgreement) << "cluster of modes " << begin << ".." << end - 1;
    max_sine = std::max(max_sine, sine);
    begin = end;
  }
  std::printf("[ numbers  ] vs dense: max eigenvalue deviation %.1e, max principal-angle sine %.1e\n", max_deviation,
              max_sine);
}

void Report(const char* what, const EigenSolution& s) {
  std::printf("[ numbers  ] %s: %td modes, max residual %.2e, orthonormality %.2e, %d factorisations, %d solves, "
              "%d Lanczos runs, %d restarts, %d refinements, %.3f s\n",
              what, s.eigenvalues.size(), s.relative_residuals.size() ? s.relative_residuals.maxCoeff() : 0.0,
              s.orthonormality_error, s.factorizations, s.operator_applications, s.krylov_runs, s.restarts,
              s.refinement_steps, s.seconds);
}

// A steel cantilever 0.6 m x 0.05 m x 0.04 m, 12 x 3 x 3 hex8, clamped at x = 0. The
// section is not square, so bending in y and z do not give repeated eigenvalues.
struct Cantilever {
  Problem full;
  reduction::FreeDofMap map;
  SparseMatrix K;
  SparseMatrix M;
};
Cantilever MakeCantilever(const fem::IsotropicMaterial& left, const fem::IsotropicMaterial& right) {
  Problem p = Assemble(HexBox({12, 3, 3}, {0.6, 0.05, 0.04}, left, right, 0.3));
  reduction::FreeDofMap map = reduction::FreeDofMap::ClampNodes(p.mesh.num_nodes(), NodesOnPlane(p.mesh, 0, 0.0));
  SparseMatrix K = map.Restrict(p.K);
  SparseMatrix M = map.Restrict(p.M);
  return {std::move(p), std::move(map), std::move(K), std::move(M)};
}

TEST(MakeEigensolver, UnknownBackendThrowsInputErrorListingTheAvailableOnes) {
  try {
    MakeEigensolver("arpack");
    FAIL() << "no exception";
  } catch (const InputError& e) {
    EXPECT_STREQ(e.what(), "unknown eigensolver backend 'arpack' (available: spectra, slepc)");
  }
  EXPECT_EQ(MakeEigensolver("spectra")->name(), "spectra");
  EXPECT_EQ(MakeEigensolver("slepc")->name(), "slepc");
}

TEST(FrequenciesHz, AreSignedSquareRootsOverTwoPi) {
  const Eigen::VectorXd hz = FrequenciesHz(Eigen::Vector3d(std::pow(2 * std::numbers::pi * 50, 2), 0.0, -4.0));
  EXPECT_NEAR(hz(0), 50.0, 1e-12);
  EXPECT_EQ(hz(1), 0.0);
  EXPECT_NEAR(hz(2), -1.0 / std::numbers::pi, 1e-15);
  EXPECT_NEAR(ShiftFromHz(-10.0), -std::pow(2 * std::numbers::pi * 10, 2), 1e-9);
}

// The solver tests run once with each check against missed modes, with Spectra's
// single-vector Lanczos and with block Lanczos (blocks of 4 columns: several steps on these
// small problems).
struct SolverVariant {
  MissedModeCheck check;
  int lanczos_block_size;
};

class SpectraEigensolverWith : public ::testing::TestWithParam<SolverVariant> {
 protected:
  EigenOptions Options() const {
    EigenOptions options;
    options.check_missed_modes = GetParam().check;
    options.lanczos_block_size = GetParam().lanczos_block_size;
    return options;
  }
  // The check was made above the last returned mode; a Sturm count equals the true number of
  // eigenvalues below its cut.
  void ExpectChecked(const EigenSolution& s, const Eigen::VectorXd& true_values) const {
    EXPECT_EQ(s.missed_mode_check, GetParam().check);
    EXPECT_EQ(s.lanczos_block_size, GetParam().lanczos_block_size);
    EXPECT_GT(s.checked_cut, s.eigenvalues(s.eigenvalues.size() - 1));
    if (GetParam().check == MissedModeCheck::kSturmCount) {
      EXPECT_EQ(s.sturm_count, (true_values.array() < s.sturm_cut).count());
    } else {
      EXPECT_EQ(s.sturm_count, -1);
    }
  }
};

INSTANTIATE_TEST_SUITE_P(Checks, SpectraEigensolverWith,
                         ::testing::Values(SolverVariant{MissedModeCheck::kSturmCount, 1},
                                           SolverVariant{MissedModeCheck::kDeflatedLanczos, 1},
                                           SolverVariant{MissedModeCheck::kBlockKrylov, 1},
                                           SolverVariant{MissedModeCheck::kSturmCount, 4},
                                           SolverVariant{MissedModeCheck::kDeflatedLanczos, 4},
                                           SolverVariant{MissedModeCheck::kBlockKrylov, 4}),
                         [](const ::testing::TestParamInfo<SolverVariant>& param) {
                           const MissedModeCheck check = param.param.check;
                           const std::string name = check == MissedModeCheck::kSturmCount        ? "SturmCount"
                                                    : check == MissedModeCheck::kDeflatedLanczos ? "DeflatedLanczos"
                                                                                                 : "BlockKrylov";
                           return param.param.lanczos_block_size == 1 ? name : name + "BlockLanczos";
                         });

TEST_P(SpectraEigensolverWith, ClampedCantileverMatchesDenseSolver) {
  const Cantilever c = MakeCantilever(Steel(), Steel());
  const testing::DenseEigen dense = SolveDense(c.K, c.M, 0.0);
  EigenOptions options = Options();
  options.num_modes = 10;
  const EigenSolution s = Spectra()->Solve(c.K, c.M, options);
  Report("clamped cantilever", s);
  ASSERT_EQ(s.eigenvalues.size(), 10);
  ExpectContract(c.K, c.M, s);
  ExpectMatchesDense(c.M, s, dense, dense.values(0));
  ExpectChecked(s, dense.values);
}

TEST_P(SpectraEigensolverWith, FreeFreeBoxHasSixRigidModesThenElasticOnes) {
  const Problem p = Assemble(HexBox({8, 4, 3}, {0.4, 0.2, 0.15}, Steel()));
  const testing::DenseEigen dense = SolveDense(p.K, p.M, FreeFreeShift(p));
  EigenOptions options = Options();
  options.num_modes = 14;
  const EigenSolution s = Spectra()->Solve(p.K, p.M, options);
  Report("free-free box", s);
  ASSERT_EQ(s.eigenvalues.size(), 14);
  EXPECT_LT(s.shift, 0.0);
  ExpectContract(p.K, p.M, s);
  const double first_elastic = dense.values(6);
  // Rigid-body eigenvalues are round-off: |lambda| <= 1e-9 of the first elastic one.
  for (int j = 0; j < 6; ++j) EXPECT_LE(std::abs(s.eigenvalues(j)), 1e-9 * first_elastic) << j;
  EXPECT_GT(s.eigenvalues(6), 0.1 * first_elastic);
  // The six rigid modes span the rigid-body displacement fields.
  EXPECT_LE(LargestPrincipalAngleSine(p.M, s.modes.leftCols(6), fem::RigidBodyModes(p.mesh.nodes)),
            kSubspaceAgreement);
  ExpectMatchesDense(p.M, s, dense, first_elastic);
  ExpectChecked(s, dense.values);
}

TEST_P(SpectraEigensolverWith, CubeRepeatedFrequenciesSpanTheDenseSubspaces) {
  const Problem p = Assemble(HexBox({5, 5, 5}, {0.1, 0.1, 0.1}, Steel()));
  const testing::DenseEigen dense = SolveDense(p.K, p.M, FreeFreeShift(p));
  const double first_elastic = dense.values(6);
  // Cubic symmetry: the elastic eigenvalues come in clusters of 1, 2 and 3. Ask for modes up
  // to the end of a cluster near mode 30.
  const auto same = [&](Eigen::Index a, Eigen::Index b) { return testing::SameCluster(dense, a, b); };
  int repeated = 0;
  for (Eigen::Index j = 7; j < 30; ++j) repeated += same(j - 1, j) ? 1 : 0;
  ASSERT_GE(repeated, 8) << "the cube's spectrum should have repeated eigenvalues";
  Eigen::Index num_modes = 30;
  while (same(num_modes - 1, num_modes)) ++num_modes;
  EigenOptions options = Options();
  options.num_modes = static_cast<int>(num_modes);
  const EigenSolution s = Spectra()->Solve(p.K, p.M, options);
  Report("free-free cube", s);
  ASSERT_EQ(s.eigenvalues.size(), num_modes);
  ExpectContract(p.K, p.M, s);
  ExpectMatchesDense(p.M, s, dense, first_elastic);
  ExpectChecked(s, dense.values);
}

TEST_P(SpectraEigensolverWith, CubeModesCuttingAClusterReturnTheRightEigenvalues) {
  const Problem p = Assemble(HexBox({5, 5, 5}, {0.1, 0.1, 0.1}, Steel()));
  const testing::DenseEigen dense = SolveDense(p.K, p.M, FreeFreeShift(p));
  // Find a cluster of 3 among the lowest elastic modes and stop after two of its three.
  Eigen::Index cut = -1;
  for (Eigen::Index j = 8; j < 40 && cut < 0; ++j) {
    if (testing::SameCluster(dense, j - 2, j) && testing::SameCluster(dense, j - 1, j)) {
      cut = j;  // modes 0 .. j-1 hold two of the three
    }
  }
  ASSERT_GT(cut, 0);
  EigenOptions options = Options();
  options.num_modes = static_cast<int>(cut);
  const EigenSolution s = Spectra()->Solve(p.K, p.M, options);
  ASSERT_EQ(s.eigenvalues.size(), cut);
  ExpectContract(p.K, p.M, s);
  ExpectMatchesDense(p.M, s, dense, dense.values(6));
  // The check's cut lies above the whole cluster.
  EXPECT_GT(s.checked_cut, dense.values(cut));
}

TEST_P(SpectraEigensolverWith, MaxFrequencyReturnsExactlyTheModesInTheBand) {
  const Cantilever c = MakeCantilever(Steel(), Steel());
  const testing::DenseEigen dense = SolveDense(c.K, c.M, 0.0);
  const Eigen::VectorXd dense_hz = FrequenciesHz(dense.values);
  // A band edge halfway between modes 7 and 8 (index 6 and 7).
  EigenOptions options = Options();
  options.max_frequency_hz = 0.5 * (dense_hz(6) + dense_hz(7));
  const EigenSolution s = Spectra()->Solve(c.K, c.M, options);
  Report("cantilever band", s);
  ASSERT_EQ(s.eigenvalues.size(), 7);
  EXPECT_LT(FrequenciesHz(s).maxCoeff(), options.max_frequency_hz);
  ExpectContract(c.K, c.M, s);
  ExpectMatchesDense(c.M, s, dense, dense.values(0));
  EXPECT_DOUBLE_EQ(s.checked_cut, std::pow(2 * std::numbers::pi * options.max_frequency_hz, 2));
  ExpectChecked(s, dense.values);

  // num_modes caps the band: the lowest four.
  options.num_modes = 4;
  const EigenSolution capped = Spectra()->Solve(c.K, c.M, options);
  ASSERT_EQ(capped.eigenvalues.size(), 4);
  ExpectMatchesDense(c.M, capped, dense, dense.values(0));
  ExpectChecked(capped, dense.values);

  // A band reaching beyond the first Lanczos subspace: the first 60 modes.
  EigenOptions wide = Options();
  wide.max_frequency_hz = 0.5 * (dense_hz(59) + dense_hz(60));
  const EigenSolution w = Spectra()->Solve(c.K, c.M, wide);
  Report("cantilever band of 60", w);
  ASSERT_EQ(w.eigenvalues.size(), 60);
  ExpectContract(c.K, c.M, w);
  ExpectMatchesDense(c.M, w, dense, dense.values(0));
  ExpectChecked(w, dense.values);
}

TEST_P(SpectraEigensolverWith, MaxFrequencyBelowTheFirstElasticModeGivesTheRigidModes) {
  const Problem p = Assemble(HexBox({8, 4, 3}, {0.4, 0.2, 0.15}, Steel()));
  const testing::DenseEigen dense = SolveDense(p.K, p.M, FreeFreeShift(p));
  EigenOptions options = Options();
  options.max_frequency_hz = 0.5 * FrequenciesHz(dense.values)(6);
  const EigenSolution s = Spectra()->Solve(p.K, p.M, options);
  ASSERT_EQ(s.eigenvalues.size(), 6);
  ExpectContract(p.K, p.M, s);
  ExpectChecked(s, dense.values);
}

TEST_P(SpectraEigensolverWith, StiffnessRatioOfAMillionAndNearlyIncompressibleMatchesDense) {
  const fem::IsotropicMaterial stiff{"stiff", 210e9, 0.499, 7850.0};
  const fem::IsotropicMaterial soft{"soft", 210e3, 0.499, 1100.0};
  const Cantilever c = MakeCantilever(stiff, soft);
  const testing::DenseEigen dense = SolveDense(c.K, c.M, 0.0);
  EigenOptions options = Options();
  options.num_modes = 12;
  const EigenSolution s = Spectra()->Solve(c.K, c.M, options);
  Report("stiffness ratio 1e6, nu 0.499", s);
  std::printf("[ numbers  ] lambda_max / lambda_1 = %.2e\n", dense.values(dense.values.size() - 1) / dense.values(0));
  ASSERT_EQ(s.eigenvalues.size(), 12);
  ExpectContract(c.K, c.M, s);
  ExpectMatchesDense(c.M, s, dense, dense.values(0));
  ExpectChecked(s, dense.values);
}

TEST_P(SpectraEigensolverWith, FindsEveryCopyOfAHighlyRepeatedEigenvalue) {
  // K = diag(1, 1, 1, 1, 1, 2, 3, ...), M = I: single-vector Lanczos sees each eigenspace only
  // through the start vector's projection; the check and deflated runs must find all five
  // copies of lambda = 1.
  const auto [K, M] = testing::FiveFoldLowestEigenvalue(200);
  EigenOptions options = Options();
  options.num_modes = 7;
  options.shift_hz = 0.0;
  const EigenSolution s = Spectra()->Solve(K, M, options);
  Report("diagonal, 5-fold eigenvalue", s);
  ASSERT_EQ(s.eigenvalues.size(), 7);
  for (int j = 0; j < 5; ++j) EXPECT_NEAR(s.eigenvalues(j), 1.0, 1e-12);
  EXPECT_NEAR(s.eigenvalues(5), 2.0, 1e-12);
  EXPECT_NEAR(s.eigenvalues(6), 3.0, 1e-12);
  // One vector sees one direction of the eigenspace per run; a block of 4 sees 4 at once.
  if (GetParam().lanczos_block_size == 1) {
    EXPECT_GE(s.krylov_runs, 2);
  }
  ExpectContract(K, M, s);
  ExpectChecked(s, K.diagonal());
}

// Each pair against max(tolerance, floor factor x its floor); a NaN residual is never accepted.
TEST(PairResiduals, WorstRatioIsTheResidualFurthestAboveItsBound) {
  PairResiduals r{Eigen::Vector3d(2e-8, 1e-9, 6e-8), Eigen::Vector3d(1e-10, 1e-9, 1e-8)};
  Eigen::Index worst = -1;
  EXPECT_DOUBLE_EQ(r.WorstRatio(1e-8, &worst, 4.0), 2.0);  // 2e-8 / 1e-8 beats 6e-8 / 4e-8
  EXPECT_EQ(worst, 0);
  EXPECT_FALSE(r.Accepted(1e-8));
  EXPECT_FALSE(r.Accepted(3e-8));  // 6e-8 against 4 x 1e-8
  EXPECT_TRUE(r.Accepted(6e-8));
  EXPECT_DOUBLE_EQ(r.WorstRatio(5e-9, &worst, 1.0), 6.0);
  EXPECT_EQ(worst, 2);
  r.relative(1) = std::numeric_limits<double>::quiet_NaN();
  EXPECT_EQ(r.WorstRatio(1.0, &worst), std::numeric_limits<double>::infinity());
  EXPECT_EQ(worst, 1);
  EXPECT_FALSE(r.Accepted(1.0));
  EXPECT_EQ(PairResiduals{}.WorstRatio(1e-8), 0.0);
}

TEST(SpectraEigensolver, AutomaticCheckIsTheSturmCountOnSmallModels) {
  const Cantilever c = MakeCantilever(Steel(), Steel());
  EigenOptions options;
  options.num_modes = 3;
  EXPECT_EQ(Spectra()->Solve(c.K, c.M, options).missed_mode_check, MissedModeCheck::kSturmCount);
  options.check_missed_modes = MissedModeCheck::kNone;
  const EigenSolution s = Spectra()->Solve(c.K, c.M, options);
  EXPECT_EQ(s.missed_mode_check, MissedModeCheck::kNone);
  EXPECT_EQ(s.sturm_count, -1);
  EXPECT_EQ(s.factorizations, 1);
}

TEST(SpectraEigensolver, SolveFactorizedUsesTheGivenFactorisationAndEqualsSolve) {
  // The same factor (CHOLMOD is deterministic) and the same Lanczos runs: the same pairs up to
  // round-off (measured: 0).
  constexpr double kSameComputation = 1e-13;
  const Cantilever c = MakeCantilever(Steel(), Steel());
  ShiftedFactorization factor;
  ASSERT_EQ(factor.Factorize(c.K, c.M, 0.0, ShiftedFactorization::Method::kSupernodalCholesky),
            ShiftedFactorization::Status::kOk);
  ASSERT_TRUE(Spectra()->UsesGivenFactorization());
  for (const MissedModeCheck check : {MissedModeCheck::kDeflatedLanczos, MissedModeCheck::kSturmCount}) {
    EigenOptions options;
    options.num_modes = 5;
    options.check_missed_modes = check;
    options.shift_hz = 0.0;
    const long before = ShiftedFactorization::NumericFactorizations();
    const EigenSolution given = Spectra()->SolveFactorized(c.K, c.M, options, factor);
    const long made = ShiftedFactorization::NumericFactorizations() - before;
    const EigenSolution own = Spectra()->Solve(c.K, c.M, options);
    ExpectContract(c.K, c.M, given);
    // Only the Sturm counts' LDL^T factorisations are made, and counted.
    EXPECT_EQ(given.factorizations, check == MissedModeCheck::kSturmCount ? 1 : 0);
    EXPECT_EQ(made, given.factorizations);
    EXPECT_EQ(given.factorization_seconds, 0.0);
    EXPECT_EQ(own.factorizations, given.factorizations + 1);
    EXPECT_EQ(given.shift, 0.0);
    EXPECT_LE((given.eigenvalues - own.eigenvalues).cwiseAbs().maxCoeff(), kSameComputation * own.eigenvalues(4));
    EXPECT_LE((given.modes - own.modes).cwiseAbs().maxCoeff(), kSameComputation * own.modes.cwiseAbs().maxCoeff());
    EXPECT_EQ(given.operator_applications, own.operator_applications);
  }
  // A shift other than the factorisation's is a programming error.
  EigenOptions other;
  other.num_modes = 2;
  other.shift_hz = -1.0;
  EXPECT_THROW(Spectra()->SolveFactorized(c.K, c.M, other, factor), InternalError);
}

TEST(SpectraEigensolver, ExpandedCantileverModesAreZeroOnTheClampAndSolveTheFullProblem) {
  const Cantilever c = MakeCantilever(Steel(), Steel());
  EigenOptions options;
  options.num_modes = 4;
  const EigenSolution s = Spectra()->Solve(c.K, c.M, options);
  const Eigen::MatrixXd full = c.map.Expand(s.modes);
  ASSERT_EQ(full.rows(), c.full.mesh.num_dofs());
  for (const int node : NodesOnPlane(c.full.mesh, 0, 0.0)) {
    EXPECT_EQ(full.middleRows(3 * node, 3).cwiseAbs().maxCoeff(), 0.0);
  }
  // On the free DOFs, the full K phi - lambda M phi vanishes (the clamp reactions are the
  // fixed rows).
  for (Eigen::Index j = 0; j < 4; ++j) {
    const Eigen::VectorXd r = c.full.K * full.col(j) - s.eigenvalues(j) * (c.full.M * full.col(j));
    const Eigen::VectorXd r_free = c.map.RestrictVectors(r);
    EXPECT_LE(r_free.norm(), kResidualBound * c.map.RestrictVectors(c.full.K * full.col(j)).norm());
  }
  EXPECT_EQ(c.map.RestrictVectors(full), s.modes);
}

TEST(SpectraEigensolver, LumpedMassMatchesDense) {
  Problem p = Assemble(HexBox({8, 4, 3}, {0.4, 0.2, 0.15}, Steel()));
  p.M = fem::AssembleSystem(p.mesh, fem::MassMatrixKind::kLumped).mass;
  const testing::DenseEigen dense = SolveDense(p.K, p.M, FreeFreeShift(p));
  EigenOptions options;
  options.num_modes = 10;
  const EigenSolution s = Spectra()->Solve(p.K, p.M, options);
  ExpectContract(p.K, p.M, s);
  ExpectMatchesDense(p.M, s, dense, dense.values(6));
}

TEST(SpectraEigensolver, AllModesOfATinyProblemAreSolvedDensely) {
  const Problem p = Assemble(HexBox({1, 1, 1}, {0.1, 0.1, 0.1}, Steel()));
  EigenOptions options;
  options.num_modes = 24;
  const EigenSolution s = Spectra()->Solve(p.K, p.M, options);
  ASSERT_EQ(s.eigenvalues.size(), 24);
  EXPECT_EQ(s.krylov_runs, 0);
  ExpectContract(p.K, p.M, s);
}

// ---- Bad input -----------------------------------------------------------------------------

std::string SolveError(const SparseMatrix& K, const SparseMatrix& M, const EigenOptions& options) {
  try {
    Spectra()->Solve(K, M, options);
  } catch (const InputError& e) {
    const std::string message = e.what();
    EXPECT_EQ(message.find('\n'), std::string::npos) << "one line";
    return message;
  }
  return "no InputError";
}

TEST(SpectraEigensolver, MoreModesThanDofIsAnInputError) {
  const Problem p = Assemble(HexBox({1, 1, 1}, {0.1, 0.1, 0.1}, Steel()));
  EigenOptions options;
  options.num_modes = 25;
  EXPECT_EQ(SolveError(p.K, p.M, options), "eigenproblem: 25 modes requested but the model has only 24 DOF");
}

TEST(SpectraEigensolver, MismatchedOrNonSquareMatricesAreInputErrors) {
  const Problem p = Assemble(HexBox({1, 1, 1}, {0.1, 0.1, 0.1}, Steel()));
  EigenOptions options;
  options.num_modes = 3;
  const SparseMatrix M23 = p.M.topRows(21);
  EXPECT_NE(SolveError(p.K, M23, options).find("mass matrix M is 21 x 24, must be square"), std::string::npos);
  const SparseMatrix K21 = p.K.topLeftCorner(21, 21);
  EXPECT_NE(SolveError(K21, p.M, options).find("K is 21 x 21 but M is 24 x 24"), std::string::npos);
  EXPECT_NE(SolveError(SparseMatrix(0, 0), SparseMatrix(0, 0), options).find("empty"), std::string::npos);
}

TEST(SpectraEigensolver, NoModeCountOrBandIsAnInputError) {
  const Problem p = Assemble(HexBox({1, 1, 1}, {0.1, 0.1, 0.1}, Steel()));
  EXPECT_NE(SolveError(p.K, p.M, EigenOptions{}).find("neither num_modes nor max_frequency_hz"), std::string::npos);
}

TEST(SpectraEigensolver, BandWithoutModesIsAnInputErrorNamingTheLowestMode) {
  const Cantilever c = MakeCantilever(Steel(), Steel());
  const double lowest_hz = FrequenciesHz(SolveDense(c.K, c.M, 0.0).values)(0);
  for (const MissedModeCheck check : {MissedModeCheck::kSturmCount, MissedModeCheck::kDeflatedLanczos}) {
    EigenOptions options;
    options.max_frequency_hz = 1.0;
    options.check_missed_modes = check;
    const std::string message = SolveError(c.K, c.M, options);
    EXPECT_EQ(message, fmt::format("eigenproblem: no mode below max_frequency_hz = 1 Hz: the lowest mode is at {:g} Hz",
                                   lowest_hz));
  }
}

TEST(SpectraEigensolver, UnconstrainedBodyWithZeroOrPositiveShiftIsAnInputError) {
  const Problem p = Assemble(HexBox({4, 2, 2}, {0.4, 0.2, 0.2}, Steel()));
  EigenOptions options;
  options.num_modes = 8;
  for (const double shift_hz : {0.0, 5.0}) {
    options.shift_hz = shift_hz;
    const std::string message = SolveError(p.K, p.M, options);
    EXPECT_NE(message.find("the body is likely unconstrained"), std::string::npos) << message;
  }
  // A negative shift works, even a small one: the rigid-body residuals, measured against
  // |sigma| ||M phi||, then sit at their (higher) round-off floor.
  options.shift_hz = -1.0;
  const EigenSolution s = Spectra()->Solve(p.K, p.M, options);
  ExpectContract(p.K, p.M, s, /*strict=*/false);
  for (int j = 0; j < 6; ++j) EXPECT_GT(s.residual_floors(j), 1e-9) << j;
}

TEST(SpectraEigensolver, IndefiniteStiffnessOrATooSmallNegativeShiftAreInputErrors) {
  const Problem p = Assemble(HexBox({4, 2, 2}, {0.4, 0.2, 0.2}, Steel()));
  EigenOptions options;
  options.num_modes = 8;
  // A negative shift of round-off size does not make K - sigma M positive definite.
  options.shift_hz = -1e-4;
  EXPECT_NE(SolveError(p.K, p.M, options).find("the negative shift is too close to zero for the rigid-body modes"),
            std::string::npos);
  // K with a negative eigenvalue (a negative diagonal entry).
  SparseMatrix K = p.K;
  K.coeffRef(0, 0) *= -1.0;
  options.shift_hz.reset();
  EXPECT_NE(SolveError(K, p.M, options).find("so it is not positive semi-definite"), std::string::npos);
}

TEST(SpectraEigensolver, ShiftAboveTheLowestModeIsAnInputError) {
  const Cantilever c = MakeCantilever(Steel(), Steel());
  const testing::DenseEigen dense = SolveDense(c.K, c.M, 0.0);
  EigenOptions options;
  options.num_modes = 3;
  options.shift_hz = 2.0 * FrequenciesHz(dense.values)(0);
  EXPECT_NE(SolveError(c.K, c.M, options).find("not positive definite"), std::string::npos);
  // Just below the lowest mode is fine and converges.
  options.shift_hz = 0.9 * FrequenciesHz(dense.values)(0);
  const EigenSolution s = Spectra()->Solve(c.K, c.M, options);
  ExpectMatchesDense(c.M, s, dense, dense.values(0));
}

TEST(SpectraEigensolver, BadOptionsAreInputErrors) {
  const Problem p = Assemble(HexBox({1, 1, 1}, {0.1, 0.1, 0.1}, Steel()));
  EigenOptions options;
  options.num_modes = -1;
  EXPECT_NE(SolveError(p.K, p.M, options).find("num_modes -1 must be >= 0"), std::string::npos);
  options.num_modes = 2;
  options.max_frequency_hz = -5.0;
  EXPECT_NE(SolveError(p.K, p.M, options).find("max_frequency_hz -5"), std::string::npos);
  options.max_frequency_hz = 0.0;
  options.tolerance = 0.0;
  EXPECT_NE(SolveError(p.K, p.M, options).find("tolerance 0 must be in (0, 1)"), std::string::npos);
  options.tolerance = 1e-10;
  options.lanczos_block_size = -2;
  EXPECT_NE(SolveError(p.K, p.M, options).find("lanczos_block_size -2 must be >= 0"), std::string::npos);
}

}  // namespace
}  // namespace flexmbs::eigensolvers
