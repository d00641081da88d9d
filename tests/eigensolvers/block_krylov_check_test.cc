#include "eigensolvers/block_krylov_check.h"

#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <random>
#include <vector>

#include "fem/assembly.h"
#include "eigensolvers/serial/block_lanczos_run.h"
#include "reduction/dof_constraints.h"
#include "eigensolvers/eigensolver.h"
#include "eigensolvers/mass_operator.h"
#include "eigensolvers/shifted_factorization.h"
#include "tests/support/eigen_contract.h"
#include "tests/support/test_problems.h"
#include "tests/input_error.h"

namespace flexmbs::eigensolvers {
namespace {

using testing::HexBox;
using testing::kOrthonormalityBound;
using testing::kResidualBound;
using testing::LargestPrincipalAngleSine;
using testing::NodesOnPlane;
using testing::SolveDense;
using testing::Steel;
using SparseMatrix = Eigen::SparseMatrix<double>;
using Index = Eigen::Index;

// The check's default target (BlockCheckOptions::failure_probability).
constexpr double kTarget = 1e-15;
// The hidden-component bound is an identity up to round-off (block Lanczos relation with full
// reorthogonalisation): it may fall below the true component by this much, relative.
constexpr double kBoundRoundOff = 1e-8;
// A missed pair is returned converged to the eigensolver's tolerance (1e-10 on the shift-inverted
// residual); its eigenvalue then agrees with the dense one to that order or better, and its
// vector (gap to the rest >= 1e-2 relative here) to residual / gap.
constexpr double kMissedValueAgreement = 1e-9;
constexpr double kMissedVectorAgreement = 1e-6;
// What two M-orthogonalisation passes leave of the found modes in the start block (round-off,
// relative to the block's entries).
constexpr double kDeflated = 1e-12;
// Converged pairs of the same problem found by the two checks: both pass the residual bound
// 1e-8 (eigenvalue error ~ residual^2 relative); measured difference 0.
constexpr double kSamePairs = 1e-12;
// The 5-fold test's eigenvalues (1, 2, 3) are exact in double precision; the solver's tolerance
// gives them to residual^2.
constexpr double kExactEigenvalue = 1e-12;

struct Problem {
  SparseMatrix K;
  SparseMatrix M;
  testing::DenseEigen dense;
  ShiftedFactorization factor;
};

// A steel cantilever 0.6 m x 0.05 m x 0.04 m, 12 x 3 x 3 hex8, clamped at x = 0, consistent mass
// (distinct eigenvalues); the factor at sigma = 0.
Problem Cantilever() {
  const fem::Mesh mesh = HexBox({12, 3, 3}, {0.6, 0.05, 0.04}, Steel());
  fem::SystemMatrices system = fem::AssembleSystem(mesh, fem::MassMatrixKind::kConsistent);
  const reduction::FreeDofMap map = reduction::FreeDofMap::ClampNodes(mesh.num_nodes(), NodesOnPlane(mesh, 0, 0.0));
  Problem p{map.Restrict(system.stiffness), map.Restrict(system.mass), {}, {}};
  p.dense = SolveDense(p.K, p.M, 0.0);
  EXPECT_EQ(p.factor.Factorize(p.K, p.M, 0.0, ShiftedFactorization::Method::kSupernodalCholesky),
            ShiftedFactorization::Status::kOk);
  return p;
}

// A free steel cube 0.1 m, 5 x 5 x 5 hex8: cubic symmetry gives clusters of 2 and 3 equal
// eigenvalues; the factor at the free-body shift.
Problem Cube() {
  const fem::Mesh mesh = HexBox({5, 5, 5}, {0.1, 0.1, 0.1}, Steel());
  fem::SystemMatrices system = fem::AssembleSystem(mesh, fem::MassMatrixKind::kConsistent);
  Problem p{std::move(system.stiffness), std::move(system.mass), {}, {}};
  const double sigma = FreeBodyShift(p.K, p.M);
  p.dense = SolveDense(p.K, p.M, sigma);
  EXPECT_EQ(p.factor.Factorize(p.K, p.M, sigma, ShiftedFactorization::Method::kSupernodalCholesky),
            ShiftedFactorization::Status::kOk);
  return p;
}

// The dense modes 0 .. count-1 without those in `left_out`.
Eigen::MatrixXd Found(const Problem& p, Index count, const std::vector<Index>& left_out) {
  std::vector<Index> keep;
  for (Index j = 0; j < count; ++j) {
    if (std::find(left_out.begin(), left_out.end(), j) == left_out.end()) keep.push_back(j);
  }
  Eigen::MatrixXd found(p.K.rows(), static_cast<Index>(keep.size()));
  for (std::size_t j = 0; j < keep.size(); ++j) found.col(static_cast<Index>(j)) = p.dense.vectors.col(keep[j]);
  return found;
}

Eigen::MatrixXd GaussianBlock(Index rows, Index cols, unsigned seed) {
  std::mt19937_64 rng(seed);
  std::normal_distribution<double> normal;
  Eigen::MatrixXd block(rows, cols);
  for (Index i = 0; i < block.size(); ++i) block.data()[i] = normal(rng);
  return block;
}

// Paige's identity, independently: every dense eigenvector u outside the found set (these are
// eigenvectors of the deflated operator) has ||u^T M start|| <= HiddenComponentBound(mu_u) at
// every step, and the bound is not loose by orders of magnitude for the modes nearest the top.
TEST(DeflatedBlockLanczos, HiddenComponentBoundHoldsForEveryEigenvectorOutsideTheFoundSet) {
  const Problem p = Cantilever();
  const Eigen::MatrixXd found = Found(p, 12, {});
  const MassOperator mass(p.M);
  const FactorizationSpace space(p.factor, mass);
  DeflatedBlockLanczos lanczos(space, found, GaussianBlock(p.K.rows(), 4, 7));
  ASSERT_EQ(lanczos.start().cols(), 4);
  EXPECT_LE((found.transpose() * (p.M * lanczos.start())).cwiseAbs().maxCoeff(),
            kDeflated * lanczos.start().cwiseAbs().maxCoeff());
  double tightest = 0.0;  // largest ratio component / bound over the modes nearest the top
  for (int step = 1; step <= 5; ++step) {
    ASSERT_TRUE(lanczos.Extend());
    EXPECT_EQ(lanczos.steps(), step);
    EXPECT_EQ(lanczos.columns_solved(), 4 * step);
    for (Index j = 12; j < 60; ++j) {
      const double mu = 1.0 / p.dense.values(j);
      const double component = (p.dense.vectors.col(j).transpose() * (p.M * lanczos.start())).norm();
      const double bound = lanczos.HiddenComponentBound(mu);
      EXPECT_LE(component, bound * (1.0 + kBoundRoundOff)) << "mode " << j << ", step " << step;
      if (j < 16) tightest = std::max(tightest, component / bound);
    }
  }
  std::printf("[ numbers  ] component / bound, modes 12..15, best over 5 steps: %.2e\n", tightest);
  EXPECT_GT(tightest, 1e-3);  // measured 0.87: the bound is not vacuous
}

// The Ritz values are those of T = (K - sigma M)^-1 M on the complement: each within its residual
// of a dense eigenvalue outside the found set (Kato's bound for the M-self-adjoint T).
TEST(DeflatedBlockLanczos, RitzValuesLieWithinTheirResidualsOfUnfoundEigenvalues) {
  const Problem p = Cantilever();
  const Eigen::MatrixXd found = Found(p, 12, {});
  const MassOperator mass(p.M);
  const FactorizationSpace space(p.factor, mass);
  DeflatedBlockLanczos lanczos(space, found, GaussianBlock(p.K.rows(), 4, 11));
  for (int step = 0; step < 4; ++step) ASSERT_TRUE(lanczos.Extend());
  const Eigen::VectorXd residuals = lanczos.RitzResiduals();
  const Eigen::ArrayXd unfound_mu = p.dense.values.tail(p.dense.values.size() - 12).array().inverse();
  for (Index j = 0; j < lanczos.dimension(); ++j) {
    const double theta = lanczos.ritz_values()(j);
    const double distance = (unfound_mu - theta).abs().minCoeff();
    EXPECT_LE(distance, residuals(j) * (1.0 + kBoundRoundOff) + kDeflated * theta) << "Ritz value " << j;
  }
  // The lowest Ritz value approaches the lowest unfound eigenvalue from below (interlacing).
  const double lowest_error = (unfound_mu(0) - lanczos.ritz_values()(0)) / unfound_mu(0);
  std::printf("[ numbers  ] lowest Ritz value after 4 steps: relative error %.1e\n", lowest_error);
  EXPECT_GE(lowest_error, -kDeflated);
  EXPECT_LE(lowest_error, 1e-2);  // measured 9.8e-4: converging
}

TEST(ScaledMassFloorEstimate, IsBelowTheSmallestEigenvalueOfTheScaledMassAndHalfOfItForALumpedMass) {
  const fem::Mesh mesh = HexBox({4, 3, 3}, {0.2, 0.1, 0.1}, Steel());
  const SparseMatrix M = fem::AssembleSystem(mesh, fem::MassMatrixKind::kConsistent).mass;
  const Eigen::VectorXd inverse_root = M.diagonal().cwiseSqrt().cwiseInverse();
  const Eigen::MatrixXd S = inverse_root.asDiagonal() * Eigen::MatrixXd(M) * inverse_root.asDiagonal();
  const double lowest = Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>(S, Eigen::EigenvaluesOnly).eigenvalues()(0);
  const double estimate = ScaledMassFloorEstimate(M, 20, 3);
  std::printf("[ numbers  ] hex8 consistent mass: lambda_min(D^-1/2 M D^-1/2) = %.4f, estimate %.4f\n", lowest,
              estimate);
  EXPECT_LE(estimate, lowest);         // conservative
  EXPECT_GE(estimate, 0.5 * lowest);   // the Ritz value is an upper bound, halved
  const SparseMatrix lumped = fem::AssembleSystem(mesh, fem::MassMatrixKind::kLumped).mass;
  EXPECT_NEAR(ScaledMassFloorEstimate(lumped, 20, 3), 0.5, kDeflated);  // S = I: exact up to round-off
}

TEST(CheckForMissedModes, CertifiesACompleteFoundSetToTheTargetProbability) {
  const Problem p = Cantilever();
  const Eigen::MatrixXd found = Found(p, 15, {});
  const double cut = 0.5 * (p.dense.values(11) + p.dense.values(12));
  BlockCheckOptions options;
  const BlockCheckResult r = CheckForMissedModes(p.factor, p.M, found, cut, options);
  std::printf("[ numbers  ] complete set: %d block solves, %td columns, bound %.2e, scale %.3f, P <= %.1e\n",
              r.steps, r.columns, r.hidden_component_bound, r.component_scale, r.failure_probability);
  EXPECT_EQ(r.verdict, BlockCheckVerdict::kNoneMissed);
  EXPECT_LE(r.failure_probability, kTarget);
  EXPECT_EQ(r.columns, 8 * r.steps);
  // One step is not enough to certify: undecided (the eigensolver then runs the Lanczos check).
  BlockCheckOptions one_step;
  one_step.max_steps = 1;
  const BlockCheckResult early = CheckForMissedModes(p.factor, p.M, found, cut, one_step);
  EXPECT_EQ(early.verdict, BlockCheckVerdict::kUndecided);
  EXPECT_EQ(early.steps, 1);
  EXPECT_GT(early.failure_probability, kTarget);
  // The component scale is conservative for every mode below the cut: s <= ||D^-1/2 M u||.
  const Eigen::VectorXd inverse_root = p.M.diagonal().cwiseSqrt().cwiseInverse();
  for (Index j = 0; j < 12; ++j) {
    EXPECT_LE(r.component_scale, (inverse_root.asDiagonal() * (p.M * p.dense.vectors.col(j))).norm()) << j;
  }
}

TEST(CheckForMissedModes, FindsAModeLeftOutOfTheFoundSet) {
  const Problem p = Cantilever();
  for (const Index left_out : {Index{0}, Index{6}, Index{11}}) {
    const double cut = 0.5 * (p.dense.values(11) + p.dense.values(12));
    const BlockCheckResult r = CheckForMissedModes(p.factor, p.M, Found(p, 15, {left_out}), cut, BlockCheckOptions{});
    std::printf("[ numbers  ] mode %td left out: %d block solves, %td columns\n", left_out, r.steps, r.columns);
    ASSERT_EQ(r.verdict, BlockCheckVerdict::kMissed) << "mode " << left_out;
    ASSERT_EQ(r.missed_values.size(), 1);
    EXPECT_NEAR(r.missed_values(0), p.dense.values(left_out), kMissedValueAgreement * p.dense.values(left_out));
    EXPECT_LE(LargestPrincipalAngleSine(p.M, r.missed_vectors, p.dense.vectors.col(left_out)),
              kMissedVectorAgreement);
  }
}

TEST(CheckForMissedModes, FindsBothMissingCopiesOfATripleEigenvalueInOnePass) {
  const Problem p = Cube();
  // The first triple cluster among the elastic modes.
  const auto same = [&](Index a, Index b) { return testing::SameCluster(p.dense, a, b); };
  Index first = -1;
  for (Index j = 6; j + 2 < 40 && first < 0; ++j) {
    if (same(j, j + 1) && same(j, j + 2) && !same(j - 1, j)) first = j;
  }
  ASSERT_GT(first, 0);
  const Index end = first + 3;
  ASSERT_FALSE(same(end - 1, end));
  const double cut = 0.5 * (p.dense.values(end - 1) + p.dense.values(end));
  // Found: one copy of the three (a single start vector sees one direction of the eigenspace).
  const BlockCheckResult r =
      CheckForMissedModes(p.factor, p.M, Found(p, end + 4, {first + 1, first + 2}), cut, BlockCheckOptions{});
  std::printf("[ numbers  ] triple at mode %td, two copies left out: %d block solves, %td columns\n", first, r.steps,
              r.columns);
  ASSERT_EQ(r.verdict, BlockCheckVerdict::kMissed);
  ASSERT_EQ(r.missed_values.size(), 2);
  for (Index j = 0; j < 2; ++j) {
    EXPECT_NEAR(r.missed_values(j), p.dense.values(first), kMissedValueAgreement * p.dense.values(first));
  }
  // Together with the found copy they span the dense eigenspace.
  Eigen::MatrixXd cluster(p.K.rows(), 3);
  cluster << p.dense.vectors.col(first), r.missed_vectors;
  EXPECT_LE(LargestPrincipalAngleSine(p.M, cluster, p.dense.vectors.middleCols(first, 3)), kMissedVectorAgreement);
}

TEST(CheckForMissedModes, NothingOutsideTheFoundSetIsCertainAtOnce) {
  const SparseMatrix K = (Eigen::VectorXd::LinSpaced(6, 1.0, 6.0)).asDiagonal().toDenseMatrix().sparseView();
  const SparseMatrix M = Eigen::VectorXd::Ones(6).asDiagonal().toDenseMatrix().sparseView();
  ShiftedFactorization factor;
  ASSERT_EQ(factor.Factorize(K, M, 0.0, ShiftedFactorization::Method::kSupernodalCholesky),
            ShiftedFactorization::Status::kOk);
  const BlockCheckResult r = CheckForMissedModes(factor, M, Eigen::MatrixXd::Identity(6, 6), 3.5, BlockCheckOptions{});
  EXPECT_EQ(r.verdict, BlockCheckVerdict::kNoneMissed);
  EXPECT_EQ(r.failure_probability, 0.0);
  EXPECT_EQ(r.columns, 0);
}

// Through the eigensolver: K = diag(1, 1, 1, 1, 1, 2, 3, ...), M = I. The first Lanczos run alone
// misses a copy of the 5-fold eigenvalue (checked); the block check finds it, with fewer solves
// and far fewer passes over the factor than the Lanczos check.
TEST(SpectraWithBlockKrylovCheck, FindsTheCopyOfAFiveFoldEigenvalueThatTheFirstRunMissed) {
  const auto [K, M] = testing::FiveFoldLowestEigenvalue(200);
  const auto solver = MakeEigensolver("spectra");
  EigenOptions options;
  options.num_modes = 7;
  options.shift_hz = 0.0;
  options.check_missed_modes = MissedModeCheck::kNone;
  const EigenSolution unchecked = solver->Solve(K, M, options);
  ASSERT_EQ(unchecked.krylov_runs, 1);
  ASSERT_GT(std::abs(unchecked.eigenvalues(4) - 1.0), 0.5) << "the first run should miss a copy";
  options.check_missed_modes = MissedModeCheck::kBlockKrylov;
  const EigenSolution block = solver->Solve(K, M, options);
  options.check_missed_modes = MissedModeCheck::kDeflatedLanczos;
  const EigenSolution lanczos = solver->Solve(K, M, options);
  const int block_columns = block.operator_applications - unchecked.operator_applications;
  const int lanczos_solves = lanczos.operator_applications - unchecked.operator_applications;
  std::printf("[ numbers  ] 5-fold eigenvalue: checks after the first run: block %d columns (%d passes), "
              "Lanczos %d solves\n", block_columns, (block_columns + 7) / 8, lanczos_solves);
  EXPECT_EQ(block.missed_mode_check, MissedModeCheck::kBlockKrylov);
  ASSERT_EQ(block.eigenvalues.size(), 7);
  for (int j = 0; j < 5; ++j) EXPECT_NEAR(block.eigenvalues(j), 1.0, kExactEigenvalue);
  EXPECT_NEAR(block.eigenvalues(5), 2.0, kExactEigenvalue);
  EXPECT_NEAR(block.eigenvalues(6), 3.0, kExactEigenvalue);
  EXPECT_LE(block.relative_residuals.maxCoeff(), kResidualBound);
  EXPECT_LE(MOrthonormalityError(M, block.modes), kOrthonormalityBound);
  EXPECT_LT(block_columns, lanczos_solves);
  EXPECT_LT((block_columns + 7) / 8, lanczos_solves / 4);
}

// Through the eigensolver on a realistic spectrum: the same pairs as with the Lanczos check,
// found with fewer passes over the factor (each block solve is one pass for 8 columns).
TEST(SpectraWithBlockKrylovCheck, CantileverGivesTheLanczosChecksPairsWithFewerPassesOverTheFactor) {
  const Problem p = Cantilever();
  const auto solver = MakeEigensolver("spectra");
  EigenOptions options;
  options.num_modes = 12;
  options.check_missed_modes = MissedModeCheck::kNone;
  const EigenSolution unchecked = solver->SolveFactorized(p.K, p.M, options, p.factor);
  options.check_missed_modes = MissedModeCheck::kBlockKrylov;
  const EigenSolution block = solver->SolveFactorized(p.K, p.M, options, p.factor);
  options.check_missed_modes = MissedModeCheck::kDeflatedLanczos;
  const EigenSolution lanczos = solver->SolveFactorized(p.K, p.M, options, p.factor);
  // Every solve of the Lanczos check is a pass over the factor; the block check makes one per 8.
  const int lanczos_passes = lanczos.operator_applications - unchecked.operator_applications;
  const int block_columns = block.operator_applications - unchecked.operator_applications;
  const int block_passes = (block_columns + 7) / 8;
  std::printf("[ numbers  ] cantilever, 12 modes: check solves: Lanczos %d (%d passes), block %d columns (%d passes)\n",
              lanczos_passes, lanczos_passes, block_columns, block_passes);
  EXPECT_EQ(block.missed_mode_check, MissedModeCheck::kBlockKrylov);
  EXPECT_EQ(block.krylov_runs, 2);
  EXPECT_LT(block_passes, lanczos_passes);
  ASSERT_EQ(block.eigenvalues.size(), 12);
  const double difference = (block.eigenvalues - lanczos.eigenvalues).cwiseAbs().maxCoeff() / lanczos.eigenvalues(11);
  std::printf("[ numbers  ] largest eigenvalue difference between the checks: %.1e\n", difference);
  EXPECT_LE(difference, kSamePairs);
  EXPECT_LE(block.relative_residuals.maxCoeff(), kResidualBound);
  EXPECT_LE(block.orthonormality_error, kOrthonormalityBound);
}

// The Rayleigh quotients v^T K v of M-orthonormal columns, ascending.
Eigen::VectorXd RayleighQuotients(const Problem& p, const Eigen::MatrixXd& V) {
  Eigen::VectorXd values = (V.transpose() * (p.K * V)).diagonal();
  std::sort(values.begin(), values.end());
  return values;
}

// Six pairs above three found ones: the dense modes 3 .. 8, M-orthonormal and M-orthogonal to
// the found ones, each converged to the eigensolver's tolerance.
TEST(RunBlockLanczos, FindsTheLowestPairsOutsideTheFoundModes) {
  const Problem p = Cantilever();
  const Eigen::MatrixXd found = Found(p, 3, {});
  const MassOperator mass(p.M);
  BlockRunOptions options;
  options.block_size = 4;
  options.max_dimension = 200;
  options.seed = 11;
  const BlockRunResult run = RunBlockLanczos(FactorizationSpace(p.factor, mass), found, 6, options);
  ASSERT_EQ(run.vectors.cols(), 6);
  EXPECT_EQ(run.columns, 4 * run.steps);
  std::printf("[ numbers  ] cantilever, 6 pairs above 3 found, blocks of 4: %d steps\n", run.steps);
  const Eigen::MatrixXd G = run.vectors.transpose() * (p.M * run.vectors);
  EXPECT_LE((G - Eigen::MatrixXd::Identity(6, 6)).cwiseAbs().maxCoeff(), kOrthonormalityBound);
  EXPECT_LE((found.transpose() * (p.M * run.vectors)).cwiseAbs().maxCoeff(), kDeflated);
  const Eigen::VectorXd values = RayleighQuotients(p, run.vectors);
  for (Index j = 0; j < 6; ++j) {
    EXPECT_NEAR(values(j), p.dense.values(3 + j), kMissedValueAgreement * p.dense.values(3 + j)) << "pair " << j;
  }
  EXPECT_LE(LargestPrincipalAngleSine(p.M, run.vectors, p.dense.vectors.middleCols(3, 6)), kMissedVectorAgreement);
}

// The free cube's elastic clusters of 2, 3, 3 and 2 equal eigenvalues above its six rigid-body
// modes (given as found): one run sees every copy, eigenvalues and eigenspaces are the dense ones.
// (With the rigid-body modes in the run itself, at the free-body shift, the elastic pairs stop
// at ~1e-7 relative residual: the solves' round-off along the rigid directions, amplified by
// 1 / |sigma|, sets a floor that the eigensolver's Rayleigh-Ritz and refinement step remove,
// after Spectra's single-vector runs as after block runs: one refinement step for both.)
TEST(RunBlockLanczos, FindsEveryCopyOfTheCubesRepeatedEigenvalues) {
  const Problem p = Cube();
  const MassOperator mass(p.M);
  constexpr Index kRigid = 6;
  constexpr Index kPairs = 10;
  BlockRunOptions options;
  options.max_dimension = 200;
  options.seed = 5;
  const BlockRunResult run = RunBlockLanczos(FactorizationSpace(p.factor, mass), Found(p, kRigid, {}), kPairs, options);
  ASSERT_EQ(run.vectors.cols(), kPairs);
  const Eigen::VectorXd values = RayleighQuotients(p, run.vectors);
  for (Index j = 0; j < kPairs; ++j) {
    EXPECT_NEAR(values(j), p.dense.values(kRigid + j), kMissedValueAgreement * p.dense.values(kRigid + j))
        << "pair " << j;
  }
  EXPECT_LE(LargestPrincipalAngleSine(p.M, run.vectors, p.dense.vectors.middleCols(kRigid, kPairs)),
            kMissedVectorAgreement);
}

// At its dimension limit the run stops and returns only the pairs converged by then.
TEST(RunBlockLanczos, StopsAtItsDimensionWithThePairsConvergedByThen) {
  const Problem p = Cantilever();
  const MassOperator mass(p.M);
  BlockRunOptions options;
  options.block_size = 4;
  options.max_dimension = 8;
  const BlockRunResult run =
      RunBlockLanczos(FactorizationSpace(p.factor, mass), Eigen::MatrixXd(p.K.rows(), 0), 6, options);
  EXPECT_EQ(run.steps, 2);
  EXPECT_EQ(run.columns, 8);
  EXPECT_LT(run.vectors.cols(), 6);
  const Eigen::VectorXd values = RayleighQuotients(p, run.vectors);
  for (Index j = 0; j < values.size(); ++j) {
    EXPECT_NEAR(values(j), p.dense.values(j), kMissedValueAgreement * p.dense.values(j)) << "pair " << j;
  }
  std::printf("[ numbers  ] cantilever, 2 blocks of 4: %td of 6 pairs converged\n", run.vectors.cols());
}

// 150 modes of a slender cantilever (30 x 3 x 3 hex8, 1 440 free DOF) through the solver with
// blocks of 4: the block run stops at its 400 Krylov vectors with part of the 180 pairs sought,
// and a deflated run finds the rest (its pairs deep in the spectrum converge only to the
// round-off of applying T; Rayleigh-Ritz and refinement finish them).
TEST(SpectraWithBlockLanczos, RunsBeyondTheirDimensionLimitContinueDeflated) {
  const fem::Mesh mesh = HexBox({30, 3, 3}, {1.5, 0.05, 0.04}, Steel());
  const fem::SystemMatrices system = fem::AssembleSystem(mesh, fem::MassMatrixKind::kConsistent);
  const reduction::FreeDofMap map = reduction::FreeDofMap::ClampNodes(mesh.num_nodes(), NodesOnPlane(mesh, 0, 0.0));
  const SparseMatrix K = map.Restrict(system.stiffness);
  const SparseMatrix M = map.Restrict(system.mass);
  EigenOptions options;
  options.num_modes = 150;
  options.lanczos_block_size = 4;
  const EigenSolution s = MakeEigensolver("spectra")->Solve(K, M, options);
  ASSERT_EQ(s.eigenvalues.size(), 150);
  EXPECT_EQ(s.lanczos_block_size, 4);
  EXPECT_GE(s.krylov_runs, 2);  // the first block run and at least one deflated one
  // The contract (a slender beam: round-off floors above 1e-8 for some pairs).
  EXPECT_TRUE((PairResiduals{s.relative_residuals, s.residual_floors}.Accepted(kResidualBound)));
  EXPECT_LE(s.orthonormality_error, kOrthonormalityBound);
  const testing::DenseEigen dense = SolveDense(K, M, 0.0);
  const double deviation =
      ((s.eigenvalues - dense.values.head(150)).array() / dense.values.head(150).array()).abs().maxCoeff();
  std::printf("[ numbers  ] slender cantilever, 150 modes, blocks of 4: %d Krylov runs, %d refinements, "
              "eigenvalues within %.1e of dense\n",
              s.krylov_runs, s.refinement_steps, deviation);
  EXPECT_LE(deviation, kResidualBound);
}

// K = diag(1 + j / n), M = I, n = 1000: eigenvalues 1e-3 apart across [1, 2], where 200 Krylov
// vectors (50 blocks of 4) bring no pair near convergence (Chebyshev: the lowest Ritz value's
// error falls like exp(-2 k sqrt(gap)) = exp(-2.2) after k = 50 steps): a one-line error.
TEST(SpectraWithBlockLanczos, ARunWithoutConvergedPairIsAnInputError) {
  constexpr int kSize = 1000;
  SparseMatrix K(kSize, kSize);
  SparseMatrix M(kSize, kSize);
  for (int j = 0; j < kSize; ++j) {
    K.insert(j, j) = 1.0 + static_cast<double>(j) / kSize;
    M.insert(j, j) = 1.0;
  }
  EigenOptions options;
  options.num_modes = 3;
  options.shift_hz = 0.0;
  options.lanczos_block_size = 4;
  EXPECT_EQ(flexmbs::testing::InputErrorMessage([&] { MakeEigensolver("spectra")->Solve(K, M, options); }),
            "eigenproblem: block Lanczos converged no pair within 200 Krylov vectors (tolerance 1e-10); raise "
            "tolerance or set lanczos_block_size 1");
}

}  // namespace
}  // namespace flexmbs::eigensolvers
