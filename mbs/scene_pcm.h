#pragma once
// Reading a `pcm_contact` force element of a scene file (docs/scene.md, "Contact elements"):
// the Polygonal Contact Model between two surfaces, each a marker's STL mesh or a reduced body's
// contact surface (mbs/pcm_contact_force.h).

#include <functional>
#include <memory>
#include <string>

#include "core/yaml_node.h"
#include "mbs/force_element.h"
#include "mbs/marker_ref.h"
#include "mbs/multibody_system.h"

namespace flexmbs::mbs {

/// The PcmContactForce `name` from its entry `node`: surfaces `a` (pressing) and `b` (its face
/// normals the contact normals), each either a marker's STL mesh `{marker: <marker entry read by
/// read_marker>, mesh: <STL file, relative to the scene file, in the marker's frame [m]>, layer,
/// closed (default true: the body's whole boundary)}` or a reduced body's contact surface
/// `{body: <flexible body of system>, surface: <its contact surface>, layer, closed (default
/// false)}` (ModalPcmSurface: deformed by the body's modes); `layer: {modulus [Pa], thickness
/// [m]}`; `max_depth` [m] required; `areal_damping` [N s/m^3] (default 0) and `friction`
/// ({coefficient, regularisation_speed}, default none). An unreadable or bad STL file, an unknown
/// or rigid body, a surface the body does not carry (ReadSurface), a flipped triangle, a hole in a
/// closed surface, a layer or depth not finite and > 0 are InputErrors "<file>:<line>:<col>:
/// <item>: force element '<name>': <problem>", a mesh side named by its file as written, a body's
/// by its surface's name.
std::unique_ptr<ForceElement> ReadPcmContact(const YamlNode& node, const std::string& name, const MultibodySystem& system,
                                             const std::function<MarkerRef(const YamlNode&)>& read_marker);

}  // namespace flexmbs::mbs
