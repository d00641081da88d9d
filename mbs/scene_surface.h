#pragma once
// Reading which contact surface of which reduced body a scene's contact entry names (docs/scene.md,
// "Unilateral contacts" and "Contact elements"): the `body` and `surface` keys of surface_plane,
// sphere_surface and sphere_surface_contact.

#include <Eigen/Core>
#include <string>

#include "core/yaml_node.h"
#include "mbs/marker_ref.h"
#include "mbs/multibody_system.h"
#include "sid/reduced_body.h"

namespace flexmbs::mbs {

/// A flexible body's contact surface named by a scene entry.
struct SurfaceRef {
  MarkerRef origin;                              ///< the body frame's marker
  const sid::ContactSurface* surface = nullptr;  ///< in the body's data, phi over its kept modes
  Eigen::Index num_modes = 0;                    ///< the body's kept modes
};

/// The surface `surface` of the flexible body `body` of entry `node`; `owner` names the entry in
/// messages ("contact 'x'", "force element 'x'"). InputError at the item for an unknown body, a
/// rigid body, or a surface the body's file does not carry (the message lists those it has).
SurfaceRef ReadSurface(const YamlNode& node, const MultibodySystem& system, const std::string& owner);

}  // namespace flexmbs::mbs
