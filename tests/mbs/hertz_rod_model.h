#pragma once
// A rigid sphere striking a full linear FE model through a Hertz spring, integrated without any
// of the multibody code: the reference for the reduced sphere-on-rod runs (tests/mbs/
// sphere_rod_impact_test.cc). The sphere moves along one axis (coordinate x_s [m], mass m), the
// body's contact point is b^T u (b: the weights of the struck face's nodes on their DOFs along
// that axis), the penetration delta = x_s - b^T u - gap0 and the force F = k max(delta, 0)^1.5
// pushes the sphere back and the face forward. Newmark's average acceleration (trapezoidal) rule
// with a constant effective stiffness K + 4/h^2 M; the one nonlinear unknown, F, is found per
// step by Newton's method on the scalar equation F = k (delta_0 - c F)^1.5.

#include <Eigen/Core>
#include <Eigen/SparseCore>
#include <vector>

namespace flexmbs::mbs::testing {

/// The model: the body's K [N/m] and M [kg] (free or supported), its contact weights b (n), the
/// sphere's mass [kg], the Hertz stiffness k [N/m^1.5] and the initial gap [m].
struct HertzImpactModel {
  Eigen::SparseMatrix<double> K, M;
  Eigen::VectorXd b;
  double sphere_mass = 0.0;
  double hertz_stiffness = 0.0;
  double gap0 = 0.0;
};

/// The contact force [N] at t = h, 2h, ..., the sphere's final velocity [m/s], the wall time [s].
struct HertzImpactHistory {
  std::vector<double> t, force;
  double sphere_velocity = 0.0;
  double seconds = 0.0;
};

/// Integrates `model` from rest (body) and the sphere at speed v0 [m/s] towards it, by steps of h
/// to end_time.
HertzImpactHistory IntegrateHertzImpact(const HertzImpactModel& model, double v0, double h, double end_time);

}  // namespace flexmbs::mbs::testing
