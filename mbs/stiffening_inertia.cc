#include "mbs/stiffening_inertia.h"

#include <Eigen/Geometry>

#include "core/centrifugal.h"

namespace flexmbs::mbs {
namespace {

using Eigen::Index;
using Eigen::Matrix3d;
using Eigen::Vector3d;
using Eigen::VectorXd;

/// The symmetric D with w^T D w = -sum_l c_l w_q,l (w_q = AngularVelocityProducts(w)).
Matrix3d InertiaOfProducts(const Eigen::Matrix<double, 6, 1>& c) {
  Matrix3d D;
  D << c(0), 0.5 * c(3), 0.5 * c(5),  //
      0.5 * c(3), c(1), 0.5 * c(4),   //
      0.5 * c(5), 0.5 * c(4), c(2);
  return -D;
}

}  // namespace

StiffeningInertia::StiffeningInertia(const sid::GeometricStiffening& K0)
    : K0t_(K0.K0t), K0r_(K0.K0r), K0w_(K0.K0omega) {}

StiffeningInertia::Moments StiffeningInertia::At(const VectorXd& q) const {
  const Index n = q.size();
  Moments m;
  m.dCt.resize(n, 3);
  m.K0w_q.resize(n, 6);
  for (Index a = 0; a < 3; ++a) m.dCt.col(a) = K0t_[static_cast<std::size_t>(a)] * q;
  for (Index l = 0; l < 6; ++l) m.K0w_q.col(l) = K0w_[static_cast<std::size_t>(l)] * q;
  m.dc = 0.5 * m.dCt.transpose() * q;
  m.dJ = InertiaOfProducts(m.K0w_q.transpose() * q);
  return m;
}

void StiffeningInertia::AddStateForces(const Moments& m, const VectorXd& qdot, const Vector3d& w, const Vector3d& g_B,
                                       Eigen::Ref<VectorXd> h) const {
  // dJ' from s_l' = 2 qdot^T K0w_l q.
  const Matrix3d dJ_dot = InertiaOfProducts(2.0 * m.K0w_q.transpose() * qdot);
  h.segment<3>(3) += m.dc.cross(g_B) - dJ_dot * w - w.cross(m.dJ * w);
  h.tail(qdot.size()) += m.dCt * g_B - m.K0w_q * AngularVelocityProducts(w);
}

void StiffeningInertia::AddAccelerationForces(const VectorXd& q, const Vector3d& a_B, const Vector3d& alpha,
                                              Eigen::Ref<VectorXd> h_e) const {
  for (std::size_t a = 0; a < 3; ++a) {
    h_e.noalias() -= a_B(static_cast<Index>(a)) * (K0t_[a] * q) + alpha(static_cast<Index>(a)) * (K0r_[a] * q);
  }
}

double StiffeningInertia::PotentialEnergy(const Moments& m, const Matrix3d& R, const Vector3d& g_W) const {
  return -g_W.dot(R * m.dc);
}

void StiffeningInertia::AddElasticStiffness(const Vector3d& w, const Vector3d& g_minus_a_B, const Vector3d& alpha,
                                            Eigen::Ref<Eigen::MatrixXd> stiffness) const {
  const Eigen::Matrix<double, 6, 1> w_q = AngularVelocityProducts(w);
  for (std::size_t l = 0; l < 6; ++l) stiffness -= w_q(static_cast<Index>(l)) * K0w_[l];
  for (std::size_t a = 0; a < 3; ++a) {
    stiffness += g_minus_a_B(static_cast<Index>(a)) * K0t_[a] - alpha(static_cast<Index>(a)) * K0r_[a];
  }
}

}  // namespace flexmbs::mbs
