#pragma once

#include <memory>

#include "eigensolvers/eigensolver.h"

namespace flexmbs::eigensolvers {

/// The serial backend "spectra": implicitly restarted Lanczos (Spectra 1.0) in shift-invert
/// mode, (K - sigma M)^{-1} M, M inner product, with a CHOLMOD factorisation of K - sigma M
/// (supernodal Cholesky when positive definite, else simplicial LDL^T); on large bodies block
/// Lanczos with the same factorisation (EigenOptions::lanczos_block_size,
/// eigensolvers/serial/lanczos_runs.h); M is multiplied through its scalar mass where it has one
/// (eigensolvers/mass_operator.h). Missed modes are found
/// again by a deflated Lanczos run after a Sturm count, or by the block Krylov check
/// (eigensolvers/block_krylov_check.h), which returns them itself; every pair is then
/// Rayleigh-Ritz refined and checked. Problems too small for Lanczos (nev >= DOF - 1) are
/// solved densely.
/// SolveFactorized uses the caller's Cholesky factorisation of K - sigma M as its shift-invert
/// operator instead of making one (UsesGivenFactorization() is true).
std::unique_ptr<Eigensolver> MakeSpectraEigensolver();

}  // namespace flexmbs::eigensolvers
