#include "app/gear_results.h"

#include <algorithm>
#include <cmath>

#include "contact/gears/gear_mesh.h"
#include "mbs/gear_mesh_element.h"

namespace flexmbs::app {
namespace {

/// The spur gear elements of `system`, in order.
std::vector<const mbs::GearMeshElement*> Gears(const mbs::MultibodySystem& system) {
  std::vector<const mbs::GearMeshElement*> gears;
  for (int k = 0; k < system.num_force_elements(); ++k) {
    if (const auto* gear = dynamic_cast<const mbs::GearMeshElement*>(&system.force_element(k))) {
      gears.push_back(gear);
    }
  }
  return gears;
}

/// Slots of one base pitch along the path of contact per flank side: floor(epsilon) + 1, enough
/// for every pair in contact at once (pairs in contact lie p_b apart within s_A ... s_E).
int SlotsPerSide(const contact::GearPair& pair) {
  return static_cast<int>(std::floor(pair.contact_ratio)) + 1;
}

}  // namespace

std::vector<mbs::ResultsLayout::ElementSeries> GearSeries(const mbs::MultibodySystem& system) {
  std::vector<mbs::ResultsLayout::ElementSeries> series;
  for (const mbs::GearMeshElement* gear : Gears(system)) {
    series.push_back({"gears",
                      gear->name(),
                      "spur_gear_contact",
                      {{"active_pairs", 0, "1"},
                       {"mesh_force", 0, "N"},
                       {"pair_force", 2 * SlotsPerSide(gear->pair()), "N"},
                       {"tooth1_deflection", 2 * SlotsPerSide(gear->pair()), "m"},
                       {"tooth2_deflection", 2 * SlotsPerSide(gear->pair()), "m"},
                       {"transmission_error", 0, "rad"},
                       {"transmission_error_length", 0, "m"},
                       {"torque", 2, "N m"}}});
  }
  return series;
}

std::vector<std::vector<Eigen::VectorXd>> GearRows(const mbs::MultibodySystem& system, double t,
                                                   const Eigen::VectorXd& y) {
  std::vector<std::vector<Eigen::VectorXd>> rows;
  for (const mbs::GearMeshElement* gear : Gears(system)) {
    const contact::GearPair& pair = gear->pair();
    const mbs::GearMeshElement::Readout mesh = gear->Read(t, system, y);
    const int slots = SlotsPerSide(pair);
    Eigen::VectorXd pair_force = Eigen::VectorXd::Zero(2 * slots);
    Eigen::VectorXd deflection1 = pair_force, deflection2 = pair_force;
    double active = 0.0, total = 0.0;
    for (std::size_t i = 0; i < mesh.pairs.size(); ++i) {
      const contact::ToothPairLoad& load = mesh.pairs[i];
      if (!(load.pair.gap < 0.0)) continue;
      active += 1.0;
      total += load.force;
      const double s = pair.gear1.base_radius * load.pair.roll1;  // from T1 along the line
      const int slot =
          std::clamp(static_cast<int>(std::floor((s - pair.path_start) / pair.gear1.base_pitch)), 0,
                     slots - 1);
      const int side = load.pair.side == contact::FlankSide::kPositive ? 0 : slots;
      pair_force(side + slot) += load.force;
      deflection1(side + slot) += mesh.deflections[i].tooth1;
      deflection2(side + slot) += mesh.deflections[i].tooth2;
    }
    // Wheel 2's lag behind its rigid kinematic angle on the positive flanks (wheel 1 driving
    // about +z), as contact::StaticTransmissionError defines it.
    const double error =
        mesh.phi2 - contact::TouchingAngle2(pair, mesh.centre_distance, mesh.phi1, mesh.phi2,
                                            contact::FlankSide::kPositive);
    rows.push_back({Eigen::VectorXd::Constant(1, active), Eigen::VectorXd::Constant(1, total),
                    pair_force, deflection1, deflection2, Eigen::VectorXd::Constant(1, error),
                    Eigen::VectorXd::Constant(1, pair.gear2.base_radius * error),
                    Eigen::Vector2d(mesh.torque1, mesh.torque2)});
  }
  return rows;
}

}  // namespace flexmbs::app
