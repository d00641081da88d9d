#include "contact/laws/law_checks.h"

#include <fmt/format.h>

#include <cmath>

#include "core/error.h"

namespace flexmbs::contact {

void RequireNonNegative(std::string_view what, double value) {
  if (!(value >= 0.0) || !std::isfinite(value)) {
    throw InputError(fmt::format("{} {} must be finite and >= 0", what, value));
  }
}

void RequirePositive(std::string_view what, double value) {
  if (!(value > 0.0) || !std::isfinite(value)) throw InputError(fmt::format("{} {} must be finite and > 0", what, value));
}

void RequireRestitution(double restitution) {
  if (!(restitution > 0.0 && restitution <= 1.0)) {
    throw InputError(fmt::format("restitution {} must be in (0, 1]", restitution));
  }
}

}  // namespace flexmbs::contact
