// The compliant contact elements in a scene file (mbs/scene_contact.h, docs/scene.md): the law,
// materials and friction keys build the law they name, and bad values are one-line errors
// naming the file, the item and the value. The Jacobian of a frictional sphere-sphere contact.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>
#include <unistd.h>

#include "contact/laws/hertz.h"
#include "mbs/contact_force.h"
#include "mbs/multibody_system.h"
#include "mbs/rigid_body.h"
#include "mbs/scene.h"
#include "tests/input_error.h"

namespace flexmbs::mbs {
namespace {

using Eigen::Vector3d;
using Eigen::VectorXd;

/// Writes a scene of two steel balls (one at z = 0.0099 m over the ground, one beside it at
/// x = 0.0199 m: both 0.1 mm into their contacts) with the force entries `forces` (YAML list
/// items, one per line) and loads it.
class ContactScene {
 public:
  ContactScene() : dir_(std::filesystem::temp_directory_path() / ("flexmbs_laws_" + std::to_string(::getpid()))) {
    std::filesystem::create_directories(dir_);
  }
  ~ContactScene() { std::filesystem::remove_all(dir_); }
  ContactScene(const ContactScene&) = delete;
  ContactScene& operator=(const ContactScene&) = delete;

  std::filesystem::path Write(const std::string& forces) const {
    const std::filesystem::path file = dir_ / "scene.yaml";
    const std::string ball = "    rigid: {mass: 0.0329, inertia: [[1.3e-6, 0, 0], [0, 1.3e-6, 0], [0, 0, 1.3e-6]]}\n"
                             "    markers: {centre: {position: [0, 0, 0]}}\n";
    std::ofstream(file) << "gravity: [0, 0, 0]\nbodies:\n  one:\n" << ball << "    initial: {position: [0, 0, 0.0099]}\n"
                        << "  two:\n" << ball << "    initial: {position: [0.0199, 0, 0.5]}\n"
                        << "forces:\n" << forces << "simulation: {end_time: 1e-4}\n";
    return file;
  }

