#include "mbs/scene_unilateral.h"

#include <fmt/format.h>

#include <string>
#include <string_view>
#include <vector>

#include "core/error.h"
#include "mbs/scene_surface.h"
#include "mbs/scene_values.h"
#include "mbs/sphere_segment_unilateral.h"
#include "mbs/surface_unilateral.h"

namespace flexmbs::mbs {
namespace {

/// `key` of `node` as a number, or `fallback` if absent.
double NumberOr(const YamlNode& node, std::string_view key, double fallback) {
  return node.Has(key) ? node.Required(key).AsDouble() : fallback;
}

/// Runs `build`, turning an InputError of the contact classes into one at `node`.
template <typename Build>
auto At(const YamlNode& node, Build build) -> decltype(build()) {
  try {
    return build();
  } catch (const InputError& e) {
    node.Fail(e.what());
  }
}

UnilateralLaw ReadLaw(const YamlNode& node, const std::string& name) {
  if (node.Has("law")) {
    const YamlNode law = node.Required("law");
    const std::string value = law.AsString();
    if (value != "unilateral") {
      law.Fail(fmt::format("contact '{}': law '{}' must be unilateral (compliant laws are the force elements "
                           "sphere_plane_contact, sphere_sphere_contact)",
                           name, value));
    }
  }
  const UnilateralLaw law{NumberOr(node, "restitution", 0.0), NumberOr(node, "friction", 0.0)};
  if (!(law.restitution >= 0.0 && law.restitution <= 1.0)) {
    node.Required("restitution").Fail(fmt::format("contact '{}': {:g} must be in [0, 1]", name, law.restitution));
  }
  if (!(law.friction >= 0.0)) {
    node.Required("friction").Fail(fmt::format("contact '{}': {:g} must be >= 0", name, law.friction));
  }
  return law;
}

}  // namespace

std::optional<MoreauJeanOptions> ReadMoreauJeanOptions(const YamlNode& simulation, bool selected) {
  if (!selected) {
    for (const std::string_view key : {"step", "theta", "impact_level"}) {
      if (simulation.Has(key)) simulation.Required(key).Fail("only for method moreau_jean");
    }
    return std::nullopt;
  }
  if (!simulation.Has("step")) {
    simulation.Required("method").Fail("moreau_jean needs step: the fixed time step [s]");
  }
  MoreauJeanOptions options;
  const YamlNode step = simulation.Required("step");
  options.step = step.AsDouble();
  if (!(options.step > 0.0)) step.Fail(fmt::format("{:g} s must be > 0", options.step));
  if (simulation.Has("theta")) {
    const YamlNode theta = simulation.Required("theta");
    options.theta = theta.AsDouble();
    if (!(options.theta >= 0.5 && options.theta <= 1.0)) theta.Fail(fmt::format("{:g} must be in [0.5, 1]", options.theta));
  }
  if (simulation.Has("impact_level") && simulation.Required("impact_level").AsChoice({"velocity", "position"}) == 1) {
    options.impact_level = ImpactLevel::kPosition;
    if (options.theta != 1.0) {
      simulation.Required("impact_level")
          .Fail(fmt::format("position needs theta: 1 (the gap the positions reach), not {:g}", options.theta));
    }
  }
  return options;
}

std::unique_ptr<UnilateralContact> ReadUnilateralContact(const YamlNode& node, const MultibodySystem& system,
                                                         const std::function<MarkerRef(const YamlNode&)>& read_marker) {
  const std::string name = node.Required("name").AsString();
  const YamlNode type = node.Required("type");
  const std::string kind = type.AsString();
  if (kind == "sphere_plane") {
    node.RejectUnknownKeys({"name", "type", "sphere", "plane", "radius", "law", "restitution", "friction"});
    const MarkerRef sphere = read_marker(node.Required("sphere")), plane = read_marker(node.Required("plane"));
    const double radius = ReadPositiveLength(node, "radius", fmt::format("contact '{}'", name));
    const UnilateralLaw law = ReadLaw(node, name);
    return At(node, [&] { return std::make_unique<SpherePlaneUnilateral>(name, sphere, plane, radius, law); });
  }
  if (kind == "sphere_segment") {
    node.RejectUnknownKeys({"name", "type", "sphere", "segment", "ends", "radius", "law", "restitution", "friction"});
    const MarkerRef sphere = read_marker(node.Required("sphere")), segment = read_marker(node.Required("segment"));
    const YamlNode ends_node = node.Required("ends");
    const std::vector<YamlNode> ends = ends_node.AsList();
    if (ends.size() != 2) {
      ends_node.Fail(fmt::format("contact '{}': {} entries, not the segment's two ends", name, ends.size()));
    }
    const double radius = ReadPositiveLength(node, "radius", fmt::format("contact '{}'", name));
    const UnilateralLaw law = ReadLaw(node, name);
    return At(node, [&] {
      return std::make_unique<SphereSegmentUnilateral>(name, sphere, segment, ReadVector3(ends[0]), ReadVector3(ends[1]),
                                                       radius, law);
    });
  }
  if (kind == "sphere_sphere") {
    node.RejectUnknownKeys({"name", "type", "sphere1", "sphere2", "radius1", "radius2", "law", "restitution", "friction"});
    const MarkerRef sphere1 = read_marker(node.Required("sphere1")), sphere2 = read_marker(node.Required("sphere2"));
    const std::string owner = fmt::format("contact '{}'", name);
    const double radius1 = ReadPositiveLength(node, "radius1", owner);
    const double radius2 = ReadPositiveLength(node, "radius2", owner);
    const UnilateralLaw law = ReadLaw(node, name);
    return At(node, [&] {
      return std::make_unique<SphereSphereUnilateral>(name, sphere1, sphere2, radius1, radius2, law);
    });
  }
  if (kind == "surface_plane") {
    node.RejectUnknownKeys({"name", "type", "body", "surface", "plane", "law", "restitution", "friction"});
    const SurfaceRef surface = ReadSurface(node, system, fmt::format("contact '{}'", name));
    const MarkerRef plane = read_marker(node.Required("plane"));
    const UnilateralLaw law = ReadLaw(node, name);
    return At(node, [&] {
      return std::make_unique<SurfacePlaneUnilateral>(name, surface.origin, *surface.surface, surface.num_modes, plane,
                                                      law);
    });
  }
  if (kind == "sphere_surface") {
    node.RejectUnknownKeys({"name", "type", "sphere", "radius", "body", "surface", "law", "restitution", "friction"});
    const MarkerRef sphere = read_marker(node.Required("sphere"));
    const double radius = ReadPositiveLength(node, "radius", fmt::format("contact '{}'", name));
    const SurfaceRef surface = ReadSurface(node, system, fmt::format("contact '{}'", name));
    const UnilateralLaw law = ReadLaw(node, name);
    return At(node, [&] {
      return std::make_unique<SphereSurfaceUnilateral>(name, sphere, radius, surface.origin, *surface.surface,
                                                       surface.num_modes, law);
    });
  }
  if (kind == "box_plane") {
    node.RejectUnknownKeys({"name", "type", "box", "size", "plane", "law", "restitution", "friction"});
    const MarkerRef box = read_marker(node.Required("box"));
    const YamlNode size_node = node.Required("size");
    const Eigen::Vector3d size = ReadVector3(size_node);
    if (!(size.minCoeff() > 0.0)) {
      size_node.Fail(fmt::format("contact '{}': the box's edges [m] must be > 0, not ({:g}, {:g}, {:g})", name,
                                 size.x(), size.y(), size.z()));
    }
    const MarkerRef plane = read_marker(node.Required("plane"));
    const UnilateralLaw law = ReadLaw(node, name);
    return At(node, [&] { return std::make_unique<BoxPlaneUnilateral>(name, box, 0.5 * size, plane, law); });
  }
  if (kind == "cylinder_plane") {
    node.RejectUnknownKeys({"name", "type", "cylinder", "radius", "length", "plane", "law", "restitution", "friction"});
    const MarkerRef cylinder = read_marker(node.Required("cylinder"));
    const std::string owner = fmt::format("contact '{}'", name);
    const double radius = ReadPositiveLength(node, "radius", owner);
    const double length = ReadPositiveLength(node, "length", owner);
    const MarkerRef plane = read_marker(node.Required("plane"));
    const UnilateralLaw law = ReadLaw(node, name);
    return At(node, [&] {
      return std::make_unique<CylinderPlaneUnilateral>(name, cylinder, radius, length, plane, law);
    });
  }
  if (kind == "surface_surface") {
    node.RejectUnknownKeys({"name", "type", "surface1", "surface2", "law", "restitution", "friction"});
    const std::string owner = fmt::format("contact '{}'", name);
    const SurfaceRef a = ReadSurface(node.Required("surface1"), system, owner);
    const SurfaceRef b = ReadSurface(node.Required("surface2"), system, owner);
    const UnilateralLaw law = ReadLaw(node, name);
    return At(node, [&] {
      return std::make_unique<SurfaceSurfaceUnilateral>(name, a.origin, *a.surface, a.num_modes, b.origin, *b.surface,
                                                        b.num_modes, law);
    });
  }
  type.Fail(fmt::format("contact '{}': '{}' must be one of: sphere_plane, sphere_sphere, box_plane, cylinder_plane, "
                        "surface_plane, sphere_surface, surface_surface, sphere_segment",
                        name, kind));
}

}  // namespace flexmbs::mbs
