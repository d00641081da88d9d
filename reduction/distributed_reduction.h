#pragma once
// The MPI path of `flexmbs reduce` for modal bases: rank 0 meshes and partitions the elements,
// every rank assembles its share of K and M into distributed PETSc matrices, the clamped DOF
// are removed there, SLEPc solves, and the modes come back to rank 0 only; the matrices may be
// kept for the products and static solves after the solve (distributed_model.h).

#include <Eigen/Core>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "fem/element_integrator.h"
#include "fem/mesh.h"
#include "eigensolvers/distributed/distributed_model.h"
#include "eigensolvers/eigensolver.h"

namespace flexmbs::reduction {

/// What one rank held and did in SolveModesDistributed.
struct RankShare {
  int rank = 0;
  Eigen::Index elements = 0;   ///< elements it integrated
  Eigen::Index nodes = 0;      ///< nodes it received (its elements' nodes)
  Eigen::Index rows = 0;       ///< DOF rows of K and M it assembled and owns (before clamping)
  Eigen::Index nonzeros = 0;   ///< entries of K stored on it (its rows)
  double peak_rss_mb = 0.0;    ///< its peak resident set size after the solve [MB] (getrusage)
};

/// Accounting of SolveModesDistributed; `ranks` is filled on rank 0 only (one per rank).
struct DistributedSolveStats {
  std::vector<RankShare> ranks;
  double partition_seconds = 0.0;  ///< partitioning on rank 0 and sending the parts
  double assembly_seconds = 0.0;   ///< element integration and PETSc assembly
  double solve_seconds = 0.0;      ///< clamping, MUMPS factorisations, Krylov-Schur, Sturm check, residuals
  double gather_seconds = 0.0;     ///< the modes to rank 0, back in the mesh's DOF numbering
};

/// Collective on PETSC_COMM_WORLD (a SlepcSession must be open). Rank 0 partitions `mesh` by
/// fem::PartitionByCoordinateBisection and sends each rank its elements and their nodes
/// (fem::ScatterMeshParts); each rank assembles them (fem::AssembleDistributed, `mass_kind`);
/// the DOF `clamped_dofs` (mesh numbering) are removed from the distributed K and M (their
/// submatrix on the other DOF, no rank gathering it); SolveDistributedEigenproblem solves as
/// `options` asks. Only rank 0 reads `mesh` and `clamped_dofs`; other ranks may pass empty
/// ones. Returns on every rank the eigenvalues, residuals and checks; on rank 0 the modes,
/// full length in the mesh's DOF numbering with zero rows at the clamped DOF (other ranks: no
/// rows). Throws (on every rank) the InputErrors of the assembly and the solve.
/// With `keep`, the distributed matrices are not destroyed after the solve but handed, as a
/// DistributedModel, to `*keep` on every rank (the held body's K_oo and the whole body's M_s,
/// or the free body's K and M), so that rank 0 can finish the basis and the SID data with
/// products and static solves while no rank holds K and M whole. For a held body's lowest modes
/// the eigen-solve then shifts by 0 and its MUMPS factorisation of K_oo goes to the model too
/// (SolveDistributedEigenproblem's `K_factor`), where it serves the static solves.
eigensolvers::EigenSolution SolveModesDistributed(const fem::Mesh& mesh, fem::MassMatrixKind mass_kind,
                                    const std::vector<int>& clamped_dofs, const eigensolvers::EigenOptions& options,
                                    DistributedSolveStats* stats, std::unique_ptr<eigensolvers::DistributedModel>* keep = nullptr);

/// Collective: if `error_on_root` (rank 0's) is not empty, every rank throws InputError with
/// it. For errors on rank 0 before a collective step, so that no rank waits for it forever.
void ShareRootError(const std::string& error_on_root);

}  // namespace flexmbs::reduction
