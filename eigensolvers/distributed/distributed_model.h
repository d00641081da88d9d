#pragma once
// A body's distributed K and M kept after the distributed eigen-solve (SolveModesDistributed),
// so that rank 0 finishes the basis and the SID data with their products and static solves
// (ModelOperators) while no rank holds K and M whole. Rank 0 asks; every other rank serves
// its rows until rank 0 is done (Serve / Finish).

#include <Eigen/Core>
#include <memory>
#include <span>
#include <vector>

#include "fem/element_integrator.h"
#include "fem/mesh_partition.h"
#include "eigensolvers/model_operators.h"
#include "eigensolvers/distributed/substructured_factor.h"

// PETSc's matrix type (`Mat` is a pointer to it), declared here so that no PETSc header
// appears in this public header.
struct _p_Mat;

namespace flexmbs::eigensolvers {

/// The scalar mass matrix M_s (N x N) of a distributed M = M_s (x) I_3 (3N x 3N, block size 3):
/// its rows and columns of the x DOF, each rank keeping its nodes' rows. Collective; the caller
/// destroys it.
_p_Mat* DistributedScalarMass(_p_Mat* M);

/// This process's peak resident set size so far [MB] (getrusage).
double PeakRssMb();

/// What the products and static solves after the eigen-solve cost, and each rank's memory.
struct DistributedModelStats {
  int product_columns = 0;            ///< columns multiplied by K, M, |K| or |M|
  double product_seconds = 0.0;       ///< rank 0's wall time in those products [s]
  /// MUMPS Cholesky factorisations of K_ff made for static solves (a given one of the eigen-solve
  /// is counted there, not here)
  int factorizations = 0;
  int static_solves = 0;              ///< right-hand sides solved
  double static_solve_seconds = 0.0;  ///< rank 0's wall time in factorisations and solves [s]
  /// Per rank (on rank 0 only; filled by Finish): its peak resident set size so far [MB].
  std::vector<double> peak_rss_mb;
};

/// The distributed K and M of a body on every rank, in the partition's DOF numbering (3 global
/// node + axis, fem::MeshPartition::new_node); on rank 0 the ModelOperators of the body in the
/// mesh's numbering. What it holds, row-distributed as the eigen-solve had it:
///  * K: the held body's K_oo (the clamped DOF removed), or the free body's K;
///  * M: the free body's M, or, for a held body, the scalar mass matrix M_s of the whole body
///    (N x N, M = M_s (x) I_3: 1/9 of M's entries), whose products give the whole M's.
/// Static solves factorise K_ff (K_oo itself, or a copy with the extra fixed DOF removed) by
/// MUMPS Cholesky, distributed, once per set of fixed DOF; the factor is kept for the next
/// solve with the same DOF. Given the eigen-solve's factorisation of K (a held body's, at
/// sigma = 0), the solves with K itself use it instead. A consistent mass for a lumped body is
/// assembled, distributed, when first asked for. Rank 0 calls the ModelOperators methods; every
/// other rank calls Serve(), which carries out rank 0's requests until rank 0 calls Finish() or
/// destroys the model.
class DistributedModel final : public ModelOperators {
 public:
  /// On every rank; takes K and M (PETSc matrices, as above) and destroys them at the end.
  /// `scalar_mass`: M is M_s. `part`: this rank's elements, for a consistent mass if
  /// `mass_kind` is lumped. On rank 0 only: `mesh_node` (per partition node, its mesh node),
  /// `clamped` (the removed DOF, partition numbering, ascending), and the diagonals of the
  /// whole K and M in the mesh's numbering. `K_factor` (on every rank, or null on every rank):
  /// a MUMPS Cholesky factorisation of this K (SolveDistributedEigenproblem's `K_factor`), taken
  /// and destroyed at the end like K and M; or `K_substructured`, its substructured one.
  DistributedModel(_p_Mat* K, _p_Mat* M, bool scalar_mass, fem::MeshPart part, fem::MassMatrixKind mass_kind,
                   std::vector<int> mesh_node, std::vector<int> clamped, Eigen::VectorXd K_diagonal,
                   Eigen::VectorXd M_diagonal, _p_Mat* K_factor = nullptr,
                   std::unique_ptr<SubstructuredFactor> K_substructured = nullptr);
  /// Collective: rank 0 ends the other ranks' Serve (if Finish has not), then every rank
  /// destroys its matrices and factors.
  ~DistributedModel() override;
  DistributedModel(const DistributedModel&) = delete;
  DistributedModel& operator=(const DistributedModel&) = delete;

  /// Rank 0 only (each call is collective with the others' Serve).
  const SymmetricOperator& stiffness() const override;
  const SymmetricOperator& mass() const override;
  const SymmetricOperator& consistent_mass() const override;
  Eigen::MatrixXd SolveFixed(std::span<const Eigen::Index> fixed, const Eigen::MatrixXd& F) const override;

  /// Ranks other than 0: carries out rank 0's requests until it calls Finish. A request that
  /// fails here fails on rank 0 too (the steps are collective): this rank carries on.
  void Serve();
  /// Rank 0: ends the other ranks' Serve and returns the accounting, with every rank's peak
  /// resident set size. Collective with the others' Serve; once.
  DistributedModelStats Finish();

  struct State;  // PETSc objects and the numbering (distributed_model.cc)

 private:
  std::unique_ptr<State> state_;
};

}  // namespace flexmbs::eigensolvers
