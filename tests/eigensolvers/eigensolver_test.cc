// The Spectra eigensolver's contract (eigensolvers/eigensolver.h) on small FE problems: pairs
// against dense solves and K, M (clamped, free-free, repeated and clustered eigenvalues, bands,
// stiffness ratios, lumped mass), each missed-mode check, factorisations reused. Bad input:
// eigensolver_input_errors_test.cc.
#include "eigensolvers/eigensolver.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <numbers>
#include <string>
#include <vector>

#include "core/error.h"
#include "fem/assembly.h"
#include "fem/mass_properties.h"
#include "reduction/dof_constraints.h"
#include "eigensolvers/shifted_factorization.h"
#include "tests/eigensolvers/spectra_test_support.h"
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
using spectra_test::Assemble;
using spectra_test::Cantilever;
using spectra_test::ExpectContract;
using spectra_test::ExpectMatchesDense;
using spectra_test::FreeFreeShift;
using spectra_test::kSubspaceAgreement;
using spectra_test::MakeCantilever;
using spectra_test::Problem;
using spectra_test::Report;
using spectra_test::Spectra;

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

}  // namespace
}  // namespace flexmbs::eigensolvers
