#include "mbs/flexible_body.h"

#include <fmt/format.h>

#include <array>
#include <cmath>
#include <utility>

#include "core/centrifugal.h"
#include "core/error.h"
#include "core/rotation.h"
#include "core/skew.h"
#include "mbs/mode_selection.h"

namespace flexmbs::mbs {
namespace {

using Eigen::Index;
using Eigen::Matrix3d;
using Eigen::MatrixXd;
using Eigen::Vector3d;
using Eigen::VectorXd;

[[noreturn]] void Fail(std::string_view body_name, std::string_view problem) {
  throw InputError(fmt::format("body '{}': {}", body_name, problem));
}

/// Checks one Taylor block's shape and order against docs/sid.md.
void CheckBlock(std::string_view body_name, const sid::TaylorMatrix& X, std::string_view block, Index rows, Index cols,
                int max_order, Index n) {
  if (X.m0.rows() != rows || X.m0.cols() != cols) {
    Fail(body_name, fmt::format("SID block {} is {} x {}, expected {} x {} for {} modes", block, X.m0.rows(),
                                X.m0.cols(), rows, cols, n));
  }
  if (X.order() > max_order) {
    Fail(body_name, fmt::format("SID block {} has order {}; it has at most order {} (docs/sid.md)", block, X.order(),
                                max_order));
  }
  if (!X.IsConsistent(n)) Fail(body_name, fmt::format("SID block {}: its order-1/2 terms do not fit {} modes", block, n));
}

/// The order-1 terms of an n x 3 or n x 6 block side by side: [X_1 .. X_c] (n x c n) with
/// X_a(i, j) = m1[j](i, a); zero if the block has order 0.
MatrixXd SideBySide(const sid::TaylorMatrix& X, Index n) {
  const Index c = X.m0.cols();
  MatrixXd out = MatrixXd::Zero(n, c * n);
  for (Index j = 0; j < static_cast<Index>(X.m1.size()); ++j) {
    for (Index a = 0; a < c; ++a) out.col(a * n + j) = X.m1[static_cast<std::size_t>(j)].col(a);
  }
  return out;
}

/// [K0_1 .. K0_c] side by side, or zero (n x c n) if the body has no stiffening matrices.
template <std::size_t C>
MatrixXd SideBySide(const std::array<MatrixXd, C>& K0, Index n) {
  MatrixXd out = MatrixXd::Zero(n, static_cast<Index>(C) * n);
  if (K0[0].size() == 0) return out;
  for (std::size_t a = 0; a < C; ++a) out.middleCols(static_cast<Index>(a) * n, n) = K0[a];
  return out;
}

/// The n x 3 block [X_1 q, X_2 q, X_3 q] of SideBySide order-1 terms X1.
Eigen::MatrixX3d OrderOneBlock(const MatrixXd& X1, const VectorXd& q) {
  const Index n = q.size();
  Eigen::MatrixX3d X(n, 3);
  for (Index a = 0; a < 3; ++a) X.col(a) = X1.middleCols(a * n, n) * q;
  return X;
}

/// The Kronecker product a (x) b: block i is a_i b.
VectorXd Kronecker(const VectorXd& a, const VectorXd& b) {
  VectorXd out(a.size() * b.size());
  for (Index i = 0; i < a.size(); ++i) out.segment(i * b.size(), b.size()) = a(i) * b;
  return out;
}

/// The coefficients of the rotation vector theta (t = |theta|): exp(theta~) = I + s theta~ +
/// a theta~^2 and T = I + a theta~ + b theta~^2 with s = sin t / t, a = (1 - cos t) / t^2,
/// b = (t - sin t) / t^3, and c = a'(t) / t, d = b'(t) / t for dT/dt. Power series below
/// t = 0.5 (ten terms: truncation < 1e-20), where the closed forms lose digits to cancellation.
struct RotationCoefficients {
  double s, a, b, c, d;
};

RotationCoefficients Coefficients(double t) {
  if (t >= 0.5) {
    const double sin_t = std::sin(t), one_minus_cos = 2.0 * std::sin(0.5 * t) * std::sin(0.5 * t);
    const double t2 = t * t;
    return {sin_t / t, one_minus_cos / t2, (t - sin_t) / (t2 * t), (t * sin_t - 2.0 * one_minus_cos) / (t2 * t2),
            (one_minus_cos * t - 3.0 * (t - sin_t)) / (t2 * t2 * t)};
  }
  // s = sum_k (-1)^k t^2k / (2k+1)!, a: / (2k+2)!, b: / (2k+3)!; c = sum_k>=1 (-1)^k 2k t^(2k-2)
  // / (2k+2)!, d: / (2k+3)!.
  static constexpr std::array<double, 24> inverse_factorial = [] {
    std::array<double, 24> out{};
    out[0] = 1.0;
    for (std::size_t m = 1; m < out.size(); ++m) out[m] = out[m - 1] / static_cast<double>(m);
    return out;
  }();
  RotationCoefficients out{0.0, 0.0, 0.0, 0.0, 0.0};
  const double t2 = t * t;
  double power = 1.0, previous_power = 0.0;  // t^2k, t^(2k-2)
  for (std::size_t k = 0; k < 10; ++k) {
    const double sign = k % 2 == 0 ? 1.0 : -1.0;
    out.s += sign * power * inverse_factorial[2 * k + 1];
    out.a += sign * power * inverse_factorial[2 * k + 2];
    out.b += sign * power * inverse_factorial[2 * k + 3];
    out.c += sign * 2.0 * static_cast<double>(k) * previous_power * inverse_factorial[2 * k + 2];
    out.d += sign * 2.0 * static_cast<double>(k) * previous_power * inverse_factorial[2 * k + 3];
    previous_power = power;
    power *= t2;
  }
  return out;
}

/// Throws InputError naming the body for SID data FlexibleBody cannot use (its constructor's
/// comment lists them).
void CheckReducedBody(const sid::ReducedBody& d, const std::string& body_name) {
  const Index n = d.num_modes();
  if (!(d.mass > 0.0)) Fail(body_name, fmt::format("mass {} kg must be > 0", d.mass));
  if (static_cast<Index>(d.mode_names.size()) != n || static_cast<Index>(d.mode_kinds.size()) != n) {
    Fail(body_name, fmt::format("{} mode names and {} kinds for {} modes", d.mode_names.size(), d.mode_kinds.size(), n));
  }
  CheckBlock(body_name, d.mdCM, "mdCM", 3, 1, 1, n);
  CheckBlock(body_name, d.J, "J", 3, 3, 2, n);
  CheckBlock(body_name, d.Ct, "Ct", n, 3, 1, n);
  CheckBlock(body_name, d.Cr, "Cr", n, 3, 1, n);
  CheckBlock(body_name, d.Me, "Me", n, n, 0, n);
  CheckBlock(body_name, d.Gr, "Gr", 3, 3 * n, 1, n);
  CheckBlock(body_name, d.Ge, "Ge", n, 3 * n, 0, n);
  CheckBlock(body_name, d.Oe, "Oe", n, 6, 1, n);
  CheckBlock(body_name, d.Ke, "Ke", n, n, 0, n);
  CheckBlock(body_name, d.De, "De", n, n, 0, n);
  CheckBlock(body_name, d.ksigma, "ksigma", n, 1, 0, n);
  const sid::GeometricStiffening& K0 = d.stiffening;
  if (K0.empty()) {
    if (d.Ct.order() > 0) Fail(body_name, "Ct has order-1 (stiffening) terms but the body has no stiffening matrices");
  } else {
    for (const auto* list : {&K0.K0t, &K0.K0r}) {
      for (const MatrixXd& matrix : *list) {
        if (matrix.rows() != n || matrix.cols() != n) Fail(body_name, "stiffening matrices K0t/K0r are not n x n");
      }
    }
    for (const MatrixXd& matrix : K0.K0omega) {
      if (matrix.rows() != n || matrix.cols() != n) Fail(body_name, "stiffening matrices K0omega are not n x n");
    }
  }
  CheckNoRigidBodyMotion(d, body_name);
}

}  // namespace

FlexibleBody::FlexibleBody(std::string name, sid::ReducedBody data, bool geometric_stiffening)
    : name_(std::move(name)), data_(std::move(data)), geometric_stiffening_(geometric_stiffening), n_(data_.num_modes()) {
  CheckReducedBody(data_, name_);
  CopyInvariants();
  ReadNodes();
}

void FlexibleBody::CopyInvariants() {
  const Index n = n_;
  const sid::ReducedBody& d = data_;
  const sid::GeometricStiffening& K0 = d.stiffening;
  mass_ = d.mass;
  mdCM0_ = d.mdCM.m0.col(0);
  mdCM1_ = Eigen::Matrix3Xd::Zero(3, n);
  for (Index j = 0; j < static_cast<Index>(d.mdCM.m1.size()); ++j) mdCM1_.col(j) = d.mdCM.m1[static_cast<std::size_t>(j)];
  J0_ = d.J.m0;
  J1_ = MatrixXd::Zero(9, n);
  J2_ = MatrixXd::Zero(9, n * n);
  for (Index j = 0; j < static_cast<Index>(d.J.m1.size()); ++j) {
    J1_.col(j) = d.J.m1[static_cast<std::size_t>(j)].reshaped();
  }
  for (Index jk = 0; jk < static_cast<Index>(d.J.m2.size()); ++jk) J2_.col(jk) = d.J.m2[static_cast<std::size_t>(jk)].reshaped();

  // The file's order-1 blocks hold kinematics + stiffening: the kinematic part is their
  // difference. M_b keeps it alone; the stiffening is the field of StiffeningInertia.
  Ct0_ = d.Ct.m0;
  Cr0_ = d.Cr.m0;
  Ct1_ = SideBySide(d.Ct, n) - SideBySide(K0.K0t, n);
  Cr1_ = SideBySide(d.Cr, n) - SideBySide(K0.K0r, n);
  if (geometric_stiffening_ && !K0.empty()) stiffening_.emplace(K0);
  Oe0_ = d.Oe.m0;
  Oe1_ = SideBySide(d.Oe, n) - SideBySide(K0.K0omega, n);
  Me_ = d.Me.m0;
  Ke_ = d.Ke.m0;
  De_ = d.De.m0;
  ksigma_ = d.ksigma.m0.col(0);
  Gr0_ = d.Gr.m0;
  Gr1_ = MatrixXd::Zero(9 * n, n);
  for (Index k = 0; k < static_cast<Index>(d.Gr.m1.size()); ++k) Gr1_.col(k) = d.Gr.m1[static_cast<std::size_t>(k)].reshaped();
  Ge0_ = d.Ge.m0;
}

void FlexibleBody::ReadNodes() {
  const Index n = n_;
  for (const sid::Node& node : data_.nodes) {
    const std::string where = fmt::format("node '{}'", node.name);
    if (node.name == kOriginMarker) Fail(name_, where + " has the name of the body-frame marker");
    for (const NodeFrame& other : nodes_) {
      if (other.name == node.name) Fail(name_, where + " appears twice");
    }
    CheckBlock(name_, node.origin, where + " origin", 3, 1, 1, n);
    CheckBlock(name_, node.psi, where + " psi", 3, n, 1, n);
    CheckBlock(name_, node.phi, where + " phi", 3, n, 1, n);
    if (node.AP.m0.rows() != 3 || node.AP.m0.cols() != 3 ||
        (node.AP.m0.transpose() * node.AP.m0 - Matrix3d::Identity()).norm() > 1e-9 || node.AP.m0.determinant() < 0.0) {
      Fail(name_, where + " AP.m0 is not a rotation matrix");
    }
    NodeFrame frame;
    frame.name = node.name;
    frame.o0 = node.origin.m0.col(0);
    frame.Phi = Eigen::Matrix3Xd::Zero(3, n);
    for (Index j = 0; j < static_cast<Index>(node.origin.m1.size()); ++j) frame.Phi.col(j) = node.origin.m1[static_cast<std::size_t>(j)];
    frame.Psi = node.psi.m0;
    frame.AP0 = node.AP.m0;
    if (geometric_stiffening_) {
      for (const MatrixXd& block : node.phi.m1) frame.phi1.emplace_back(block);
      for (const MatrixXd& block : node.psi.m1) frame.psi1.emplace_back(block);
    }
    nodes_.push_back(std::move(frame));
  }
}

FlexibleBody::Blocks FlexibleBody::Evaluate(const VectorXd& q) const {
  Blocks b;
  b.mdCM = mdCM0_ + mdCM1_ * q;
  const VectorXd qq = (q * q.transpose()).reshaped();
  b.J = J0_ + (J1_ * q + J2_ * qq).reshaped(3, 3);
  b.Ct = Ct0_ + OrderOneBlock(Ct1_, q);
  b.Cr = Cr0_ + OrderOneBlock(Cr1_, q);
  return b;
}

void FlexibleBody::MassMatrix(const ConstVectorRef& x, Eigen::Ref<MatrixXd> M) const {
  const Index n = n_;
  const VectorXd q = x.tail(n);
  const Matrix3d R = RotationFromEulerParameters(x.segment<4>(3));
  const Blocks b = Evaluate(q);
  M.setZero();
  M.topLeftCorner<3, 3>() = mass_ * Matrix3d::Identity();
  const Matrix3d R_S = R * Skew(b.mdCM).transpose();
  M.block<3, 3>(0, 3) = R_S;
  M.block<3, 3>(3, 0) = R_S.transpose();
  M.block(0, 6, 3, n) = R * b.Ct.transpose();
  M.block(6, 0, n, 3) = b.Ct * R.transpose();
  M.block<3, 3>(3, 3) = b.J;
  M.block(3, 6, 3, n) = b.Cr.transpose();
  M.block(6, 3, n, 3) = b.Cr;
  M.bottomRightCorner(n, n) = Me_;
}

void FlexibleBody::Forces(double, const ConstVectorRef& x, const ConstVectorRef& u, const Vector3d& g_W,
                          Eigen::Ref<VectorXd> h) const {
  const Index n = n_;
  const VectorXd q = x.tail(n), qdot = u.tail(n);
  const Vector3d w = u.segment<3>(3);
  const Matrix3d R = RotationFromEulerParameters(x.segment<4>(3));
  const Blocks b = Evaluate(q);
  const Matrix3d W = Skew(w);
  const Vector3d g_B = R.transpose() * g_W;
  const VectorXd qdot_w = Kronecker(qdot, w);  // block j: qdot_j w
  h.head<3>() = mass_ * g_W - R * (W * (W * b.mdCM) + 2.0 * (W * (b.Ct.transpose() * qdot)));
  const MatrixXd Gr = Gr0_ + (Gr1_ * q).reshaped(3, 3 * n);
  h.segment<3>(3) = b.mdCM.cross(g_B) - W * (b.J * w) - Gr * qdot_w;
  const Eigen::Matrix<double, 6, 1> w_q = AngularVelocityProducts(w);
  h.tail(n) = b.Ct * g_B - Oe0_ * w_q - Oe1_ * Kronecker(w_q, q) - Ge0_ * qdot_w - Ke_ * q - De_ * qdot - ksigma_;
  if (stiffening_) stiffening_->AddStateForces(stiffening_->At(q), qdot, w, g_B, h);
}

bool FlexibleBody::AddAccelerationDependentForces(const ConstVectorRef& x, const ConstVectorRef&,
                                                  const ConstVectorRef& u_dot, Eigen::Ref<VectorXd> h) const {
  if (!stiffening_) return false;
  const Vector3d a_B = RotationFromEulerParameters(x.segment<4>(3)).transpose() * u_dot.head<3>();
  stiffening_->AddAccelerationForces(x.tail(n_), a_B, u_dot.segment<3>(3), h.tail(n_));
  return true;
}

void FlexibleBody::AddForceJacobian(const ConstVectorRef& x, const ConstVectorRef& u, const ConstVectorRef& u_dot,
                                    const Vector3d& g_W, Eigen::Ref<MatrixXd> dh_dx, Eigen::Ref<MatrixXd> dh_du) const {
  const Index n = n_;
  const Matrix3d R = RotationFromEulerParameters(x.segment<4>(3));
  const Vector3d w = u.segment<3>(3), g_B = R.transpose() * g_W;
  const Eigen::Matrix<double, 6, 1> w_q = AngularVelocityProducts(w);
  auto stiffness = dh_dx.bottomRightCorner(n, n);
  stiffness -= Ke_;
  for (Index a = 0; a < 3; ++a) stiffness += g_B(a) * Ct1_.middleCols(a * n, n);
  for (Index l = 0; l < 6; ++l) stiffness -= w_q(l) * Oe1_.middleCols(l * n, n);
  if (stiffening_) {
    stiffening_->AddElasticStiffness(w, g_B - R.transpose() * u_dot.head<3>(), u_dot.segment<3>(3), stiffness);
  }
  auto damping = dh_du.bottomRightCorner(n, n);
  damping -= De_;
  for (Index j = 0; j < n; ++j) damping.col(j) -= Ge0_.middleCols(3 * j, 3) * w;
}

VectorXd FlexibleBody::Momenta(const ConstVectorRef& x, const ConstVectorRef& u) const {
  const Index n = n_;
  const VectorXd q = x.tail(n), qdot = u.tail(n);
  const Vector3d v = u.head<3>(), w = u.segment<3>(3);
  const Matrix3d R = RotationFromEulerParameters(x.segment<4>(3));
  const Blocks b = Evaluate(q);
  const Vector3d v_B = R.transpose() * v;
  VectorXd out(6 + n);
  out.head<3>() = mass_ * v + R * (w.cross(b.mdCM) + b.Ct.transpose() * qdot);
  out.segment<3>(3) = b.mdCM.cross(v_B) + b.J * w + b.Cr.transpose() * qdot;
  out.tail(n) = b.Ct * v_B + b.Cr * w + Me_ * qdot;
  if (stiffening_) out.segment<3>(3) += stiffening_->At(q).dJ * w;
  return out;
}

double FlexibleBody::KineticEnergy(const ConstVectorRef& x, const ConstVectorRef& u) const {
  return 0.5 * u.dot(Momenta(x, u));
}

double FlexibleBody::PotentialEnergy(const ConstVectorRef& x, const Vector3d& g_W) const {
  const VectorXd q = x.tail(n_);
  const Matrix3d R = RotationFromEulerParameters(x.segment<4>(3));
  const Vector3d mdCM = mdCM0_ + mdCM1_ * q;
  const double field = stiffening_ ? stiffening_->PotentialEnergy(stiffening_->At(q), R, g_W) : 0.0;
  return 0.5 * q.dot(Ke_ * q) + ksigma_.dot(q) - g_W.dot(mass_ * x.head<3>() + R * mdCM) + field;
}

Momentum FlexibleBody::ComputeMomentum(const ConstVectorRef& x, const ConstVectorRef& u) const {
  const VectorXd momenta = Momenta(x, u);
  const Matrix3d R = RotationFromEulerParameters(x.segment<4>(3));
  Momentum out;
  out.linear_W = momenta.head<3>();
  out.angular_Wo_W = Vector3d(x.head<3>()).cross(out.linear_W) + R * momenta.segment<3>(3);
  return out;
}

int FlexibleBody::FindMarker(std::string_view name) const {
  for (std::size_t k = 0; k < nodes_.size(); ++k) {
    if (nodes_[k].name == name) return static_cast<int>(k);
  }
  return name == kOriginMarker ? static_cast<int>(nodes_.size()) : -1;
}

MarkerKinematics FlexibleBody::Marker(int marker, const ConstVectorRef& x, const ConstVectorRef& u) const {
  FLEXMBS_CHECK(marker >= 0 && marker <= static_cast<int>(nodes_.size()), "marker index from FindMarker");
  const Index n = n_;
  const Vector3d p = x.head<3>(), v = u.head<3>(), w = u.segment<3>(3);
  const Matrix3d R = RotationFromEulerParameters(x.segment<4>(3));
  MarkerKinematics out;
  out.jacobian = Eigen::Matrix<double, 6, Eigen::Dynamic>::Zero(6, 6 + n);
  out.jacobian.topLeftCorner<3, 3>().setIdentity();
  out.jacobian.block<3, 3>(3, 3) = R;
  if (marker == static_cast<int>(nodes_.size())) {  // the body frame
    out.p_WM_W = p;
    out.R_WM = R;
    out.v_WM_W = v;
    out.w_WM_W = R * w;
    return out;
  }
  const NodeFrame& node = nodes_[static_cast<std::size_t>(marker)];
  const VectorXd q = x.tail(n), qdot = u.tail(n);
  // With stiffening on, the node's second-order position u2 = 1/2 sum_j q_j phi1_j q and rotation
  // theta2 = 1/2 sum_j q_j psi1_j q (their Jacobians SID's phi(q), psi(q)), so that every force
  // and moment at the node, joint reactions included, does the stiffening work.
  const auto at_q = [&](const std::vector<Eigen::Matrix3Xd>& blocks, const VectorXd& weights, Eigen::Matrix3Xd sum) {
    for (std::size_t j = 0; j < blocks.size(); ++j) sum += weights(static_cast<Index>(j)) * blocks[j];
    return sum;
  };
  const Eigen::Matrix3Xd zero = Eigen::Matrix3Xd::Zero(3, n);
  const Eigen::Matrix3Xd Phi_q = at_q(node.phi1, q, node.Phi), Phi_rate = at_q(node.phi1, qdot, zero);
  const Eigen::Matrix3Xd Psi_q = at_q(node.psi1, q, node.Psi), Psi_rate = at_q(node.psi1, qdot, zero);
  const Vector3d s = node.o0 + 0.5 * (node.Phi + Phi_q) * q;
  const Vector3d theta = 0.5 * (node.Psi + Psi_q) * q, theta_dot = Psi_q * qdot;
  const RotationCoefficients k = Coefficients(theta.norm());
  const Matrix3d Theta = Skew(theta), Theta2 = Theta * Theta;
  const Matrix3d T = Matrix3d::Identity() + k.a * Theta + k.b * Theta2;
  // dT/dt theta_dot = c (theta . theta_dot) theta x theta_dot + d (theta . theta_dot) theta x
  // (theta x theta_dot) + b theta_dot x (theta x theta_dot) (the other terms of dT/dt vanish on theta_dot).
  const double rate = theta.dot(theta_dot);
  const Vector3d cross = theta.cross(theta_dot);
  const Vector3d T_dot_theta_dot = k.c * rate * cross + k.d * rate * theta.cross(cross) + k.b * theta_dot.cross(cross);
  const Vector3d elastic_velocity = Phi_q * qdot, angular_rate = T * theta_dot;

  out.p_WM_W = p + R * s;
  out.R_WM = R * (Matrix3d::Identity() + k.s * Theta + k.a * Theta2) * node.AP0;
  out.v_WM_W = v + R * (w.cross(s) + elastic_velocity);
  out.w_WM_W = R * (w + angular_rate);
  out.jacobian.block<3, 3>(0, 3) = -R * Skew(s);
  out.jacobian.block(0, 6, 3, n) = R * Phi_q;
  out.jacobian.block(3, 6, 3, n) = R * T * Psi_q;
  out.bias.head<3>() = R * (w.cross(w.cross(s)) + 2.0 * w.cross(elastic_velocity) + Phi_rate * qdot);
  out.bias.tail<3>() = R * (w.cross(angular_rate) + T_dot_theta_dot + T * (Psi_rate * qdot));
  return out;
}

}  // namespace flexmbs::mbs
