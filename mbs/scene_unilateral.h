#pragma once
// Reading the unilateral contacts of a scene file and the Moreau-Jean settings that integrate
// them (docs/scene.md, "Unilateral contacts"): the top-level `contacts:` list and the keys
// `simulation.step`, `simulation.theta` of `method: moreau_jean`.

#include <functional>
#include <memory>
#include <optional>

#include "core/yaml_node.h"
#include "mbs/marker_ref.h"
#include "mbs/moreau_jean.h"
#include "mbs/multibody_system.h"
#include "mbs/unilateral_contact.h"

namespace flexmbs::mbs {

/// The Moreau-Jean settings of the scene's `simulation` node: with `selected` (method
/// moreau_jean) `step` [s] (required, > 0) and `theta` (default 0.5, in [0.5, 1]); without it
/// none, and `step` or `theta` are refused as keys of moreau_jean only. InputError
/// "<file>:<line>:<col>: <item>: <problem>" naming the value.
std::optional<MoreauJeanOptions> ReadMoreauJeanOptions(const YamlNode& simulation, bool selected);

/// One entry of `contacts:`: `{name, type: sphere_plane, sphere: <marker>, plane: <marker>,
/// radius}`, `{name, type: sphere_sphere, sphere1, sphere2, radius1, radius2}` or `{name, type:
/// surface_plane, body: <flexible body of `system`>, surface: <its contact surface>, plane:
/// <marker>}` or `{name, type: sphere_surface, sphere, radius, body, surface}`, with
/// `law: unilateral` (the default and the only law here: compliant laws are force elements),
/// `restitution` (default 0, in [0, 1]) and `friction` (default 0, >= 0). `read_marker` reads a
/// marker entry ({body, marker} or the ground). Every bad key or value is an InputError naming
/// the file, the item and the value.
std::unique_ptr<UnilateralContact> ReadUnilateralContact(const YamlNode& node, const MultibodySystem& system,
                                                         const std::function<MarkerRef(const YamlNode&)>& read_marker);

}  // namespace flexmbs::mbs
