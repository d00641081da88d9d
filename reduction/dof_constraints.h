#pragma once

#include <Eigen/Core>
#include <Eigen/SparseCore>
#include <span>
#include <vector>

namespace flexmbs::reduction {

/// The free DOFs of a model with some DOFs fixed to zero (homogeneous Dirichlet conditions,
/// e.g. a clamped node set). DOF 3 n + i is node n along axis i (fem::Mesh). Restricting K
/// and M to the free DOFs gives the constrained eigenproblem K_ff phi_f = lambda M_ff phi_f;
/// expanding puts zeros on the fixed DOFs.
class FreeDofMap {
 public:
  /// All `num_dofs` DOFs free.
  explicit FreeDofMap(Eigen::Index num_dofs);
  /// `fixed_dofs`: in any order, duplicates allowed. Throws InputError naming the DOF if one
  /// is outside [0, num_dofs).
  FreeDofMap(Eigen::Index num_dofs, std::span<const Eigen::Index> fixed_dofs);

  /// All three DOFs of every node in `nodes` fixed (a clamped node set) in a model of
  /// `num_nodes` nodes. Throws InputError naming the node if one is outside [0, num_nodes).
  static FreeDofMap ClampNodes(Eigen::Index num_nodes, std::span<const int> nodes);

  Eigen::Index num_dofs() const { return static_cast<Eigen::Index>(reduced_of_full_.size()); }
  Eigen::Index num_free() const { return static_cast<Eigen::Index>(free_dofs_.size()); }
  Eigen::Index num_fixed() const { return num_dofs() - num_free(); }

  /// The full DOF of each reduced DOF, ascending.
  const std::vector<Eigen::Index>& free_dofs() const { return free_dofs_; }
  /// The reduced index of full DOF `dof`, or -1 if it is fixed.
  Eigen::Index ReducedIndex(Eigen::Index dof) const { return reduced_of_full_[static_cast<std::size_t>(dof)]; }
  bool IsFixed(Eigen::Index dof) const { return ReducedIndex(dof) < 0; }

  /// A_ff: the rows and columns of the free DOFs (A: num_dofs x num_dofs). Keeps the storage
  /// of A (full stays full).
  Eigen::SparseMatrix<double> Restrict(const Eigen::SparseMatrix<double>& A) const;
  /// The free entries of a full-size vector (or of each column of a full-size matrix).
  Eigen::MatrixXd RestrictVectors(const Eigen::MatrixXd& full) const;
  /// A full-size vector (or matrix, column by column) from its free entries, zero on fixed DOFs.
  Eigen::MatrixXd Expand(const Eigen::MatrixXd& reduced) const;

 private:
  void Build(const std::vector<bool>& fixed);

  std::vector<Eigen::Index> free_dofs_;
  std::vector<Eigen::Index> reduced_of_full_;
};

}  // namespace flexmbs::reduction
