#pragma once
// The driven spur gear pair that the gear tests (tests/mbs/spur_gear_contact_test.cc,
// tests/mbs/spur_gear_rattle_test.cc, tests/app/simulate_gears_test.cc) and bench_gears share,
// as scene text (docs/scene.md).

#include <fmt/format.h>

#include <string>

namespace flexmbs::testing {

/// The keys of the pair's spur_gear_contact element after wheel1 and wheel2: module 2 mm, 19
/// (x = 0.3) and 31 (x = -0.1) teeth of 20 mm face width at the centre distance 50.5 mm (1.0e-4 m
/// of normal backlash), damping 8e3 N s/m.
inline constexpr const char* kDrivenPairGearKeys =
    "    gear1: {module: 2e-3, teeth: 19, profile_shift: 0.3, face_width: 0.02}\n"
    "    gear2: {module: 2e-3, teeth: 31, profile_shift: -0.1, face_width: 0.02}\n"
    "    centre_distance: 0.0505\n"
    "    damping: 8e3\n";

/// The `teeth` entry (massless elastic teeth, docs/scene.md) of the pair's two wheels: their FE
/// teeth's compliance tables (gear_tooth_fe::ToothComplianceFromFe with default options and 7
/// load points, printed once; tests/contact/gear_tooth_fe_test.cc checks the model), to follow
/// kDrivenPairGearKeys or another entry's wheels of the same geometry.
inline constexpr const char* kDrivenPairFeTeeth =
    "    teeth:\n"
    "      gear1: {roll: [0.13472, 0.22575, 0.31678, 0.40781, 0.49884, 0.58987, 0.6809],\n"
    "              compliance: [9.0213e-12, 9.8865e-12, 1.1617e-11, 1.4715e-11, 2.0165e-11,\n"
    "                           3.0004e-11, 5.0378e-11],\n"
    "              centre_depth: [0.0019473, 0.0019379, 0.0018931, 0.0017828, 0.0015722,\n"
    "                             0.0012185, 0.00066685]}\n"
    "      gear2: {roll: [0.14316, 0.20555, 0.26794, 0.33033, 0.39272, 0.45511, 0.5175],\n"
    "              compliance: [9.638e-12, 1.1031e-11, 1.3419e-11, 1.7388e-11, 2.3972e-11,\n"
    "                           3.5112e-11, 5.5476e-11],\n"
    "              centre_depth: [0.0018369, 0.0018136, 0.0017571, 0.0016514, 0.0014787,\n"
    "                             0.0012192, 0.00084956]}\n";

/// The `teeth` entry of the pair's two wheels coupled through their rims (docs/scene.md): each
/// wheel's tooth on its three-tooth segment (gear_tooth_fe::ToothCouplingFromFe with default
/// options and 7 load points, printed once): its own compliance table and its neighbours'
/// deflections ahead and behind (`.nan` off the neighbour's flank).
inline constexpr const char* kDrivenPairCoupledTeeth =
    "    teeth:\n"
    "      gear1: {roll: [0.13472, 0.22575, 0.31678, 0.40781, 0.49884, 0.58987, 0.6809],\n"
    "              compliance: [1.0694e-11, 1.1569e-11, 1.3322e-11, 1.6453e-11, 2.1953e-11,\n"
    "                           3.187e-11, 5.231e-11],\n"
    "              centre_depth: [0.0019473, 0.0019379, 0.0018931, 0.0017828, 0.0015722,\n"
    "                             0.0012185, 0.00066685],\n"
    "              rim: {roll: [0.13472, 0.22575, 0.31678, 0.40781, 0.49884, 0.58987, 0.6809],\n"
    "                    ahead: [3.6474e-12, 3.5095e-12, 3.2747e-12, .nan, .nan, .nan, .nan],\n"
    "                    behind: [.nan, .nan, .nan, .nan, 3.2959e-12, 3.1072e-12, 2.8015e-12]}}\n"
    "      gear2: {roll: [0.14316, 0.20555, 0.26794, 0.33033, 0.39272, 0.45511, 0.5175],\n"
    "              compliance: [1.0786e-11, 1.2193e-11, 1.4607e-11, 1.8611e-11, 2.5244e-11,\n"
    "                           3.6438e-11, 5.6932e-11],\n"
    "              centre_depth: [0.0018369, 0.0018136, 0.0017571, 0.0016514, 0.0014787,\n"
    "                             0.0012192, 0.00084956],\n"
    "              rim: {roll: [0.14316, 0.20555, 0.26794, 0.33033, 0.39272, 0.45511, 0.5175],\n"
    "                    ahead: [2.6318e-12, 2.4512e-12, 2.1881e-12, .nan, .nan, .nan, .nan],\n"
    "                    behind: [.nan, .nan, .nan, .nan, 2.3563e-12, 2.1168e-12, 1.7603e-12]}}\n";

/// Pinion (19 teeth) at the origin, wheel (31 teeth) at (0.0505, 0, 0), both steel discs of
/// 20 mm on revolute joints about z; the pinion driven at 2 rad/s, the wheel loaded by 10 N m
/// about +z (the mesh turns it about -z) and starting at `wheel_angle` [rad] with the kinematic
/// speed; the spur_gear_contact element "mesh" with `gear_keys` (none where empty); explicit,
/// rtol 1e-8, atol 1e-11, outputs every 0.1 ms to end_time [s].
inline std::string DrivenGearPairScene(double wheel_angle, const std::string& gear_keys,
                                       double end_time = 1.1) {
  std::string text = fmt::format(
      "gravity: [0, 0, 0]\n"
      "bodies:\n"
      "  pinion:\n"
      "    rigid: {{mass: 0.18, inertia: [[2e-5, 0, 0], [0, 2e-5, 0], [0, 0, 3.4e-5]]}}\n"
      "    markers: {{axis: {{position: [0, 0, 0]}}}}\n"
      "    initial: {{angular_velocity: [0, 0, 2.0]}}\n"
      "  wheel:\n"
      "    rigid: {{mass: 0.47, inertia: [[1.2e-4, 0, 0], [0, 1.2e-4, 0], [0, 0, 2.3e-4]]}}\n"
      "    markers: {{axis: {{position: [0, 0, 0]}}}}\n"
      "    initial: {{position: [0.0505, 0, 0], rotation: {{axis: [0, 0, 1], angle: {:.17g}}}, "
      "angular_velocity: [0, 0, {:.17g}]}}\n"
      "joints:\n"
      "  - {{name: pinion_axis, type: revolute, i: {{body: ground}}, j: {{body: pinion, marker: "
      "axis}}, "
      "driver: {{ramp: {{offset: 0, slope: 2.0}}}}}}\n"
      "  - {{name: wheel_axis, type: revolute, i: {{body: ground, position: [0.0505, 0, 0]}}, "
      "j: {{body: wheel, marker: axis}}}}\n"
      "forces:\n"
      "  - {{name: load, type: point_load, at: {{body: wheel, marker: axis}}, torque: [0, 0, "
      "10.0]}}\n",
      wheel_angle, -2.0 * 19.0 / 31.0);
  if (!gear_keys.empty()) {
    text +=
        "  - name: mesh\n    type: spur_gear_contact\n    wheel1: {body: pinion, marker: axis}\n"
        "    wheel2: {body: wheel, marker: axis}\n" +
        gear_keys;
  }
  return text + fmt::format(
                    "simulation: {{end_time: {}, output_interval: 1e-4, method: explicit, "
                    "relative_tolerance: 1e-8, absolute_tolerance: 1e-11, max_step: 1e-4}}\n",
                    end_time);
}

}  // namespace flexmbs::testing
