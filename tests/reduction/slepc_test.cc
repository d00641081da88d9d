// The SLEPc backend agrees with the Spectra backend, through the serial interface and through
// the distributed assembly, on one rank and under `mpiexec -n 2` (both registered with CTest).
#include <gtest/gtest.h>
#include <petsclog.h>

#include <string>

#include "fem/assembly.h"
#include "fem/distributed_assembly.h"
#include "reduction/dof_constraints.h"
#include "reduction/eigensolver.h"
#include "reduction/slepc_solver.h"
#include "tests/reduction/test_problems.h"

namespace flexmbs::reduction {
namespace {

// The agreement bound between the two backends; both reach about 1e-11 alone.
constexpr double kBackendAgreement = 1e-8;
// Eigenvalues within this (relative) are one repeated eigenvalue: the structured cube is exactly
// symmetric, so its repeated eigenvalues split by round-off only (~1e-12).
constexpr double kClusterTolerance = 1e-7;

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
  const FreeDofMap free = FreeDofMap::ClampNodes(p.mesh.num_nodes(), p.clamp);
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

TEST(SlepcBackend, FrequencyBandBySpectrumSlicingEqualsSpectrasBand) {
  const auto [K, M] = ClampedMatrices(ClampedBox());
  EigenOptions options;
  options.max_frequency_hz = 3000.0;
  const EigenSolution slepc = MakeEigensolver("slepc")->Solve(K, M, options);
  const EigenSolution spectra = MakeEigensolver("spectra")->Solve(K, M, options);
  EXPECT_GT(slepc.eigenvalues.size(), 3);
  ExpectSameModes(slepc, spectra, M, "band");
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
  const FreeDofMap free = FreeDofMap::ClampNodes(p.mesh.num_nodes(), p.clamp);
  const EigenSolution spectra = MakeEigensolver("spectra")->Solve(
      free.Restrict(system.stiffness), free.Restrict(system.mass), options);
  EigenSolution spectra_full = spectra;
  spectra_full.modes = free.Expand(spectra.modes);
  ExpectSameModes(slepc, spectra_full, system.mass, "distributed");
  EXPECT_LT(slepc.relative_residuals.maxCoeff(), options.residual_tolerance);
}

// How often PETSc's log has seen `event` on this rank so far. Logging starts on the first call,
// and the event must be registered (a solve has run).
int EventCount(const char* event) {
  static const bool started = PetscLogDefaultBegin() == 0;
  EXPECT_TRUE(started);
  PetscLogEvent id = 0;
  PetscEventPerfInfo info{};
  EXPECT_EQ(PetscLogEventGetId(event, &id), 0) << event;
  EXPECT_EQ(PetscLogEventGetPerfInfo(0, id, &info), 0) << event;
  return info.count;
}

// The work SLEPc reports, against PETSc's log of the same solve: numeric factorisations
// (MatCholFctrNum), symbolic analyses (MatCholFctrSym) and solves (MatSolve).
struct LoggedWork {
  int analyses, factorizations, solves;
};
LoggedWork LoggedWorkOf(const Eigen::SparseMatrix<double>& K, const Eigen::SparseMatrix<double>& M,
                        const EigenOptions& options, EigenSolution* solution) {
  const LoggedWork before{EventCount("MatCholFctrSym"), EventCount("MatCholFctrNum"), EventCount("MatSolve")};
  *solution = MakeEigensolver("slepc")->Solve(K, M, options);
  return {EventCount("MatCholFctrSym") - before.analyses, EventCount("MatCholFctrNum") - before.factorizations,
          EventCount("MatSolve") - before.solves};
}

TEST(SlepcBackend, ReportsItsFactorisationsSolvesAndTimesAsPetscLogsThem) {
  const auto [K, M] = ClampedMatrices(ClampedBox());
  EigenOptions options;
  options.num_modes = 10;
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

  // A band: spectrum slicing factorises and solves inside SLEPc; no separate Sturm count.
  EigenOptions band;
  band.max_frequency_hz = 3000.0;
  const LoggedWork sliced = LoggedWorkOf(K, M, band, &s);
  EXPECT_EQ(sliced.factorizations, s.factorizations);
  EXPECT_EQ(sliced.solves, s.operator_applications);
  EXPECT_GT(s.operator_applications, 0);
  EXPECT_EQ(s.krylov_runs, 1);
  EXPECT_EQ(s.sturm_seconds, 0.0);
  EXPECT_LE(s.factorization_seconds + s.krylov_seconds, s.seconds);
}

// A lumped (diagonal) M has fewer entries than K: K - sigma M is then built on the union
// pattern and moved to the cut on a pattern M's is a subset of. The count is still the dense one.
TEST(SlepcBackend, SturmCountWithALumpedMassEqualsTheDenseCount) {
  const Problem p = ClampedBox();
  const fem::SystemMatrices system = fem::AssembleSystem(p.mesh, fem::MassMatrixKind::kLumped);
  const FreeDofMap free = FreeDofMap::ClampNodes(p.mesh.num_nodes(), p.clamp);
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
  const auto same = [&](Eigen::Index a, Eigen::Index b) {
    return std::abs(dense.values(a) - dense.values(b)) <= kClusterTolerance * dense.values(b);
  };
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

}  // namespace
}  // namespace flexmbs::reduction
