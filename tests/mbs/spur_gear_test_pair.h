#pragma once
// Shared by the spur gear element's tests (tests/mbs/spur_gear_contact_test.cc,
// spur_gear_joint_test.cc): a scene file in a temporary directory, two free wheels in mesh and
// the element's Jacobian against central differences of its forces.

#include <unistd.h>

#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <functional>
#include <memory>
#include <numbers>
#include <string>
#include <utility>
#include <vector>

#include "contact/gears/gear_mesh.h"
#include "contact/gears/gear_mesh_force.h"
#include "mbs/multibody_system.h"
#include "mbs/rigid_body.h"
#include "mbs/spur_gear_contact.h"

namespace flexmbs::mbs::gear_test {

inline constexpr double kCentre = 0.0505;  ///< a [m] of the driven pair: 1.0e-4 m of backlash

/// A scene file in a temporary directory, removed with the object.
class GearScene {
 public:
  GearScene()
      : dir_(std::filesystem::temp_directory_path() /
             ("flexmbs_gears_" + std::to_string(::getpid()))) {
    std::filesystem::create_directories(dir_);
  }
  ~GearScene() { std::filesystem::remove_all(dir_); }
  GearScene(const GearScene&) = delete;
  GearScene& operator=(const GearScene&) = delete;

  /// Writes `text` as scene.yaml in the directory.
  std::filesystem::path Write(const std::string& text) const {
    const std::filesystem::path file = dir_ / "scene.yaml";
    std::ofstream(file) << text;
    return file;
  }

 private:
  std::filesystem::path dir_;
};

/// Two free rigid wheels (pinion, wheel) meshing through a spur_gear_contact element: the pair
/// of the driven pair's gears at kCentre with `law` of the pair (by default c' = 1.4e10 N/m per
/// m of face width, damping 3e3 N s/m).
inline contact::GearPair AddFreeWheelsInMesh(
    MultibodySystem& system,
    const std::function<contact::MeshLaw(const contact::GearPair&)>& law = {}) {
  for (const char* name : {"pinion", "wheel"}) {
    system.AddBody(std::make_unique<RigidBody>(
        name, 0.3, Eigen::Vector3d::Zero(), 1e-4 * Eigen::Matrix3d::Identity(),
        std::vector<RigidBodyMarker>{
            {"axis", Eigen::Vector3d::Zero(), Eigen::Matrix3d::Identity()}}));
  }
  contact::GearPairSpec spec;
  spec.gear1 =
      contact::SpurGearSpec{2e-3, 19, 20.0 * std::numbers::pi / 180.0, 0.3, 1.0, 1.25, 0.02};
  spec.gear2 =
      contact::SpurGearSpec{2e-3, 31, 20.0 * std::numbers::pi / 180.0, -0.1, 1.0, 1.25, 0.02};
  spec.centre_distance = kCentre;
  const contact::GearPair pair = contact::MakeGearPair(spec);
  system.AddForceElement(std::make_unique<SpurGearContact>(
      "mesh", system.Marker("pinion", "axis"), system.Marker("wheel", "axis"), pair,
      law ? law(pair) : contact::MeshLaw(contact::ToothPairLaw({1.4e10, 3e3}, pair))));
  return pair;
}

/// The wheels at pinion angle phi1 (0.37: in double contact), `depth` [m] deep on the positive
/// flanks, turning at 3 and -1 rad/s, the wheel's centre sliding along y at 0.01 m/s (the
/// damping's rate sees it).
inline Eigen::VectorXd DoubleContactState(const MultibodySystem& system, const contact::GearPair& pair,
                                   double phi1 = 0.37, double depth = 5e-6) {
  const double phi2 =
      contact::TouchingAngle2(pair, kCentre, phi1, 0.0, contact::FlankSide::kPositive) +
      depth / pair.gear2.base_radius;
  Eigen::VectorXd y = system.NeutralState();
  const auto set = [&](int body, double x, double angle, double omega) {
    Eigen::VectorXd q(7), u = Eigen::VectorXd::Zero(6);
    q << x, 0.0, 0.0, std::cos(angle / 2), 0.0, 0.0, std::sin(angle / 2);
    u(5) = omega;
    u(1) = 0.01 * body;  // a sliding centre: the damping's rate sees it
    system.SetBodyState(body, q, u, y);
  };
  set(0, 0.0, phi1, 3.0);
  set(1, kCentre, phi2, -1.0);
  return y;
}

/// Central differences of the element's forces h in the positions (steps of 1e-8 along the
/// velocity directions) and in the velocities (steps of 1e-6).
struct ForceDifferences {
  Eigen::MatrixXd dh_dx, dh_du;
};

/// The central differences of `mesh`'s forces at state y.
inline ForceDifferences CentralDifferences(const MultibodySystem& system, const ForceElement& mesh,
                                    const Eigen::VectorXd& y) {
  const Eigen::Index n = system.num_velocities();
  const auto forces = [&](const Eigen::VectorXd& state) {
    Eigen::VectorXd h = Eigen::VectorXd::Zero(n);
    mesh.AddForces(0.0, system, state, h);
    return h;
  };
  ForceDifferences fd{Eigen::MatrixXd(n, n), Eigen::MatrixXd(n, n)};
  for (Eigen::Index c = 0; c < n; ++c) {
    Eigen::VectorXd step = Eigen::VectorXd::Zero(n);
    step(c) = 1e-8;
    Eigen::VectorXd plus = y, minus = y;
    system.DisplacePositions(step, plus);
    system.DisplacePositions(-step, minus);
    fd.dh_dx.col(c) = (forces(plus) - forces(minus)) / 2e-8;
    plus = y;
    minus = y;
    plus.tail(n)(c) += 1e-6;
    minus.tail(n)(c) -= 1e-6;
    fd.dh_du.col(c) = (forces(plus) - forces(minus)) / 2e-6;
  }
  return fd;
}

/// How far the Jacobian of `jacobian` at y is from the central differences of the forces of
/// `forces`: the largest difference in dh/du, and in dh/dx over the wheels' turns about z
/// (columns 5 and 11), each relative to its largest entry.
inline std::pair<double, double> JacobianErrors(const MultibodySystem& system,
                                                const ForceElement& forces,
                                                const ForceElement& jacobian,
                                                const Eigen::VectorXd& y) {
  const Eigen::Index n = system.num_velocities();
  Eigen::MatrixXd dh_dx = Eigen::MatrixXd::Zero(n, n), dh_du = dh_dx;
  jacobian.AddForceJacobian(0.0, system, y, dh_dx, dh_du);
  const ForceDifferences fd = CentralDifferences(system, forces, y);
  const double error_u = (dh_du - fd.dh_du).cwiseAbs().maxCoeff() / fd.dh_du.cwiseAbs().maxCoeff();
  double error_x = 0.0;
  for (const Eigen::Index c : {Eigen::Index{5}, Eigen::Index{11}}) {  // the turns about z
    error_x = std::max(error_x, (dh_dx.col(c) - fd.dh_dx.col(c)).cwiseAbs().maxCoeff() /
                                    fd.dh_dx.col(c).cwiseAbs().maxCoeff());
  }
  return {error_u, error_x};
}

/// JacobianErrors of `mesh`'s own Jacobian against its forces.
inline std::pair<double, double> JacobianErrors(const MultibodySystem& system,
                                                const ForceElement& mesh,
                                                const Eigen::VectorXd& y) {
  return JacobianErrors(system, mesh, mesh, y);
}

}  // namespace flexmbs::mbs::gear_test
