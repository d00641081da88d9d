// The SLEPc backend's pairs meet the residual bound on a slender clamped beam (issue 19): the
// path of `flexmbs reduce` for a held body (SolveModesDistributed, K factorised at sigma = 0 and
// kept), on one rank (MUMPS) and under `mpiexec -n 2` (substructured). Krylov-Schur's own pairs
// miss the bound there, as on cases/01's beam; one step of subspace iteration with Rayleigh-Ritz
// takes every pair to its round-off floor.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <memory>
#include <optional>
#include <vector>

#include "eigensolvers/distributed/distributed_model.h"
#include "eigensolvers/distributed/slepc_solver.h"
#include "eigensolvers/eigensolver.h"
#include "fem/assembly.h"
#include "reduction/distributed_reduction.h"
#include "reduction/dof_constraints.h"
#include "tests/support/test_problems.h"

namespace flexmbs::eigensolvers {
namespace {

// Residuals reached after the refinement, in round-off floors: 0.5 at most measured (one and two
// ranks, the backend's and the serial residual code alike).
constexpr double kFloorsReached = 1.0;
// Eigenvalues against the dense solve, relative, in round-off floors of the pair: a pair at its
// floor has its eigenvalue to a fraction of that floor (0.22 floors at most measured).
constexpr double kDenseAgreementFloors = 1.0;

// A steel cantilever 1 m x 5 mm x 5 mm in 40 x 2 x 2 hex8 cells (1080 free DOF), clamped at
// x = 0: square, so its bending modes come in pairs of equal frequency, like cases/01's beam; its
// 4th pair lies 1183 times above the 1st (lambda), which is what leaves Krylov-Schur's pairs
// above the bound.
struct Beam {
  fem::Mesh mesh = testing::HexBox({40, 2, 2}, {1.0, 0.005, 0.005}, testing::Steel());
  std::vector<int> clamped_nodes = testing::NodesOnPlane(mesh, 0, 0.0);
  std::vector<int> clamped_dofs;
  Beam() {
    for (int node : clamped_nodes) {
      for (int i = 0; i < 3; ++i) clamped_dofs.push_back(3 * node + i);
    }
  }
};

// The lowest four bending pairs as `flexmbs reduce` solves them (fixed interface, eigensolver
// slepc) with `residual_tolerance`: the solution on rank 0, nothing on the others (they serve the
// kept model until rank 0 is done).
std::optional<EigenSolution> SolveAsReduce(const Beam& beam, double residual_tolerance) {
  const bool root = SlepcSession::Rank() == 0;
  EigenOptions options;
  options.num_modes = 8;
  options.residual_tolerance = residual_tolerance;
  reduction::DistributedSolveStats stats;
  std::unique_ptr<DistributedModel> model;
  EigenSolution solution =
      reduction::SolveModesDistributed(root ? beam.mesh : fem::Mesh{}, fem::MassMatrixKind::kConsistent,
                                       root ? beam.clamped_dofs : std::vector<int>{}, options, &stats, &model);
  if (!root) {
    model->Serve();
    return std::nullopt;
  }
  model->Finish();
  return solution;
}

// What the issue saw: with no bound to meet (residual tolerance 1, so no refinement), Krylov-Schur's
// pairs of the 4th bending pair lie far above their round-off floor and above 1e-8 (measured: one
// rank 6.85e-8 and 3.6e-8, 106 and 56 floors; two ranks 4.21e-8 and 5.4e-9, 59 and 7.6 floors),
// whatever the convergence tolerance: the beam makes the case the next test needs.
TEST(SlepcResidual, KrylovSchurPairsOfASlenderBeamMissTheBound) {
  const std::optional<EigenSolution> raw = SolveAsReduce(Beam(), 1.0);
  if (!raw) return;
  EXPECT_EQ(raw->refinement_steps, 0);
  const double worst = std::max(raw->relative_residuals(6), raw->relative_residuals(7));
  EXPECT_GT(worst, EigenOptions().residual_tolerance);
  EXPECT_GT(worst, 10.0 * raw->residual_floors(6));
  std::printf("[ numbers  ] Krylov-Schur's 4th pair (%.3f Hz): residuals %.3g, %.3g, floor %.3g\n",
              FrequenciesHz(raw->eigenvalues)(6), raw->relative_residuals(6), raw->relative_residuals(7),
              raw->residual_floors(6));
}

// The beam's K and M without the clamped DOF.
struct Reference {
  Eigen::SparseMatrix<double> K, M;
  reduction::FreeDofMap free;
};
Reference BeamReference(const Beam& beam) {
  const fem::SystemMatrices system = fem::AssembleSystem(beam.mesh, fem::MassMatrixKind::kConsistent);
  Reference r{{}, {}, reduction::FreeDofMap::ClampNodes(beam.mesh.num_nodes(), beam.clamped_nodes)};
  r.K = r.free.Restrict(system.stiffness);
  r.M = r.free.Restrict(system.mass);
  return r;
}

// The dense eigenvalues of the beam, ascending (computed once, by the rank that checks).
const Eigen::VectorXd& DenseEigenvalues(const Reference& reference) {
  static const Eigen::VectorXd values = testing::SolveDense(reference.K, reference.M, 0.0).values;
  return values;
}

// One refinement step was made, every pair meets the default bound by the backend's residuals
// and, at its round-off floor, by the backend's and by the serial residual code (ComputeResiduals:
// Eigen products, not PETSc's) on `modes` (free DOF only), and the eigenvalues are the dense
// solve's.
void ExpectRefinedToTheFloor(const EigenSolution& slepc, const Eigen::MatrixXd& modes, const Reference& reference,
                             const char* what) {
  EXPECT_EQ(slepc.refinement_steps, 1) << what;
  ASSERT_EQ(slepc.eigenvalues.size(), 8) << what;
  const PairResiduals backend{slepc.relative_residuals, slepc.residual_floors};
  EXPECT_TRUE(backend.Accepted(EigenOptions().residual_tolerance)) << what;
  const PairResiduals serial = ComputeResiduals(reference.K, reference.M, slepc.eigenvalues, modes, slepc.shift);
  for (Eigen::Index j = 0; j < slepc.eigenvalues.size(); ++j) {
    const double lambda = DenseEigenvalues(reference)(j);
    const double from_dense = std::abs(slepc.eigenvalues(j) - lambda) / lambda;
    EXPECT_LE(slepc.relative_residuals(j), kFloorsReached * slepc.residual_floors(j)) << what << " mode " << j;
    EXPECT_LE(serial.relative(j), kFloorsReached * serial.floor(j)) << what << " mode " << j;
    EXPECT_LE(from_dense, kDenseAgreementFloors * serial.floor(j)) << what << " mode " << j;
    std::printf("[ numbers  ] %s mode %ld %.6f Hz: residual %.3g (serial code %.3g), floor %.3g; eigenvalue %.2g "
                "from dense (%.2g floors)\n",
                what, static_cast<long>(j), FrequenciesHz(slepc.eigenvalues)(j), slepc.relative_residuals(j),
                serial.relative(j), slepc.residual_floors(j), from_dense, from_dense / serial.floor(j));
  }
  std::printf("[ numbers  ] %s: %s factorisation, %d solves, %d refinement step(s)\n", what,
              slepc.factorization.c_str(), slepc.operator_applications, slepc.refinement_steps);
}

// With the default bound, as `flexmbs reduce` solves: refined to the floor.
TEST(SlepcResidual, EveryPairOfASlenderBeamReachesItsRoundOffFloor) {
  const Beam beam;
  const std::optional<EigenSolution> slepc = SolveAsReduce(beam, EigenOptions().residual_tolerance);
  if (!slepc) return;
  EXPECT_EQ(slepc->shift, 0.0);
  const Reference reference = BeamReference(beam);
  ExpectRefinedToTheFloor(*slepc, reference.free.RestrictVectors(slepc->modes), reference, "held, sigma 0");
}

// Through the serial interface at a shift of -1 Hz (sigma = -39.5 rad^2/s^2): K - sigma M is
// factorised by MUMPS's LDL^T (no factor kept), the refinement solves with it before the Sturm
// count refactorises it for K - cut M, and that count is the dense one. (Krylov-Schur's pairs:
// 127 floors on one rank, 168 on two. At the automatic shift, -1.8e7 here, they reach 0.54 floors
// unrefined: the first pair no longer dominates the Krylov vectors.)
TEST(SlepcResidual, RefinementBeforeTheSturmCountWithTheFactorItReuses) {
  const Beam beam;
  const Reference reference = BeamReference(beam);
  EigenOptions options;
  options.num_modes = 8;
  options.shift_hz = -1.0;
  options.check_missed_modes = MissedModeCheck::kSturmCount;
  options.distributed_factorization = DistributedFactorization::kMumps;
  const EigenSolution slepc = MakeEigensolver("slepc")->Solve(reference.K, reference.M, options);
  if (SlepcSession::Rank() != 0) return;  // the same solution on every rank: checked once
  EXPECT_EQ(slepc.factorization, "mumps");
  EXPECT_EQ(slepc.missed_mode_check, MissedModeCheck::kSturmCount);
  EXPECT_EQ(slepc.sturm_count, (DenseEigenvalues(reference).array() < slepc.sturm_cut).count());
  ExpectRefinedToTheFloor(slepc, slepc.modes, reference, "shift -1 Hz");
}

}  // namespace
}  // namespace flexmbs::eigensolvers
