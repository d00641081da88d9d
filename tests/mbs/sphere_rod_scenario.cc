#include "tests/mbs/sphere_rod_scenario.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <map>
#include <string>
#include <vector>
#include <memory>
#include <span>
#include <utility>

#include "contact/laws/hertz.h"
#include "contact/laws/normal_law.h"
#include "mbs/flexible_body.h"
#include "mbs/multibody_system.h"
#include "mbs/rigid_body.h"
#include "mbs/simulation.h"
#include "mbs/surface_contact_force.h"
#include "reduction/correction_modes.h"
#include "reduction/modal_basis.h"
#include "tests/mbs/hertz_rod_model.h"
#include "tests/support/test_problems.h"

namespace flexmbs::mbs::testing {
namespace {

using Eigen::Index;

/// The end face's nodes nearest its centre and their weights: one node at the centre, or the
/// nodes around it in equal shares.
void FindContactNodes(SphereRod* scenario) {
  const fem::Mesh& mesh = scenario->rod.mesh;
  const Eigen::Vector2d centre(0.5 * scenario->setup.side, 0.5 * scenario->setup.side);
  double nearest = HUGE_VAL;
  for (int node : mesh.node_sets.at("end")) {
    nearest = std::min(nearest, (mesh.nodes.col(node).tail<2>() - centre).norm());
  }
  for (int node : mesh.node_sets.at("end")) {
    if ((mesh.nodes.col(node).tail<2>() - centre).norm() <= nearest + 1e-12) scenario->contact_nodes.push_back(node);
  }
  scenario->b = Eigen::VectorXd::Zero(scenario->rod.K.rows());
  const double share = 1.0 / static_cast<double>(scenario->contact_nodes.size());
  for (int node : scenario->contact_nodes) scenario->b(3 * node) = share;
}

/// The elastic modes b^T phi reaches (above 1e-6 of the largest), ascending.
std::vector<Index> LoadedModes(const SphereRod& scenario) {
  const std::vector<Index> elastic = ElasticColumns(scenario.rod.basis);
  double largest = 0.0;
  for (Index j : elastic) largest = std::max(largest, std::abs(scenario.b.dot(scenario.rod.basis.Phi.col(j))));
  std::vector<Index> loaded;
  for (Index j : elastic) {
    if (std::abs(scenario.b.dot(scenario.rod.basis.Phi.col(j))) > 1e-6 * largest) loaded.push_back(j);
  }
  return loaded;
}

/// The lowest `modes` loaded modes, with the contact load's static correction mode if asked.
reduction::ReducedBasis RodBasis(const SphereRod& scenario, int modes, bool correction) {
  const std::vector<Index> loaded = LoadedModes(scenario);
  const reduction::ReducedBasis basis =
      KeepColumns(scenario.rod.basis, std::vector<Index>(loaded.begin(), loaded.begin() + modes));
  if (!correction) return basis;
  const reduction::LoadSet hit{"hit", scenario.contact_nodes, Eigen::Vector3d::UnitX(),
                               reduction::LoadDistribution::kResultant, {}};
  const FeReducedBody& fe = scenario.rod;
  return reduction::AddStaticCorrectionModes({fe.K, fe.M, fe.mesh.nodes}, basis, std::span(&hit, 1)).basis;
}

}  // namespace

SphereRod MakeSphereRod(const SphereRodSetup& setup) {
  SphereRod scenario;
  scenario.setup = setup;
  const fem::IsotropicMaterial steel = flexmbs::testing::Steel();
  scenario.rod = FreeFreeBox(
      setup.cells, Eigen::Vector3d(setup.length, setup.side, setup.side), steel,
      [](const fem::Mesh& mesh) {
        return std::map<std::string, std::vector<int>>{{"end", flexmbs::testing::NodesOnPlane(mesh, 0, 0.0)}};
      },
      {"end"}, setup.axial_band * std::sqrt(steel.youngs_modulus_pa / steel.density_kg_m3) / (2.0 * setup.length));
  FindContactNodes(&scenario);
  scenario.sphere_mass = steel.density_kg_m3 * 4.0 / 3.0 * M_PI * std::pow(setup.radius, 3);
  const contact::ElasticMaterial material{steel.youngs_modulus_pa, steel.poisson_ratio};
  scenario.hertz_stiffness = contact::HertzStiffness(contact::EffectiveModulus(material, material), setup.radius);
  return scenario;
}

ForceHistory FullSphereRod(const SphereRod& scenario, int substeps) {
  const SphereRodSetup& setup = scenario.setup;
  const HertzImpactModel model{scenario.rod.K, scenario.rod.M, scenario.b, scenario.sphere_mass,
                               scenario.hertz_stiffness, 0.0};
  const HertzImpactHistory run = IntegrateHertzImpact(model, setup.speed, setup.output / substeps, setup.end_time);
  ForceHistory history;
  const std::size_t every = static_cast<std::size_t>(substeps);
  for (std::size_t k = every - 1; k < run.force.size(); k += every) history.force.push_back(run.force[k]);
  history.seconds = run.seconds;
  return history;
}

ForceHistory ReducedSphereRod(const SphereRod& scenario, int modes, bool correction, double rtol) {
  const SphereRodSetup& setup = scenario.setup;
  const reduction::ReducedBasis basis = RodBasis(scenario, modes, correction);
  sid::ReducedBody data = Reduce(scenario.rod, basis);
  data.name = "rod";
  const sid::ContactSurface end = data.surfaces.at(0);
  ForceHistory history;
  history.highest_mode_hz = data.frequency_hz(modes - 1);

  MultibodySystem system(Eigen::Vector3d::Zero());
  const int rod = system.AddBody(std::make_unique<FlexibleBody>("rod", std::move(data), false));
  const double inertia = 0.4 * scenario.sphere_mass * setup.radius * setup.radius;
  const int ball = system.AddBody(std::make_unique<RigidBody>("ball", scenario.sphere_mass, Eigen::Vector3d::Zero(),
                                                              inertia * Eigen::Matrix3d::Identity(),
                                                              std::vector<RigidBodyMarker>{{"centre"}}));
  auto element = std::make_unique<SphereSurfaceContact>(
      "hit", MarkerRef::OnBody(ball, 0), setup.radius,
      MarkerRef::OnBody(rod, system.body(rod).FindMarker(FlexibleBody::kOriginMarker)), end, basis.num_modes(),
      CompliantContactLaw{contact::HertzLaw(scenario.hertz_stiffness), {}});
  const SphereSurfaceContact* hit = element.get();
  system.AddForceElement(std::move(element));
  Eigen::VectorXd y0 = system.NeutralState();
  y0.segment<3>(system.position_offset(ball)) = Eigen::Vector3d(-setup.radius, 0.5 * setup.side, 0.5 * setup.side);
  y0(system.num_positions() + system.velocity_offset(ball)) = setup.speed;

  SimulationOptions options;
  options.integrator.method = OdeMethod::kImplicit;
  options.integrator.relative_tolerance = rtol;
  options.integrator.absolute_tolerance = 1e-6 * rtol;
  options.end_time = setup.end_time;
  options.output_interval = setup.output;
  const auto start = std::chrono::steady_clock::now();
  Simulate(system, options, y0, [&](double t, const Eigen::VectorXd& y, const Eigen::VectorXd&) {
    if (t > 0.0) history.force.push_back(hit->NormalForce(t, system, y));
  });
  history.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return history;
}

double Peak(const ForceHistory& history) { return *std::max_element(history.force.begin(), history.force.end()); }

double Duration(const ForceHistory& history, double output) {
  std::size_t first = 0, last = 0;
  for (std::size_t k = 0; k < history.force.size(); ++k) {
    if (history.force[k] > 0.0) {
      if (last == 0) first = k;
      last = k + 1;
    }
  }
  return static_cast<double>(last - first) * output;
}

double HistoryError(const ForceHistory& a, const ForceHistory& b) {
  double largest = 0.0;
  for (std::size_t k = 0; k < std::min(a.force.size(), b.force.size()); ++k) {
    largest = std::max(largest, std::abs(a.force[k] - b.force[k]));
  }
  return largest / Peak(b);
}

double HertzContactTime(const SphereRod& scenario) {
  const double v = scenario.setup.speed;
  return 2.94 * std::pow(5.0 * scenario.sphere_mass * v * v / (4.0 * scenario.hertz_stiffness), 0.4) / v;
}

}  // namespace flexmbs::mbs::testing
