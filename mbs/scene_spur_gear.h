#pragma once
// Reading a `spur_gear_contact` force element of a scene file (docs/scene.md, "Contact elements").

#include <functional>
#include <memory>
#include <string>

#include "core/yaml_node.h"
#include "mbs/force_element.h"
#include "mbs/marker_ref.h"
#include "mbs/scene_hooks.h"

namespace flexmbs::mbs {

/// The SpurGearContact `name` from its entry `node`: markers `wheel1`, `wheel2` (read by
/// `read_marker`), wheels `gear1`, `gear2` ({module, teeth, face_width} required;
/// pressure_angle default 20 deg, profile_shift 0, addendum_coefficient 1, dedendum_coefficient
/// 1.25, tip_relief {amount, length, shape: linear (default) | parabolic}), optional
/// `centre_distance` (default a_0), `backlash` (0), `tip_corners` (true: a tip corner may touch
/// the mating flank off the line of action, contact::GearPairSpec), `damping` [N s/m] (0) and
/// either `mesh_stiffness` c' [N/m^2] (1.4e10; `iso`: ISO 6336-1's c' of the pair) or `teeth`,
/// massless elastic teeth (contact::MeshLaw): {gear1, gear2: {roll, compliance, centre_depth}
/// (contact::ToothCompliance) with optional `rim: {roll, ahead, behind}` (contact::RimCoupling,
/// `.nan` off the neighbour's flank; both wheels or neither), youngs_modulus (2.1e11),
/// poisson_ratio (0.3), reference_load (3e5 N/m), flattening (`linearised` at reference_load,
/// the default, or `at_load`: ElasticTeeth::flattening_at_load)}, or `fe` in place of the tables (the word, or `fe: {mesh_size [m], element_order,
/// loads, rim}`): each wheel's table from `tooth_table` (an FE tooth of the wheel, after the pair's
/// checks; with `rim: true` its three-tooth segment's table and rim coupling). Every bad key or value, a pair that cannot mesh, and `fe` without a `tooth_table` is
/// an InputError "<file>:<line>:<col>: <item>: force element '<name>': <problem>".
std::unique_ptr<ForceElement> ReadSpurGearContact(
    const YamlNode& node, const std::string& name,
    const std::function<MarkerRef(const YamlNode&)>& read_marker,
    const ToothTableProvider& tooth_table);

}  // namespace flexmbs::mbs
