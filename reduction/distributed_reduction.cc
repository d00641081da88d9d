#include "reduction/distributed_reduction.h"

#include <algorithm>
#include <chrono>
#include <fmt/format.h>
#include <petscmat.h>
#include <sys/resource.h>

#include "core/error.h"
#include "fem/distributed_assembly.h"
#include "fem/mesh_partition.h"
#include "fem/mesh_scatter.h"
#include "fem/petsc_check.h"
#include "reduction/slepc_solver.h"

namespace flexmbs::reduction {
namespace {

using Index = Eigen::Index;

double SecondsSince(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

// This process's peak resident set size so far [MB] (Linux reports ru_maxrss in KiB).
double PeakRssMb() {
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);
  return static_cast<double>(usage.ru_maxrss) / 1024.0;
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

// Mesh-numbered full-length modes from the rows of the free DOF in partition numbering:
// row p of `free_rows` is new DOF free_new[p].
Eigen::MatrixXd ToMeshNumbering(const Eigen::MatrixXd& free_rows, const std::vector<int>& free_new,
                                const std::vector<int>& new_node) {
  std::vector<int> old_node(new_node.size());
  for (std::size_t n = 0; n < new_node.size(); ++n) old_node[static_cast<std::size_t>(new_node[n])] = static_cast<int>(n);
  Eigen::MatrixXd out = Eigen::MatrixXd::Zero(3 * static_cast<Index>(new_node.size()), free_rows.cols());
  for (std::size_t p = 0; p < free_new.size(); ++p) {
    const int dof = free_new[p];
    out.row(3 * old_node[static_cast<std::size_t>(dof / 3)] + dof % 3) = free_rows.row(static_cast<Index>(p));
  }
  return out;
}

class PrecomputedEigensolver final : public Eigensolver {
 public:
  PrecomputedEigensolver(EigenSolution solution, std::vector<int> clamped, EigenOptions asked)
      : solution_(std::move(solution)), clamped_(std::move(clamped)), asked_(asked) {}

  std::string_view name() const override { return solution_.backend; }

  EigenSolution Solve(const Eigen::SparseMatrix<double>& K, const Eigen::SparseMatrix<double>&,
                      const EigenOptions& options) const override {
    const Index n = solution_.modes.rows();
    const Index n_free = n - static_cast<Index>(clamped_.size());
    if (K.rows() != n_free || options.num_modes != asked_.num_modes ||
        options.max_frequency_hz != asked_.max_frequency_hz) {
      throw InputError(fmt::format(
          "eigenproblem: the distributed solve (mpirun, slepc) computed {} modes of {} DOF; a second solve for {} "
          "modes of {} DOF is not available there: run on one rank",
          solution_.modes.cols(), n_free, options.num_modes, K.rows()));
    }
    EigenSolution out = solution_;
    out.modes.resize(n_free, solution_.modes.cols());
    auto next = clamped_.begin();
    Index row = 0;
    for (Index dof = 0; dof < n; ++dof) {
      if (next != clamped_.end() && *next == dof) {
        ++next;
      } else {
        out.modes.row(row++) = solution_.modes.row(dof);
      }
    }
    return out;
  }

 private:
  EigenSolution solution_;
  std::vector<int> clamped_;
  EigenOptions asked_;
};

}  // namespace

void ShareRootError(const std::string& error_on_root) {
  std::vector<int> chars(error_on_root.begin(), error_on_root.end());
  chars = Broadcast(std::move(chars));
  if (!chars.empty()) throw InputError(std::string(chars.begin(), chars.end()));
}

EigenSolution SolveModesDistributed(const fem::Mesh& mesh, fem::MassMatrixKind mass_kind,
                                    const std::vector<int>& clamped_dofs, const EigenOptions& options,
                                    DistributedSolveStats* stats) {
  const int rank = SlepcSession::Rank();
  const int size = SlepcSession::Size();
  auto start = std::chrono::steady_clock::now();
  fem::MeshPartition partition;
  if (rank == 0) partition = fem::PartitionByCoordinateBisection(mesh, size);
  const fem::MeshPart part = fem::ScatterMeshParts(mesh, partition);
  // The clamped DOF in partition numbering, ascending, on every rank.
  std::vector<int> clamped;
  if (rank == 0) {
    for (int dof : clamped_dofs) clamped.push_back(3 * partition.new_node[static_cast<std::size_t>(dof / 3)] + dof % 3);
    std::sort(clamped.begin(), clamped.end());
  }
  clamped = Broadcast(std::move(clamped));
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
  Mat K = matrices.stiffness, M = matrices.mass;
  matrices = {};
  EigenSolution solution;
  double gather_seconds = 0.0;
  try {
    if (!clamped.empty()) {
      K = RemoveClamped(K, clamped);
      M = RemoveClamped(M, clamped);
    }
    solution = SolveDistributedEigenproblem(K, M, {}, options, ModesOn::kRankZero, &gather_seconds);
  } catch (...) {
    MatDestroy(&K);
    MatDestroy(&M);
    throw;
  }
  FLEXMBS_PETSC(MatDestroy(&K));
  FLEXMBS_PETSC(MatDestroy(&M));
  stats->solve_seconds = SecondsSince(start) - gather_seconds;

  start = std::chrono::steady_clock::now();
  if (rank == 0) {
    std::vector<int> free_new;
    auto next = clamped.begin();
    for (int dof = 0; dof < 3 * static_cast<int>(mesh.num_nodes()); ++dof) {
      if (next != clamped.end() && *next == dof) {
        ++next;
      } else {
        free_new.push_back(dof);
      }
    }
    solution.modes = ToMeshNumbering(solution.modes, free_new, partition.new_node);
  }
  stats->gather_seconds = gather_seconds + SecondsSince(start);
  share.peak_rss_mb = PeakRssMb();
  stats->ranks = GatherShares(share);
  return solution;
}

std::optional<std::vector<int>> ClampedDofs(const Eigen::Matrix3Xd& nodes, const BoundaryConditions& conditions) {
  const ConstraintTransform transform = BuildConstraintTransform(nodes, conditions);
  const Eigen::SparseMatrix<double, Eigen::RowMajor> G = transform.G;
  std::vector<int> clamped;
  for (Index dof = 0; dof < G.rows(); ++dof) {
    const Index count = G.outerIndexPtr()[dof + 1] - G.outerIndexPtr()[dof];
    if (count == 0) {
      clamped.push_back(static_cast<int>(dof));
    } else if (count != 1 || G.valuePtr()[G.outerIndexPtr()[dof]] != 1.0) {
      return std::nullopt;
    }
  }
  // A selection: each interior coordinate is one free DOF, in ascending order.
  if (G.cols() != G.rows() - static_cast<Index>(clamped.size())) return std::nullopt;
  Index expected = 0;
  for (Index dof = 0; dof < G.rows(); ++dof) {
    if (G.outerIndexPtr()[dof + 1] == G.outerIndexPtr()[dof]) continue;
    if (G.innerIndexPtr()[G.outerIndexPtr()[dof]] != expected++) return std::nullopt;
  }
  return clamped;
}

std::unique_ptr<Eigensolver> MakePrecomputedEigensolver(EigenSolution solution, std::vector<int> clamped_dofs,
                                                        EigenOptions asked) {
  return std::make_unique<PrecomputedEigensolver>(std::move(solution), std::move(clamped_dofs), asked);
}

}  // namespace flexmbs::reduction
