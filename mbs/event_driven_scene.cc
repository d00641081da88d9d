#include "mbs/event_driven_scene.h"

#include <fmt/format.h>

#include <cmath>
#include <string_view>

namespace flexmbs::mbs {

std::optional<EventDrivenOptions> ReadEventDrivenOptions(const YamlNode& simulation,
                                                         bool selected) {
  if (!selected) {
    for (const std::string_view key : kEventDrivenKeys) {
      if (simulation.Has(key)) simulation.Required(key).Fail("only for method event_driven");
    }
    return std::nullopt;
  }
  for (const std::string_view key : {"fixed_step", "jacobian", "newton"}) {
    if (simulation.Has(key)) {
      simulation.Required(key).Fail(
          "not for method event_driven (adaptive explicit steps between the events, which cut "
          "them)");
    }
  }
  EventDrivenOptions options;
  const auto positive = [&](std::string_view key, double* value) {
    if (!simulation.Has(key)) return;
    const YamlNode item = simulation.Required(key);
    *value = item.AsDouble();
    if (!(*value > 0.0) || !std::isfinite(*value))
      item.Fail(fmt::format("{:g} must be finite and > 0", *value));
  };
  positive("rest_velocity", &options.rest_velocity);
  positive("stick_velocity", &options.stick_velocity);
  if (simulation.Has("impact_law")) {
    const int law = simulation.Required("impact_law").AsChoice({"newton", "poisson"});
    options.impact_law = law == 1 ? ImpactLaw::kPoisson : ImpactLaw::kNewton;
  }
  positive("gap_tolerance", &options.gap_tolerance);
  if (simulation.Has("max_events")) {
    const YamlNode item = simulation.Required("max_events");
    const double count = item.AsDouble();
    if (!(count >= 1.0 && count <= 1e15 && std::floor(count) == count)) {
      item.Fail(fmt::format("{:g} must be a whole number >= 1", count));
    }
    options.max_events = static_cast<long>(count);
  }
  return options;
}

}  // namespace flexmbs::mbs
