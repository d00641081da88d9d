#include "mbs/constraint_solver.h"

#include <fmt/format.h>

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <array>
#include <numeric>

#include "core/error.h"
#include "mbs/simulation_error.h"

namespace flexmbs::mbs {
namespace {

using Eigen::Index;
using Eigen::MatrixXd;
using Eigen::VectorXd;

// A constraint row takes part in a near-null vector of the scaled S when its component is at
// least this share of the vector's largest one (rows of one loop have comparable components
// after the unit-diagonal scaling; unrelated rows are at round-off).
constexpr double kInvolvedShare = 0.05;

/// The bodies whose velocities a joint's rows touch, ascending: kGround first for a joint to the
/// ground (Joint refuses two markers on one body).
std::array<int, 2> JointBodies(const Joint& joint) {
  return {std::min(joint.marker_i().body, joint.marker_j().body), std::max(joint.marker_i().body, joint.marker_j().body)};
}

/// The joints in the order the sparse LDL^T eliminates their rows: by the depth of their deeper
/// body (breadth first from the ground; a group of bodies not joined to the ground from its first
/// body), deepest first, ties in joint order. For a tree, a joint's rows then meet only rows of
/// joints at its body nearer the ground, which share that body already: no fill.
std::vector<int> JointEliminationOrder(const MultibodySystem& system) {
  const int num_bodies = system.num_bodies(), num_joints = system.num_joints();
  // The joints at each body (CSR).
  std::vector<int> start(static_cast<std::size_t>(num_bodies) + 1, 0), joints;
  for (int k = 0; k < num_joints; ++k) {
    for (const int b : JointBodies(system.joint(k))) {
      if (b != kGround) ++start[static_cast<std::size_t>(b) + 1];
    }
  }
  std::partial_sum(start.begin(), start.end(), start.begin());
  joints.resize(static_cast<std::size_t>(start.back()));
  std::vector<int> next(start.begin(), start.end() - 1);
  for (int k = 0; k < num_joints; ++k) {
    for (const int b : JointBodies(system.joint(k))) {
      if (b != kGround) joints[static_cast<std::size_t>(next[static_cast<std::size_t>(b)]++)] = k;
    }
  }
  std::vector<int> depth(static_cast<std::size_t>(num_bodies), -1), queue;
  queue.reserve(static_cast<std::size_t>(num_bodies));
  for (int k = 0; k < num_joints; ++k) {
    const std::array<int, 2> bodies = JointBodies(system.joint(k));
    if (bodies[0] == kGround && bodies[1] != kGround && depth[static_cast<std::size_t>(bodies[1])] < 0) {
      depth[static_cast<std::size_t>(bodies[1])] = 0;
      queue.push_back(bodies[1]);
    }
  }
  std::size_t head = 0;
  for (int root = 0;; ++root) {
    for (; head < queue.size(); ++head) {
      const std::size_t b = static_cast<std::size_t>(queue[head]);
      for (int j = start[b]; j < start[b + 1]; ++j) {
        for (const int other : JointBodies(system.joint(joints[static_cast<std::size_t>(j)]))) {
          if (other != kGround && depth[static_cast<std::size_t>(other)] < 0) {
            depth[static_cast<std::size_t>(other)] = depth[b] + 1;
            queue.push_back(other);
          }
        }
      }
    }
    while (root < num_bodies && depth[static_cast<std::size_t>(root)] >= 0) ++root;
    if (root == num_bodies) break;
    depth[static_cast<std::size_t>(root)] = 0;
    queue.push_back(root);
  }
  std::vector<int> key(static_cast<std::size_t>(num_joints), -1), order(static_cast<std::size_t>(num_joints));
  for (int k = 0; k < num_joints; ++k) {
    for (const int b : JointBodies(system.joint(k))) {
      if (b != kGround) key[static_cast<std::size_t>(k)] = std::max(key[static_cast<std::size_t>(k)], depth[static_cast<std::size_t>(b)]);
    }
  }
  std::iota(order.begin(), order.end(), 0);
  std::stable_sort(order.begin(), order.end(),
                   [&](int a, int b) { return key[static_cast<std::size_t>(a)] > key[static_cast<std::size_t>(b)]; });
  return order;
}

}  // namespace

ConstraintSolver::ConstraintSolver(const MultibodySystem& system, double t, const ConstVectorRef& y,
                                   const Eigen::MatrixXd& G, SolverRows rows)
    : system_(system) {
  const int num_bodies = system.num_bodies();
  mass_factors_.reserve(static_cast<std::size_t>(num_bodies));
  if (system.planar()) kept_.reserve(static_cast<std::size_t>(num_bodies));
  for (int b = 0; b < num_bodies; ++b) {
    if (system.planar()) {
      kept_.push_back(system.KeptVelocities(b));
      mass_factors_.emplace_back(system.BodyMassMatrix(b, y)(kept_.back(), kept_.back()));
    } else {
      mass_factors_.emplace_back(system.BodyMassMatrix(b, y));
    }
    if (mass_factors_.back().info() != Eigen::Success) {
      throw SimulationError(t, fmt::format("t = {:.9g} s: body '{}': mass matrix is not positive definite", t,
                                           system.body(b).name()));
    }
  }
  const Index m = G.rows(), nu = system.num_velocities();
  FLEXMBS_CHECK(m == system.num_constraints() && G.cols() == nu,
                "ConstraintSolver: G is not the system's constraint Jacobian");
  if (rows == SolverRows::kKept) {
    rows_ = system.KeptConstraints();
  } else {
    rows_.resize(static_cast<std::size_t>(m));
    std::iota(rows_.begin(), rows_.end(), Index{0});
  }
  position_in_rows_.assign(static_cast<std::size_t>(m), -1);
  for (std::size_t i = 0; i < rows_.size(); ++i) position_in_rows_[static_cast<std::size_t>(rows_[i])] = static_cast<Index>(i);
  SetPattern();
  FormBodyBlocks(G);
  if (!rows_.empty()) FactoriseSchur();
}

void ConstraintSolver::SetPattern() {
  const MultibodySystem& system = system_;
  const int num_bodies = system.num_bodies();
  const Index m = system.num_constraints(), nu = system.num_velocities();
  body_row_start_.assign(static_cast<std::size_t>(num_bodies) + 1, 0);
  G_.resize(m, nu);
  G_.outerIndexPtr()[0] = 0;
  for (int k = 0; k < system.num_joints(); ++k) {
    const Index first = system.constraint_offset(k), count = system.joint(k).num_equations();
    Index row_nonzeros = 0;
    for (const int b : JointBodies(system.joint(k))) {
      if (b == kGround) continue;
      body_row_start_[static_cast<std::size_t>(b) + 1] += count;
      row_nonzeros += NumColumns(b);
    }
    for (Index row = first; row < first + count; ++row) {
      G_.outerIndexPtr()[row + 1] = static_cast<int>(G_.outerIndexPtr()[row] + row_nonzeros);
    }
  }
  const Index nonzeros = G_.outerIndexPtr()[m];
  G_.resizeNonZeros(nonzeros);
  std::partial_sum(body_row_start_.begin(), body_row_start_.end(), body_row_start_.begin());
  body_rows_.resize(static_cast<std::size_t>(body_row_start_.back()));
  std::vector<Index> next_row(body_row_start_.begin(), body_row_start_.end() - 1);
  row_at_body_.resize(static_cast<std::size_t>(m));
  for (int k = 0; k < system.num_joints(); ++k) {
    const std::array<int, 2> bodies = JointBodies(system.joint(k));
    const Index first = system.constraint_offset(k), count = system.joint(k).num_equations();
    for (Index row = first; row < first + count; ++row) {
      int* inner = G_.innerIndexPtr() + G_.outerIndexPtr()[row];
      for (std::size_t slot = 0; slot < 2; ++slot) {
        const int b = bodies[slot];
        if (b == kGround) continue;
        Index& next = next_row[static_cast<std::size_t>(b)];
        row_at_body_[static_cast<std::size_t>(row)][slot] = {b, next - body_row_start_[static_cast<std::size_t>(b)]};
        body_rows_[static_cast<std::size_t>(next++)] = row;
        const Index offset = system.velocity_block(b).start;
        if (kept_.empty()) {
          for (Index column = 0; column < system.velocity_block(b).size; ++column) *inner++ = static_cast<int>(offset + column);
        } else {
          for (const Index column : kept_[static_cast<std::size_t>(b)]) *inner++ = static_cast<int>(offset + column);
        }
      }
    }
  }
  Minv_GT_.resize(nu, m);
  Minv_GT_.resizeNonZeros(nonzeros);
  std::copy(G_.outerIndexPtr(), G_.outerIndexPtr() + m + 1, Minv_GT_.outerIndexPtr());
  std::copy(G_.innerIndexPtr(), G_.innerIndexPtr() + nonzeros, Minv_GT_.innerIndexPtr());
}

void ConstraintSolver::FormBodyBlocks(const Eigen::MatrixXd& G) {
  // Per body b with rows R_b: G_b = G(R_b, b's columns), Y = L_b^-1 G_b^T (M_b = L_b L_b^T),
  // M_b^-1 G_b^T = L_b^-T Y, and G_b M_b^-1 G_b^T = Y^T Y.
  const int num_bodies = system_.num_bodies();
  schur_block_start_.assign(static_cast<std::size_t>(num_bodies) + 1, 0);
  for (std::size_t b = 0; b < static_cast<std::size_t>(num_bodies); ++b) {
    const Index count = body_row_start_[b + 1] - body_row_start_[b];
    schur_block_start_[b + 1] = schur_block_start_[b] + count * count;
  }
  schur_blocks_.assign(static_cast<std::size_t>(schur_block_start_.back()), 0.0);
  for (int b = 0; b < num_bodies; ++b) {
    const std::size_t ub = static_cast<std::size_t>(b);
    const Index first = body_row_start_[ub], count = body_row_start_[ub + 1] - first;
    if (count == 0) continue;
    const Index offset = system_.velocity_block(b).start, n = system_.velocity_block(b).size;
    const Eigen::Map<const Eigen::Matrix<Index, Eigen::Dynamic, 1>> R_b(body_rows_.data() + first, count);
    // A planar scene's body: M_b^-1 is S_b M_b(s, s)^-1 S_b^T over its kept columns s, and G_, Minv_GT_
    // hold those columns only.
    const MatrixXd G_b_T = kept_.empty() ? MatrixXd(G(R_b, Eigen::seqN(offset, n)).transpose())
                                         : MatrixXd(G(R_b, Eigen::seqN(offset, n))(Eigen::all, kept_[ub]).transpose());
    const MatrixXd Y = mass_factors_[ub].matrixL().solve(G_b_T);
    const MatrixXd Minv_G_b_T = mass_factors_[ub].matrixU().solve(Y);
    const Index first_column = offset + (kept_.empty() ? 0 : kept_[ub].front()), columns = G_b_T.rows();
    for (Index l = 0; l < count; ++l) {
      const Index row = R_b(l);
      // b's columns open the row if b is its joint's first body, else close it.
      const Index start = G_.innerIndexPtr()[G_.outerIndexPtr()[row]] == first_column
                              ? G_.outerIndexPtr()[row]
                              : G_.outerIndexPtr()[row + 1] - columns;
      Eigen::Map<VectorXd>(G_.valuePtr() + start, columns) = G_b_T.col(l);
      Eigen::Map<VectorXd>(Minv_GT_.valuePtr() + start, columns) = Minv_G_b_T.col(l);
    }
    Eigen::Map<MatrixXd>(schur_blocks_.data() + schur_block_start_[ub], count, count).noalias() =
        Y.transpose().lazyProduct(Y);  // coefficient by coefficient: symmetric to the bit
  }
}

void ConstraintSolver::FactoriseSchur() {
  // S's diagonal and the scaling to unit diagonal.
  const int num_bodies = system_.num_bodies();
  const Index r = static_cast<Index>(rows_.size());
  VectorXd diagonal = VectorXd::Zero(r);
  for (int b = 0; b < num_bodies; ++b) {
    const std::size_t ub = static_cast<std::size_t>(b);
    const auto S_b = BodySchur(b);
    for (Index l = 0; l < S_b.rows(); ++l) {
      const Index i = position_in_rows_[static_cast<std::size_t>(body_rows_[static_cast<std::size_t>(body_row_start_[ub] + l)])];
      if (i >= 0) diagonal(i) += S_b(l, l);
    }
  }
  if (diagonal.minCoeff() <= 0.0) smallest_pivot_ = 0.0;  // a row of G that moves nothing
  inverse_scale_ = (diagonal.array() > 0.0).select(diagonal.cwiseSqrt().cwiseInverse(), 1.0);

  if (r > kDenseSchurRows) {
    for (const int k : JointEliminationOrder(system_)) {
      const Index first = system_.constraint_offset(k);
      for (Index row = first; row < first + system_.joint(k).num_equations(); ++row) {
        const Index i = position_in_rows_[static_cast<std::size_t>(row)];
        if (i >= 0) elimination_order_.push_back(i);
      }
    }
    Eigen::SparseMatrix<double> S_scaled;
    EliminationOrderedScaledSchur(S_scaled);
    sparse_factor_.compute(S_scaled);
    const double pivot = sparse_factor_.info() == Eigen::Success ? sparse_factor_.vectorD().minCoeff() : 0.0;
    if (pivot >= kPivotedCheckBelow) {
      pivoted_ = false;
      smallest_pivot_ = std::min(smallest_pivot_, pivot);
      return;
    }
  }
  dense_factor_.compute(scaled_schur());
  smallest_pivot_ = std::min(smallest_pivot_, dense_factor_.vectorD().minCoeff());
}

Eigen::Index ConstraintSolver::NumColumns(int b) const {
  return kept_.empty() ? system_.velocity_block(b).size : static_cast<Index>(kept_[static_cast<std::size_t>(b)].size());
}

Eigen::Map<const Eigen::MatrixXd> ConstraintSolver::BodySchur(int b) const {
  const std::size_t ub = static_cast<std::size_t>(b);
  const Index count = body_row_start_[ub + 1] - body_row_start_[ub];
  return {schur_blocks_.data() + schur_block_start_[ub], count, count};
}

template <typename Add>
void ConstraintSolver::ForEachScaledSchurEntry(Add add) const {
  for (int b = 0; b < system_.num_bodies(); ++b) {
    const Index first = body_row_start_[static_cast<std::size_t>(b)];
    const auto S_b = BodySchur(b);
    for (Index l1 = 0; l1 < S_b.rows(); ++l1) {
      const Index i = position_in_rows_[static_cast<std::size_t>(body_rows_[static_cast<std::size_t>(first + l1)])];
      if (i < 0) continue;
      for (Index l2 = 0; l2 <= l1; ++l2) {
        const Index j = position_in_rows_[static_cast<std::size_t>(body_rows_[static_cast<std::size_t>(first + l2)])];
        if (j >= 0) add(i, j, S_b(l1, l2) * inverse_scale_(i) * inverse_scale_(j));
      }
    }
  }
}

void ConstraintSolver::EliminationOrderedScaledSchur(Eigen::SparseMatrix<double>& S) const {
  const Index r = static_cast<Index>(rows_.size());
  std::vector<Index> order_of(static_cast<std::size_t>(r));  // per index into rows_: its place in the order
  for (Index e = 0; e < r; ++e) order_of[static_cast<std::size_t>(elimination_order_[static_cast<std::size_t>(e)])] = e;
  // Column e: the rows f <= e that share a body with it, summed over the bodies they share (at
  // most sum_b |R_b|^2 entries).
  S.resize(r, r);
  S.resizeNonZeros(static_cast<Index>(schur_blocks_.size()));
  int* outer = S.outerIndexPtr();
  int* inner = S.innerIndexPtr();
  double* values = S.valuePtr();
  std::vector<double> column(static_cast<std::size_t>(r), 0.0);
  std::vector<bool> seen(static_cast<std::size_t>(r), false);
  int nonzeros = 0;
  outer[0] = 0;
  for (Index e = 0; e < r; ++e) {
    const Index i = elimination_order_[static_cast<std::size_t>(e)], row = rows_[static_cast<std::size_t>(i)];
    int* pattern = inner + nonzeros;
    int* pattern_end = pattern;
    for (const RowAtBody& at : row_at_body_[static_cast<std::size_t>(row)]) {
      if (at.body == kGround) continue;
      const Index first = body_row_start_[static_cast<std::size_t>(at.body)];
      const auto S_b = BodySchur(at.body);
      for (Index l = 0; l < S_b.rows(); ++l) {
        const Index j = position_in_rows_[static_cast<std::size_t>(body_rows_[static_cast<std::size_t>(first + l)])];
        if (j < 0) continue;
        const std::size_t f = static_cast<std::size_t>(order_of[static_cast<std::size_t>(j)]);
        if (static_cast<Index>(f) > e) continue;
        if (!seen[f]) {
          seen[f] = true;
          *pattern_end++ = static_cast<int>(f);
        }
        column[f] += S_b(at.index, l) * inverse_scale_(i) * inverse_scale_(j);
      }
    }
    std::sort(pattern, pattern_end);
    for (int* f = pattern; f != pattern_end; ++f) {
      values[nonzeros++] = column[static_cast<std::size_t>(*f)];
      column[static_cast<std::size_t>(*f)] = 0.0;
      seen[static_cast<std::size_t>(*f)] = false;
    }
    outer[e + 1] = nonzeros;
  }
  S.resizeNonZeros(nonzeros);
}

Eigen::MatrixXd ConstraintSolver::scaled_schur() const {
  const Index r = static_cast<Index>(rows_.size());
  MatrixXd S = MatrixXd::Zero(r, r);
  ForEachScaledSchurEntry([&](Index i, Index j, double value) {
    S(i, j) += value;
    if (i != j) S(j, i) += value;
  });
  return S;
}

Eigen::VectorXd ConstraintSolver::SolveMass(const ConstVectorRef& r) const {
  Eigen::VectorXd out(r.size());
  for (int b = 0; b < system_.num_bodies(); ++b) {
    const Index offset = system_.velocity_block(b).start, n = system_.velocity_block(b).size;
    SolveBodyMass(b, r.segment(offset, n), out.segment(offset, n));
  }
  return out;
}

void ConstraintSolver::SolveBodyMass(int b, const ConstVectorRef& r_b, Eigen::Ref<Eigen::VectorXd> out_b) const {
  const std::size_t ub = static_cast<std::size_t>(b);
  if (kept_.empty()) {
    out_b = mass_factors_[ub].solve(r_b);
    return;
  }
  out_b.setZero();
  const Eigen::VectorXd solved = mass_factors_[ub].solve(r_b(kept_[ub]).eval());
  out_b(kept_[ub]) = solved;
}

Eigen::MatrixXd ConstraintSolver::SolveMassColumns(const Eigen::MatrixXd& R) const {
  MatrixXd out = MatrixXd::Zero(R.rows(), R.cols());
  for (int b = 0; b < system_.num_bodies(); ++b) {
    const Index offset = system_.velocity_block(b).start, n = system_.velocity_block(b).size;
    for (Index j = 0; j < R.cols(); ++j) {
      const auto column = R.col(j).segment(offset, n);
      if (!column.isZero(0.0)) SolveBodyMass(b, column, out.col(j).segment(offset, n));
    }
  }
  return out;
}

Eigen::VectorXd ConstraintSolver::SolveSchur(const ConstVectorRef& r) const {
  Eigen::VectorXd out = Eigen::VectorXd::Zero(r.size());
  if (rows_.empty()) return out;
  VectorXd scaled = inverse_scale_.cwiseProduct(r(rows_));
  if (pivoted_) {
    scaled = dense_factor_.solve(scaled);
  } else {
    scaled(elimination_order_) = sparse_factor_.solve(VectorXd(scaled(elimination_order_)));
  }
  out(rows_) = inverse_scale_.cwiseProduct(scaled);
  return out;
}

std::vector<int> ConstraintSolver::DependentJoints(double pivot) const {
  std::vector<int> joints;
  if (rows_.empty()) return joints;
  const MatrixXd S = scaled_schur();
  const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eigen(S);
  for (Index i = 0; i < S.rows() && (i == 0 || eigen.eigenvalues()(i) < pivot); ++i) {
    const Eigen::VectorXd v = eigen.eigenvectors().col(i).cwiseAbs();
    for (Index row = 0; row < v.size(); ++row) {
      if (v(row) >= kInvolvedShare * v.maxCoeff()) {
        joints.push_back(system_.JointOfConstraint(rows_[static_cast<std::size_t>(row)]));
      }
    }
  }
  std::sort(joints.begin(), joints.end());
  joints.erase(std::unique(joints.begin(), joints.end()), joints.end());
  return joints;
}

std::string ConstraintSolver::DescribeRankDeficiency(double t, double pivot) const {
  std::string names;
  for (const int joint : DependentJoints(pivot)) {
    names += fmt::format("{}'{}'", names.empty() ? "" : ", ", system_.joint(joint).name());
  }
  return fmt::format("t = {:.9g} s: the constraint Jacobian is rank deficient (smallest relative pivot {:.3g}, "
                     "limit {:.3g}) in joints {}: redundant joints, or a closed loop in a singular configuration",
                     t, smallest_pivot_, pivot, names);
}

void ConstraintSolver::RequireFullRank(double t, double pivot) const {
  if (!(smallest_pivot_ >= pivot)) throw SimulationError(t, DescribeRankDeficiency(t, pivot));
}

}  // namespace flexmbs::mbs
