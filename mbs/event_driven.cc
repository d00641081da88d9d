#include "mbs/event_driven.h"

#include <fmt/format.h>

#include <cmath>

#include "core/error.h"

namespace flexmbs::mbs {

void CheckEventDrivenOptions(const EventDrivenOptions& options) {
  const auto positive = [](double value) { return value > 0.0 && std::isfinite(value); };
  if (!positive(options.rest_velocity)) {
    throw InputError(fmt::format("simulation: rest_velocity {:g} m/s must be finite and > 0",
                                 options.rest_velocity));
  }
  if (!positive(options.stick_velocity)) {
    throw InputError(fmt::format("simulation: stick_velocity {:g} m/s must be finite and > 0",
                                 options.stick_velocity));
  }
  if (!positive(options.gap_tolerance) || !positive(options.gap_projection_tolerance)) {
    throw InputError(
        fmt::format("simulation: gap tolerances {:g} m and {:g} m must be finite and > 0",
                    options.gap_tolerance, options.gap_projection_tolerance));
  }
  if (options.max_events < 1 || !positive(options.lcp_tolerance)) {
    throw InputError(
        fmt::format("simulation: max_events {} must be >= 1 and the LCP tolerance {:g} > 0",
                    options.max_events, options.lcp_tolerance));
  }
}

}  // namespace flexmbs::mbs
