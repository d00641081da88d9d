#pragma once
// Sending each rank its share of a mesh partitioned on rank 0 (MPI point-to-point).

#include "fem/mesh_partition.h"

namespace flexmbs::fem {

/// Collective on PETSC_COMM_WORLD (PETSc must be initialised; partition.parts must equal the
/// number of ranks): rank 0 extracts every part of `partition` of `mesh` and sends part r
/// (element connectivity, the coordinates and tags of the nodes it uses, its owned node range)
/// to rank r; every rank returns its own part. Only rank 0 reads `mesh` and `partition`: the
/// other ranks may pass empty ones. Throws InternalError for an MPI failure.
MeshPart ScatterMeshParts(const Mesh& mesh, const MeshPartition& partition);

}  // namespace flexmbs::fem
