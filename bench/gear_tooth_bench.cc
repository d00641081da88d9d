// The FE tooth's compliance and the single-pair mesh stiffness it gives (issue 18; docs/contact.md,
// "Elastic teeth"), on refined meshes and for the rim segment's modelling choices: the pair of
// tests/contact/gear_tooth_fe_test.cc (m 4 mm, z 20/40, basic rack), printed per mesh the nodes,
// the seconds of both FE runs, and the stiffness at the path's start, maximum, pitch point and end
// [N/(mm um)] with ISO 6336-1's c'_th beside them. Prints a table; takes no options.
//
//   bench_gear_tooth
#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <numbers>

#include "gear_tooth_fe/tooth_model.h"
#include "contact/gears/tooth_stiffness.h"

namespace flexmbs {
namespace {

constexpr double kPerMmMicron = 1e9;

contact::SpurGearSpec Wheel(int teeth) {
  return contact::SpurGearSpec{4e-3, teeth, 20.0 * std::numbers::pi / 180.0, 0.0, 1.0, 1.25,
                               0.04};
}

/// One line of the table for `options` (and the label of what it varies).
void Row(const std::string& label, const gear_tooth_fe::ToothModelOptions& options) {
  const contact::GearPair pair = contact::MakeGearPair({Wheel(20), Wheel(40), 0.0, 0.0});
  contact::ElasticTeeth teeth;
  const auto start = std::chrono::steady_clock::now();
  const auto fe1 = gear_tooth_fe::ToothComplianceFromFe(contact::MakeSpurGear(Wheel(20), "g1"),
                                                        teeth.material, options);
  const auto fe2 = gear_tooth_fe::ToothComplianceFromFe(contact::MakeSpurGear(Wheel(40), "g2"),
                                                        teeth.material, options);
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  teeth.tooth1 = fe1.compliance;
  teeth.tooth2 = fe2.compliance;
  const auto c = [&](double s) {
    return contact::TeethPairStiffness(teeth, pair, s / pair.gear1.base_radius,
                                       (pair.line_length - s) / pair.gear2.base_radius) /
           kPerMmMicron;
  };
  double c_max = 0.0;
  for (int i = 0; i <= 400; ++i)
    c_max = std::max(c_max, c(pair.path_start + (pair.path_end - pair.path_start) * i / 400.0));
  const double s_pitch = pair.gear1.base_radius * std::tan(pair.working_pressure_angle);
  fmt::print("{:<28} {:>7} {:>7.2f} {:>8.4f} {:>8.4f} {:>8.4f} {:>8.4f}\n", label,
             fe1.nodes + fe2.nodes, seconds, c(pair.path_start), c_max, c(s_pitch),
             c(pair.path_end));
}

int Main() {
  const contact::IsoMeshStiffness iso = contact::IsoSinglePairStiffness(Wheel(20), Wheel(40));
  fmt::print("z 20/40, m 4 mm, basic rack: ISO 6336-1 c'_th {:.4f}, c' {:.4f} N/(mm um)\n",
             iso.theoretical / kPerMmMicron, iso.single_pair / kPerMmMicron);
  fmt::print("{:<28} {:>7} {:>7} {:>8} {:>8} {:>8} {:>8}\n", "model", "nodes", "s", "c_start",
             "c_max", "c_pitch", "c_end");
  for (const int order : {1, 2}) {
    for (const double size : {0.4, 0.25, 0.15, 0.1}) {
      gear_tooth_fe::ToothModelOptions options;
      options.element_order = order;
      options.geometry.mesh_size = size;
      Row(fmt::format("order {} edge {} m", order, size), options);
    }
  }
  for (const double depth : {2.0, 3.5, 5.0, 7.0}) {
    for (const double pitches : {1.0, 1.5, 2.5, 3.5}) {
      gear_tooth_fe::ToothModelOptions options;
      options.geometry.mesh_size = 0.25;
      options.geometry.rim_depth = depth;
      options.geometry.segment_pitches = pitches;
      Row(fmt::format("rim {} m, segment {} p", depth, pitches), options);
    }
  }
  return 0;
}

}  // namespace
}  // namespace flexmbs

int main() { return flexmbs::Main(); }
