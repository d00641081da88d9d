#include "mbs/scene_surface.h"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <vector>

#include "mbs/flexible_body.h"

namespace flexmbs::mbs {

SurfaceRef ReadSurface(const YamlNode& node, const MultibodySystem& system, const std::string& owner) {
  const YamlNode body_node = node.Required("body");
  const std::string body_name = body_node.AsString();
  const int b = system.FindBody(body_name);
  if (b < 0) body_node.Fail(fmt::format("{}: no body '{}'", owner, body_name));
  const auto* flexible = dynamic_cast<const FlexibleBody*>(&system.body(b));
  if (flexible == nullptr) {
    body_node.Fail(fmt::format("{}: body '{}' is rigid; surfaces are a flexible body's", owner, body_name));
  }
  const YamlNode surface_node = node.Required("surface");
  const std::string surface_name = surface_node.AsString();
  std::vector<std::string> names;
  for (const sid::ContactSurface& surface : flexible->data().surfaces) {
    if (surface.name == surface_name) {
      return {MarkerRef::OnBody(b, flexible->FindMarker(FlexibleBody::kOriginMarker)), &surface, flexible->num_modes()};
    }
    names.push_back(surface.name);
  }
  surface_node.Fail(fmt::format("{}: body '{}' carries no contact surface '{}' (it has: {})", owner, body_name,
                                surface_name, names.empty() ? "none" : fmt::format("{}", fmt::join(names, ", "))));
}

}  // namespace flexmbs::mbs
