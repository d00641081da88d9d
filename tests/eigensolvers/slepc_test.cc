// The SLEPc backend agrees with the Spectra backend, through the serial interface and through
// the distributed assembly, on one rank and under `mpiexec -n 2` (both registered with CTest).
#include <gtest/gtest.h>

#include <functional>
#include <petscmat.h>

#include <algorithm>
#include <cstdlib>
#include <string>
#include <thread>

#include "fem/assembly.h"
#include "fem/distributed_assembly.h"
#include "eigensolvers/blas_threads.h"
#include "eigensolvers/distributed/distributed_model.h"
#include "reduction/distributed_reduction.h"
#include "reduction/dof_constraints.h"
#include "eigensolvers/eigensolver.h"
#include "eigensolvers/distributed/slepc_solver.h"
#include "tests/eigensolvers/petsc_log_count.h"
#include "tests/support/eigen_contract.h"
#include "tests/support/test_problems.h"

namespace flexmbs::eigensolvers {
namespace {

using testing::kClusterTolerance;
using testing::LoggedEventCount;

// The agreement bound between the two backends; both reach about 1e-11 alone.
constexpr double kBackendAgreement = 1e-8;

struct Problem {
  fem::Mesh mesh;
  std::vector<int> clamp;  // nodes on x = 0
};

Problem ClampedBox() {
  Problem p{testing::HexBox({8, 3, 2}, {0.4, 0.15, 0.1}, testing::Steel()), {}};
  p.clamp = testing::NodesOnPlane(p.mesh, 0, 0.0);
  return p;
}

// K and M of the problem with its clamped DOF removed.
std::pair<Eigen::SparseMatrix<double>, Eigen::SparseMatrix<double>> ClampedMatrices(const Problem& p) {
  const fem::SystemMatrices system = fem::AssembleSystem(p.mesh, fem::MassMatrixKind::kConsistent);
  const reduction::FreeDofMap free = reduction::FreeDofMap::ClampNodes(p.mesh.num_nodes(), p.clamp);
  return {free.Restrict(system.stiffness), free.Restrict(system.mass)};
}

// Eigenvalues agree to kBackendAgreement relative and each mode spans the same line.
void ExpectSameModes(const EigenSolution& a, const EigenSolution& b,
                     const Eigen::SparseMatrix<double>& M, std::string_view what) {
  ASSERT_EQ(a.eigenvalues.size(), b.eigenvalues.size()) << what;
  for (Eigen::Index j = 0; j < a.eigenvalues.size(); ++j) {
    EXPECT_NEAR(a.eigenvalues(j), b.eigenvalues(j), kBackendAgreement * std::abs(b.eigenvalues(j)))
        << what << " mode " << j;
  }
  EXPECT_LT(testing::LargestPrincipalAngleSine(M, a.modes, b.modes), kBackendAgreement) << what;
}

// The session shares the node's cores among the ranks' BLAS threads (this test's ranks all run
// on one node): one thread each for two ranks on two cores, not two each.
TEST(SlepcSession, RanksOnANodeShareItsCoresForBlas) {
  if (BlasThreads() == 0) GTEST_SKIP() << "the BLAS has no thread control";
  if (std::getenv("OPENBLAS_NUM_THREADS") != nullptr || std::getenv("OMP_NUM_THREADS") != nullptr) {
    GTEST_SKIP() << "the user chose the BLAS threads";
  }
  const int cores = static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
  if (SlepcSession::Size() == 1) {
    EXPECT_GE(BlasThreads(), 1);  // left as the BLAS started
  } else {
    EXPECT_EQ(BlasThreads(), std::max(1, cores / SlepcSession::Size()));
  }
}

TEST(SlepcBackend, AgreesWithSpectraOnAClampedBody) {
  const auto [K, M] = ClampedMatrices(ClampedBox());
  EigenOptions options;
  options.num_modes = 10;
  const EigenSolution slepc = MakeEigensolver("slepc")->Solve(K, M, options);
  const EigenSolution spectra = MakeEigensolver("spectra")->Solve(K, M, options);
  ExpectSameModes(slepc, spectra, M, "clamped");
  EXPECT_LT(slepc.relative_residuals.maxCoeff(), options.residual_tolerance);
  EXPECT_LT(slepc.orthonormality_error, 1e-10);
}

TEST(SlepcBackend, SturmCountAfterTheWantedModesEqualsTheDenseCount) {
  const auto [K, M] = ClampedMatrices(ClampedBox());
  EigenOptions options;
  options.num_modes = 7;
  const EigenSolution slepc = MakeEigensolver("slepc")->Solve(K, M, options);
  EXPECT_EQ(slepc.missed_mode_check, MissedModeCheck::kSturmCount);
  ASSERT_GE(slepc.sturm_count, options.num_modes);
  EXPECT_GT(slepc.sturm_cut, slepc.eigenvalues(options.num_modes - 1));
  // The count from MUMPS' inertia against every eigenvalue of the dense problem (the clamped
  // DOF give infinite eigenvalues there: K = 1, M = 0, excluded by the cut).
  const testing::DenseEigen dense = testing::SolveDense(K, M, 0.0);
  const auto below = (dense.values.array() < slepc.sturm_cut).count();
  EXPECT_EQ(slepc.sturm_count, below);
}

TEST(SlepcBackend, FindsTheSixRigidModesOfAFreeBody) {
  const fem::Mesh mesh = testing::HexBox({4, 3, 2}, {0.2, 0.15, 0.1}, testing::Steel());
  const fem::SystemMatrices system = fem::AssembleSystem(mesh, fem::MassMatrixKind::kConsistent);
  EigenOptions options;
  options.num_modes = 9;
  const EigenSolution slepc = MakeEigensolver("slepc")->Solve(system.stiffness, system.mass, options);
  const EigenSolution spectra = MakeEigensolver("spectra")->Solve(system.stiffness, system.mass, options);
  for (int j = 0; j < 6; ++j) EXPECT_LT(std::abs(slepc.eigenvalues(j)), 1e-8 * slepc.eigenvalues(6));
  // Rigid modes are a six-dimensional subspace; compare it and the elastic modes separately.
  EXPECT_LT(testing::LargestPrincipalAngleSine(system.mass, slepc.modes.leftCols(6),
                                               spectra.modes.leftCols(6)), 1e-6);
  for (int j = 6; j < 9; ++j) {
    EXPECT_NEAR(slepc.eigenvalues(j), spectra.eigenvalues(j), kBackendAgreement * spectra.eigenvalues(j));
  }
}

TEST(SlepcBackend, FrequencyBandEqualsSpectrasBand) {
  const auto [K, M] = ClampedMatrices(ClampedBox());
  EigenOptions options;
  options.max_frequency_hz = 3000.0;
  const EigenSolution slepc = MakeEigensolver("slepc")->Solve(K, M, options);
  const EigenSolution spectra = MakeEigensolver("spectra")->Solve(K, M, options);
  EXPECT_GT(slepc.eigenvalues.size(), 3);
  ExpectSameModes(slepc, spectra, M, "band");
}

// A free body's band holds its six rigid modes at zero. Their residuals are measured against the
// shift's scale (EigenSolution), so they must come from a shift near zero; a band up to 20 kHz
// (35 modes) used to fail here with a rigid-mode residual of 5.9e-6 (SLEPc's spectrum slicing
// ran its Krylov-Schur iteration at the band's upper end; 3 kHz passed, 10 kHz failed with
// 1.7e-7). The modes must be Spectra's: the rigid subspace and the elastic eigenvalues; the
// count at the band's end is the Sturm check.
TEST(SlepcBackend, FrequencyBandOfAFreeBodyHasAccurateRigidModes) {
  const fem::Mesh mesh = testing::HexBox({8, 3, 2}, {0.4, 0.15, 0.1}, testing::Steel());
  const fem::SystemMatrices system = fem::AssembleSystem(mesh, fem::MassMatrixKind::kConsistent);
  EigenOptions options;
  options.max_frequency_hz = 20000.0;
  const EigenSolution slepc = MakeEigensolver("slepc")->Solve(system.stiffness, system.mass, options);
  const EigenSolution spectra = MakeEigensolver("spectra")->Solve(system.stiffness, system.mass, options);
  ASSERT_EQ(slepc.eigenvalues.size(), spectra.eigenvalues.size());
  ASSERT_GT(slepc.eigenvalues.size(), 6);
  EXPECT_EQ(slepc.checked_cut, ShiftFromHz(options.max_frequency_hz));
  EXPECT_EQ(slepc.sturm_count, spectra.eigenvalues.size());
  const PairResiduals residuals{slepc.relative_residuals, slepc.residual_floors};
  EXPECT_TRUE(residuals.Accepted(options.residual_tolerance));
  EXPECT_LT(testing::LargestPrincipalAngleSine(system.mass, slepc.modes.leftCols(6), spectra.modes.leftCols(6)),
            kBackendAgreement);
  for (Eigen::Index j = 6; j < spectra.eigenvalues.size(); ++j) {
    EXPECT_NEAR(slepc.eigenvalues(j), spectra.eigenvalues(j), kBackendAgreement * spectra.eigenvalues(j)) << j;
  }
}

TEST(SlepcBackend, DistributedAssemblyPathEqualsTheSerialSolve) {
  const Problem p = ClampedBox();
  std::vector<int> fixed;
  for (int node : p.clamp) {
    for (int i = 0; i < 3; ++i) fixed.push_back(3 * node + i);
  }
  EigenOptions options;
  options.num_modes = 8;
  fem::DistributedMatrices distributed = fem::AssembleDistributed(p.mesh, fem::MassMatrixKind::kConsistent);
  const EigenSolution slepc =
      SolveDistributedEigenproblem(distributed.stiffness, distributed.mass, fixed, options);
  fem::DestroyDistributed(&distributed);

  const fem::SystemMatrices system = fem::AssembleSystem(p.mesh, fem::MassMatrixKind::kConsistent);
  const reduction::FreeDofMap free = reduction::FreeDofMap::ClampNodes(p.mesh.num_nodes(), p.clamp);
  const EigenSolution spectra = MakeEigensolver("spectra")->Solve(
      free.Restrict(system.stiffness), free.Restrict(system.mass), options);
  EigenSolution spectra_full = spectra;
  spectra_full.modes = free.Expand(spectra.modes);
  ExpectSameModes(slepc, spectra_full, system.mass, "distributed");
  EXPECT_LT(slepc.relative_residuals.maxCoeff(), options.residual_tolerance);
}

// The work SLEPc reports, against PETSc's log of the same solve: numeric factorisations
// (MatCholFctrNum), symbolic analyses (MatCholFctrSym) and solves (MatSolve).
struct LoggedWork {
  int analyses, factorizations, solves;
};
LoggedWork LoggedWorkOf(const Eigen::SparseMatrix<double>& K, const Eigen::SparseMatrix<double>& M,
                        const EigenOptions& options, EigenSolution* solution) {
  const LoggedWork before{LoggedEventCount("MatCholFctrSym"), LoggedEventCount("MatCholFctrNum"),
                          LoggedEventCount("MatSolve")};
  *solution = MakeEigensolver("slepc")->Solve(K, M, options);
  return {LoggedEventCount("MatCholFctrSym") - before.analyses,
          LoggedEventCount("MatCholFctrNum") - before.factorizations, LoggedEventCount("MatSolve") - before.solves};
}

TEST(SlepcBackend, ReportsItsFactorisationsSolvesAndTimesAsPetscLogsThem) {
  const auto [K, M] = ClampedMatrices(ClampedBox());
  EigenOptions options;
  options.num_modes = 10;
  options.distributed_factorization = DistributedFactorization::kMumps;  // MUMPS's events
  EigenSolution s;
  LoggedWorkOf(K, M, options, &s);  // registers the events
  const LoggedWork logged = LoggedWorkOf(K, M, options, &s);
  // One analysis: the Sturm count refactorises K - cut M in the shift-invert's MUMPS instance.
  EXPECT_EQ(logged.analyses, 1);
  EXPECT_EQ(s.factorizations, 2);
  EXPECT_EQ(logged.factorizations, s.factorizations);
  EXPECT_EQ(logged.solves, s.operator_applications);
  // Krylov-Schur's first basis alone is ncv = max(2 nev, nev + 15) solves (SLEPc's default).
  EXPECT_GE(s.operator_applications, 25);
  EXPECT_EQ(s.krylov_runs, 1);
  EXPECT_GE(s.restarts, 1);
  EXPECT_EQ(s.missed_mode_check, MissedModeCheck::kSturmCount);
  EXPECT_EQ(s.sturm_count, options.num_modes);
  for (double part : {s.factorization_seconds, s.krylov_seconds, s.sturm_seconds}) EXPECT_GT(part, 0.0);
  EXPECT_LE(s.factorization_seconds + s.krylov_seconds + s.sturm_seconds, s.seconds);

  // A band: the count at its end first (an analysis and a factorisation of its own), then the
  // shift-invert's; that count is the whole band's Sturm check, so no third factorisation.
  EigenOptions band;
  band.max_frequency_hz = 3000.0;
  band.distributed_factorization = DistributedFactorization::kMumps;
  const LoggedWork banded = LoggedWorkOf(K, M, band, &s);
  EXPECT_EQ(banded.analyses, 2);
  EXPECT_EQ(s.factorizations, 2);
  EXPECT_EQ(banded.factorizations, s.factorizations);
  EXPECT_EQ(banded.solves, s.operator_applications);
  EXPECT_GT(s.operator_applications, 0);
  EXPECT_EQ(s.krylov_runs, 1);
  EXPECT_EQ(s.sturm_cut, ShiftFromHz(band.max_frequency_hz));
  EXPECT_EQ(s.sturm_count, s.eigenvalues.size());
  for (double part : {s.factorization_seconds, s.krylov_seconds, s.sturm_seconds}) EXPECT_GT(part, 0.0);
  EXPECT_LE(s.factorization_seconds + s.krylov_seconds + s.sturm_seconds, s.seconds);
}

// A lumped (diagonal) M has fewer entries than K: K - sigma M is then built on the union
// pattern and moved to the cut on a pattern M's is a subset of. The count is still the dense one.
TEST(SlepcBackend, SturmCountWithALumpedMassEqualsTheDenseCount) {
  const Problem p = ClampedBox();
  const fem::SystemMatrices system = fem::AssembleSystem(p.mesh, fem::MassMatrixKind::kLumped);
  const reduction::FreeDofMap free = reduction::FreeDofMap::ClampNodes(p.mesh.num_nodes(), p.clamp);
  const Eigen::SparseMatrix<double> K = free.Restrict(system.stiffness), M = free.Restrict(system.mass);
  ASSERT_LT(M.nonZeros(), K.nonZeros());
  EigenOptions options;
  options.num_modes = 8;
  const EigenSolution slepc = MakeEigensolver("slepc")->Solve(K, M, options);
  const EigenSolution spectra = MakeEigensolver("spectra")->Solve(K, M, options);
  ExpectSameModes(slepc, spectra, M, "lumped");
  const testing::DenseEigen dense = testing::SolveDense(K, M, 0.0);
  EXPECT_EQ(slepc.sturm_count, (dense.values.array() < slepc.sturm_cut).count());
  EXPECT_EQ(slepc.sturm_count, options.num_modes);
}

// A free cube's spectrum has clusters of 2 and 3 equal eigenvalues. Asking for modes up to the
// end of a cluster and for two of a cluster's three, the count at the cut is the dense count, the
// cut lies above the whole cluster and the eigenvalues are the dense ones.
TEST(SlepcBackend, SturmCountOfACubeWithRepeatedFrequenciesEqualsTheDenseCount) {
  const fem::Mesh mesh = testing::HexBox({5, 5, 5}, {0.1, 0.1, 0.1}, testing::Steel());
  const fem::SystemMatrices system = fem::AssembleSystem(mesh, fem::MassMatrixKind::kConsistent);
  const Eigen::SparseMatrix<double>& K = system.stiffness;
  const Eigen::SparseMatrix<double>& M = system.mass;
  const testing::DenseEigen dense = testing::SolveDense(K, M, FreeBodyShift(K, M));
  const auto same = [&](Eigen::Index a, Eigen::Index b) { return testing::SameCluster(dense, a, b); };
  Eigen::Index end_of_cluster = -1, inside_triple = -1;
  for (Eigen::Index j = 8; j < 40; ++j) {
    if (end_of_cluster < 0 && j > 20 && same(j - 2, j - 1) && !same(j - 1, j)) end_of_cluster = j;
    if (inside_triple < 0 && same(j - 2, j) && same(j - 1, j)) inside_triple = j;  // modes 0 .. j-1 hold two of three
  }
  ASSERT_GT(end_of_cluster, 0);
  ASSERT_GT(inside_triple, 0);
  for (const Eigen::Index wanted : {end_of_cluster, inside_triple}) {
    EigenOptions options;
    options.num_modes = static_cast<int>(wanted);
    const EigenSolution s = MakeEigensolver("slepc")->Solve(K, M, options);
    const std::string what = "cube, " + std::to_string(wanted) + " modes";
    ASSERT_EQ(s.eigenvalues.size(), wanted) << what;
    EXPECT_EQ(s.sturm_count, (dense.values.array() < s.sturm_cut).count()) << what;
    EXPECT_GE(s.sturm_count, wanted) << what;
    Eigen::Index last_of_cluster = wanted - 1;
    while (same(last_of_cluster, last_of_cluster + 1)) ++last_of_cluster;
    EXPECT_GT(s.sturm_cut, dense.values(last_of_cluster)) << what;
    for (Eigen::Index j = 6; j < wanted; ++j) {
      EXPECT_NEAR(s.eigenvalues(j), dense.values(j), kBackendAgreement * dense.values(j)) << what << " mode " << j;
    }
    std::printf("[ numbers  ] %s: %d Krylov-Schur run(s), %d solves, Sturm count %d\n", what.c_str(), s.krylov_runs,
                s.operator_applications, s.sturm_count);
  }
}

// A kept factorisation must solve K itself: its solution of K x = K x_true against x_true, to
// about eps times the condition number of this K (the clamped box; measured 3e-14).
constexpr double kKeptSolveAgreement = 1e-10;

// The DOF of the clamped nodes (zeroed by the solve: K diagonal 1, M diagonal 0).
std::vector<int> ClampedDofs(const Problem& p) {
  std::vector<int> fixed;
  for (int node : p.clamp) {
    for (int i = 0; i < 3; ++i) fixed.push_back(3 * node + i);
  }
  return fixed;
}

// Relative error of the factor's solution of K x = K x_true, x_true random.
double SolveError(Mat K, const std::function<void(Vec, Vec)>& solve) {
  Vec x_true, b, x;
  EXPECT_EQ(MatCreateVecs(K, &x_true, &b), 0);
  EXPECT_EQ(VecDuplicate(x_true, &x), 0);
  EXPECT_EQ(VecSetRandom(x_true, nullptr), 0);
  EXPECT_EQ(MatMult(K, x_true, b), 0);
  solve(b, x);
  PetscReal error = 0.0, norm = 0.0;
  EXPECT_EQ(VecNorm(x_true, NORM_2, &norm), 0);
  EXPECT_EQ(VecAXPY(x, -1.0, x_true), 0);
  EXPECT_EQ(VecNorm(x, NORM_2, &error), 0);
  for (Vec* v : {&x_true, &b, &x}) VecDestroy(v);
  return error / norm;
}

// A held body's lowest modes with the factorisation kept: the shift is 0, K itself is factorised
// once and that factor, handed out, solves K; the Sturm count (a second factorisation, of
// K - cut M) is the dense count; the modes are Spectra's.
TEST(SlepcBackend, KeptFactorisationOfAHeldBodySolvesKAndTheSturmCountIsTheDenseCount) {
  const Problem p = ClampedBox();
  EigenOptions options;
  options.num_modes = 8;
  options.distributed_factorization = DistributedFactorization::kMumps;
  fem::DistributedMatrices distributed = fem::AssembleDistributed(p.mesh, fem::MassMatrixKind::kConsistent);
  const int factorizations_before = LoggedEventCount("MatCholFctrNum");
  Mat K_factor = nullptr;
  const EigenSolution slepc = SolveDistributedEigenproblem(distributed.stiffness, distributed.mass, ClampedDofs(p),
                                                           options, ModesOn::kEveryRank, nullptr, &K_factor);
  ASSERT_NE(K_factor, nullptr);
  EXPECT_EQ(slepc.shift, 0.0);
  EXPECT_EQ(slepc.factorizations, 2);
  EXPECT_EQ(LoggedEventCount("MatCholFctrNum") - factorizations_before, slepc.factorizations);
  EXPECT_EQ(slepc.krylov_runs, 1);
  EXPECT_EQ(slepc.missed_mode_check, MissedModeCheck::kSturmCount);
  const auto [K, M] = ClampedMatrices(p);
  const testing::DenseEigen dense = testing::SolveDense(K, M, 0.0);
  EXPECT_GT(slepc.sturm_cut, slepc.eigenvalues(options.num_modes - 1));
  EXPECT_EQ(slepc.sturm_count, (dense.values.array() < slepc.sturm_cut).count());
  const EigenSolution spectra = MakeEigensolver("spectra")->Solve(K, M, options);
  const reduction::FreeDofMap free = reduction::FreeDofMap::ClampNodes(p.mesh.num_nodes(), p.clamp);
  EigenSolution spectra_full = spectra;
  spectra_full.modes = free.Expand(spectra.modes);
  const fem::SystemMatrices system = fem::AssembleSystem(p.mesh, fem::MassMatrixKind::kConsistent);
  ExpectSameModes(slepc, spectra_full, system.mass, "kept");
  EXPECT_LT(slepc.relative_residuals.maxCoeff(), options.residual_tolerance);

  const double solve_error =
      SolveError(distributed.stiffness, [&](Vec b, Vec x) { EXPECT_EQ(MatSolve(K_factor, b, x), 0); });
  EXPECT_LT(solve_error, kKeptSolveAgreement);
  EXPECT_EQ(LoggedEventCount("MatCholFctrNum") - factorizations_before, slepc.factorizations);  // no new one
  MatDestroy(&K_factor);
  fem::DestroyDistributed(&distributed);
  std::printf("[ numbers  ] kept factor: solve error %.1e, %d solves, Sturm count %d\n", solve_error,
              slepc.operator_applications, slepc.sturm_count);
}

// A cube clamped on its base has pairs of equal frequencies (its symmetry). Asking for 5 modes
// splits the pair at 15.1 kHz, and the kept path's first Krylov-Schur run does not see the
// pair's second mode at all (measured on 1 and 2 ranks; on 1 rank likewise for 11, 14, 15, 17,
// 22 and 27 modes): the Sturm count says so, a second run (K factorised again) finds the pair, and the
// factor kept is the second run's. The modes are the dense ones.
TEST(SlepcBackend, KeptFactorisationSurvivesAMissedModeAndItsSecondRun) {
  const fem::Mesh mesh = testing::HexBox({5, 5, 5}, {0.1, 0.1, 0.1}, testing::Steel());
  const Problem p{mesh, testing::NodesOnPlane(mesh, 2, 0.0)};
  EigenOptions options;
  options.num_modes = 5;
  options.distributed_factorization = DistributedFactorization::kMumps;  // refactorised per run
  fem::DistributedMatrices distributed = fem::AssembleDistributed(p.mesh, fem::MassMatrixKind::kConsistent);
  Mat K_factor = nullptr;
  const EigenSolution slepc = SolveDistributedEigenproblem(distributed.stiffness, distributed.mass, ClampedDofs(p),
                                                           options, ModesOn::kEveryRank, nullptr, &K_factor);
  ASSERT_NE(K_factor, nullptr);
  EXPECT_EQ(slepc.krylov_runs, 2);
  EXPECT_EQ(slepc.factorizations, 4);  // K and K - cut M, twice
  const auto [K, M] = ClampedMatrices(p);
  const testing::DenseEigen dense = testing::SolveDense(K, M, 0.0);
  EXPECT_EQ(slepc.sturm_count, (dense.values.array() < slepc.sturm_cut).count());
  EXPECT_GT(slepc.sturm_count, options.num_modes);  // the cut lies above the whole pair
  ASSERT_EQ(slepc.eigenvalues.size(), options.num_modes);
  for (Eigen::Index j = 0; j < options.num_modes; ++j) {
    EXPECT_NEAR(slepc.eigenvalues(j), dense.values(j), kBackendAgreement * dense.values(j)) << "mode " << j;
  }
  EXPECT_LT(SolveError(distributed.stiffness, [&](Vec b, Vec x) { EXPECT_EQ(MatSolve(K_factor, b, x), 0); }),
            kKeptSolveAgreement);
  MatDestroy(&K_factor);
  fem::DestroyDistributed(&distributed);
}

// The same held body with K factorised by substructuring (any rank count): one factorisation
// for the Krylov-Schur run and the static solves after it, whose factor solves K, and the Sturm
// count's own (fixed DOF: no block check); the modes are the MUMPS path's.
TEST(SlepcBackend, SubstructuredKeptFactorisationGivesTheModesAndSolvesK) {
  const Problem p = ClampedBox();
  EigenOptions options;
  options.num_modes = 8;
  EigenSolution mumps_path;
  for (const auto choice : {DistributedFactorization::kMumps, DistributedFactorization::kSubstructured}) {
    options.distributed_factorization = choice;
    fem::DistributedMatrices distributed = fem::AssembleDistributed(p.mesh, fem::MassMatrixKind::kConsistent);
    Mat K_factor = nullptr;
    std::unique_ptr<SubstructuredFactor> K_substructured;
    const EigenSolution slepc =
        SolveDistributedEigenproblem(distributed.stiffness, distributed.mass, ClampedDofs(p), options,
                                     ModesOn::kEveryRank, nullptr, &K_factor, &K_substructured);
    if (choice == DistributedFactorization::kMumps) {
      ASSERT_NE(K_factor, nullptr);
      MatDestroy(&K_factor);
      mumps_path = slepc;
      fem::DestroyDistributed(&distributed);
      continue;
    }
    EXPECT_EQ(K_factor, nullptr);
    ASSERT_TRUE(K_substructured);
    EXPECT_EQ(slepc.factorization, "substructured");
    EXPECT_EQ(slepc.factorizations, 2);
    EXPECT_EQ(slepc.missed_mode_check, MissedModeCheck::kSturmCount);
    EXPECT_EQ(slepc.sturm_count, mumps_path.sturm_count);
    const fem::SystemMatrices system = fem::AssembleSystem(p.mesh, fem::MassMatrixKind::kConsistent);
    ExpectSameModes(slepc, mumps_path, system.mass, "substructured");
    EXPECT_LT(slepc.relative_residuals.maxCoeff(), options.residual_tolerance);
    EXPECT_LT(SolveError(distributed.stiffness, [&](Vec b, Vec x) { K_substructured->Solve(b, x); }),
              kKeptSolveAgreement);
    K_substructured.reset();
    fem::DestroyDistributed(&distributed);
  }
}

// A free body's K is singular: nothing is kept, and the solve is the usual one (negative shift),
// the attempt at sigma = 0 counted.
TEST(SlepcBackend, AFreeBodyKeepsNoFactorisationAndSolvesWithTheNegativeShift) {
  const fem::Mesh mesh = testing::HexBox({4, 3, 2}, {0.2, 0.15, 0.1}, testing::Steel());
  EigenOptions options;
  options.num_modes = 9;
  fem::DistributedMatrices plain_matrices = fem::AssembleDistributed(mesh, fem::MassMatrixKind::kConsistent);
  const EigenSolution plain = SolveDistributedEigenproblem(plain_matrices.stiffness, plain_matrices.mass, {}, options);
  fem::DestroyDistributed(&plain_matrices);
  fem::DistributedMatrices distributed = fem::AssembleDistributed(mesh, fem::MassMatrixKind::kConsistent);
  Mat K_factor = nullptr;
  const EigenSolution tried = SolveDistributedEigenproblem(distributed.stiffness, distributed.mass, {}, options,
                                                           ModesOn::kEveryRank, nullptr, &K_factor);
  fem::DestroyDistributed(&distributed);
  EXPECT_EQ(K_factor, nullptr);
  EXPECT_EQ(tried.shift, plain.shift);
  EXPECT_LT(tried.shift, 0.0);
  EXPECT_EQ(tried.missed_mode_check, MissedModeCheck::kSturmCount);
  EXPECT_EQ(tried.sturm_count, plain.sturm_count);
  EXPECT_EQ(tried.factorizations, plain.factorizations + 1);
  ASSERT_EQ(tried.eigenvalues.size(), plain.eigenvalues.size());
  for (Eigen::Index j = 6; j < plain.eigenvalues.size(); ++j) {
    EXPECT_NEAR(tried.eigenvalues(j), plain.eigenvalues(j), kBackendAgreement * plain.eigenvalues(j));
  }
}

// The block Krylov check instead of the Sturm count (asked for here; automatic above 1e10 flops
// of the factorisation): on the serial wrapper's path (K - sigma M, sigma < 0) one factorisation
// instead of two, the same modes as Spectra, no count made.
TEST(SlepcBackend, BlockKrylovCheckNeedsNoFactorisationOfItsOwn) {
  const auto [K, M] = ClampedMatrices(ClampedBox());
  EigenOptions options;
  options.num_modes = 10;
  options.check_missed_modes = MissedModeCheck::kBlockKrylov;
  SubstructuredEvents();  // registered before they are counted
  auto logged = [] { return LoggedEventCount("MatCholFctrNum") + LoggedEventCount("SubstrFactor"); };
  const int factorizations_before = logged();
  const EigenSolution slepc = MakeEigensolver("slepc")->Solve(K, M, options);
  EXPECT_EQ(logged() - factorizations_before, 1);
  EXPECT_EQ(slepc.factorizations, 1);
  EXPECT_EQ(slepc.missed_mode_check, MissedModeCheck::kBlockKrylov);
  EXPECT_EQ(slepc.sturm_count, -1);
  EXPECT_EQ(slepc.krylov_runs, 2);  // Krylov-Schur and the check
  EXPECT_GT(slepc.checked_cut, slepc.eigenvalues(options.num_modes - 1));
  const EigenSolution spectra = MakeEigensolver("spectra")->Solve(K, M, options);
  ExpectSameModes(slepc, spectra, M, "block-checked");
  EXPECT_LT(slepc.relative_residuals.maxCoeff(), options.residual_tolerance);
}

// The distributed path of a held body (K_oo, M_oo without the clamped rows, K_oo factorised at
// sigma = 0 and kept) with the block check: on the cube whose first run can miss the second mode
// of a pair (see KeptFactorisationSurvivesAMissedModeAndItsSecondRun), the check finds it, the
// second run takes it in, and the modes are the dense ones, with one factorisation per run.
TEST(SlepcBackend, BlockKrylovCheckOnTheKeptPathFindsAMissedPairMode) {
  const fem::Mesh mesh = testing::HexBox({5, 5, 5}, {0.1, 0.1, 0.1}, testing::Steel());
  const Problem p{mesh, testing::NodesOnPlane(mesh, 2, 0.0)};
  const bool root = SlepcSession::Rank() == 0;
  const fem::Mesh empty;
  const std::vector<int> clamped = ClampedDofs(p);
  for (const int modes : {5, 11}) {
    EigenOptions options;
    options.num_modes = modes;
    options.check_missed_modes = MissedModeCheck::kBlockKrylov;
    reduction::DistributedSolveStats stats;
    std::unique_ptr<DistributedModel> model;
    const EigenSolution slepc = reduction::SolveModesDistributed(root ? mesh : empty, fem::MassMatrixKind::kConsistent,
                                                      root ? clamped : std::vector<int>{}, options, &stats, &model);
    ASSERT_TRUE(model);
    if (!root) {
      model->Serve();
      continue;
    }
    model->Finish();
    EXPECT_EQ(slepc.shift, 0.0);
    EXPECT_EQ(slepc.missed_mode_check, MissedModeCheck::kBlockKrylov);
    EXPECT_EQ(slepc.sturm_count, -1);
    // One Krylov-Schur run and one check, or, after a miss, two of each; K factorised per run
    // by MUMPS, once by substructuring.
    EXPECT_TRUE(slepc.krylov_runs == 2 || slepc.krylov_runs == 4) << slepc.krylov_runs;
    EXPECT_EQ(slepc.factorizations, slepc.factorization == "substructured" ? 1 : slepc.krylov_runs / 2);
    const auto [K, M] = ClampedMatrices(p);
    const testing::DenseEigen dense = testing::SolveDense(K, M, 0.0);
    ASSERT_EQ(slepc.eigenvalues.size(), modes);
    for (Eigen::Index j = 0; j < modes; ++j) {
      EXPECT_NEAR(slepc.eigenvalues(j), dense.values(j), kBackendAgreement * dense.values(j)) << "mode " << j;
    }
    // The checked cut lies above the last wanted mode's whole cluster (the pair's second mode).
    Eigen::Index last_of_cluster = modes - 1;
    while (dense.values(last_of_cluster + 1) - dense.values(last_of_cluster) < kClusterTolerance * dense.values(last_of_cluster)) {
      ++last_of_cluster;
    }
    EXPECT_GT(last_of_cluster, modes - 1);  // these counts split a pair
    EXPECT_GT(slepc.checked_cut, dense.values(last_of_cluster));
    std::printf("[ numbers  ] %d modes: %d Krylov-Schur runs and checks, %d solves\n", modes, slepc.krylov_runs,
                slepc.operator_applications);
  }
}

}  // namespace
}  // namespace flexmbs::eigensolvers
