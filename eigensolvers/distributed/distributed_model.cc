#include "eigensolvers/distributed/distributed_model.h"

#include <petscmat.h>
#include <sys/resource.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <exception>
#include <optional>
#include <utility>

#include "core/error.h"
#include "fem/distributed_assembly.h"
#include "fem/petsc_check.h"
#include "eigensolvers/distributed/slepc_pair_measures.h"

namespace flexmbs::eigensolvers {
namespace {

using Index = Eigen::Index;

// What rank 0 asks the other ranks to do (the first entry of a Request).
enum Op : long long { kApply = 1, kSolve = 2, kFinish = 3 };
// Which matrix an kApply request multiplies by.
enum Which : long long { kStiffness = 0, kMass = 1, kConsistentMass = 2 };

// A request: {op, which or the number of excluded rows, number of columns, abs or gather flag}.
using Request = std::array<long long, 4>;

Request Broadcast(Request request) {
  FLEXMBS_PETSC(MPI_Bcast(request.data(), 4, MPI_LONG_LONG, 0, PETSC_COMM_WORLD));
  return request;
}

double SecondsSince(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

// The vectors of one matrix's row layout, and the scatter that moves a column between rank 0
// (all rows, in the matrix's order) and the rows' owners.
class RowScatter {
 public:
  explicit RowScatter(Mat A) {
    FLEXMBS_PETSC(MatCreateVecs(A, &input, &output));
    FLEXMBS_PETSC(VecScatterCreateToZero(input, &scatter_, &root_));
  }
  ~RowScatter() {
    VecScatterDestroy(&scatter_);
    VecDestroy(&root_);
    VecDestroy(&input);
    VecDestroy(&output);
  }
  RowScatter(const RowScatter&) = delete;
  RowScatter& operator=(const RowScatter&) = delete;

  // input <- column j of X at the rows' DOF `dofs` (rank 0's X; the others pass null).
  void Send(const Eigen::MatrixXd* X, Index j, const std::vector<int>& dofs) {
    if (X != nullptr) {
      PetscScalar* values = nullptr;
      FLEXMBS_PETSC(VecGetArray(root_, &values));
      for (std::size_t p = 0; p < dofs.size(); ++p) values[p] = (*X)(dofs[p], j);
      FLEXMBS_PETSC(VecRestoreArray(root_, &values));
    }
    FLEXMBS_PETSC(VecScatterBegin(scatter_, root_, input, INSERT_VALUES, SCATTER_REVERSE));
    FLEXMBS_PETSC(VecScatterEnd(scatter_, root_, input, INSERT_VALUES, SCATTER_REVERSE));
  }
  // Column j of Y at the rows' DOF `dofs` <- output (on rank 0; the others pass null).
  void Receive(Eigen::MatrixXd* Y, Index j, const std::vector<int>& dofs) {
    FLEXMBS_PETSC(VecScatterBegin(scatter_, output, root_, INSERT_VALUES, SCATTER_FORWARD));
    FLEXMBS_PETSC(VecScatterEnd(scatter_, output, root_, INSERT_VALUES, SCATTER_FORWARD));
    if (Y == nullptr) return;
    const PetscScalar* values = nullptr;
    FLEXMBS_PETSC(VecGetArrayRead(root_, &values));
    for (std::size_t p = 0; p < dofs.size(); ++p) (*Y)(dofs[p], j) = values[p];
    FLEXMBS_PETSC(VecRestoreArrayRead(root_, &values));
  }

  Vec input = nullptr;
  Vec output = nullptr;

 private:
  VecScatter scatter_ = nullptr;
  Vec root_ = nullptr;
};

// The rows of A owned here, every `stride`-th from the first (all: 1; the x DOF: 3), but those
// in `excluded` (ascending).
IS OwnedRows(Mat A, PetscInt stride, const std::vector<PetscInt>& excluded) {
  PetscInt begin = 0, end = 0;
  FLEXMBS_PETSC(MatGetOwnershipRange(A, &begin, &end));
  std::vector<PetscInt> rows;
  auto next = std::lower_bound(excluded.begin(), excluded.end(), begin);
  for (PetscInt r = begin; r < end; r += stride) {
    while (next != excluded.end() && *next < r) ++next;
    if (next != excluded.end() && *next == r) continue;
    rows.push_back(r);
  }
  IS is;
  FLEXMBS_PETSC(ISCreateGeneral(PETSC_COMM_WORLD, static_cast<PetscInt>(rows.size()), rows.data(), PETSC_COPY_VALUES,
                                &is));
  return is;
}

// The submatrix of A on its rows (and the same columns) that OwnedRows selects.
Mat Submatrix(Mat A, PetscInt stride, const std::vector<PetscInt>& excluded) {
  IS rows = OwnedRows(A, stride, excluded);
  Mat out;
  FLEXMBS_PETSC(MatCreateSubMatrix(A, rows, rows, MAT_INITIAL_MATRIX, &out));
  FLEXMBS_PETSC(ISDestroy(&rows));
  FLEXMBS_PETSC(MatSetOption(out, MAT_SYMMETRIC, PETSC_TRUE));
  return out;
}

}  // namespace

double PeakRssMb() {
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);
  return static_cast<double>(usage.ru_maxrss) / 1024.0;  // Linux reports KiB
}

Mat DistributedScalarMass(Mat M) { return Submatrix(M, 3, {}); }

// A symmetric operator of the model: products go through State::Apply.
class DistributedOperator final : public SymmetricOperator {
 public:
  DistributedOperator(DistributedModel::State* state, Which which) : state_(state), which_(which) {}
  Index rows() const override;
  Eigen::MatrixXd Times(const Eigen::MatrixXd& X) const override { return Product(X, false); }
  Eigen::MatrixXd AbsTimes(const Eigen::MatrixXd& X) const override { return Product(X, true); }
  Eigen::VectorXd Diagonal() const override;

