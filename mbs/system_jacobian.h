#pragma once
// The Jacobian df/dy of a multibody system's y' = f(t, y) = [x'; u'; s'] (MultibodySystem::Derivative)
// from the model, for the implicit integrator's Newton matrix I - gamma h df/dy (docs/mbs.md,
// "Integrators", "The implicit method's Jacobian"):
//
//   x' rows: exact (p' = v, e' = 1/2 e (x) (0, w_B), q' = qdot);
//   u' rows: u' = A h + Z (gamma - 2 omega_B (G u + g_t) - omega_B^2 g), with A = M^-1 - Z G M^-1
//            the constrained solution operator and Z = M^-1 G^T S^-1 (S = G M^-1 G^T over the kept
//            rows), taken as  du'/du = A dh/du - 2 omega_B Z G,  du'/dx = A dh/dx - omega_B^2 Z G,
//
// dh/dx, dh/du the stiff parts the bodies and force elements give (Body::AddForceJacobian,
// ForceElement::AddForceJacobian). The force elements' own states s (docs/mbs.md, "Force elements
// with states") give their rows ds'/dx, ds'/du, ds'/ds and the columns du'/ds = A dh/ds from
// ForceElement::AddStateJacobian, as the element states them. The columns of every body's v and
// w_B are forward differences of u' instead (6 evaluations of the accelerations per body,
// increments scaled by the coordinates, not by atol): they add what the model leaves out there
// (gyroscopic and centrifugal terms, gamma's velocity terms). Left out: the derivatives of A itself (dM/dx,
// dG/dx), of gamma and of the rigid rows' inertia and gravity terms in the position columns, and
// the loaded force elements' lever rotations: first order in the deformation or of the motion's
// own rates, small against the stiff entries (tests/mbs/system_jacobian_test.cc); modified
// Newton tolerates them. Measured (docs/mbs.md, "The implicit method's Jacobian"): the
// differences in the velocity columns take 28 % fewer steps on the flexible pendulum's full
// model than the model alone; differences in the position columns too add nothing there and cost
// 68 % more Newton iterations on a frame driven through stiff modes.

#include <Eigen/Core>

#include "mbs/multibody_system.h"

namespace flexmbs::mbs {

/// L(e) (4 x 3): de/dt = 1/2 e (x) (0, w_B) = L(e) w_B (EulerParameterRate, linear in w_B). The
/// same L moves e by a rotation increment: e (x) exp(dtheta / 2) = e + L(e) dtheta + O(dtheta^2).
Eigen::Matrix<double, 4, 3> RateByAngularVelocity(const Eigen::Vector4d& e);

/// d/de of 1/2 e (x) (0, w_B) (4 x 4, linear in e): 1/2 the right product by (0, w_B), skew, with
/// square -|w_B|^2 / 4 I.
Eigen::Matrix4d RateByEulerParameters(const Eigen::Vector3d& w_B);

/// Fills dfdy (state_size() x state_size()) at (t, y) as in the file comment: 1 + 6 B
/// evaluations of the accelerations (B bodies) and one more factorisation of M and S. Throws
/// SimulationError as MultibodySystem::Accelerations does.
void SystemJacobian(const MultibodySystem& system, double t, const ConstVectorRef& y, Eigen::Ref<Eigen::MatrixXd> dfdy);

}  // namespace flexmbs::mbs
