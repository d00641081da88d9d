#include "mbs/scene_spur_gear.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <optional>
#include <string_view>
#include <utility>
#include <vector>

#include "contact/gears/gear_mesh_force.h"
#include "contact/gears/spur_gear.h"
#include "contact/gears/tooth_stiffness.h"
#include "core/error.h"
#include "mbs/movable_teeth_gear_contact.h"
#include "mbs/spur_gear_contact.h"

namespace flexmbs::mbs {
namespace {

contact::SpurGearSpec ReadWheel(const YamlNode& node) {
  node.RejectUnknownKeys({"module", "teeth", "pressure_angle", "profile_shift",
                          "addendum_coefficient", "dedendum_coefficient", "face_width",
                          "tip_relief"});
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
  if (node.Has("tip_relief")) {  // {amount C_a [m], length L_Ca [m], shape linear|parabolic}
    const YamlNode relief = node.Required("tip_relief");
    relief.RejectUnknownKeys({"amount", "length", "shape"});
    spec.tip_relief = relief.Required("amount").AsDouble();
    spec.tip_relief_length = relief.Required("length").AsDouble();
    if (relief.Has("shape")) {
      spec.tip_relief_exponent = 1 + relief.Required("shape").AsChoice({"linear", "parabolic"});
    }
  }
  return spec;
}

/// The numbers of the sequence `key` of `node`.
std::vector<double> ReadNumbers(const YamlNode& node, std::string_view key) {
  std::vector<double> numbers;
  for (const YamlNode& item : node.Required(key).AsList()) numbers.push_back(item.AsDouble());
  return numbers;
}

/// The numbers of the sequence `key` of `node`, `.nan` read as NaN (a rim column's "off the
/// neighbour's flank").
std::vector<double> ReadNumbersOrNan(const YamlNode& node, std::string_view key) {
  std::vector<double> numbers;
  for (const YamlNode& item : node.Required(key).AsList()) {
    numbers.push_back(item.IsScalar() && item.AsString() == ".nan"
                          ? std::numeric_limits<double>::quiet_NaN()
                          : item.AsDouble());
  }
  return numbers;
}

/// One wheel's tooth compliance table {roll, compliance, centre_depth} and, optionally, its
/// coupling to its neighbours through the rim, `rim: {roll, ahead, behind}` (into `rim`).
contact::ToothCompliance ReadToothTable(const YamlNode& node,
                                        std::optional<contact::RimCoupling>* rim) {
  node.RejectUnknownKeys({"roll", "compliance", "centre_depth", "rim"});
  if (node.Has("rim")) {
    const YamlNode columns = node.Required("rim");
    columns.RejectUnknownKeys({"roll", "ahead", "behind"});
    *rim = contact::RimCoupling{ReadNumbers(columns, "roll"), ReadNumbersOrNan(columns, "ahead"),
                                ReadNumbersOrNan(columns, "behind")};
  }
  return {ReadNumbers(node, "roll"), ReadNumbers(node, "compliance"),
          ReadNumbers(node, "centre_depth")};
}

/// The `fe` map's options of both wheels' FE teeth (a ToothTableRequest without gear and material).
ToothTableRequest ReadFeOptions(const YamlNode& fe) {
  ToothTableRequest request;
  fe.RejectUnknownKeys({"mesh_size", "element_order", "loads", "rim"});
  if (fe.Has("mesh_size")) {
    const YamlNode size = fe.Required("mesh_size");
    request.mesh_size = size.AsDouble();
    if (!(*request.mesh_size > 0.0)) size.Fail(fmt::format("{:g} must be > 0 [m]", *request.mesh_size));
  }
  if (fe.Has("element_order")) {
    const YamlNode order = fe.Required("element_order");
    request.element_order = order.AsInt();
    if (*request.element_order != 1 && *request.element_order != 2) {
      order.Fail(fmt::format("{} must be 1 or 2", *request.element_order));
    }
  }
  if (fe.Has("loads")) {
    const YamlNode loads = fe.Required("loads");
    request.loads = loads.AsInt();
    if (*request.loads < 2 || *request.loads > 100) {
      loads.Fail(fmt::format("{} load points: give 2 to 100", *request.loads));
    }
  }
  if (fe.Has("rim")) request.rim = fe.Required("rim").AsBool();
  return request;
}

/// The `teeth` entry: both wheels' tables (with their rims' coupling) or `fe`, their material,
/// the flattening's reference load and whether it is taken at each pair's load. For `fe` (the word, or a map with `fe: {mesh_size, element_order, loads, rim}`) the tables
/// are left empty and `fe` holds the FE tooth's options.
struct TeethEntry {
  contact::ElasticTeeth teeth;
  std::optional<ToothTableRequest> fe;
  /// `movable: {damping}`: each tooth's dashpot c_t [N s/m] (contact::MovableTeeth); none: the
  /// massless teeth of the quasi-static series (contact::MeshLaw).
  std::optional<double> movable_damping;
};

TeethEntry ReadTeeth(const YamlNode& node) {
  TeethEntry entry;
  if (node.IsScalar()) {
    node.AsChoice({"fe"});
    entry.fe.emplace();
    return entry;
  }
  contact::ElasticTeeth& teeth = entry.teeth;
  if (node.Has("fe")) {
    node.RejectUnknownKeys(
        {"fe", "youngs_modulus", "poisson_ratio", "reference_load", "flattening", "movable"});
    entry.fe = ReadFeOptions(node.Required("fe"));
  } else {
    node.RejectUnknownKeys({"gear1", "gear2", "youngs_modulus", "poisson_ratio", "reference_load",
                            "flattening", "movable"});
    teeth.tooth1 = ReadToothTable(node.Required("gear1"), &teeth.rim1);
    teeth.tooth2 = ReadToothTable(node.Required("gear2"), &teeth.rim2);
  }
  if (node.Has("flattening")) {
    teeth.flattening_at_load =
        node.Required("flattening").AsChoice({"linearised", "at_load"}) == 1;
  }
  const auto optional = [&](std::string_view key, double fallback) {
    return node.Has(key) ? node.Required(key).AsDouble() : fallback;
  };
  teeth.material.youngs_modulus = optional("youngs_modulus", teeth.material.youngs_modulus);
  teeth.material.poisson_ratio = optional("poisson_ratio", teeth.material.poisson_ratio);
  teeth.reference_load = optional("reference_load", teeth.reference_load);
  if (node.Has("movable")) {
    const YamlNode movable = node.Required("movable");
    movable.RejectUnknownKeys({"damping"});
    entry.movable_damping = movable.Required("damping").AsDouble();
  }
  return entry;
}

/// InputError unless the neighbours ahead and behind of the FE tooth of `label` ("gear 1") are
/// each hit at two load points or more (the rims' coupling interpolates between them): too few
/// load points leave the neighbour's flank with fewer.
void CheckFeRimReachesNeighbours(const contact::RimCoupling& rim, const char* label) {
  for (const auto& [side, values] : {std::pair{"ahead", &rim.ahead}, {"behind", &rim.behind}}) {
    const auto on_flank =
        std::count_if(values->begin(), values->end(), [](double q) { return std::isfinite(q); });
    if (on_flank < 2) {
      throw InputError(fmt::format(
          "{}'s FE segment: {} of its {} load points reach the flank of the neighbour {}; the "
          "rims' coupling needs two or more: give more loads",
          label, on_flank, values->size(), side));
    }
  }
}

/// Fills the tables of `entry` (`fe`) from `tooth_table`, one FE tooth per wheel of `spec` (the
/// pair already checked), with the rims' coupling when `fe` asks for it; errors located at the
/// `teeth` entry `node`, naming element `name`.
void ComputeFeTeeth(const YamlNode& node, const std::string& name,
                    const contact::GearPairSpec& spec, const ToothTableProvider& tooth_table,
                    TeethEntry* entry) {
  if (!tooth_table) {
    node.Fail(fmt::format("force element '{}': teeth fe: the FE tooth is computed by `flexmbs "
                          "simulate`, and this reader was given no FE stage; give the tables "
                          "gear1, gear2",
                          name));
  }
  ToothTableRequest request = *entry->fe;
  if (request.rim && entry->movable_damping) {  // refused before the FE runs, not after
    node.Required("fe").Required("rim").Fail(fmt::format(
        "force element '{}': movable teeth take no rims' coupling (it is the static law's)", name));
  }
  request.material = entry->teeth.material;
  contact::ElasticTeeth& teeth = entry->teeth;
  const auto compute = [&](const contact::SpurGearSpec& wheel, const char* label,
                           contact::ToothCompliance* tooth,
                           std::optional<contact::RimCoupling>* rim) {
    request.gear = contact::MakeSpurGear(wheel, label);
    ToothTables tables = tooth_table(request);
    FLEXMBS_CHECK(tables.rim.has_value() == request.rim,
                  "the FE stage gives a wheel's rim coupling exactly when asked for it");
    if (tables.rim) CheckFeRimReachesNeighbours(*tables.rim, label);
    *tooth = std::move(tables.compliance);
    *rim = std::move(tables.rim);
  };
  try {
    contact::CheckToothMaterial(teeth.material, teeth.reference_load);
    compute(spec.gear1, "gear 1", &teeth.tooth1, &teeth.rim1);
    compute(spec.gear2, "gear 2", &teeth.tooth2, &teeth.rim2);
  } catch (const InputError& e) {
    node.Fail(fmt::format("force element '{}': {}", name, e.what()));
  }
}

/// What the entry says of the teeth' stiffness: elastic `teeth` (and where they are), or c' from
/// `mesh_stiffness` (a number [N/m^2], or `iso`: ISO 6336-1's c' of the pair), or neither (the
/// default c').
struct StiffnessEntry {
  std::optional<TeethEntry> teeth;
  std::optional<YamlNode> teeth_node;
  std::optional<double> stiffness;
  bool iso = false;
};

StiffnessEntry ReadStiffness(const YamlNode& node) {
  StiffnessEntry entry;
  if (node.Has("teeth")) {
    if (node.Has("mesh_stiffness")) {
      node.Required("mesh_stiffness").Fail("give either mesh_stiffness or teeth, not both");
    }
    entry.teeth_node = node.Required("teeth");
    entry.teeth = ReadTeeth(*entry.teeth_node);
  } else if (node.Has("mesh_stiffness")) {
    const YamlNode stiffness = node.Required("mesh_stiffness");
    entry.iso = stiffness.AsString() == "iso";
    if (!entry.iso) entry.stiffness = stiffness.AsDouble();
  }
  return entry;
}

/// The mesh law of `entry` for `pair` (InputErrors of the values, unlocated).
contact::MeshLaw MakeMeshLaw(const StiffnessEntry& entry, const contact::GearPairSpec& spec,
                             const contact::GearPair& pair, double damping) {
  if (entry.teeth) return contact::MeshLaw(pair, entry.teeth->teeth, damping);
  contact::GearMeshCompliance compliance{contact::GearMeshCompliance{}.single_pair_stiffness,
                                         damping};
  if (entry.iso) {
    compliance.single_pair_stiffness =
        contact::IsoSinglePairStiffness(spec.gear1, spec.gear2).single_pair;
  }
  if (entry.stiffness) compliance.single_pair_stiffness = *entry.stiffness;
  return contact::ToothPairLaw(compliance, pair);
}

}  // namespace

std::unique_ptr<ForceElement> ReadSpurGearContact(
    const YamlNode& node, const std::string& name,
    const std::function<MarkerRef(const YamlNode&)>& read_marker,
    const ToothTableProvider& tooth_table) {
  node.RejectUnknownKeys({"name", "type", "wheel1", "wheel2", "gear1", "gear2", "centre_distance",
                          "backlash", "mesh_stiffness", "damping", "teeth", "tip_corners"});
  const MarkerRef wheel1 = read_marker(node.Required("wheel1")),
                  wheel2 = read_marker(node.Required("wheel2"));
  contact::GearPairSpec spec{ReadWheel(node.Required("gear1")), ReadWheel(node.Required("gear2")),
                             0.0, 0.0};
  const auto optional = [&](std::string_view key, double fallback) {
    return node.Has(key) ? node.Required(key).AsDouble() : fallback;
  };
  spec.centre_distance = optional("centre_distance", 0.0);
  spec.backlash = optional("backlash", 0.0);
  if (node.Has("tip_corners")) spec.tip_corners = node.Required("tip_corners").AsBool();
  const double damping = optional("damping", 0.0);
  StiffnessEntry stiffness = ReadStiffness(node);
  contact::GearPair pair;
  try {
    pair = contact::MakeGearPair(spec);
  } catch (const InputError& e) {
    node.Fail(fmt::format("force element '{}': {}", name, e.what()));
  }
  if (stiffness.teeth && stiffness.teeth->fe) {
    ComputeFeTeeth(*stiffness.teeth_node, name, spec, tooth_table, &*stiffness.teeth);
  }
  const bool movable = stiffness.teeth && stiffness.teeth->movable_damping;
  if (movable && node.Has("damping")) {
    node.Required("damping").Fail(fmt::format(
        "force element '{}': movable teeth take their damping per tooth (teeth: movable: "
        "damping), not per tooth pair",
        name));
  }
  try {
    if (movable) {
      return std::make_unique<MovableTeethGearContact>(
          name, wheel1, wheel2, pair,
          contact::MovableTeeth{stiffness.teeth->teeth, *stiffness.teeth->movable_damping});
    }
    return std::make_unique<SpurGearContact>(name, wheel1, wheel2, pair,
                                             MakeMeshLaw(stiffness, spec, pair, damping));
  } catch (const InputError& e) {
    node.Fail(fmt::format("force element '{}': {}", name, e.what()));
  }
}

}  // namespace flexmbs::mbs
