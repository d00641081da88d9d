// flexmbs' side of the FE-pair reference (bench/gear_pair_calculix.py; issue 18, docs/contact.md
// "Elastic teeth"): for the z 20/40 steel pair of tests/contact/gear_tooth_fe_test.cc (m 4 mm,
// b 40 mm, basic rack, a = a_0) it prints, as one JSON object, each wheel's tooth outline in its
// tooth frame (contact/gears/tooth_profile.h: the right flank's fillet and involute; the left is
// its mirror) and, at `angles` wheel-1 angles over one mesh cycle under the torque T on wheel 1
// (wheel 2 held), the rigid touching angle of wheel 2 and the static transmission error and
// per-pair forces of the elastic teeth (FE tables, gear_tooth_fe's defaults) and of ISO 6336-1's
// c', with the seconds per StaticTransmissionError and per EvaluateMesh.
//
//   bench_gear_pair_fe [angles=8] [torque=400]
#include <fmt/format.h>
#include <fmt/ranges.h>

#include <chrono>
#include <cmath>
#include <numbers>
#include <string>
#include <utility>
#include <vector>

#include "contact/gears/gear_mesh.h"
#include "contact/gears/gear_mesh_force.h"
#include "contact/gears/tooth_profile.h"
#include "contact/gears/tooth_stiffness.h"
#include "gear_tooth_fe/tooth_model.h"

