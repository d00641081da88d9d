#include "mbs/scene_spur_gear.h"

#include <fmt/format.h>

#include <numbers>

#include "contact/gears/gear_mesh_force.h"
#include "contact/gears/spur_gear.h"
#include "core/error.h"
#include "mbs/spur_gear_contact.h"

namespace flexmbs::mbs {
namespace {

contact::SpurGearSpec ReadWheel(const YamlNode& node) {
  node.RejectUnknownKeys({"module", "teeth", "pressure_angle", "profile_shift",
                          "addendum_coefficient", "dedendum_coefficient", "face_width"});
  contact::SpurGearSpec spec;
  spec.module = node.Required("module").AsDouble();
  spec.teeth = node.Required("teeth").AsInt();
  spec.face_width = node.Required("face_width").AsDouble();
  const auto optional = [&](std::string_view key, double fallback) {
    return node.Has(key) ? node.Required(key).AsDouble() : fallback;
  };
  spec.pressure_angle = optional("pressure_angle", 20.0 * std::numbers::pi / 180.0);
  spec.profile_shift = optional("profile_shift", 0.0);
  spec.addendum_coefficient = optional("addendum_coefficient", spec.addendum_coefficient);
  spec.dedendum_coefficient = optional("dedendum_coefficient", spec.dedendum_coefficient);
  return spec;
}

}  // namespace

std::unique_ptr<ForceElement> ReadSpurGearContact(
    const YamlNode& node, const std::string& name,
    const std::function<MarkerRef(const YamlNode&)>& read_marker) {
  node.RejectUnknownKeys({"name", "type", "wheel1", "wheel2", "gear1", "gear2", "centre_distance",
                          "backlash", "mesh_stiffness", "damping"});
  const MarkerRef wheel1 = read_marker(node.Required("wheel1")),
                  wheel2 = read_marker(node.Required("wheel2"));
  contact::GearPairSpec spec{ReadWheel(node.Required("gear1")), ReadWheel(node.Required("gear2")),
                             0.0, 0.0};
  const auto optional = [&](std::string_view key, double fallback) {
    return node.Has(key) ? node.Required(key).AsDouble() : fallback;
  };
  spec.centre_distance = optional("centre_distance", 0.0);
  spec.backlash = optional("backlash", 0.0);
  const contact::GearMeshCompliance compliance{
      optional("mesh_stiffness", contact::GearMeshCompliance{}.single_pair_stiffness),
      optional("damping", 0.0)};
  try {
    const contact::GearPair pair = contact::MakeGearPair(spec);
    const contact::NormalLaw law = contact::ToothPairLaw(compliance, pair);
    return std::make_unique<SpurGearContact>(name, wheel1, wheel2, pair, law);
  } catch (const InputError& e) {
    node.Fail(fmt::format("force element '{}': {}", name, e.what()));
  }
}

}  // namespace flexmbs::mbs
