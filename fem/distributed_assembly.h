#pragma once

#include <Eigen/Core>

#include "fem/element_integrator.h"
#include "fem/mesh.h"

// PETSc's matrix type (`Mat` is a pointer to it), declared here so that no PETSc header
// appears in this public header.
struct _p_Mat;

namespace flexmbs::fem {

/// A contiguous index range [begin, end).
struct IndexRange {
  Eigen::Index begin = 0;
  Eigen::Index end = 0;
};

/// Part `part` of an even split of `count` items into `parts` contiguous ranges (the first
/// count % parts ranges are one longer).
IndexRange EvenPartition(Eigen::Index count, int parts, int part);

/// K and M as row-distributed PETSc AIJ matrices on PETSC_COMM_WORLD (block size 3). The
/// caller owns them: DestroyDistributed (collective) before PETSc is finalised.
struct DistributedMatrices {
  _p_Mat* stiffness = nullptr;  ///< K [N/m]
  _p_Mat* mass = nullptr;       ///< M [kg]
};

/// Collective on PETSC_COMM_WORLD (PETSc must be initialised). Each rank computes only the
/// element matrices of its part of an even partition of the elements (blocks in order) and
/// adds them; rank r owns the DOF rows of the nodes in EvenPartition(num_nodes, size, r), and
/// contributions to rows of other ranks are sent by PETSc's assembly. Preallocation is exact
/// (a first pass inserts the element patterns into a MATPREALLOCATOR). The result equals
/// AssembleSystem's to round-off, on any number of ranks. Throws InputError for an element
/// with a non-positive Jacobian, InternalError for a PETSc failure.
DistributedMatrices AssembleDistributed(const Mesh& mesh, MassMatrixKind mass_kind);

/// Collective: destroys both matrices and sets the pointers to null.
void DestroyDistributed(DistributedMatrices* matrices);

}  // namespace flexmbs::fem
