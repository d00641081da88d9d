#pragma once
// Central differences of a force element's generalised forces, the reference its analytic
// Jacobian (ForceElement::AddForceJacobian) is tested against.

#include <Eigen/Core>

#include "mbs/force_element.h"
#include "mbs/multibody_system.h"

namespace flexmbs::testing {

/// A force element's Jacobian by central differences of AddForces at (t = 0, y): dh/du with each
/// velocity moved by +-step, dh/dx with the positions moved by +-step along each velocity-space
/// direction (MultibodySystem::DisplacePositions), both num_velocities() square.
struct DifferenceJacobian {
  Eigen::MatrixXd dh_dx, dh_du;
};

inline DifferenceJacobian ForceJacobianByDifferences(const mbs::MultibodySystem& system, const mbs::ForceElement& element,
                                                     const Eigen::VectorXd& y, double step) {
  const Eigen::Index n = system.num_velocities();
  const auto forces = [&](const Eigen::VectorXd& state) {
    Eigen::VectorXd h = Eigen::VectorXd::Zero(n);
    element.AddForces(0.0, system, state, h);
    return h;
  };
  DifferenceJacobian fd{Eigen::MatrixXd(n, n), Eigen::MatrixXd(n, n)};
  for (Eigen::Index k = 0; k < n; ++k) {
    Eigen::VectorXd plus = y, minus = y;
    plus(system.num_positions() + k) += step;
    minus(system.num_positions() + k) -= step;
    fd.dh_du.col(k) = (forces(plus) - forces(minus)) / (2.0 * step);
    plus = y;
    minus = y;
    system.DisplacePositions(Eigen::VectorXd::Unit(n, k) * step, plus);
    system.DisplacePositions(-Eigen::VectorXd::Unit(n, k) * step, minus);
    fd.dh_dx.col(k) = (forces(plus) - forces(minus)) / (2.0 * step);
  }
  return fd;
}

}  // namespace flexmbs::testing
