// The distributed path of `reduce` piece by piece, on one rank and on two: the element
// partition, the scatter of the parts and their assembly, and the held body's modes from
// SolveModesDistributed against Spectra on the serial matrices.
#include <gtest/gtest.h>
#include <mpi.h>
#include <petscmat.h>

#include <algorithm>
#include <set>

#include "fem/assembly.h"
#include "fem/distributed_assembly.h"
#include "fem/mesh_partition.h"
#include "fem/mesh_scatter.h"
#include "reduction/distributed_reduction.h"
#include "reduction/dof_constraints.h"
#include "eigensolvers/distributed/slepc_solver.h"
#include "tests/support/test_problems.h"

namespace flexmbs::reduction {
namespace {

// The agreement bound between the backends; both reach about 1e-11 alone.
constexpr double kBackendAgreement = 1e-8;
// Assembly order differs between the serial and the distributed sums: round-off of a sum of
// at most 8 element contributions, relative to the largest entry.
constexpr double kAssemblyRoundOff = 1e-13;
// The bound on one rank's share on 2 ranks.
constexpr double kMaxShare = 0.6;

// An 8 x 3 x 2 hex8 steel bar 0.4 m long, clamped at x = 0.
fem::Mesh Bar() { return testing::HexBox({8, 3, 2}, {0.4, 0.15, 0.1}, testing::Steel()); }

int Rank() { return eigensolvers::SlepcSession::Rank(); }
int Size() { return eigensolvers::SlepcSession::Size(); }

TEST(MeshPartition, CoordinateBisectionCutsABarAcrossItsLength) {
  const fem::Mesh mesh = Bar();
  const fem::MeshPartition partition = fem::PartitionByCoordinateBisection(mesh, 2);
  // Half the 48 elements each, the cut at the median of the element centres along x (the
  // longest extent): x = 0.2 m. The nodes both parts use are the 4 x 3 nodes of that plane.
  std::vector<std::set<int>> nodes(2);
  for (Eigen::Index e = 0; e < mesh.num_elements(); ++e) {
    const int part = partition.element_part[static_cast<std::size_t>(e)];
    double centre_x = 0.0;
    for (Eigen::Index a = 0; a < 8; ++a) {
      const int node = mesh.blocks[0].connectivity(a, e);
      nodes[static_cast<std::size_t>(part)].insert(node);
      centre_x += mesh.nodes(0, node) / 8.0;
    }
    EXPECT_EQ(part, centre_x < 0.2 ? 0 : 1) << "element " << e;
  }
  EXPECT_EQ(std::count(partition.element_part.begin(), partition.element_part.end(), 0), 24);
  std::vector<int> shared;
  std::set_intersection(nodes[0].begin(), nodes[0].end(), nodes[1].begin(), nodes[1].end(), std::back_inserter(shared));
  EXPECT_EQ(shared.size(), 12u);
  // The new numbering is a permutation; part 0 owns its nodes and the shared plane.
  std::vector<int> sorted = partition.new_node;
  std::sort(sorted.begin(), sorted.end());
  for (std::size_t n = 0; n < sorted.size(); ++n) EXPECT_EQ(sorted[n], static_cast<int>(n));
  EXPECT_EQ(partition.node_offsets, (std::vector<Eigen::Index>{0, static_cast<Eigen::Index>(nodes[0].size()),
                                                                mesh.num_nodes()}));
}

TEST(DistributedAssembly, ScatteredPartsAssembleTheSerialMatricesInTheirShare) {
  const fem::Mesh mesh = Bar();
  // Only rank 0 passes the mesh: the others assemble from what they receive.
  const fem::Mesh empty;
  const fem::MeshPartition partition = fem::PartitionByCoordinateBisection(mesh, Size());
  const fem::MeshPart part =
      fem::ScatterMeshParts(Rank() == 0 ? mesh : empty, Rank() == 0 ? partition : fem::MeshPartition{});
  fem::DistributedMatrices distributed = fem::AssembleDistributed(part, fem::MassMatrixKind::kConsistent);
  const fem::SystemMatrices serial = fem::AssembleSystem(mesh, fem::MassMatrixKind::kConsistent);
  std::vector<int> old_node(partition.new_node.size());
  for (std::size_t n = 0; n < old_node.size(); ++n) old_node[static_cast<std::size_t>(partition.new_node[n])] = static_cast<int>(n);

  PetscInt begin = 0, end = 0;
  MatGetOwnershipRange(distributed.stiffness, &begin, &end);
  EXPECT_EQ(begin, 3 * part.owned_nodes.begin);
  EXPECT_EQ(end, 3 * part.owned_nodes.end);
  long long nonzeros = 0;
  for (const auto& [A, reference] : {std::pair{distributed.stiffness, &serial.stiffness},
                                     std::pair{distributed.mass, &serial.mass}}) {
    const double scale = reference->coeffs().cwiseAbs().maxCoeff();
    for (PetscInt r = begin; r < end; ++r) {
      PetscInt count = 0;
      const PetscInt* cols = nullptr;
      const PetscScalar* values = nullptr;
      MatGetRow(A, r, &count, &cols, &values);
      const int row = 3 * old_node[static_cast<std::size_t>(r / 3)] + static_cast<int>(r % 3);
      double row_sum = 0.0, reference_sum = 0.0;
      for (PetscInt k = 0; k < count; ++k) {
        const int col = 3 * old_node[static_cast<std::size_t>(cols[k] / 3)] + static_cast<int>(cols[k] % 3);
        EXPECT_NEAR(values[k], reference->coeff(row, col), kAssemblyRoundOff * scale);
        row_sum += std::abs(values[k]);
      }
      for (Eigen::SparseMatrix<double>::InnerIterator it(*reference, row); it; ++it) reference_sum += std::abs(it.value());
      // Every entry of the serial row is among the distributed row's (K, M symmetric: column = row).
      EXPECT_NEAR(row_sum, reference_sum, kAssemblyRoundOff * scale * static_cast<double>(count));
      if (A == distributed.stiffness) nonzeros += count;
      MatRestoreRow(A, r, &count, &cols, &values);
    }
  }
  long long total = nonzeros;
  MPI_Allreduce(MPI_IN_PLACE, &total, 1, MPI_LONG_LONG, MPI_SUM, PETSC_COMM_WORLD);
  EXPECT_EQ(total, static_cast<long long>(serial.stiffness.nonZeros()));
  if (Size() == 2) {
    EXPECT_LT(static_cast<double>(nonzeros), kMaxShare * static_cast<double>(total));
    EXPECT_LT(static_cast<double>(part.mesh.num_elements()), kMaxShare * static_cast<double>(mesh.num_elements()));
  }
  fem::DestroyDistributed(&distributed);
}

TEST(SolveModesDistributed, HeldBarEqualsSpectraOnTheSerialMatrices) {
  const fem::Mesh mesh = Bar();
  const std::vector<int> clamp = testing::NodesOnPlane(mesh, 0, 0.0);
  std::vector<int> clamped;
  for (int node : clamp) {
    for (int i = 0; i < 3; ++i) clamped.push_back(3 * node + i);
  }
  eigensolvers::EigenOptions options;
  options.num_modes = 8;
  DistributedSolveStats stats;
  const fem::Mesh empty;
  const eigensolvers::EigenSolution distributed = SolveModesDistributed(Rank() == 0 ? mesh : empty, fem::MassMatrixKind::kConsistent,
                                                          Rank() == 0 ? clamped : std::vector<int>{}, options, &stats);
  const fem::SystemMatrices system = fem::AssembleSystem(mesh, fem::MassMatrixKind::kConsistent);
  const FreeDofMap free = FreeDofMap::ClampNodes(mesh.num_nodes(), clamp);
  const eigensolvers::EigenSolution spectra =
      eigensolvers::MakeEigensolver("spectra")->Solve(free.Restrict(system.stiffness), free.Restrict(system.mass), options);
  ASSERT_EQ(distributed.eigenvalues.size(), spectra.eigenvalues.size());
  for (Eigen::Index j = 0; j < spectra.eigenvalues.size(); ++j) {
    EXPECT_NEAR(distributed.eigenvalues(j), spectra.eigenvalues(j), kBackendAgreement * spectra.eigenvalues(j));
  }
  EXPECT_LT(distributed.relative_residuals.maxCoeff(), options.residual_tolerance);
  if (Rank() == 0) {
    ASSERT_EQ(distributed.modes.rows(), mesh.num_dofs());
    for (int dof : clamped) EXPECT_EQ(distributed.modes.row(dof).norm(), 0.0);
    EXPECT_LT(testing::LargestPrincipalAngleSine(system.mass, distributed.modes, free.Expand(spectra.modes)),
              kBackendAgreement);
    ASSERT_EQ(stats.ranks.size(), static_cast<std::size_t>(Size()));
    Eigen::Index rows = 0;
    for (const RankShare& share : stats.ranks) rows += share.rows;
    EXPECT_EQ(rows, mesh.num_dofs());
  } else {
    EXPECT_EQ(distributed.modes.rows(), 0);
  }
}

}  // namespace
}  // namespace flexmbs::reduction
