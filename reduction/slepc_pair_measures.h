#pragma once
// What the SLEPc backend measures on distributed eigenpairs: the residuals, their round-off
// floors and the M-orthonormality (as defined in EigenSolution), with the products run where
// the rows are; and the gather of a distributed mode. Internal to the PETSc code of this
// module: it names PETSc types, so only .cc files include it (slepc_solver.cc,
// distributed_reduction.cc, distributed_model.cc), never a header other modules see.

#include <petscmat.h>

#include <Eigen/Core>
#include <vector>

#include "reduction/eigensolver.h"
#include "reduction/slepc_solver.h"

namespace flexmbs::reduction {

/// |A|: a copy of the AIJ matrix A (sequential or distributed) with the absolute values of its
/// entries; the caller destroys it. Collective.
Mat AbsoluteCopy(Mat A);

/// Copies a distributed vector into a full-length Eigen vector on every rank, or on rank 0 only
/// (the other ranks get an empty vector). Collective.
Eigen::VectorXd GatherVector(Vec x, ModesOn modes_on);

/// Fills solution's relative_residuals, residual_floors and orthonormality_error for the pairs
/// (solution->eigenvalues(j), x[j]) of K, M (distributed AIJ, same layout as x), with the shift
/// solution->shift. Collective.
void MeasurePairs(Mat K, Mat M, const std::vector<Vec>& x, EigenSolution* solution);

}  // namespace flexmbs::reduction