namespace flexmbs {
namespace {

constexpr double kPi = std::numbers::pi;

contact::SpurGearSpec Wheel(int teeth) {
  return contact::SpurGearSpec{4e-3, teeth, 20.0 * kPi / 180.0, 0.0, 1.0, 1.25, 0.04};
}

std::string Points(const std::vector<Eigen::Vector2d>& points) {
  std::vector<std::string> items;
  for (const Eigen::Vector2d& p : points) items.push_back(fmt::format("[{:.17g}, {:.17g}]", p.x(), p.y()));
  return fmt::format("[{}]", fmt::join(items, ", "));
}

/// One wheel's outline and radii as JSON.
std::string WheelJson(const contact::SpurGear& gear) {
  const contact::ToothFlankProfile profile =
      contact::RightFlankProfile(gear, contact::kBasicRackTipRadius, 24);
  std::vector<Eigen::Vector2d> involute;
  constexpr int kInvolute = 40;
  for (int i = 0; i <= kInvolute; ++i) {
    involute.push_back(contact::ToothFlankPoint(
        gear, profile.form_roll + (gear.tip_roll - profile.form_roll) * i / kInvolute));
  }
  return fmt::format(
      "{{\"teeth\": {}, \"module\": {:.17g}, \"root_radius\": {:.17g}, \"tip_radius\": {:.17g}, "
      "\"base_radius\": {:.17g}, \"form_roll\": {:.17g}, \"tip_roll\": {:.17g}, \"fillet\": {}, "
      "\"involute\": {}}}",
      gear.spec.teeth, gear.spec.module, gear.root_radius, gear.tip_radius, gear.base_radius,
      profile.form_roll, gear.tip_roll, Points(profile.fillet), Points(involute));
}

/// The static transmission error delta [m] of `law` under `torque` at phi1 (wheel 2's touching
/// angle phi2_0) and the mesh's loads at wheel 2's angle phi2_0 + delta / r_b2.
std::pair<double, contact::MeshLoads> LoadedMesh(const contact::GearPair& pair, const contact::MeshLaw& law,
                                                 double phi1, double phi2_0, double torque) {
  const double a = pair.centre_distance;
  const double delta = contact::StaticTransmissionError(pair, law, a, phi1, torque);
  return {delta, contact::EvaluateMesh(pair, law, a, phi1, phi2_0 + delta / pair.gear2.base_radius, 0, 0)};
}

/// The static transmission error [m] and the loaded pairs' [tooth1, tooth2, roll1, roll2, force [N],
/// contact point x, y [m]] of `law` at
/// phi1, with wheel 2's touching angle phi2_0.
std::string ModelJson(const contact::GearPair& pair, const contact::MeshLaw& law, double phi1,
                      double phi2_0, double torque) {
  const auto [delta, loads] = LoadedMesh(pair, law, phi1, phi2_0, torque);
  std::vector<std::string> pairs;
  for (const contact::ToothPairLoad& p : loads.pairs) {
    pairs.push_back(fmt::format("[{}, {}, {:.17g}, {:.17g}, {:.17g}, {:.17g}, {:.17g}]",
                                p.pair.tooth1, p.pair.tooth2, p.pair.roll1, p.pair.roll2,
                                p.force, p.pair.p_O1C.x(), p.pair.p_O1C.y()));
  }
  return fmt::format("{{\"ste\": {:.17g}, \"pairs\": [{}]}}", delta, fmt::join(pairs, ", "));
}

/// A three-tooth segment's coupling table beside the one-tooth table `single` (same rolls) as
/// JSON (NaN as null).
std::string CouplingJson(const gear_tooth_fe::ToothCoupling& c, const contact::ToothCompliance& single) {
  const auto list = [](const std::vector<double>& v) {
    std::vector<std::string> items;
    for (const double x : v) items.push_back(std::isfinite(x) ? fmt::format("{:.6g}", x) : "null");
    return fmt::format("[{}]", fmt::join(items, ", "));
  };
  return fmt::format(
      "{{\"nodes\": {}, \"roll\": {}, \"single\": {}, \"own\": {}, \"ahead\": {}, "
      "\"behind\": {}}}",
      c.nodes, list(c.rim.roll), list(single.compliance), list(c.compliance.compliance),
      list(c.rim.ahead), list(c.rim.behind));
}

/// The static transmission error [m] at phi1 of `law` and each loaded pair's [wheel 1's tooth,
/// share of the load] as JSON.
std::string ShareJson(const contact::GearPair& pair, const contact::MeshLaw& law, double phi1,
                      double phi2_0, double torque) {
  const auto [delta, loads] = LoadedMesh(pair, law, phi1, phi2_0, torque);
  double total = 0.0;
  for (const contact::ToothPairLoad& p : loads.pairs) total += p.force;
  std::vector<std::string> shares;
  for (const contact::ToothPairLoad& p : loads.pairs)
    shares.push_back(fmt::format("[{}, {:.17g}]", p.pair.tooth1, p.force / total));
  return fmt::format("{{\"ste\": {:.17g}, \"shares\": [{}]}}", delta, fmt::join(shares, ", "));
}

/// Seconds per call of `f`, repeated for about 0.2 s.
template <typename F>
double SecondsPerCall(F&& f) {
  const auto start = std::chrono::steady_clock::now();
  int calls = 0;
  double seconds = 0.0;
  do {
    f();
    ++calls;
    seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  } while (seconds < 0.2);
  return seconds / calls;
}

int Main(int angles, double torque) {
  const contact::GearPair pair = contact::MakeGearPair({Wheel(20), Wheel(40), 0.0, 0.0});
  const contact::SpurGear gear1 = contact::MakeSpurGear(Wheel(20), "gear 1");
  const contact::SpurGear gear2 = contact::MakeSpurGear(Wheel(40), "gear 2");
  contact::ElasticTeeth teeth;
  const auto fe_start = std::chrono::steady_clock::now();
  teeth.tooth1 = gear_tooth_fe::ToothComplianceFromFe(gear1, teeth.material, {}).compliance;
  teeth.tooth2 = gear_tooth_fe::ToothComplianceFromFe(gear2, teeth.material, {}).compliance;
  const double fe_seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - fe_start).count();
  const contact::MeshLaw elastic(pair, teeth, 0.0);
  const auto coupling_start = std::chrono::steady_clock::now();
  const gear_tooth_fe::ToothCoupling coupling1 =
      gear_tooth_fe::ToothCouplingFromFe(gear1, teeth.material, {});
  const gear_tooth_fe::ToothCoupling coupling2 =
      gear_tooth_fe::ToothCouplingFromFe(gear2, teeth.material, {});
  const double coupling_seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - coupling_start).count();
  // The teeth on the three-tooth segments, alone (segment3) and coupled through the rims.
  contact::ElasticTeeth segments = teeth;
  segments.tooth1 = coupling1.compliance;
  segments.tooth2 = coupling2.compliance;
  const contact::MeshLaw segment3(pair, segments, 0.0);
  segments.rim1 = coupling1.rim;
  segments.rim2 = coupling2.rim;
  const contact::MeshLaw rims(pair, segments, 0.0);
  const contact::IsoMeshStiffness iso_stiffness = contact::IsoSinglePairStiffness(Wheel(20), Wheel(40));
  const contact::MeshLaw iso = contact::ToothPairLaw({iso_stiffness.single_pair, 0.0}, pair);
  const contact::MeshLaw iso_th = contact::ToothPairLaw({iso_stiffness.theoretical, 0.0}, pair);
  const double a = pair.centre_distance;
  std::vector<std::string> samples;
  for (int k = 0; k < angles; ++k) {
    const double phi1 = 2.0 * kPi / 20.0 * k / angles;
    const double phi2_0 = contact::TouchingAngle2(pair, a, phi1, 0.0, contact::FlankSide::kPositive);
    samples.push_back(fmt::format("{{\"phi1\": {:.17g}, \"phi2\": {:.17g}, \"fe_teeth\": {}, "
                                  "\"iso\": {}, \"iso_theoretical\": {}, \"segment3\": {}, "
                                  "\"coupled\": {}}}",
                                  phi1, phi2_0, ModelJson(pair, elastic, phi1, phi2_0, torque),
                                  ModelJson(pair, iso, phi1, phi2_0, torque),
                                  ModelJson(pair, iso_th, phi1, phi2_0, torque),
                                  ShareJson(pair, segment3, phi1, phi2_0, torque),
                                  ShareJson(pair, rims, phi1, phi2_0, torque)));
  }
  const double phi1 = 0.3 * 2.0 * kPi / 20.0;
  const double phi2_0 = contact::TouchingAngle2(pair, a, phi1, 0.0, contact::FlankSide::kPositive);
  const double ste_seconds = SecondsPerCall(
      [&] { return contact::StaticTransmissionError(pair, elastic, a, phi1, torque); });
  const double mesh_seconds = SecondsPerCall(
      [&] { return contact::EvaluateMesh(pair, elastic, a, phi1, phi2_0 - 1e-6, 0.0, 0.0); });
  fmt::print(
      "{{\"torque\": {}, \"centre_distance\": {:.17g}, \"face_width\": {:.17g}, "
      "\"youngs_modulus\": {}, \"poisson_ratio\": {}, \"contact_ratio\": {:.17g}, "
      "\"path_start\": {:.17g}, \"path_end\": {:.17g}, \"line_length\": {:.17g}, "
      "\"working_pressure_angle\": {:.17g}, \"gear1\": {}, \"gear2\": {}, \"samples\": [{}], "
      "\"fe_table_seconds\": {}, \"ste_seconds\": {}, \"mesh_seconds\": {}, "
      "\"coupling_seconds\": {}, \"coupling1\": {}, \"coupling2\": {}}}\n",
      torque, a, pair.gear1.spec.face_width, teeth.material.youngs_modulus,
      teeth.material.poisson_ratio, pair.contact_ratio, pair.path_start, pair.path_end,
      pair.line_length, pair.working_pressure_angle, WheelJson(gear1), WheelJson(gear2),
      fmt::join(samples, ", "), fe_seconds, ste_seconds, mesh_seconds, coupling_seconds,
      CouplingJson(coupling1, teeth.tooth1), CouplingJson(coupling2, teeth.tooth2));
  return 0;
}

}  // namespace
}  // namespace flexmbs

int main(int argc, char** argv) {
  const int angles = argc > 1 ? std::stoi(argv[1]) : 8;
  const double torque = argc > 2 ? std::stod(argv[2]) : 400.0;
  return flexmbs::Main(angles, torque);
}
