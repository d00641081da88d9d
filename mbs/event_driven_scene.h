#pragma once
// Reading the settings of `simulation.method: event_driven` from a scene file (docs/scene.md,
// "Unilateral contacts"): the keys rest_velocity, stick_velocity, impact_law, gap_tolerance and
// max_events, and the keys the method does not take.

#include <optional>

#include "core/yaml_node.h"
#include "mbs/event_driven.h"

namespace flexmbs::mbs {

/// The event-driven keys of the scene's `simulation` node, all of them optional.
inline constexpr const char* kEventDrivenKeys[] = {"rest_velocity", "stick_velocity", "gap_tolerance",
                                                      "max_events", "impact_law"};

/// The event-driven settings of the scene's `simulation` node: with `selected` (method
/// event_driven) `rest_velocity` [m/s] (default 1e-3, > 0), `stick_velocity` [m/s] (default 1e-6,
/// > 0), `impact_law` (newton, the default, or poisson), `gap_tolerance` [m] (default 1e-9,
/// > 0) and `max_events` (default 10^6, a whole number >= 1), refusing `fixed_step`, `jacobian` and
/// `newton` (the smooth phases run on the adaptive explicit method); without it none, and the
/// event-driven keys are refused. InputError "<file>:<line>:<col>: <item>: <problem>".
std::optional<EventDrivenOptions> ReadEventDrivenOptions(const YamlNode& simulation, bool selected);

}  // namespace flexmbs::mbs
