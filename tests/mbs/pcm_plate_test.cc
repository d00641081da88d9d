// mbs/pcm_contact_force.h between a rigid sphere and a reduced body: a steel plate clamped at its
// four sides, a rigid sphere pressed into its top face with a known force. The contact carries the
// force, and the plate deflects as its FE model does under the elements' nodal loads (K u = f
// solved here, without the multibody code) and near Kirchhoff's clamped square plate under a
// central load. Struck by the sphere, the plate (its fixed-interface modes) keeps the energy and
// the force history follows the point contact of the same law (sphere_surface_contact, k delta^2
// with k = c pi R) on the same reduced plate; the implicit method, Newton on the element's
// Jacobian with its modal columns, gives the explicit run's history. The mode advice's contact
// time for the pair (its layers' law fitted past first touch) is the strike's.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <functional>
#include <memory>
#include <vector>

#include "mbs/contact_mode_advice.h"
#include "mbs/flexible_body.h"
#include "mbs/multibody_system.h"
#include "mbs/pcm_contact_force.h"
#include "mbs/rigid_body.h"
#include "mbs/simulation.h"
#include "mbs/surface_contact_force.h"
#include "tests/contact/pcm_meshes.h"
#include "tests/mbs/pcm_flexible_bodies.h"
#include "tests/support/test_problems.h"

