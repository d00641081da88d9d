#include "mbs/scene_pcm.h"

#include <fmt/format.h>

#include <utility>

#include "contact/pcm/stl_file.h"
#include "core/error.h"
#include "mbs/pcm_contact_force.h"
#include "mbs/scene_contact.h"
#include "mbs/scene_surface.h"

namespace flexmbs::mbs {
namespace {

/// The elastic layer `{modulus, thickness}` of a side.
contact::ElasticLayer ReadLayer(const YamlNode& node) {
  node.RejectUnknownKeys({"modulus", "thickness"});
  return {node.Required("modulus").AsDouble(), node.Required("thickness").AsDouble()};
}

/// One side `a` or `b` of the element: a reduced body's contact surface (keys body, surface) or a
/// marker's STL mesh (read relative to the scene file), its layer and whether it must be closed.
PcmSurface ReadSide(const YamlNode& node, const std::string& element, const MultibodySystem& system,
                    const std::function<MarkerRef(const YamlNode&)>& read_marker) {
  const std::string owner = fmt::format("force element '{}'", element);
  if (node.Has("surface")) {
    node.RejectUnknownKeys({"body", "surface", "layer", "closed"});
    const SurfaceRef ref = ReadSurface(node, system, owner);
    const contact::ElasticLayer layer = ReadLayer(node.Required("layer"));
    const bool closed = node.Has("closed") && node.Required("closed").AsBool();
    try {
      return ModalPcmSurface(ref.origin, *ref.surface, ref.num_modes, layer, closed);
    } catch (const InputError& e) {
      node.Required("surface").Fail(fmt::format("{}: {}", owner, e.what()));
    }
  }
  node.RejectUnknownKeys({"marker", "mesh", "layer", "closed"});
  PcmSurface surface;
  surface.marker = read_marker(node.Required("marker"));
  const YamlNode mesh = node.Required("mesh");
  surface.name = mesh.AsString();
  try {
    surface.mesh_M = contact::ReadStlFile(node.file().parent_path() / surface.name);
  } catch (const InputError& e) {
    mesh.Fail(fmt::format("{}: {}", owner, e.what()));
  }
  surface.layer = ReadLayer(node.Required("layer"));
  surface.closed = node.Has("closed") ? node.Required("closed").AsBool() : true;
  return surface;
}

}  // namespace

std::unique_ptr<ForceElement> ReadPcmContact(const YamlNode& node, const std::string& name, const MultibodySystem& system,
                                             const std::function<MarkerRef(const YamlNode&)>& read_marker) {
  node.RejectUnknownKeys({"name", "type", "a", "b", "max_depth", "areal_damping", "friction"});
  PcmSurface a = ReadSide(node.Required("a"), name, system, read_marker);
  PcmSurface b = ReadSide(node.Required("b"), name, system, read_marker);
  const double max_depth = node.Required("max_depth").AsDouble();
  const double areal_damping = node.Has("areal_damping") ? node.Required("areal_damping").AsDouble() : 0.0;
  const contact::RegularisedCoulomb friction =
      node.Has("friction") ? ReadFriction(node.Required("friction"), name) : contact::RegularisedCoulomb{};
  try {  // the element names itself
    return std::make_unique<PcmContactForce>(name, std::move(a), std::move(b), areal_damping, friction, max_depth);
  } catch (const InputError& e) {
    node.Fail(e.what());
  }
}

}  // namespace flexmbs::mbs
