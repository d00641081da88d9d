#include "reduction/distributed_reduction.h"

#include <algorithm>
#include <chrono>
#include <fmt/format.h>
#include <petscmat.h>

#include "core/error.h"
#include "fem/distributed_assembly.h"
#include "fem/mesh_partition.h"
#include "fem/mesh_scatter.h"
#include "fem/petsc_check.h"
#include "eigensolvers/distributed/slepc_pair_measures.h"
#include "eigensolvers/distributed/slepc_solver.h"

namespace flexmbs::reduction {
namespace {

using Index = Eigen::Index;

double SecondsSince(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

// Rank 0's vector on every rank.
std::vector<int> Broadcast(std::vector<int> values) {
  auto count = static_cast<long long>(values.size());
  FLEXMBS_PETSC(MPI_Bcast(&count, 1, MPI_LONG_LONG, 0, PETSC_COMM_WORLD));
  values.resize(static_cast<std::size_t>(count));
  FLEXMBS_PETSC(MPI_Bcast(values.data(), static_cast<int>(count), MPI_INT, 0, PETSC_COMM_WORLD));
  return values;
}

// K or M restricted to its rows and columns not in `clamped` (global, ascending, every rank):
// each rank keeps its owned free rows. Destroys A.
Mat RemoveClamped(Mat A, const std::vector<int>& clamped) {
  PetscInt begin = 0, end = 0;
  FLEXMBS_PETSC(MatGetOwnershipRange(A, &begin, &end));
  std::vector<PetscInt> free;
  auto next = std::lower_bound(clamped.begin(), clamped.end(), static_cast<int>(begin));
  for (PetscInt r = begin; r < end; ++r) {
    if (next != clamped.end() && *next == r) {
      ++next;
    } else {
      free.push_back(r);
    }
  }
  IS rows;
  FLEXMBS_PETSC(ISCreateGeneral(PETSC_COMM_WORLD, static_cast<PetscInt>(free.size()), free.data(), PETSC_COPY_VALUES,
                                &rows));
  Mat out;
  FLEXMBS_PETSC(MatCreateSubMatrix(A, rows, rows, MAT_INITIAL_MATRIX, &out));
  FLEXMBS_PETSC(ISDestroy(&rows));
  FLEXMBS_PETSC(MatDestroy(&A));
  FLEXMBS_PETSC(MatSetOption(out, MAT_SYMMETRIC, PETSC_TRUE));
  return out;
}

// Gathers every rank's share to rank 0.
std::vector<RankShare> GatherShares(const RankShare& mine) {
  const double values[] = {static_cast<double>(mine.elements), static_cast<double>(mine.nodes),
                           static_cast<double>(mine.rows), static_cast<double>(mine.nonzeros), mine.peak_rss_mb};
  constexpr int kCount = 5;
  PetscMPIInt size = 1, rank = 0;
  FLEXMBS_PETSC(MPI_Comm_size(PETSC_COMM_WORLD, &size));
  FLEXMBS_PETSC(MPI_Comm_rank(PETSC_COMM_WORLD, &rank));
  std::vector<double> all(static_cast<std::size_t>(rank == 0 ? kCount * size : 0));
  FLEXMBS_PETSC(MPI_Gather(values, kCount, MPI_DOUBLE, all.data(), kCount, MPI_DOUBLE, 0, PETSC_COMM_WORLD));
  std::vector<RankShare> out;
  for (std::size_t r = 0; kCount * r < all.size(); ++r) {
    const double* v = all.data() + kCount * r;
    out.push_back({static_cast<int>(r), static_cast<Index>(v[0]), static_cast<Index>(v[1]), static_cast<Index>(v[2]),
                   static_cast<Index>(v[3]), v[4]});
  }
  return out;
}

// Mesh-numbered full-length rows from the rows of the DOF `new_dofs` in partition numbering:
// row p of `rows` is new DOF new_dofs[p]; old_node[n] is the mesh node of partition node n.
Eigen::MatrixXd ToMeshNumbering(const Eigen::MatrixXd& rows, const std::vector<int>& new_dofs,
                                const std::vector<int>& old_node) {
  Eigen::MatrixXd out = Eigen::MatrixXd::Zero(3 * static_cast<Index>(old_node.size()), rows.cols());
  for (std::size_t p = 0; p < new_dofs.size(); ++p) {
    const int dof = new_dofs[p];
    out.row(3 * old_node[static_cast<std::size_t>(dof / 3)] + dof % 3) = rows.row(static_cast<Index>(p));
  }
  return out;
}

// The diagonal of the distributed A on rank 0, in the mesh's DOF numbering (others: empty).
Eigen::VectorXd GatherDiagonal(Mat A, const std::vector<int>& old_node) {
  Vec diagonal;
  FLEXMBS_PETSC(MatCreateVecs(A, &diagonal, nullptr));
  FLEXMBS_PETSC(MatGetDiagonal(A, diagonal));
  const Eigen::VectorXd values = eigensolvers::GatherVector(diagonal, eigensolvers::ModesOn::kRankZero);
  FLEXMBS_PETSC(VecDestroy(&diagonal));
  if (values.size() == 0) return values;
  std::vector<int> all(static_cast<std::size_t>(values.size()));
  for (std::size_t dof = 0; dof < all.size(); ++dof) all[dof] = static_cast<int>(dof);
  return ToMeshNumbering(values, all, old_node);
}

// The partition's numbering of what the solve needs on every rank: the clamped DOF in partition
// numbering, ascending (every rank), and on rank 0 the mesh node of each partition node.
struct PartitionNumbering {
  std::vector<int> clamped;
  std::vector<int> old_node;
};
PartitionNumbering Renumber(const fem::MeshPartition& partition, const std::vector<int>& clamped_dofs, int rank) {
  PartitionNumbering numbering;
  numbering.old_node.resize(partition.new_node.size());
  if (rank == 0) {
    for (int dof : clamped_dofs) {
      numbering.clamped.push_back(3 * partition.new_node[static_cast<std::size_t>(dof / 3)] + dof % 3);
    }
    std::sort(numbering.clamped.begin(), numbering.clamped.end());
    for (std::size_t n = 0; n < numbering.old_node.size(); ++n) {
      numbering.old_node[static_cast<std::size_t>(partition.new_node[n])] = static_cast<int>(n);
    }
  }
  numbering.clamped = Broadcast(std::move(numbering.clamped));
  return numbering;
}

// The DOF 0 .. num_dofs - 1 not in `clamped` (ascending), ascending.
std::vector<int> FreeDofs(int num_dofs, const std::vector<int>& clamped) {
  std::vector<int> free;
  auto next = clamped.begin();
  for (int dof = 0; dof < num_dofs; ++dof) {
    if (next != clamped.end() && *next == dof) {
      ++next;
    } else {
      free.push_back(dof);
    }
  }
  return free;
}

}  // namespace

void ShareRootError(const std::string& error_on_root) {
  std::vector<int> chars(error_on_root.begin(), error_on_root.end());
  chars = Broadcast(std::move(chars));
  if (!chars.empty()) throw InputError(std::string(chars.begin(), chars.end()));
}

eigensolvers::EigenSolution SolveModesDistributed(const fem::Mesh& mesh, fem::MassMatrixKind mass_kind,
                                    const std::vector<int>& clamped_dofs, const eigensolvers::EigenOptions& options,
                                    DistributedSolveStats* stats, std::unique_ptr<eigensolvers::DistributedModel>* keep) {
  const int rank = eigensolvers::SlepcSession::Rank();
  const int size = eigensolvers::SlepcSession::Size();
  auto start = std::chrono::steady_clock::now();
  fem::MeshPartition partition;
  if (rank == 0) partition = fem::PartitionByCoordinateBisection(mesh, size);
  fem::MeshPart part = fem::ScatterMeshParts(mesh, partition);
  const PartitionNumbering numbering = Renumber(partition, clamped_dofs, rank);
  const std::vector<int>& clamped = numbering.clamped;
  const std::vector<int>& old_node = numbering.old_node;
  stats->partition_seconds = SecondsSince(start);

  start = std::chrono::steady_clock::now();
  fem::DistributedMatrices matrices = fem::AssembleDistributed(part, mass_kind);
  RankShare share;
  share.rank = rank;
  share.elements = part.mesh.num_elements();
  share.nodes = part.mesh.num_nodes();
  share.rows = 3 * (part.owned_nodes.end - part.owned_nodes.begin);
  MatInfo info;
  FLEXMBS_PETSC(MatGetInfo(matrices.stiffness, MAT_LOCAL, &info));
  share.nonzeros = static_cast<Index>(info.nz_used);
  stats->assembly_seconds = SecondsSince(start);

  start = std::chrono::steady_clock::now();
  Mat K = matrices.stiffness, M = matrices.mass, M_s = nullptr;
  matrices = {};
  eigensolvers::EigenSolution solution;
  Eigen::VectorXd K_diagonal, M_diagonal;
  double gather_seconds = 0.0;
  // A held body kept for static solves: the eigen-solve's factorisation of K_oo serves them.
  Mat K_factor = nullptr;
  std::unique_ptr<eigensolvers::SubstructuredFactor> K_substructured;
  try {
    if (keep) {
      // What the products after the solve need of the whole matrices: their diagonals and,
      // for a held body, the whole M as M_s (1/9 of its entries).
      K_diagonal = GatherDiagonal(K, old_node);
      M_diagonal = GatherDiagonal(M, old_node);
      if (!clamped.empty()) M_s = eigensolvers::DistributedScalarMass(M);
    }
    if (!clamped.empty()) {
      K = RemoveClamped(K, clamped);
      M = RemoveClamped(M, clamped);
    }
    solution = eigensolvers::SolveDistributedEigenproblem(K, M, {}, options, eigensolvers::ModesOn::kRankZero, &gather_seconds,
                                            keep && !clamped.empty() ? &K_factor : nullptr, &K_substructured);
  } catch (...) {
    if (K_factor != nullptr) MatDestroy(&K_factor);
    MatDestroy(&K);
    MatDestroy(&M);
    if (M_s != nullptr) MatDestroy(&M_s);
    throw;
  }
  if (keep && M_s != nullptr) {
    FLEXMBS_PETSC(MatDestroy(&M));
    M = M_s;
  }
  if (keep) {
    const bool lumped = mass_kind != fem::MassMatrixKind::kConsistent;
    *keep = std::make_unique<eigensolvers::DistributedModel>(K, M, M_s != nullptr, lumped ? std::move(part) : fem::MeshPart{},
                                               mass_kind, old_node, clamped, std::move(K_diagonal),
                                               std::move(M_diagonal), K_factor, std::move(K_substructured));
  } else {
    FLEXMBS_PETSC(MatDestroy(&K));
    FLEXMBS_PETSC(MatDestroy(&M));
  }
  stats->solve_seconds = SecondsSince(start) - gather_seconds;

  start = std::chrono::steady_clock::now();
  if (rank == 0) {
    solution.modes = ToMeshNumbering(solution.modes, FreeDofs(3 * static_cast<int>(mesh.num_nodes()), clamped), old_node);
  }
  stats->gather_seconds = gather_seconds + SecondsSince(start);
  share.peak_rss_mb = eigensolvers::PeakRssMb();
  stats->ranks = GatherShares(share);
  return solution;
}

}  // namespace flexmbs::reduction
