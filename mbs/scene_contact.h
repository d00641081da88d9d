#pragma once
// Reading the compliant contact force elements of a scene file (docs/scene.md, "Contact
// elements"): `sphere_plane_contact`, `sphere_sphere_contact`, `sphere_surface_contact` and
// `surface_plane_contact` with their law, restitution, materials and friction keys;
// `spur_gear_contact` by mbs/scene_spur_gear.h, `pcm_contact` by mbs/scene_pcm.h.

#include <array>
#include <functional>
#include <memory>
#include <string>
#include <string_view>

#include "contact/laws/friction.h"
#include "core/yaml_node.h"
#include "mbs/force_element.h"
#include "mbs/marker_ref.h"
#include "mbs/multibody_system.h"
#include "mbs/scene_hooks.h"

namespace flexmbs::mbs {

/// Regularised Coulomb friction `{coefficient, regularisation_speed}` (mu >= 0; eps > 0 [m/s],
/// default 1e-4) of force element `element`; InputError at `node` naming the element otherwise.
contact::RegularisedCoulomb ReadFriction(const YamlNode& node, const std::string& element);

/// The force-element types ReadContactForce reads, as the scene spells them.
inline constexpr std::array<std::string_view, 7> kContactForceTypes{
    "sphere_plane_contact",  "sphere_sphere_contact", "box_plane_contact", "sphere_surface_contact",
    "surface_plane_contact", "spur_gear_contact",     "pcm_contact"};

/// True for the force-element types ReadContactForce reads (kContactForceTypes).
bool IsContactForceType(std::string_view type);

/// The contact element `name` of type `type` (IsContactForceType) from its scene entry `node`;
/// `read_marker` reads one of its marker entries, `system` holds the bodies whose contact
/// surfaces sphere_surface_contact names, `hooks` what spur_gear_contact's `teeth: fe` computes.
/// Every bad key or value is an InputError "<file>:<line>:<col>: <item>: <problem>" naming the
/// element and the value.
std::unique_ptr<ForceElement> ReadContactForce(const YamlNode& node, const std::string& name, std::string_view type,
                                               const MultibodySystem& system,
                                               const std::function<MarkerRef(const YamlNode&)>& read_marker,
                                               const SceneHooks& hooks);

}  // namespace flexmbs::mbs