 private:
  Eigen::MatrixXd Product(const Eigen::MatrixXd& X, bool absolute) const;

  DistributedModel::State* state_;
  Which which_;
};

struct DistributedModel::State {
  int rank = 0;
  Mat K = nullptr;
  Mat M = nullptr;
  bool scalar_mass = false;
  fem::MeshPart part;
  fem::MassMatrixKind mass_kind = fem::MassMatrixKind::kConsistent;
  Mat M_consistent = nullptr;  // M_s of the consistent mass, assembled when first asked for (lumped bodies)

  // Rank 0: the mesh DOF of each row of K, of M (whole M: one list; M_s: one per axis) and of
  // the consistent M_s; each mesh DOF's row of K (-1: clamped); the whole matrices' diagonals.
  std::vector<int> mesh_node;
  std::vector<std::vector<int>> K_rows;  // one list
  std::vector<std::vector<int>> M_rows;
  std::vector<std::vector<int>> scalar_rows;
  std::vector<Index> K_row_of_dof;
  Index num_clamped = 0;
  Eigen::VectorXd K_diagonal, M_diagonal, consistent_diagonal;

  std::unique_ptr<RowScatter> K_scatter, M_scatter, consistent_scatter;

  // The eigen-solve's factorisation of K (null: none), MUMPS's or the substructured one.
  Mat K_factor = nullptr;
  std::unique_ptr<SubstructuredFactor> K_substructured;
  // The factorisation for static solves: K without the rows `excluded` (K itself if none).
  std::optional<std::vector<PetscInt>> excluded;
  Mat K_ff = nullptr;    // owned if a submatrix
  Mat factor = nullptr;  // MUMPS Cholesky factor of K_ff: owned, or K_factor
  std::unique_ptr<RowScatter> ff_scatter;
  std::vector<int> ff_rows;  // rank 0: the mesh DOF of each row of K_ff

  DistributedModelStats stats;
  bool finished = false;
  DistributedOperator stiffness{this, kStiffness}, mass{this, kMass}, consistent{this, kConsistentMass};

  // Collective: the consistent M_s of a lumped body and its diagonal (rank 0, mesh numbering).
  void AssembleConsistentMass() {
    fem::DistributedMatrices consistent_matrices = fem::AssembleDistributed(part, fem::MassMatrixKind::kConsistent);
    Vec diagonal;
    FLEXMBS_PETSC(MatCreateVecs(consistent_matrices.mass, &diagonal, nullptr));
    FLEXMBS_PETSC(MatGetDiagonal(consistent_matrices.mass, diagonal));
    const Eigen::VectorXd d = GatherVector(diagonal, ModesOn::kRankZero);
    FLEXMBS_PETSC(VecDestroy(&diagonal));
    M_consistent = DistributedScalarMass(consistent_matrices.mass);
    fem::DestroyDistributed(&consistent_matrices);
    if (rank == 0) {
      consistent_diagonal.resize(d.size());
      for (Index p = 0; p < d.size(); ++p) consistent_diagonal(3 * mesh_node[static_cast<std::size_t>(p / 3)] + p % 3) = d(p);
    }
  }

