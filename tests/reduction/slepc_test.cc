// The SLEPc backend agrees with the Spectra backend, through the serial interface and through
// the distributed assembly, on one rank and under `mpiexec -n 2` (both registered with CTest).
#include <gtest/gtest.h>

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

}  // namespace
}  // namespace flexmbs::reduction
