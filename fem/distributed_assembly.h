#pragma once

#include <Eigen/Core>

#include "fem/element_integrator.h"
#include "fem/mesh.h"
#include "fem/mesh_partition.h"

// PETSc's matrix type (`Mat` is a pointer to it), declared here so that no PETSc header
// appears in this public header.
struct _p_Mat;

namespace flexmbs::fem {

/// K and M as row-distributed PETSc AIJ matrices on PETSC_COMM_WORLD (block size 3). The
/// caller owns them: DestroyDistributed (collective) before PETSc is finalised.
struct DistributedMatrices {
  _p_Mat* stiffness = nullptr;  ///< K [N/m]
  _p_Mat* mass = nullptr;       ///< M [kg]
};

/// Collective on PETSC_COMM_WORLD (PETSc must be initialised): each rank computes the element
/// matrices of its own `part` only and adds them at the global DOF 3 global_node + i; rank r
/// owns the DOF rows of part.owned_nodes (the parts' owned ranges must follow each other in
/// rank order and cover all part.num_global_nodes nodes), and contributions to rows of other
/// ranks are sent by PETSc's assembly. No rank holds more than its elements, the nodes they use
/// and its rows. Preallocation is exact (a first pass inserts the element patterns into a
/// MATPREALLOCATOR). The result equals AssembleSystem's in the partition's node numbering to
/// round-off, on any number of ranks. Throws InputError (on every rank) for an element with a
/// non-positive Jacobian on any rank, InternalError for a PETSc failure.
DistributedMatrices AssembleDistributed(const MeshPart& part, MassMatrixKind mass_kind);

/// The same with every rank holding the whole `mesh`: rank r assembles its part of
/// PartitionInMeshOrder(mesh, size), which keeps the mesh's node numbering.
DistributedMatrices AssembleDistributed(const Mesh& mesh, MassMatrixKind mass_kind);

/// Collective: destroys both matrices and sets the pointers to null.
void DestroyDistributed(DistributedMatrices* matrices);

}  // namespace flexmbs::fem