  // Collective: Y = A X (|A| X if `absolute`) for the matrix `which`; X and Y on rank 0 only
  // (the others pass X null and get an empty Y).
  Eigen::MatrixXd Apply(Which which, bool absolute, Index columns, const Eigen::MatrixXd* X) {
    if (which == kConsistentMass && mass_kind == fem::MassMatrixKind::kConsistent) which = kMass;
    if (which == kConsistentMass && M_consistent == nullptr) AssembleConsistentMass();
    Mat A = which == kStiffness ? K : which == kMass ? M : M_consistent;
    std::unique_ptr<RowScatter>& scatter = which == kStiffness ? K_scatter : which == kMass ? M_scatter : consistent_scatter;
    if (!scatter) scatter = std::make_unique<RowScatter>(A);
    const std::vector<std::vector<int>>& rows = which == kStiffness ? K_rows : which == kMass ? M_rows : scalar_rows;
    Mat used = absolute ? AbsoluteCopy(A) : A;
    Eigen::MatrixXd Y;
    if (rank == 0) Y = Eigen::MatrixXd::Zero(X->rows(), columns);
    // Every axis of M_s (x) I_3 in turn (one pass for K or a whole M); |M_s| (x) I_3 = |M|.
    const std::size_t passes = which == kStiffness || (which == kMass && !scalar_mass) ? 1 : 3;
    static const std::vector<int> none;
    for (std::size_t pass = 0; pass < passes; ++pass) {
      const std::vector<int>& dofs = rank == 0 ? rows[pass] : none;
      for (Index j = 0; j < columns; ++j) {
        scatter->Send(X, j, dofs);
        FLEXMBS_PETSC(MatMult(used, scatter->input, scatter->output));
        scatter->Receive(rank == 0 ? &Y : nullptr, j, dofs);
      }
    }
    if (absolute) FLEXMBS_PETSC(MatDestroy(&used));
    return Y;
  }

  // Collective: the factorisation of K without the rows `rows_out` (ascending), unless held.
  void Factorize(const std::vector<PetscInt>& rows_out) {
    if (excluded && *excluded == rows_out) return;
    DestroyFactor();
    K_ff = rows_out.empty() ? K : Submatrix(K, 1, rows_out);
    if (rows_out.empty() && (K_factor != nullptr || K_substructured)) {
      factor = K_factor;  // the eigen-solve's (null: the substructured one)
    } else {
      factor = MumpsCholesky(K_ff, MumpsFactorization::kPositiveDefinite, "flexmbs_static_");
      ++stats.factorizations;
      FLEXMBS_CHECK(FactoredPositiveDefinite(factor),
                    "static solve: MUMPS Cholesky of K_ff failed: K_ff is not positive definite");
    }
    ff_scatter = std::make_unique<RowScatter>(K_ff);
    excluded = rows_out;
    if (rank == 0) {
      ff_rows.clear();
      auto next = rows_out.begin();
      for (std::size_t r = 0; r < K_rows[0].size(); ++r) {
        if (next != rows_out.end() && *next == static_cast<PetscInt>(r)) {
          ++next;
        } else {
          ff_rows.push_back(K_rows[0][r]);
        }
      }
    }
  }

  // Collective: X with K_ff X_f = F_f (rank 0's F and X; the others pass F null).
  Eigen::MatrixXd Solve(const std::vector<PetscInt>& rows_out, Index columns, const Eigen::MatrixXd* F) {
    Factorize(rows_out);
    Eigen::MatrixXd X;
    if (rank == 0) X = Eigen::MatrixXd::Zero(F->rows(), columns);
    static const std::vector<int> none;
    const std::vector<int>& dofs = rank == 0 ? ff_rows : none;
    for (Index j = 0; j < columns; ++j) {
      ff_scatter->Send(F, j, dofs);
      if (factor != nullptr) {
        FLEXMBS_PETSC(MatSolve(factor, ff_scatter->input, ff_scatter->output));
      } else {
        K_substructured->Solve(ff_scatter->input, ff_scatter->output);
      }
      ff_scatter->Receive(rank == 0 ? &X : nullptr, j, dofs);
    }
    stats.static_solves += static_cast<int>(columns);
    return X;
  }