 private:
  std::filesystem::path dir_;
};

constexpr double kSteelE = 210e9, kSteelNu = 0.3, kRadius = 0.01;

TEST(ContactScene, HertzFromMaterialsGivesJohnsonsStiffness) {
  ContactScene scene;
  const Scene loaded = LoadScene(scene.Write(
      "  - {name: floor, type: sphere_plane_contact, sphere: {body: one, marker: centre}, plane: {body: ground},\n"
      "     radius: 0.01, law: hertz, materials: {sphere: {youngs_modulus: 210e9, poissons_ratio: 0.3}}}\n"
      "  - {name: flat, type: sphere_plane_contact, sphere: {body: one, marker: centre}, plane: {body: ground},\n"
      "     radius: 0.01, law: flores, restitution: 0.8, impact_speed: 1.0,\n"
      "     materials: {sphere: {youngs_modulus: 210e9, poissons_ratio: 0.3}, plane: {youngs_modulus: 70e9, "
      "poissons_ratio: 0.33}},\n"
      "     friction: {coefficient: 0.3, regularisation_speed: 1e-3}}\n"
      "  - {name: pair, type: sphere_sphere_contact, sphere1: {body: one, marker: centre}, sphere2: {body: two, "
      "marker: centre},\n"
      "     radius1: 0.01, radius2: 0.01, law: hunt_crossley, restitution: 0.9, impact_speed: 0.5,\n"
      "     materials: {sphere1: {youngs_modulus: 210e9, poissons_ratio: 0.3}, sphere2: {youngs_modulus: 210e9, "
      "poissons_ratio: 0.3}}}\n"
      "  - {name: legacy, type: sphere_plane_contact, sphere: {body: one, marker: centre}, plane: {body: ground},\n"
      "     radius: 0.01, stiffness: 1e9, damping: 10, exponent: 1.5}\n"));
  const MultibodySystem& system = *loaded.system;
  ASSERT_EQ(system.num_force_elements(), 4);
  VectorXd y = loaded.initial_state;
  VectorXd x(7);
  x << 0.0199, 0.0, 0.0099, 1.0, 0.0, 0.0, 0.0;  // ball two beside ball one
  system.SetBodyState(1, x, VectorXd::Zero(6), y);
  const contact::ElasticMaterial steel{kSteelE, kSteelNu}, aluminium{70e9, 0.33};
  const double delta = 1e-4;
  // Potential energies k delta^(5/2) / (5/2) with Johnson's k = 4/3 E* sqrt(R*).
  const auto energy = [&](double k) { return k * std::pow(delta, 2.5) / 2.5; };
  EXPECT_NEAR(system.force_element(0).PotentialEnergy(0.0, system, y),
              energy(contact::HertzStiffness(contact::EffectiveModulusOnRigid(steel), kRadius)), 1e-12);
  EXPECT_NEAR(system.force_element(1).PotentialEnergy(0.0, system, y),
              energy(contact::HertzStiffness(contact::EffectiveModulus(steel, aluminium), kRadius)), 1e-12);
  EXPECT_NEAR(system.force_element(2).PotentialEnergy(0.0, system, y),
              energy(contact::HertzStiffness(contact::EffectiveModulus(steel, steel), 0.5 * kRadius)), 1e-12);
  EXPECT_NEAR(system.force_element(3).PotentialEnergy(0.0, system, y), 1e9 * std::pow(delta, 2.5) / 2.5, 1e-12);
}

// Each bad value: one line with the file, the element's item and the value.
TEST(ContactScene, BadLawParametersAreOneLineErrors) {
  ContactScene scene;
  const auto error = [&](const std::string& keys) {
    return flexmbs::testing::InputErrorMessage([&] {
      LoadScene(scene.Write("  - {name: floor, type: sphere_plane_contact, sphere: {body: one, marker: centre}, "
                            "plane: {body: ground}, radius: 0.01, " +
                            keys + "}\n"));
    });
  };
  const auto expect = [&](const std::string& keys, const std::string& problem) {
    const std::string message = error(keys);
    EXPECT_NE(message.find("scene.yaml:"), std::string::npos) << message;
    EXPECT_NE(message.find("forces"), std::string::npos) << message;
    EXPECT_NE(message.find(problem), std::string::npos) << message;
  };
  expect("stiffness: -1e6", "force element 'floor': stiffness -1000000 must be finite and >= 0");
  expect("stiffness: 1e6, damping: -5", "force element 'floor': damping [N s/m] -5 must be finite and >= 0");
  expect("law: hunt_crossley, stiffness: 1e9, restitution: 1.5, impact_speed: 1",
         "force element 'floor': restitution 1.5 must be in (0, 1]");
  expect("law: flores, stiffness: 1e9, restitution: 0, impact_speed: 1",
         "force element 'floor': restitution 0 must be in (0, 1]");
  expect("law: lankarani_nikravesh, stiffness: -2, restitution: 0.5, impact_speed: 1",
         "force element 'floor': stiffness -2 must be finite and >= 0");
  expect("law: hertz, stiffness: 1e9, friction: {coefficient: -0.2}",
         "force element 'floor': friction coefficient -0.2 must be finite and >= 0");
  expect("law: coulomb, stiffness: 1e9",
         "'coulomb' must be one of: linear, hertz, hunt_crossley, lankarani_nikravesh, flores");
  expect("law: hertz, materials: {sphere: {youngs_modulus: -2e11, poissons_ratio: 0.3}}",
         "force element 'floor': sphere: Young's modulus -200000000000 must be finite and > 0");
  expect("law: hertz", "force element 'floor': law 'hertz' takes one of stiffness, materials");
  expect("law: hertz, stiffness: 1e9, restitution: 0.5", "not a parameter of law 'hertz'");
  expect("stiffness: 1e9, restitution: 0.5", "not a parameter of law 'linear'");
  expect("law: flores, stiffness: 1e9, restitution: 0.5, impact_speed: 1, damping: 3",
         "not a parameter of law 'flores'");
}

// The frictional sphere-sphere contact's Jacobian against central differences of its forces:
// in u exact (the law's and the friction's derivatives by the relative velocity at c), measured
// 3.4e-10 of the largest entry; in x the translations of both spheres without spin (delta,
// delta' and the turning of n), measured 1.0e-9 (the differences' round-off at steps of 1e-9 m,
// 1e-7 m/s). Tolerance 1e-8.
TEST(SphereSphereContact, JacobianIsTheForcesDerivative) {
  MultibodySystem system(Vector3d::Zero());
  for (const char* name : {"one", "two"}) {
    system.AddBody(std::make_unique<RigidBody>(name, 0.0329, Vector3d::Zero(), 1.3e-6 * Eigen::Matrix3d::Identity(),
                                               std::vector<RigidBodyMarker>{{"centre", Vector3d::Zero(),
                                                                             Eigen::Matrix3d::Identity()}}));
  }
  const double k = contact::HertzStiffness(contact::EffectiveModulus({kSteelE, kSteelNu}, {kSteelE, kSteelNu}), 0.005);
  system.AddForceElement(std::make_unique<SphereSphereContact>(
      "pair", system.Marker("one", "centre"), system.Marker("two", "centre"), kRadius, kRadius,
      CompliantContactLaw{contact::HuntCrossleyLaw(k, 0.7, 1.0), contact::MakeRegularisedCoulomb(0.3, 1e-2)}));
  VectorXd y = system.NeutralState();
  VectorXd x(7), u(6);
  x << 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0;
  u << 0.1, 0.0, 0.0, 0.0, 0.0, 0.0;
  system.SetBodyState(0, x, u, y);
  x.head<3>() << 0.0199, 0.0012, -0.0007;  // 0.07 mm into sphere one, off the x axis
  u.head<3>() << -0.2, 0.006, 0.003;       // approaching and slipping at ~ eps
  system.SetBodyState(1, x, u, y);
  const ForceElement& pair = system.force_element(0);
  const Eigen::Index n = system.num_velocities();
  const auto forces = [&](const VectorXd& state) {
    VectorXd h = VectorXd::Zero(n);
    pair.AddForces(0.0, system, state, h);
    return h;
  };
  Eigen::MatrixXd dh_dx = Eigen::MatrixXd::Zero(n, n), dh_du = dh_dx, fd_x(n, n), fd_u(n, n);
  pair.AddForceJacobian(0.0, system, y, dh_dx, dh_du);
  for (Eigen::Index c = 0; c < n; ++c) {
    VectorXd step = VectorXd::Zero(n);
    step(c) = 1e-9;
    VectorXd plus = y, minus = y;
    system.DisplacePositions(step, plus);
    system.DisplacePositions(-step, minus);
    fd_x.col(c) = (forces(plus) - forces(minus)) / 2e-9;
    plus = y;
    minus = y;
    plus.tail(n)(c) += 1e-7;
    minus.tail(n)(c) -= 1e-7;
    fd_u.col(c) = (forces(plus) - forces(minus)) / 2e-7;
  }
  const double error_u = (dh_du - fd_u).cwiseAbs().maxCoeff() / fd_u.cwiseAbs().maxCoeff();
  // Translations of both bodies: rows and columns 0-2 and 6-8.
  Eigen::MatrixXd translation_error(6, 6), translation_fd(6, 6);
  for (int r = 0; r < 6; ++r) {
    for (int c = 0; c < 6; ++c) {
      const Eigen::Index row = r < 3 ? r : r + 3, column = c < 3 ? c : c + 3;
      translation_error(r, c) = dh_dx(row, column) - fd_x(row, column);
      translation_fd(r, c) = fd_x(row, column);
    }
  }
  const double error_x = translation_error.cwiseAbs().maxCoeff() / translation_fd.cwiseAbs().maxCoeff();
  EXPECT_LE(error_u, 1e-8);
  EXPECT_LE(error_x, 1e-8);
  std::printf("[ numbers  ] sphere-sphere Jacobian: u %.1e, x (translations) %.1e of the largest entry\n", error_u,
              error_x);
}

}  // namespace
}  // namespace flexmbs::mbs
