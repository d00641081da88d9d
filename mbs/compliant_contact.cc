#include "mbs/compliant_contact.h"

#include <Eigen/Geometry>
#include <array>
#include <utility>

#include "core/skew.h"
#include "mbs/multibody_system.h"

namespace flexmbs::mbs {
namespace {

/// One body's end of the contact: its marker, the sign of its share of v_rel (A +1, B -1) and the
/// Jacobian of its material point at c, J_v - (c - p_M)~ J_w (3 x n_u of its body).
struct End {
  const MarkerRef* marker;
  double sign;
  Eigen::MatrixXd point_jacobian;
};

/// The Jacobian of the end's point at c through its body's velocities: the marker frame's
/// material point, plus modal_W on the body's modal columns (the last modal_W.cols()) for a
/// surface point.
Eigen::MatrixXd PointJacobian(const MarkerKinematics& marker, const Eigen::Vector3d& p_Wc_W,
                              const Eigen::Matrix3Xd& modal_W) {
  Eigen::MatrixXd J = marker.jacobian.topRows<3>() - Skew(p_Wc_W - marker.p_WM_W) * marker.jacobian.bottomRows<3>();
  if (modal_W.cols() > 0) J.rightCols(modal_W.cols()) += modal_W;
  return J;
}

/// Adds modal_W^T f_W to the modal rows of the end's body (nothing for a marker's point).
void AddModalLoad(const MultibodySystem& system, const MarkerRef& end, const Eigen::Matrix3Xd& modal_W,
                  const Eigen::Vector3d& f_W, Eigen::Ref<Eigen::VectorXd> h) {
  if (modal_W.cols() == 0) return;
  const VelocityBlock& block = system.velocity_block(end.body);
  const Eigen::Index last = block.start + block.size;
  h.segment(last - modal_W.cols(), modal_W.cols()) += modal_W.transpose() * f_W;
}

/// Adds sign_i sign_j J_i^T K J_j over the non-ground ends to out (num_velocities() square).
void AddCoupling(const MultibodySystem& system, const std::array<End, 2>& ends, const Eigen::Matrix3d& K,
                 Eigen::Ref<Eigen::MatrixXd> out) {
  for (const End& row : ends) {
    if (row.marker->is_ground()) continue;
    for (const End& column : ends) {
      if (column.marker->is_ground()) continue;
      out.block(system.velocity_block(row.marker->body).start, system.velocity_block(column.marker->body).start,
                row.point_jacobian.cols(), column.point_jacobian.cols()) +=
          (row.sign * column.sign) * row.point_jacobian.transpose() * K * column.point_jacobian;
    }
  }
}

}  // namespace

Eigen::Vector3d RelativeVelocity(const ContactPoint& point) {
  const auto material_velocity = [&](const MarkerKinematics& M) {
    return Eigen::Vector3d(M.v_WM_W + M.w_WM_W.cross(point.p_Wc_W - M.p_WM_W));
  };
  return material_velocity(point.a) + point.modal_velocity_a_W - material_velocity(point.b) - point.modal_velocity_b_W;
}

CompliantContact::CompliantContact(CompliantContactLaw law, MarkerRef a, MarkerRef b)
    : law_(std::move(law)), a_(std::move(a)), b_(std::move(b)) {}

CompliantContact::Loads CompliantContact::Evaluate(const ContactPoint& point) const {
  Loads loads;
  if (!(point.penetration > 0.0)) return loads;
  const Eigen::Vector3d& n = point.n_W;
  loads.v_rel_W = RelativeVelocity(point);
  const double rate = -n.dot(loads.v_rel_W);
  loads.normal = contact::Evaluate(law_.normal, point.penetration, rate);
  if (law_.friction && loads.normal.force > 0.0) {
    loads.tangential = contact::Evaluate(*law_.friction, loads.v_rel_W + rate * n, loads.normal.force);
  }
  return loads;
}

void CompliantContact::AddForces(const MultibodySystem& system, const ContactPoint& point,
                                 Eigen::Ref<Eigen::VectorXd> h) const {
  const Loads loads = Evaluate(point);
  if (loads.normal.force == 0.0) return;
  const Eigen::Vector3d f_W = loads.normal.force * point.n_W + loads.tangential.force;
  system.AddMarkerLoad(a_, point.a, f_W, (point.p_Wc_W - point.a.p_WM_W).cross(f_W), h);
  system.AddMarkerLoad(b_, point.b, -f_W, (point.p_Wc_W - point.b.p_WM_W).cross(-f_W), h);
  AddModalLoad(system, a_, point.modal_a, f_W, h);
  AddModalLoad(system, b_, point.modal_b, -f_W, h);
}

void CompliantContact::AppendLoad(const ContactPoint& point, std::vector<ContactLoad>* loads) const {
  const Loads evaluated = Evaluate(point);
  if (!(evaluated.normal.force > 0.0)) return;
  loads->push_back({0, point.p_Wc_W, point.n_W, evaluated.normal.force * point.n_W + evaluated.tangential.force});
}

void CompliantContact::AddForceJacobian(const MultibodySystem& system, const ContactPoint& point,
                                        Eigen::Ref<Eigen::MatrixXd> dh_dx, Eigen::Ref<Eigen::MatrixXd> dh_du) const {
  const Loads loads = Evaluate(point);
  if (loads.normal.force == 0.0) return;
  const Eigen::Vector3d& n = point.n_W;
  const Eigen::Matrix3d& N = point.n_turning;
  const contact::NormalForce& F = loads.normal;
  const contact::TangentialForce& T = loads.tangential;
  const Eigen::Matrix3d across = Eigen::Matrix3d::Identity() - n * n.transpose();
  // f = F_N n + F_T(v_T, F_N); df = (n + dF_T/dF_N) dF_N + F_N dn + dF_T/dv_T dv_T.
  const Eigen::Vector3d along = n + T.d_normal_force;
  const Eigen::Matrix3d K_u = -F.d_rate * along * n.transpose() + T.d_slip * across;
  // In d: d delta = -n^T dd, d delta' = -v_rel^T N dd, dv_T = -(n v_rel^T + (n . v_rel) I) N dd.
  const Eigen::RowVector3d dF_dd = -F.d_delta * n.transpose() - F.d_rate * loads.v_rel_W.transpose() * N;
  const Eigen::Matrix3d K_x =
      along * dF_dd + F.force * N -
      T.d_slip * (n * loads.v_rel_W.transpose() + n.dot(loads.v_rel_W) * Eigen::Matrix3d::Identity()) * N;
  const std::array<End, 2> ends{
      End{&a_, 1.0, a_.is_ground() ? Eigen::MatrixXd() : PointJacobian(point.a, point.p_Wc_W, point.modal_a)},
      End{&b_, -1.0, b_.is_ground() ? Eigen::MatrixXd() : PointJacobian(point.b, point.p_Wc_W, point.modal_b)}};
  AddCoupling(system, ends, K_x, dh_dx);
  AddCoupling(system, ends, K_u, dh_du);
}

double CompliantContact::PotentialEnergy(const ContactPoint& point) const {
  return contact::ElasticEnergy(law_.normal, point.penetration);
}

}  // namespace flexmbs::mbs
