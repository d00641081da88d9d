#include "reduction/dof_constraints.h"

#include <fmt/format.h>

#include "core/error.h"

namespace flexmbs::reduction {

FreeDofMap::FreeDofMap(Eigen::Index num_dofs) {
  if (num_dofs < 0) throw InputError(fmt::format("number of DOF {} must be >= 0", num_dofs));
  Build(std::vector<bool>(static_cast<std::size_t>(num_dofs), false));
}

FreeDofMap::FreeDofMap(Eigen::Index num_dofs, std::span<const Eigen::Index> fixed_dofs) {
  if (num_dofs < 0) throw InputError(fmt::format("number of DOF {} must be >= 0", num_dofs));
  std::vector<bool> fixed(static_cast<std::size_t>(num_dofs), false);
  for (const Eigen::Index dof : fixed_dofs) {
    if (dof < 0 || dof >= num_dofs) {
      throw InputError(fmt::format("fixed DOF {} is outside the model's DOF range [0, {})", dof, num_dofs));
    }
    fixed[static_cast<std::size_t>(dof)] = true;
  }
  Build(fixed);
}

FreeDofMap FreeDofMap::ClampNodes(Eigen::Index num_nodes, std::span<const int> nodes) {
  if (num_nodes < 0) throw InputError(fmt::format("number of nodes {} must be >= 0", num_nodes));
  std::vector<Eigen::Index> dofs;
  dofs.reserve(3 * nodes.size());
  for (const int node : nodes) {
    if (node < 0 || node >= num_nodes) {
      throw InputError(fmt::format("clamped node {} is outside the mesh's node range [0, {})", node, num_nodes));
    }
    for (int i = 0; i < 3; ++i) dofs.push_back(3 * static_cast<Eigen::Index>(node) + i);
  }
  return FreeDofMap(3 * num_nodes, dofs);
}

void FreeDofMap::Build(const std::vector<bool>& fixed) {
  reduced_of_full_.assign(fixed.size(), -1);
  free_dofs_.clear();
  for (std::size_t dof = 0; dof < fixed.size(); ++dof) {
    if (fixed[dof]) continue;
    reduced_of_full_[dof] = static_cast<Eigen::Index>(free_dofs_.size());
    free_dofs_.push_back(static_cast<Eigen::Index>(dof));
  }
}

Eigen::SparseMatrix<double> FreeDofMap::Restrict(const Eigen::SparseMatrix<double>& A) const {
  if (A.rows() != num_dofs() || A.cols() != num_dofs()) {
    throw InputError(fmt::format("matrix is {} x {}, the DOF map has {} DOF", A.rows(), A.cols(), num_dofs()));
  }
  const Eigen::Index n = num_free();
  // Count, then fill, column by column (columns stay sorted because the map is monotone).
  Eigen::SparseMatrix<double> R(n, n);
  Eigen::VectorXi counts = Eigen::VectorXi::Zero(n);
  for (Eigen::Index j = 0; j < n; ++j) {
    for (Eigen::SparseMatrix<double>::InnerIterator it(A, free_dofs_[static_cast<std::size_t>(j)]); it; ++it) {
      if (ReducedIndex(it.row()) >= 0) ++counts(j);
    }
  }
  R.reserve(counts);
  for (Eigen::Index j = 0; j < n; ++j) {
    for (Eigen::SparseMatrix<double>::InnerIterator it(A, free_dofs_[static_cast<std::size_t>(j)]); it; ++it) {
      const Eigen::Index i = ReducedIndex(it.row());
      if (i >= 0) R.insert(i, j) = it.value();
    }
  }
  R.makeCompressed();
  return R;
}

Eigen::MatrixXd FreeDofMap::RestrictVectors(const Eigen::MatrixXd& full) const {
  if (full.rows() != num_dofs()) {
    throw InputError(fmt::format("vector has {} rows, the DOF map has {} DOF", full.rows(), num_dofs()));
  }
  Eigen::MatrixXd reduced(num_free(), full.cols());
  for (Eigen::Index i = 0; i < num_free(); ++i) reduced.row(i) = full.row(free_dofs_[static_cast<std::size_t>(i)]);
  return reduced;
}

Eigen::MatrixXd FreeDofMap::Expand(const Eigen::MatrixXd& reduced) const {
  if (reduced.rows() != num_free()) {
    throw InputError(fmt::format("vector has {} rows, the DOF map has {} free DOF", reduced.rows(), num_free()));
  }
  Eigen::MatrixXd full = Eigen::MatrixXd::Zero(num_dofs(), reduced.cols());
  for (Eigen::Index i = 0; i < num_free(); ++i) full.row(free_dofs_[static_cast<std::size_t>(i)]) = reduced.row(i);
  return full;
}

}  // namespace flexmbs::reduction