namespace flexmbs::mbs {
namespace {

using Eigen::Index;
using Eigen::Vector3d;
using Eigen::VectorXd;

constexpr double kSide = 0.2, kThickness = 0.01, kCell = 0.01;  // plate 0.2 x 0.2 x 0.01 m, 20 x 20 x 2 hex8
constexpr double kRadius = 0.02, kForce = 500.0;               // the sphere [m] and the force pressing it [N]
const contact::ElasticLayer kLayer{1e8, 2e-3};                  // c = 2.5e10 N/m^3 for two
constexpr double kMaxDepth = 3e-3;                              // [m]
const Vector3d kCentre(0.5 * kSide + 1.3e-3, 0.5 * kSide + 0.7e-3, 0.0);  // under the sphere, off the node

/// The plate clamped at its four side faces, its top face the contact surface "top" with the
/// attachment modes of the top nodes within a cell of the centre.
const testing::ClampedBox& Plate() {
  static const testing::ClampedBox plate = testing::MakeClampedBox(
      "plate", Eigen::Vector3i(20, 20, 2), Vector3d(kSide, kSide, kThickness),
      [](const fem::Mesh& mesh) { return testing::SideFaceNodes(mesh, kSide, kSide); },
      "top", [](const fem::Mesh& mesh) { return flexmbs::testing::NodesOnPlane(mesh, 2, kThickness); },
      [](const fem::Mesh& mesh) {
        return testing::NodesInBox(mesh, Vector3d(0.5 * kSide - kCell, 0.5 * kSide - kCell, kThickness),
                                   Vector3d(0.5 * kSide + kCell, 0.5 * kSide + kCell, kThickness));
      },
      4);
  return plate;
}

TEST(PcmPlate, ASpherePressedIntoAClampedPlateDeflectsItAsItsFeModel) {
  MultibodySystem system(Vector3d::Zero());
  const int plate = system.AddBody(std::make_unique<FlexibleBody>("plate", Plate().fe.body, false));
  const int ball = system.AddBody(std::make_unique<RigidBody>(
      "ball", 0.26, Vector3d::Zero(), (0.4 * 0.26 * kRadius * kRadius * Eigen::Matrix3d::Identity()).eval(),
      std::vector<RigidBodyMarker>{{"centre", Vector3d::Zero(), Eigen::Matrix3d::Identity()}}));
  const auto& body = dynamic_cast<const FlexibleBody&>(system.body(plate));
  const sid::ContactSurface& top = body.data().surfaces.at(0);
  const contact::PolygonMesh sphere = contact::testing::Icosphere(Vector3d::Zero(), kRadius, 4);
  auto element = std::make_unique<PcmContactForce>(
      "press", PcmSurface{"sphere", MarkerRef::OnBody(ball, 0), sphere, kLayer, true},
      ModalPcmSurface(MarkerRef::OnBody(plate, body.FindMarker(FlexibleBody::kOriginMarker)), top, body.num_modes(), kLayer,
                      false),
      0.0, contact::RegularisedCoulomb{0.0, 1e-3}, kMaxDepth);
  const PcmContactForce& press = *element;
  system.AddForceElement(std::move(element));
  VectorXd y = system.NeutralState(), x_ball(7);
  x_ball << kCentre + Vector3d(0.0, 0.0, kThickness + kRadius - 5e-4), 1.0, 0.0, 0.0, 0.0;
  system.SetBodyState(ball, x_ball, VectorXd::Zero(6), y);
  // Unknowns: the sphere's height (pressed down by kForce) and the plate's modal coordinates.
  std::vector<testing::Unknown> unknowns{testing::Translation(system, ball, 2)};
  for (const testing::Unknown& u : testing::ModalCoordinates(system, plate)) unknowns.push_back(u);
  VectorXd extra = VectorXd::Zero(static_cast<Index>(unknowns.size()));
  extra(0) = -kForce;
  const int iterations = testing::SolveStatics(system, unknowns, extra, 1e-8, 1e-8, y);
  ASSERT_GE(iterations, 0) << "Newton did not converge";

  double normal_force = 0.0;
  for (const ContactLoad& load : press.ContactLoads(0.0, system, y)) normal_force += load.f_W.z();
  // The FE model under the elements' nodal loads, solved here.
  const VectorXd q = system.BodyPositions(y, plate).tail(body.num_modes());
  const testing::ReferenceSide sphere_side{nullptr, nullptr, sphere, y.segment<3>(system.position_offset(ball)),
                                           Eigen::Matrix3d::Identity(), VectorXd()};
  const testing::ReferenceSide plate_side{
      &Plate(), &top, ModalPcmSurface(MarkerRef::Ground(Vector3d::Zero()), top, body.num_modes(), kLayer, false).mesh_M,
      Vector3d::Zero(), Eigen::Matrix3d::Identity(), q};
  const contact::ElasticFoundation law =
      contact::MakeElasticFoundation(kLayer, "sphere", kLayer, "top", 0.0, contact::RegularisedCoulomb{0.0, 1e-3});
  const VectorXd f = testing::ReferenceNodalLoads(sphere_side, plate_side, law, kMaxDepth)[1];
  const VectorXd u_fe = testing::ClampedStaticResponse(Plate(), f), u_reduced = Plate().fe.basis.Phi * q;
  const double fe_error = (u_reduced - u_fe).cwiseAbs().maxCoeff() / u_fe.cwiseAbs().maxCoeff();
  // Kirchhoff: the clamped square plate's centre under a central load P deflects 0.00560 P a^2 / D
  // (Timoshenko & Woinowsky-Krieger 1959, table 35). The FE plate's mid-surface at its centre: the
  // mean of the bottom and top nodes' deflections under the load's centre, read at the nearest
  // node column (the load is 1.5 mm off it).
  const fem::IsotropicMaterial steel = flexmbs::testing::Steel();
  const double D = steel.youngs_modulus_pa * std::pow(kThickness, 3) / (12.0 * (1.0 - std::pow(steel.poisson_ratio, 2)));
  const double kirchhoff = 0.00560 * kForce * kSide * kSide / D;
  double mid_surface = 0.0;
  for (const int node : testing::NodesInBox(Plate().fe.mesh, Vector3d(0.5 * kSide, 0.5 * kSide, kThickness / 2.0),
                                            Vector3d(0.5 * kSide, 0.5 * kSide, kThickness / 2.0))) {
    mid_surface = -u_fe(3 * node + 2);
  }
  std::printf("[ numbers  ] %d Newton steps; normal force %.9g N (applied %.9g); depth of the sphere %.4e m; reduced vs FE "
              "deflection %.3e (largest %.4e m); mid-surface centre deflection %.5e m, Kirchhoff %.5e m (%.3e)\n",
              iterations, normal_force, kForce, kThickness + kRadius - y(system.position_offset(ball) + 2), fe_error,
              u_fe.cwiseAbs().maxCoeff(), mid_surface, kirchhoff, mid_surface / kirchhoff - 1.0);
  EXPECT_NEAR(normal_force, kForce, 1e-7);  // Newton's tolerance 1e-8 N on the sphere's row
  // Measured 6.0e-13: the attachment modes hold every static response to loads on the patch.
  EXPECT_LT(fe_error, 1e-11);
  // Measured -19.8 %: hex8 cells 10 x 10 x 5 mm lock in bending (the FE plate is stiffer than
  // Kirchhoff's; Mindlin's shear, a/h = 20, would soften the theory further).
  EXPECT_NEAR(mid_surface / kirchhoff, 1.0, 0.5);
}

/// The plate with only its 8 lowest fixed-interface modes (to 2.2e4 Hz), for the impact.
const testing::ClampedBox& ModalPlate() {
  static const testing::ClampedBox plate = testing::MakeClampedBox(
      "plate", Eigen::Vector3i(20, 20, 2), Vector3d(kSide, kSide, kThickness),
      [](const fem::Mesh&) { return Plate().clamped; },
      "top", [](const fem::Mesh& mesh) { return flexmbs::testing::NodesOnPlane(mesh, 2, kThickness); },
      [](const fem::Mesh&) { return std::vector<int>(); }, 8);
  return plate;
}

/// A steel sphere striking the clamped plate's centre at 0.3 m/s (no gravity, no damping) through
/// `contact(system, plate, ball)`, explicit at tolerances 1e-9 / 1e-12 (or implicit at 1e-8 /
/// 1e-11) for 3 ms: per output (every 10 us) the normal force, and the largest energy gain.
struct Impact {
  std::vector<double> force;
  double energy_gain = 0.0, start_energy = 0.0, rebound = 0.0;
  std::vector<ContactModeAdvice> advice;  ///< at the start (mbs/contact_mode_advice.h)
};
using ContactFactory = std::function<std::unique_ptr<ForceElement>(const MultibodySystem&, int, int)>;
using ForceReader = std::function<double(const MultibodySystem&, const VectorXd&)>;
Impact Strike(const ContactFactory& contact, const ForceReader& normal_force, OdeMethod method = OdeMethod::kExplicit) {
  constexpr double kMass = 7850.0 * 4.0 / 3.0 * M_PI * kRadius * kRadius * kRadius, kSpeed = 0.3;
  MultibodySystem system(Vector3d::Zero());
  const int plate = system.AddBody(std::make_unique<FlexibleBody>("plate", ModalPlate().fe.body, false));
  const int ball = system.AddBody(std::make_unique<RigidBody>(
      "ball", kMass, Vector3d::Zero(), (0.4 * kMass * kRadius * kRadius * Eigen::Matrix3d::Identity()).eval(),
      std::vector<RigidBodyMarker>{{"centre", Vector3d::Zero(), Eigen::Matrix3d::Identity()}}));
  system.AddJoint(Joint("clamp", JointType::kFixed, MarkerRef::Ground(Vector3d::Zero()),
                        MarkerRef::OnBody(plate, system.body(plate).FindMarker(FlexibleBody::kOriginMarker))));
  system.AddForceElement(contact(system, plate, ball));
  VectorXd y = system.NeutralState(), x_ball(7), u_ball = VectorXd::Zero(6);
  x_ball << kCentre + Vector3d(0.0, 0.0, kThickness + kRadius + 1e-5), 1.0, 0.0, 0.0, 0.0;
  u_ball(2) = -kSpeed;
  system.SetBodyState(ball, x_ball, u_ball, y);
  SimulationOptions options;
  options.integrator.method = method;  // implicit: Newton on the model Jacobian, the element's included
  options.end_time = 3e-3;
  options.output_interval = 1e-5;
  options.integrator.relative_tolerance = method == OdeMethod::kExplicit ? 1e-9 : 1e-8;
  options.integrator.absolute_tolerance = method == OdeMethod::kExplicit ? 1e-12 : 1e-11;
  const auto energy = [&](const VectorXd& s) { return system.KineticEnergy(s) + system.PotentialEnergy(0.0, s); };
  Impact impact;
  impact.start_energy = energy(y);
  impact.advice = AdviseContactModes(system, y);
  Simulate(system, options, y, [&](double, const VectorXd& s, const VectorXd&) {
    impact.force.push_back(normal_force(system, s));
    impact.energy_gain = std::max(impact.energy_gain, energy(s) - impact.start_energy);
    impact.rebound = s(system.num_positions() + system.velocity_offset(ball) + 2) / kSpeed;
  });
  return impact;
}

/// The PCM contact of the sphere's lower cap of `level` on the plate, and its normal force.
ContactFactory CapOnPlate(int level) {
  return [level](const MultibodySystem& system, int plate, int ball) {
    const auto& body = dynamic_cast<const FlexibleBody&>(system.body(plate));
    return std::make_unique<PcmContactForce>(
        "strike",
        PcmSurface{"cap", MarkerRef::OnBody(ball, 0), contact::testing::LowerCap(kRadius, level),
                   kLayer, false},
        ModalPcmSurface(MarkerRef::OnBody(plate, body.FindMarker(FlexibleBody::kOriginMarker)),
                        body.data().surfaces.at(0), body.num_modes(), kLayer, false),
        0.0, contact::RegularisedCoulomb{0.0, 1e-3}, kMaxDepth);
  };
}
double PcmNormalForce(const MultibodySystem& system, const VectorXd& y) {
  double sum = 0.0;
  for (const ContactLoad& load : system.force_element(0).ContactLoads(0.0, system, y)) sum += load.f_W.z();
  return sum;
}

TEST(PcmPlate, ASphereStrikingThePlateKeepsTheEnergyAndFollowsThePointContactOfTheSameLaw) {
  const contact::ElasticFoundation law =
      contact::MakeElasticFoundation(kLayer, "sphere", kLayer, "top", 0.0, contact::RegularisedCoulomb{0.0, 1e-3});
  const auto origin = [](const MultibodySystem& system, int plate) {
    return MarkerRef::OnBody(plate, system.body(plate).FindMarker(FlexibleBody::kOriginMarker));
  };
  const auto surface = [](const MultibodySystem& system, int plate) -> const sid::ContactSurface& {
    return dynamic_cast<const FlexibleBody&>(system.body(plate)).data().surfaces.at(0);
  };
  const Impact pcm = Strike(CapOnPlate(5), PcmNormalForce);
  // The point contact of the foundation's law on a sphere, c pi delta^2 (R - delta / 3), to first
  // order: k delta^2 with k = c pi R.
  const Impact point = Strike(
      [&](const MultibodySystem& system, int plate, int ball) {
        return std::make_unique<SphereSurfaceContact>(
            "strike", MarkerRef::OnBody(ball, 0), kRadius, origin(system, plate), surface(system, plate),
            system.body(plate).num_modes(), CompliantContactLaw{contact::LinearLaw(law.stiffness * M_PI * kRadius, 0.0, 2.0), {}});
      },
      [](const MultibodySystem& system, const VectorXd& y) {
        return dynamic_cast<const SphereSurfaceContact&>(system.force_element(0)).NormalForce(0.0, system, y);
      });
  ASSERT_EQ(pcm.force.size(), point.force.size());
  const double peak_pcm = *std::max_element(pcm.force.begin(), pcm.force.end());
  const double peak_point = *std::max_element(point.force.begin(), point.force.end());
  double history = 0.0;
  int contact_pcm = 0, contact_point = 0;
  for (std::size_t k = 0; k < pcm.force.size(); ++k) {
    history = std::max(history, std::abs(pcm.force[k] - point.force[k]) / peak_point);
    contact_pcm += pcm.force[k] > 0.0;
    contact_point += point.force[k] > 0.0;
  }
  std::printf("[ numbers  ] peak force %.5g N, point contact %.5g N (%.3e); samples in contact %d, %d; history error %.3e "
              "of the peak; rebound %.9f, %.9f of the speed; energy gained %.2e J, %.2e J of %.4e J\n",
              peak_pcm, peak_point, peak_pcm / peak_point - 1.0, contact_pcm, contact_point, history, pcm.rebound,
              point.rebound, pcm.energy_gain, point.energy_gain, pcm.start_energy);
  EXPECT_GT(peak_point, 10.0);
  // Measured: peak -0.24 %, history 1.8e-2 of the peak, in contact 268 against 265 samples
  // (the polyhedral cap, 20480-triangle sphere, against k delta^2 at the nearest point).
  EXPECT_NEAR(peak_pcm / peak_point, 1.0, 0.025);
  EXPECT_LT(history, 0.1);
  EXPECT_NEAR(contact_pcm, contact_point, 10);
  EXPECT_LT(pcm.energy_gain, 5e-12);  // [J], measured 4.1e-13 of 1.18e-2 J
  // Both rebound at 0.99999954 v (the plate keeps 9e-7 of the energy in its modes), 3.2e-8 apart.
  EXPECT_NEAR(pcm.rebound, point.rebound, 3e-7);
}

TEST(PcmPlate, TheModeAdvicesContactTimeIsTheStrikesFromTheLayersLawOnTheCap) {
  // The advice fits F = k delta^n to the layers' force on the polyhedral cap past first touch; the
  // closed form is the sphere's c pi delta^2 (R - delta / 3), to first order k delta^2 with
  // k = c pi R, struck by the ball alone (the plate is clamped: m* = m).
  const Impact pcm = Strike(CapOnPlate(5), PcmNormalForce);
  ASSERT_EQ(pcm.advice.size(), 1u);
  const ContactModeAdvice& a = pcm.advice.front();
  const double mass = 7850.0 * 4.0 / 3.0 * M_PI * kRadius * kRadius * kRadius, c = 2.5e10;
  const double closed_form = PowerLawContactTime(mass, 0.3, c * M_PI * kRadius, 2.0);
  // The strike's contact time: the outputs (every 10 us) with a force, each end interpolated
  // linearly to the zero crossing.
  const std::vector<double>& f = pcm.force;
  const auto first = std::find_if(f.begin(), f.end(), [](double x) { return x > 0.0; });
  const auto last = std::find_if(f.rbegin(), f.rend(), [](double x) { return x > 0.0; });
  ASSERT_TRUE(first != f.begin() && first != f.end() && last != f.rbegin());
  const double begin = static_cast<double>(first - f.begin()) - *first / (*first - *(first - 1));
  const double end = static_cast<double>(f.rend() - last - 1) + *last / (*last - *(last - 1));
  const double measured = 1e-5 * (end - begin);
  std::printf("[ numbers  ] %s\n[ numbers  ] t_c %.4e s: closed form %.4e s (%.3e), the strike %.4e s (%.3e); fitted "
              "n = %.4f, m* / m - 1 = %.2e\n",
              a.Describe().c_str(), a.contact_time, closed_form, a.contact_time / closed_form - 1.0, measured,
              a.contact_time / measured - 1.0, a.law_exponent, a.effective_mass / mass - 1.0);
  EXPECT_EQ(a.type, "pcm_contact");
  EXPECT_EQ(a.body, "plate");
  EXPECT_NEAR(a.effective_mass / mass, 1.0, 1e-12);  // measured 0: the clamped plate counts as the ground
  // Measured: n = 2.034 (the facets' sag: the polyhedral cap stiffens a little faster than delta^2);
  // t_c +1.10 % from the closed form (the cap's n and its shallower sag), -0.66 % from the strike
  // (the plate's own compliance, 8 modes, lengthens the strike).
  EXPECT_NEAR(a.law_exponent, 2.0, 0.1);
  EXPECT_NEAR(a.contact_time / closed_form, 1.0, 0.03);
  EXPECT_NEAR(a.contact_time / measured, 1.0, 0.02);
}

TEST(PcmPlate, TheImplicitMethodOnTheElementsJacobianGivesTheExplicitStrike) {
  // The 5120-triangle sphere's cap: the comparison needs no finer one.
  const Impact explicit_run = Strike(CapOnPlate(4), PcmNormalForce);
  const Impact implicit_run = Strike(CapOnPlate(4), PcmNormalForce, OdeMethod::kImplicit);
  ASSERT_EQ(implicit_run.force.size(), explicit_run.force.size());
  const double peak = *std::max_element(explicit_run.force.begin(), explicit_run.force.end());
  double history = 0.0;
  for (std::size_t k = 0; k < explicit_run.force.size(); ++k) {
    history = std::max(history, std::abs(implicit_run.force[k] - explicit_run.force[k]) / peak);
  }
  std::printf("[ numbers  ] implicit against explicit: peak %.5g N, force history %.3e of the peak, rebound %.9f and "
              "%.9f, energy gained %.2e J and %.2e J\n",
              peak, history, implicit_run.rebound, explicit_run.rebound, implicit_run.energy_gain, explicit_run.energy_gain);
  EXPECT_GT(peak, 10.0);
  // Measured: history 4.2e-9 of the peak, rebounds 4e-9 apart, the implicit run gains 4.0e-10 J
  // of 1.18e-2 J (its tolerances, 1e-8 / 1e-11).
  EXPECT_LT(history, 4e-8);
  EXPECT_NEAR(implicit_run.rebound, explicit_run.rebound, 1e-8);
  EXPECT_LT(implicit_run.energy_gain, 3e-9);
}

}  // namespace
}  // namespace flexmbs::mbs
