#pragma once
// One attempt of the SLEPc backend (eigensolvers/distributed/slepc_solver.h): a Krylov-Schur run
// with shift-and-invert for the wanted pairs, the pairs extracted and M-normalised, and the
// missed-mode check below the cut after them (a Sturm count or the block Krylov check).
// SolveDistributedEigenproblem runs attempts until every wanted pair is found. Internal: names
// PETSc and SLEPc types, so only .cc files include it.

#include <slepceps.h>

#include <algorithm>
#include <chrono>
#include <cstddef>
#include <vector>

#include "eigensolvers/eigensolver.h"
#include "eigensolvers/distributed/slepc_shifted_matrix.h"
#include "eigensolvers/distributed/substructured_factor.h"

namespace flexmbs::eigensolvers {

/// Seconds since *since [s]; *since moves to now.
double SecondsSince(std::chrono::steady_clock::time_point* since);

/// Distributed vectors destroyed with their owner (also when an exception passes).
struct OwnedVectors {
  std::vector<Vec> v;
  OwnedVectors() = default;
  OwnedVectors(const OwnedVectors&) = delete;
  OwnedVectors& operator=(const OwnedVectors&) = delete;
  ~OwnedVectors() { Clear(); }
  /// Destroys every vector.
  void Clear() {
    for (Vec& x : v) VecDestroy(&x);
    v.clear();
  }
  /// Keeps the first `count` vectors.
  void Truncate(std::size_t count) {
    for (std::size_t j = count; j < v.size(); ++j) VecDestroy(&v[j]);
    v.resize(std::min(count, v.size()));
  }
};

/// The band's size and what is wanted of it (EigenvaluesBelow at its upper end `top`, counted
/// before any run): the lowest `wanted` pairs; `band_count` >= 0 when that is the whole band.
struct BandWanted {
  PetscInt wanted = 0;
  PetscInt band_count = -1;
};

/// What one attempt's Krylov-Schur run shares with the others.
struct AttemptContext {
  Mat K, M;
  const EigenOptions& options;
  bool fixed_dofs;                     // DOF were removed (the check's choice depends on it)
  bool keep;                           // a held K at sigma = 0, its factor kept for the caller
  SubstructuredFactor* substructured;  // the substructured factor, or null (MUMPS)
  BandWanted band;
  double top;                          // the band's upper end [rad^2/s^2]
  double zero_eigenvalue;              // below this an eigenvalue is zero to round-off
};

/// How an attempt ended.
enum class AttemptEnd {
  kFound,                // every wanted pair, checked
  kMissed,               // the check counted more below the cut: *nev raised for the next attempt
  kNotPositiveDefinite,  // a held K is not positive definite
};

/// One attempt: Krylov-Schur for *nev pairs (MUMPS factorises K - sigma M unless substructured),
/// the pairs into *x and *solution, the wanted pairs' residuals (MeasurePairs) with one step of
/// subspace iteration and Rayleigh-Ritz on the pairs if one misses its bound (slepc_refinement.h),
/// and the missed-mode check below the cut. Throws InputError when
/// SLEPc converges too few pairs or a second attempt still misses some.
AttemptEnd RunAttempt(const AttemptContext& c, int attempt, PetscInt* nev, OwnedVectors* x, OwnedMat* held_factor,
                      EigenSolution* solution);

}  // namespace flexmbs::eigensolvers
