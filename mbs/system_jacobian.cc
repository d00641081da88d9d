#include "mbs/system_jacobian.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>

#include "core/error.h"
#include "core/rotation.h"
#include "mbs/constraint_solver.h"

namespace flexmbs::mbs {
namespace {

using Eigen::Index;
using Eigen::MatrixXd;
using Eigen::VectorXd;

/// The x' rows (exact): p' = v, e' = L(e) w_B, q' = qdot.
void SetPositionRows(const MultibodySystem& system, const ConstVectorRef& y, Eigen::Ref<MatrixXd> dfdy) {
  const Index nx = system.num_positions();
  for (int b = 0; b < system.num_bodies(); ++b) {
    const Index px = system.position_offset(b), pu = nx + system.velocity_block(b).start, n = system.body(b).num_modes();
    dfdy.block<3, 3>(px, pu).setIdentity();
    dfdy.block<4, 3>(px + 3, pu + 3) = RateByAngularVelocity(y.segment<4>(px + 3));
    dfdy.block<4, 4>(px + 3, px + 3) = RateByEulerParameters(y.segment<3>(pu + 3));
    dfdy.block(px + 7, pu + 6, n, n).setIdentity();
  }
}

/// Maps a derivative D (rows x num_velocities()) with respect to velocity-space position
/// increments (MultibodySystem::DisplacePositions) to the positions x (rows x num_positions()):
/// p and q columns as they are; the rotation's three to the Euler parameters' four by
/// d/de = d/dtheta (L^T L)^-1 L^T (de = L dtheta): the derivative along the sphere |e| = const,
/// none across it (R_WB(e) is normalised, so f does not change across it).
void SetPositionColumns(const MultibodySystem& system, const ConstVectorRef& y, const Eigen::Ref<const MatrixXd>& D,
                        Eigen::Ref<MatrixXd> out) {
  for (int b = 0; b < system.num_bodies(); ++b) {
    const Index px = system.position_offset(b), pu = system.velocity_block(b).start, n = system.body(b).num_modes();
    const Eigen::Matrix<double, 4, 3> L = RateByAngularVelocity(y.segment<4>(px + 3));
    out.middleCols<3>(px) = D.middleCols<3>(pu);
    out.middleCols<4>(px + 3) = D.middleCols<3>(pu + 3) * (L.transpose() * L).inverse() * L.transpose();
    out.middleCols(px + 7, n) = D.middleCols(pu + 6, n);
  }
}

/// Replaces the columns of every body's v and w_B in du_dot (num_velocities() x 2
/// num_velocities(): [du'/dx by DisplacePositions increments, du'/du]) by forward differences
/// of the accelerations, u_dot those at (t, y). Increments sqrt(eps) max(|u_j|, 1) [m/s, rad/s]:
/// the scale of the coordinates, not of the tolerances (ARKODE's scale with atol).
void SetRigidVelocityColumnsByDifferences(const MultibodySystem& system, double t, const ConstVectorRef& y,
                                          const VectorXd& u_dot, MatrixXd& du_dot) {
  const Index nx = system.num_positions(), nu = system.num_velocities();
  const double root_eps = std::sqrt(std::numeric_limits<double>::epsilon());
  VectorXd moved(y.size()), u_dot_moved(nu), lambda(system.num_constraints());
  for (int b = 0; b < system.num_bodies(); ++b) {
    const Index start = system.velocity_block(b).start;
    for (Index k = start; k < start + 6; ++k) {
      moved = y;
      const double increment = root_eps * std::max(std::abs(y(nx + k)), 1.0);
      moved(nx + k) += increment;
      system.Accelerations(t, moved, u_dot_moved, lambda);
      du_dot.col(nu + k) = (u_dot_moved - u_dot) / increment;
    }
  }
}

}  // namespace

Eigen::Matrix<double, 4, 3> RateByAngularVelocity(const Eigen::Vector4d& e) {
  Eigen::Matrix<double, 4, 3> L;
  for (int k = 0; k < 3; ++k) L.col(k) = EulerParameterRate(e, Eigen::Vector3d::Unit(k));
  return L;
}

Eigen::Matrix4d RateByEulerParameters(const Eigen::Vector3d& w_B) {
  Eigen::Matrix4d D;
  for (int i = 0; i < 4; ++i) D.col(i) = EulerParameterRate(Eigen::Vector4d::Unit(i), w_B);
  return D;
}

void SystemJacobian(const MultibodySystem& system, double t, const ConstVectorRef& y, Eigen::Ref<MatrixXd> dfdy) {
  const Index nx = system.num_positions(), nu = system.num_velocities(), ns = system.num_element_states(),
              m = system.num_constraints();
  FLEXMBS_CHECK(y.size() == system.state_size() && dfdy.rows() == y.size() && dfdy.cols() == y.size(),
                fmt::format("SystemJacobian: state of size {} and a {} x {} matrix for a system of {}", y.size(),
                            dfdy.rows(), dfdy.cols(), system.state_size()));
  dfdy.setZero();
  SetPositionRows(system, y, dfdy);

  // dh = [dh/dx (velocity-space increments), dh/du, dh/ds], at the accelerations of (t, y), and
  // the force elements' states' ds = [ds'/dx, ds'/du, ds'/ds].
  VectorXd u_dot(nu), lambda(m);
  system.Accelerations(t, y, u_dot, lambda);
  MatrixXd dh = MatrixXd::Zero(nu, 2 * nu + ns), ds = MatrixXd::Zero(ns, 2 * nu + ns);
  for (int b = 0; b < system.num_bodies(); ++b) {
    const auto [pu, n] = system.velocity_block(b);
    system.body(b).AddForceJacobian(system.BodyPositions(y, b), system.BodyVelocities(y, b), u_dot.segment(pu, n),
                                    system.gravity(), dh.block(pu, pu, n, n), dh.block(pu, nu + pu, n, n));
  }
  for (int k = 0; k < system.num_force_elements(); ++k) {
    const ForceElement& element = system.force_element(k);
    element.AddForceJacobian(t, system, y, dh.leftCols(nu), dh.middleCols(nu, nu));
    const Index n = element.num_states(), start = system.element_state_offset(k) - nx - nu;
    if (n == 0) continue;
    ElementStateJacobian blocks{ds.block(start, 0, n, nu), ds.block(start, nu, n, nu),
                                ds.block(start, 2 * nu + start, n, n), dh.middleCols(2 * nu + start, n)};
    element.AddStateJacobian(t, system, y, blocks);
  }

  // du'/d. = M^-1 dh - Z (G M^-1 dh + [omega^2 G, 2 omega G, 0]), Z = M^-1 G^T S^-1.
  const SystemConstraints c = system.Constraints(t, y);
  const ConstraintSolver solver(system, t, y, c.G);
  MatrixXd du_dot = solver.SolveMassColumns(dh);
  if (m > 0) {
    const double omega = system.constraint_settings().baumgarte_frequency;
    MatrixXd target = solver.constraint_jacobian() * du_dot;
    target.leftCols(nu) += omega * omega * c.G;
    target.middleCols(nu, nu) += 2.0 * omega * c.G;
    MatrixXd multipliers(m, target.cols());
    for (Index j = 0; j < target.cols(); ++j) multipliers.col(j) = solver.SolveSchur(target.col(j));
    du_dot -= solver.mass_inverse_G_transpose() * multipliers;
  }
  SetRigidVelocityColumnsByDifferences(system, t, y, u_dot, du_dot);
  SetPositionColumns(system, y, du_dot.leftCols(nu), dfdy.block(nx, 0, nu, nx));
  dfdy.block(nx, nx, nu, nu) = du_dot.middleCols(nu, nu);
  if (ns == 0) return;
  dfdy.block(nx, nx + nu, nu, ns) = du_dot.rightCols(ns);
  SetPositionColumns(system, y, ds.leftCols(nu), dfdy.block(nx + nu, 0, ns, nx));
  dfdy.block(nx + nu, nx, ns, nu) = ds.middleCols(nu, nu);
  dfdy.bottomRightCorner(ns, ns) = ds.rightCols(ns);
}

}  // namespace flexmbs::mbs
