#pragma once
// Reading a `pcm_contact` force element of a scene file (docs/scene.md, "Contact elements"):
// the Polygonal Contact Model between two markers' STL surfaces (mbs/pcm_contact_force.h).

#include <functional>
#include <memory>
#include <string>

#include "core/yaml_node.h"
#include "mbs/force_element.h"
#include "mbs/marker_ref.h"

namespace flexmbs::mbs {

/// The PcmContactForce `name` from its entry `node`: surfaces `a` (pressing) and `b` (its face
/// normals the contact normals), each `{marker: <marker entry read by read_marker>, mesh: <STL
/// file, relative to the scene file, in the marker's frame [m]>, layer: {modulus [Pa],
/// thickness [m]}, closed: true|false (default true: the body's whole boundary)}`;
/// `max_depth` [m] required; `areal_damping` [N s/m^3] (default 0) and `friction`
/// ({coefficient, regularisation_speed}, default none). An unreadable or bad STL file, a
/// flipped triangle, a hole in a closed surface, a layer or depth not finite and > 0 are
/// InputErrors "<file>:<line>:<col>: <item>: force element '<name>': <problem>", the surface
/// named by its mesh file as written.
std::unique_ptr<ForceElement> ReadPcmContact(const YamlNode& node, const std::string& name,
                                             const std::function<MarkerRef(const YamlNode&)>& read_marker);

}  // namespace flexmbs::mbs
