#include "mbs/scene_contact.h"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <initializer_list>

#include "contact/laws/hertz.h"
#include "core/error.h"
#include "mbs/compliant_contact.h"
#include "mbs/contact_force.h"
#include "mbs/scene_pcm.h"
#include "mbs/scene_spur_gear.h"
#include "mbs/scene_surface.h"
#include "mbs/scene_values.h"
#include "mbs/surface_contact_force.h"

namespace flexmbs::mbs {
namespace {

constexpr std::array kLawKinds{contact::NormalLawKind::kLinear, contact::NormalLawKind::kHertz,
                               contact::NormalLawKind::kHuntCrossley, contact::NormalLawKind::kLankaraniNikravesh,
                               contact::NormalLawKind::kFlores};

/// Runs `build`, turning an InputError into one at `node` (prefixed with the element's name
/// unless `element` is empty: the element classes name themselves).
template <typename Build>
auto At(const YamlNode& node, const std::string& element, Build build) -> decltype(build()) {
  try {
    return build();
  } catch (const InputError& e) {
    node.Fail(element.empty() ? std::string(e.what()) : fmt::format("force element '{}': {}", element, e.what()));
  }
}

/// What differs between the two element types when their law is read.
struct ContactShape {
  std::string_view first, second;  ///< the bodies' names under `materials`
  bool second_may_be_rigid;        ///< the plane: no material means a rigid flat
  double effective_radius;         ///< R* [m] (contact/laws/hertz.h)
};

contact::NormalLawKind ReadLawKind(const YamlNode& node) {
  if (!node.Has("law")) return contact::NormalLawKind::kLinear;
  const YamlNode law = node.Required("law");
  const std::string value = law.AsString();
  for (const contact::NormalLawKind kind : kLawKinds) {
    if (value == contact::Name(kind)) return kind;
  }
  law.Fail(fmt::format("'{}' must be one of: linear, hertz, hunt_crossley, lankarani_nikravesh, flores", value));
}

contact::ElasticMaterial ReadMaterial(const YamlNode& node, const std::string& element, std::string_view body) {
  node.RejectUnknownKeys({"youngs_modulus", "poissons_ratio"});
  const contact::ElasticMaterial material{node.Required("youngs_modulus").AsDouble(),
                                          node.Required("poissons_ratio").AsDouble()};
  At(node, element, [&] { contact::CheckMaterial(std::string(body).c_str(), material); });
  return material;
}

/// k = 4/3 E* sqrt(R*) from `materials: {<first>: {youngs_modulus, poissons_ratio}, <second>: ...}`.
double StiffnessFromMaterials(const YamlNode& node, const std::string& element, const ContactShape& shape) {
  node.RejectUnknownKeys({shape.first, shape.second});
  const contact::ElasticMaterial first = ReadMaterial(node.Required(shape.first), element, shape.first);
  const double modulus = (shape.second_may_be_rigid && !node.Has(shape.second))
                             ? contact::EffectiveModulusOnRigid(first)
                             : contact::EffectiveModulus(first, ReadMaterial(node.Required(shape.second), element,
                                                                             shape.second));
  return contact::HertzStiffness(modulus, shape.effective_radius);
}

/// Fails at the first of `keys` that `node` has: it does not belong to law `kind`.
void RejectKeysOfOtherLaws(const YamlNode& node, contact::NormalLawKind kind, std::initializer_list<std::string_view> keys) {
  for (const std::string_view key : keys) {
    if (node.Has(key)) node.Required(key).Fail(fmt::format("not a parameter of law '{}'", contact::Name(kind)));
  }
}

contact::NormalLaw ReadNormalLaw(const YamlNode& node, const std::string& element, const ContactShape& shape) {
  const contact::NormalLawKind kind = ReadLawKind(node);
  const auto number = [&](std::string_view key) { return node.Required(key).AsDouble(); };
  if (kind == contact::NormalLawKind::kLinear) {
    RejectKeysOfOtherLaws(node, kind, {"restitution", "impact_speed", "materials"});
    return At(node, element, [&] {
      return contact::LinearLaw(number("stiffness"), node.Has("damping") ? number("damping") : 0.0,
                                node.Has("exponent") ? number("exponent") : 1.0);
    });
  }
  RejectKeysOfOtherLaws(node, kind, {"damping", "exponent"});
  if (node.Has("stiffness") == node.Has("materials")) {
    node.Fail(fmt::format("force element '{}': law '{}' takes one of stiffness, materials", element, contact::Name(kind)));
  }
  const double stiffness =
      node.Has("stiffness") ? number("stiffness") : StiffnessFromMaterials(node.Required("materials"), element, shape);
  if (kind == contact::NormalLawKind::kHertz) {
    RejectKeysOfOtherLaws(node, kind, {"restitution", "impact_speed"});
    return At(node, element, [&] { return contact::HertzLaw(stiffness); });
  }
  const double restitution = number("restitution"), impact_speed = number("impact_speed");
  return At(node, element, [&] {
    switch (kind) {
      case contact::NormalLawKind::kHuntCrossley:
        return contact::HuntCrossleyLaw(stiffness, restitution, impact_speed);
      case contact::NormalLawKind::kLankaraniNikravesh:
        return contact::LankaraniNikraveshLaw(stiffness, restitution, impact_speed);
      default:
        return contact::FloresLaw(stiffness, restitution, impact_speed);
    }
  });
}

CompliantContactLaw ReadLaw(const YamlNode& node, const std::string& element, const ContactShape& shape) {
  CompliantContactLaw law{ReadNormalLaw(node, element, shape), {}};
  if (node.Has("friction")) law.friction = ReadFriction(node.Required("friction"), element);
  return law;
}

}  // namespace

contact::RegularisedCoulomb ReadFriction(const YamlNode& node, const std::string& element) {
  node.RejectUnknownKeys({"coefficient", "regularisation_speed"});
  const double coefficient = node.Required("coefficient").AsDouble();
  const double speed = node.Has("regularisation_speed") ? node.Required("regularisation_speed").AsDouble()
                                                        : contact::RegularisedCoulomb{}.regularisation_speed;
  return At(node, element, [&] { return contact::MakeRegularisedCoulomb(coefficient, speed); });
}

bool IsContactForceType(std::string_view type) {
  return std::find(kContactForceTypes.begin(), kContactForceTypes.end(), type) != kContactForceTypes.end();
}

std::unique_ptr<ForceElement> ReadContactForce(const YamlNode& node, const std::string& name, std::string_view type,
                                               const MultibodySystem& system,
                                               const std::function<MarkerRef(const YamlNode&)>& read_marker,
                                               const SceneHooks& hooks) {
  if (type == "spur_gear_contact") return ReadSpurGearContact(node, name, read_marker, hooks.tooth_table);
  if (type == "pcm_contact") return ReadPcmContact(node, name, system, read_marker);
  if (type == "sphere_plane_contact") {
    node.RejectUnknownKeys({"name", "type", "sphere", "plane", "radius", "law", "stiffness", "damping", "exponent",
                            "restitution", "impact_speed", "materials", "friction"});
    const MarkerRef sphere = read_marker(node.Required("sphere")), plane = read_marker(node.Required("plane"));
    const double radius = ReadPositiveLength(node, "radius", fmt::format("force element '{}'", name));
    CompliantContactLaw law = ReadLaw(node, name, {"sphere", "plane", true, radius});
    return At(node, "", [&] { return std::make_unique<SpherePlaneContact>(name, sphere, plane, radius, std::move(law)); });
  }
  if (type == "sphere_surface_contact") {
    node.RejectUnknownKeys({"name", "type", "sphere", "radius", "body", "surface", "law", "stiffness", "damping",
                            "exponent", "restitution", "impact_speed", "materials", "friction"});
    const MarkerRef sphere = read_marker(node.Required("sphere"));
    const double radius = ReadPositiveLength(node, "radius", fmt::format("force element '{}'", name));
    const SurfaceRef surface = ReadSurface(node, system, fmt::format("force element '{}'", name));
    CompliantContactLaw law = ReadLaw(node, name, {"sphere", "surface", false, radius});
    return At(node, "", [&] {
      return std::make_unique<SphereSurfaceContact>(name, sphere, radius, surface.origin, *surface.surface,
                                                    surface.num_modes, std::move(law));
    });
  }
  if (type == "box_plane_contact") {
    node.RejectUnknownKeys({"name", "type", "box", "size", "plane", "law", "stiffness", "damping", "exponent",
                            "restitution", "impact_speed", "friction"});
    const MarkerRef box = read_marker(node.Required("box")), plane = read_marker(node.Required("plane"));
    const YamlNode size_node = node.Required("size");
    const Eigen::Vector3d size = ReadVector3(size_node);
    if (!(size.minCoeff() > 0.0)) {
      size_node.Fail(fmt::format("force element '{}': the box's edges [m] must be > 0, not ({:g}, {:g}, {:g})", name,
                                 size.x(), size.y(), size.z()));
    }
    CompliantContactLaw law = ReadLaw(node, name, {"box", "plane", true, 0.0});
    return At(node, "", [&] { return std::make_unique<BoxPlaneContact>(name, box, 0.5 * size, plane, std::move(law)); });
  }
  if (type == "surface_plane_contact") {
    node.RejectUnknownKeys({"name", "type", "body", "surface", "plane", "law", "stiffness", "damping", "exponent",
                            "restitution", "impact_speed", "friction"});
    const SurfaceRef surface = ReadSurface(node, system, fmt::format("force element '{}'", name));
    const MarkerRef plane = read_marker(node.Required("plane"));
    CompliantContactLaw law = ReadLaw(node, name, {"surface", "plane", true, 0.0});
    return At(node, "", [&] {
      return std::make_unique<SurfacePlaneContact>(name, surface.origin, *surface.surface, surface.num_modes, plane,
                                                   std::move(law));
    });
  }
  FLEXMBS_CHECK(type == "sphere_sphere_contact", "ReadContactForce: not a contact type");
  node.RejectUnknownKeys({"name", "type", "sphere1", "sphere2", "radius1", "radius2", "law", "stiffness", "restitution",
                          "impact_speed", "materials", "friction", "damping", "exponent"});
  const MarkerRef sphere1 = read_marker(node.Required("sphere1")), sphere2 = read_marker(node.Required("sphere2"));
  const std::string owner = fmt::format("force element '{}'", name);
  const double radius1 = ReadPositiveLength(node, "radius1", owner);
  const double radius2 = ReadPositiveLength(node, "radius2", owner);
  CompliantContactLaw law = ReadLaw(node, name, {"sphere1", "sphere2", false, contact::EffectiveRadius(radius1, radius2)});
  return At(node, "", [&] {
    return std::make_unique<SphereSphereContact>(name, sphere1, sphere2, radius1, radius2, std::move(law));
  });
}

}  // namespace flexmbs::mbs
