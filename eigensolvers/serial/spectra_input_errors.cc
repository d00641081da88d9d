#include "eigensolvers/serial/spectra_input_errors.h"

#include <fmt/format.h>

#include <cmath>
#include <numbers>

#include "core/error.h"
#include "eigensolvers/eigensolver.h"

namespace flexmbs::eigensolvers {
namespace {

// How the shift was given, for the messages.
std::string ShiftText(double sigma, bool automatic) {
  return automatic ? fmt::format("the automatic shift {:g} Hz (sigma = {:g} rad^2/s^2)", HzOf(sigma), sigma)
                   : fmt::format("shift_hz = {:g} (sigma = {:g} rad^2/s^2)", HzOf(sigma), sigma);
}

}  // namespace

double HzOf(double lambda) {
  const double f = std::sqrt(std::abs(lambda)) / (2.0 * std::numbers::pi);
  return lambda < 0.0 ? -f : f;
}

std::string NotPositiveDefiniteMessage(double sigma, bool automatic, bool free_body_shift_works,
                                       double free_body_shift) {
  if (sigma >= 0.0) {
    return fmt::format("eigenproblem: K - sigma M is not positive definite at {}: the body is likely "
                       "unconstrained (rigid-body modes at 0 Hz, not above the shift) or the shift is above the "
                       "lowest mode; use a negative shift_hz or the automatic shift", ShiftText(sigma, automatic));
  }
  if (free_body_shift_works) {
    return fmt::format("eigenproblem: K - sigma M is not positive definite at {}: the negative shift is too close "
                       "to zero for the rigid-body modes (round-off); use a more negative shift_hz ({:.3g} Hz works) or the "
                       "automatic shift", ShiftText(sigma, automatic), HzOf(free_body_shift));
  }
  return fmt::format("eigenproblem: K - sigma M is not positive definite at {}: K has eigenvalues below a "
                     "negative shift, so it is not positive semi-definite (inverted elements or a bad material?)",
                     ShiftText(sigma, automatic));
}

void CheckNotSingular(const Eigen::VectorXd& values, double sigma, bool automatic, double lambda_scale) {
  if (values.size() == 0) return;
  const double distance = (values.array() - sigma).abs().minCoeff();
  if (distance > kZeroEigenvalue * lambda_scale) return;
  throw InputError(fmt::format(
      "eigenproblem: K - sigma M is numerically singular at {}: an eigenvalue lies at the shift to round-off "
      "(|lambda - sigma| = {:.3g} rad^2/s^2, {:.2g} of trace(K)/trace(M)); {}", ShiftText(sigma, automatic),
      distance, distance / lambda_scale,
      sigma >= 0.0 ? "the body is likely unconstrained (rigid-body modes at 0 Hz): use a negative shift_hz or the "
                     "automatic shift"
                   : "the negative shift is too close to zero for the rigid-body modes: use the automatic shift"));
}

[[noreturn]] void ThrowEmptyBand(double max_frequency_hz, std::optional<double> lowest_lambda) {
  throw InputError(fmt::format("eigenproblem: no mode below max_frequency_hz = {:g} Hz{}", max_frequency_hz,
                               lowest_lambda ? fmt::format(": the lowest mode is at {:g} Hz", HzOf(*lowest_lambda))
                                             : std::string()));
}

}  // namespace flexmbs::eigensolvers