  void DestroyFactor() {
    ff_scatter.reset();
    if (factor != nullptr && factor != K_factor) MatDestroy(&factor);
    factor = nullptr;
    if (K_ff != nullptr && K_ff != K) MatDestroy(&K_ff);
    K_ff = nullptr;
    excluded.reset();
  }

  // Collective with Serve on the other ranks: gathers every rank's peak resident set size.
  std::vector<double> GatherPeaks() {
    const double mine = PeakRssMb();
    PetscMPIInt size = 1;
    FLEXMBS_PETSC(MPI_Comm_size(PETSC_COMM_WORLD, &size));
    std::vector<double> all(static_cast<std::size_t>(rank == 0 ? size : 0));
    FLEXMBS_PETSC(MPI_Gather(&mine, 1, MPI_DOUBLE, all.data(), 1, MPI_DOUBLE, 0, PETSC_COMM_WORLD));
    return all;
  }
};

Index DistributedOperator::rows() const { return 3 * static_cast<Index>(state_->mesh_node.size()); }

Eigen::MatrixXd DistributedOperator::Product(const Eigen::MatrixXd& X, bool absolute) const {
  FLEXMBS_CHECK(state_->rank == 0 && X.rows() == rows(), "distributed products are asked for on rank 0, with all DOF");
  if (which_ == kStiffness) {
    // The held body's K: defined for vectors that vanish at the clamped DOF.
    for (std::size_t dof = 0; dof < state_->K_row_of_dof.size(); ++dof) {
      if (state_->K_row_of_dof[dof] < 0) {
        FLEXMBS_CHECK(X.row(static_cast<Index>(dof)).isZero(0.0),
                      "a product with the held body's K of a vector that moves a clamped DOF");
      }
    }
  }
  const auto start = std::chrono::steady_clock::now();
  Broadcast({kApply, which_, X.cols(), absolute ? 1 : 0});
  Eigen::MatrixXd Y = state_->Apply(which_, absolute, X.cols(), &X);
  state_->stats.product_columns += static_cast<int>(X.cols());
  state_->stats.product_seconds += SecondsSince(start);
  return Y;
}

Eigen::VectorXd DistributedOperator::Diagonal() const {
  FLEXMBS_CHECK(state_->rank == 0, "distributed products are asked for on rank 0");
  if (which_ == kStiffness) return state_->K_diagonal;
  if (which_ == kMass || state_->mass_kind == fem::MassMatrixKind::kConsistent) return state_->M_diagonal;
  if (state_->M_consistent == nullptr) Times(Eigen::MatrixXd::Zero(rows(), 0));  // assembles it
  return state_->consistent_diagonal;
}

DistributedModel::DistributedModel(Mat K, Mat M, bool scalar_mass, fem::MeshPart part, fem::MassMatrixKind mass_kind,
                                   std::vector<int> mesh_node, std::vector<int> clamped, Eigen::VectorXd K_diagonal,
                                   Eigen::VectorXd M_diagonal, Mat K_factor,
                                   std::unique_ptr<SubstructuredFactor> K_substructured)
    : state_(std::make_unique<State>()) {
  State& s = *state_;
  s.K_factor = K_factor;
  s.K_substructured = std::move(K_substructured);
  PetscMPIInt rank = 0;
  FLEXMBS_PETSC(MPI_Comm_rank(PETSC_COMM_WORLD, &rank));
  s.rank = rank;
  s.K = K;
  s.M = M;
  s.scalar_mass = scalar_mass;
  s.part = std::move(part);
  s.mass_kind = mass_kind;
  if (rank != 0) return;
  s.mesh_node = std::move(mesh_node);
  s.K_diagonal = std::move(K_diagonal);
  s.M_diagonal = std::move(M_diagonal);
  s.num_clamped = static_cast<Index>(clamped.size());
  const auto num_nodes = static_cast<int>(s.mesh_node.size());
  s.K_row_of_dof.assign(static_cast<std::size_t>(3 * num_nodes), -1);
  auto next = clamped.begin();
  std::vector<int> whole(static_cast<std::size_t>(3 * num_nodes)), K_rows;
  for (int dof = 0; dof < 3 * num_nodes; ++dof) {
    const int mesh_dof = 3 * s.mesh_node[static_cast<std::size_t>(dof / 3)] + dof % 3;
    whole[static_cast<std::size_t>(dof)] = mesh_dof;
    if (next != clamped.end() && *next == dof) {
      ++next;
      continue;
    }
    s.K_row_of_dof[static_cast<std::size_t>(mesh_dof)] = static_cast<Index>(K_rows.size());
    K_rows.push_back(mesh_dof);
  }
  s.K_rows = {std::move(K_rows)};
  s.scalar_rows.assign(3, std::vector<int>(static_cast<std::size_t>(num_nodes)));
  for (int v = 0; v < num_nodes; ++v) {
    const int node = s.mesh_node[static_cast<std::size_t>(v)];
    for (int a = 0; a < 3; ++a) s.scalar_rows[static_cast<std::size_t>(a)][static_cast<std::size_t>(v)] = 3 * node + a;
  }
  if (scalar_mass) {
    s.M_rows = s.scalar_rows;
  } else {
    s.M_rows = {std::move(whole)};
  }
}

DistributedModel::~DistributedModel() {
  State& s = *state_;
  if (s.rank == 0 && !s.finished) {
    try {
      Broadcast({kFinish, 0, 0, 0});
    } catch (const std::exception&) {  // MPI is broken: nothing more to tell the others
    }
  }
  s.DestroyFactor();
  if (s.K_factor != nullptr) MatDestroy(&s.K_factor);
  s.K_scatter.reset();
  s.M_scatter.reset();
  s.consistent_scatter.reset();
  MatDestroy(&s.K);
  MatDestroy(&s.M);
  if (s.M_consistent != nullptr) MatDestroy(&s.M_consistent);
}

const SymmetricOperator& DistributedModel::stiffness() const { return state_->stiffness; }
const SymmetricOperator& DistributedModel::mass() const { return state_->mass; }
const SymmetricOperator& DistributedModel::consistent_mass() const { return state_->consistent; }

Eigen::MatrixXd DistributedModel::SolveFixed(std::span<const Eigen::Index> fixed, const Eigen::MatrixXd& F) const {
  State& s = *state_;
  FLEXMBS_CHECK(s.rank == 0 && F.rows() == 3 * static_cast<Index>(s.mesh_node.size()),
                "distributed static solves are asked for on rank 0, with all DOF");
  std::vector<PetscInt> rows_out;
  Index clamped = 0;
  for (const Index dof : fixed) {
    const Index row = s.K_row_of_dof[static_cast<std::size_t>(dof)];
    if (row < 0) {
      ++clamped;
    } else {
      rows_out.push_back(static_cast<PetscInt>(row));
    }
  }
  FLEXMBS_CHECK(clamped == s.num_clamped, "a static solve of the held body must hold every clamped DOF");
  std::sort(rows_out.begin(), rows_out.end());
  const auto start = std::chrono::steady_clock::now();
  Broadcast({kSolve, static_cast<long long>(rows_out.size()), F.cols(), 0});
  FLEXMBS_PETSC(MPI_Bcast(rows_out.data(), static_cast<int>(rows_out.size()), MPIU_INT, 0, PETSC_COMM_WORLD));
  Eigen::MatrixXd X = s.Solve(rows_out, F.cols(), &F);
  s.stats.static_solve_seconds += SecondsSince(start);
  return X;
}

void DistributedModel::Serve() {
  State& s = *state_;
  FLEXMBS_CHECK(s.rank != 0, "rank 0 asks, the others serve");
  for (;;) {
    const Request request = Broadcast({});
    if (request[0] == kFinish) {
      if (request[3] != 0) s.GatherPeaks();
      return;
    }
    try {
      if (request[0] == kApply) {
        s.Apply(static_cast<Which>(request[1]), request[3] != 0, static_cast<Index>(request[2]), nullptr);
      } else {
        FLEXMBS_CHECK(request[0] == kSolve, "unknown request");
        std::vector<PetscInt> rows_out(static_cast<std::size_t>(request[1]));
        FLEXMBS_PETSC(MPI_Bcast(rows_out.data(), static_cast<int>(rows_out.size()), MPIU_INT, 0, PETSC_COMM_WORLD));
        s.Solve(rows_out, static_cast<Index>(request[2]), nullptr);
      }
    } catch (const std::exception&) {
      // Collective steps fail on every rank: rank 0 reports it, and ends the service.
    }
  }
}

DistributedModelStats DistributedModel::Finish() {
  State& s = *state_;
  FLEXMBS_CHECK(s.rank == 0 && !s.finished, "rank 0 finishes, once");
  Broadcast({kFinish, 0, 0, 1});
  s.finished = true;
  s.stats.peak_rss_mb = s.GatherPeaks();
  return s.stats;
}

}  // namespace flexmbs::eigensolvers
