#include "fem/distributed_assembly.h"

#include <fmt/format.h>
#include <petscmat.h>
#include <string>
#include <vector>

#include "core/error.h"
#include "fem/assembly.h"
#include "fem/petsc_check.h"

namespace flexmbs::fem {
namespace {

// The element's global DOF indices, 3 global_node[a] + i.
void ElementDofs(std::span<const int> nodes, const std::vector<int>& global_node, std::vector<PetscInt>* dofs) {
  dofs->resize(3 * nodes.size());
  for (std::size_t a = 0; a < nodes.size(); ++a) {
    const int node = global_node[static_cast<std::size_t>(nodes[a])];
    for (int i = 0; i < 3; ++i) (*dofs)[3 * a + static_cast<std::size_t>(i)] = 3 * node + i;
  }
}

// Adds element matrices into PETSc matrices (values are symmetric, so storage order does not
// matter).
class PetscScatter final : public ElementMatrixVisitor {
 public:
  PetscScatter(Mat K, Mat M, const std::vector<int>& global_node) : K_(K), M_(M), global_node_(global_node) {}

  void Visit(std::span<const int> nodes, const Eigen::MatrixXd& K_e,
             const Eigen::MatrixXd& m_e) override {
    ElementDofs(nodes, global_node_, &dofs_);
    const auto n = static_cast<PetscInt>(dofs_.size());
    M_e_.setZero(n, n);
    for (Eigen::Index a = 0; a < m_e.rows(); ++a) {
      for (Eigen::Index b = 0; b < m_e.cols(); ++b) {
        for (int i = 0; i < 3; ++i) M_e_(3 * a + i, 3 * b + i) = m_e(a, b);
      }
    }
    FLEXMBS_PETSC(MatSetValues(K_, n, dofs_.data(), n, dofs_.data(), K_e.data(), ADD_VALUES));
    FLEXMBS_PETSC(MatSetValues(M_, n, dofs_.data(), n, dofs_.data(), M_e_.data(), ADD_VALUES));
  }

 private:
  Mat K_, M_;
  const std::vector<int>& global_node_;
  std::vector<PetscInt> dofs_;
  Eigen::MatrixXd M_e_;
};

// A PETSc AIJ matrix with block size 3 whose owned rows are the DOF of `nodes`.
Mat CreateMatrix(Eigen::Index num_nodes, IndexRange nodes) {
  Mat A;
  const auto local = static_cast<PetscInt>(3 * (nodes.end - nodes.begin));
  const auto global = static_cast<PetscInt>(3 * num_nodes);
  FLEXMBS_PETSC(MatCreate(PETSC_COMM_WORLD, &A));
  FLEXMBS_PETSC(MatSetSizes(A, local, local, global, global));
  FLEXMBS_PETSC(MatSetType(A, MATAIJ));
  FLEXMBS_PETSC(MatSetBlockSize(A, 3));
  return A;
}

// Exact preallocation of `target` from the element patterns of the part.
void Preallocate(const MeshPart& part, Mat target) {
  Mat pattern;
  const auto local = static_cast<PetscInt>(3 * (part.owned_nodes.end - part.owned_nodes.begin));
  const auto global = static_cast<PetscInt>(3 * part.num_global_nodes);
  FLEXMBS_PETSC(MatCreate(PETSC_COMM_WORLD, &pattern));
  FLEXMBS_PETSC(MatSetSizes(pattern, local, local, global, global));
  FLEXMBS_PETSC(MatSetType(pattern, MATPREALLOCATOR));
  FLEXMBS_PETSC(MatSetBlockSize(pattern, 3));
  FLEXMBS_PETSC(MatSetUp(pattern));
  std::vector<PetscInt> dofs;
  std::vector<PetscScalar> zeros;
  for (const ElementBlock& block : part.mesh.blocks) {
    for (Eigen::Index e = 0; e < block.num_elements(); ++e) {
      const auto col = block.connectivity.col(e);
      ElementDofs(std::span<const int>(col.data(), static_cast<std::size_t>(col.size())), part.global_node, &dofs);
      zeros.assign(dofs.size() * dofs.size(), 0.0);
      const auto n = static_cast<PetscInt>(dofs.size());
      FLEXMBS_PETSC(MatSetValues(pattern, n, dofs.data(), n, dofs.data(), zeros.data(), INSERT_VALUES));
    }
  }
  FLEXMBS_PETSC(MatAssemblyBegin(pattern, MAT_FINAL_ASSEMBLY));
  FLEXMBS_PETSC(MatAssemblyEnd(pattern, MAT_FINAL_ASSEMBLY));
  FLEXMBS_PETSC(MatPreallocatorPreallocate(pattern, PETSC_TRUE, target));
  FLEXMBS_PETSC(MatDestroy(&pattern));
}

}  // namespace

DistributedMatrices AssembleDistributed(const Mesh& mesh, MassMatrixKind mass_kind) {
  PetscMPIInt size = 0, rank = 0;
  FLEXMBS_PETSC(MPI_Comm_size(PETSC_COMM_WORLD, &size));
  FLEXMBS_PETSC(MPI_Comm_rank(PETSC_COMM_WORLD, &rank));
  return AssembleDistributed(ExtractMeshPart(mesh, PartitionInMeshOrder(mesh, size), rank), mass_kind);
}

DistributedMatrices AssembleDistributed(const MeshPart& part, MassMatrixKind mass_kind) {
  PetscMPIInt rank = 0;
  FLEXMBS_PETSC(MPI_Comm_rank(PETSC_COMM_WORLD, &rank));
  // K and M share one pattern: preallocate K (a preallocator serves once), then copy its
  // structure for M.
  DistributedMatrices out{CreateMatrix(part.num_global_nodes, part.owned_nodes), nullptr};
  Preallocate(part, out.stiffness);
  FLEXMBS_PETSC(MatDuplicate(out.stiffness, MAT_DO_NOT_COPY_VALUES, &out.mass));
  PetscScatter scatter(out.stiffness, out.mass, part.global_node);
  // An element error on one rank must stop every rank, or the others would wait forever in
  // the collective assembly below.
  std::string error;
  try {
    VisitElementMatrices(part.mesh, mass_kind, 0, part.mesh.num_elements(), scatter);
  } catch (const InputError& e) {
    error = e.what();
  }
  PetscMPIInt failed_rank = error.empty() ? -1 : rank;
  FLEXMBS_PETSC(MPI_Allreduce(MPI_IN_PLACE, &failed_rank, 1, MPI_INT, MPI_MAX, PETSC_COMM_WORLD));
  if (failed_rank >= 0) {
    DestroyDistributed(&out);
    throw InputError(error.empty() ? fmt::format("the assembly failed on rank {}", failed_rank) : error);
  }
  for (Mat A : {out.stiffness, out.mass}) {
    FLEXMBS_PETSC(MatAssemblyBegin(A, MAT_FINAL_ASSEMBLY));
    FLEXMBS_PETSC(MatAssemblyEnd(A, MAT_FINAL_ASSEMBLY));
  }
  return out;
}

void DestroyDistributed(DistributedMatrices* matrices) {
  MatDestroy(&matrices->stiffness);
  MatDestroy(&matrices->mass);
}

}  // namespace flexmbs::fem
