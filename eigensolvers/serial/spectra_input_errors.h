#pragma once
// The Spectra backend's one-line errors for eigenproblems it cannot solve as given: a shift at
// which K - sigma M is not positive definite or numerically singular, an empty frequency band.

#include <optional>
#include <string>

#include <Eigen/Core>

namespace flexmbs::eigensolvers {

/// The signed frequency [Hz] of an eigenvalue lambda [rad^2/s^2]: sign(lambda) sqrt(|lambda|) / 2 pi.
double HzOf(double lambda);

/// Why K - sigma M [rad^2/s^2] failed its Cholesky factorisation. `automatic`: sigma was chosen
/// by the solver; `free_body_shift_works`: K - free_body_shift M is positive definite (for a
/// negative sigma closer to zero than that: the shift was too small for the rigid-body modes).
std::string NotPositiveDefiniteMessage(double sigma, bool automatic, bool free_body_shift_works,
                                       double free_body_shift);

/// Throws InputError if one of `values` [rad^2/s^2] lies at the shift to round-off (within
/// kZeroEigenvalue lambda_scale): K - sigma M was numerically singular (its Cholesky
/// factorisation can still succeed, with pivots of round-off size).
void CheckNotSingular(const Eigen::VectorXd& values, double sigma, bool automatic, double lambda_scale);

/// Throws InputError: no mode below max_frequency_hz [Hz]; names the lowest mode if known.
[[noreturn]] void ThrowEmptyBand(double max_frequency_hz, std::optional<double> lowest_lambda);

}  // namespace flexmbs::eigensolvers
