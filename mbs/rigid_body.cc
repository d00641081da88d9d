#include "mbs/rigid_body.h"

#include <fmt/format.h>

#include <Eigen/Eigenvalues>
#include <cmath>
#include <utility>

#include "core/error.h"
#include "core/rotation.h"
#include "core/skew.h"

namespace flexmbs::mbs {
namespace {

// Relative round-off allowed in the symmetry of an inertia tensor, the triangle inequality of
// its principal moments (a thin plate meets it with equality) and the orthonormality of a
// marker's rotation: a few ulps of values read from text.
constexpr double kRelativeRoundOff = 1e-12;
constexpr double kRotationTolerance = 1e-9;

void CheckInertia(const std::string& body, const Eigen::Matrix3d& I) {
  if (!I.allFinite() || (I - I.transpose()).norm() > kRelativeRoundOff * I.norm()) {
    throw InputError(fmt::format("rigid body '{}': inertia tensor must be finite and symmetric", body));
  }
  const Eigen::Vector3d moments = Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d>(I).eigenvalues();
  if (!(moments(0) > 0.0)) {
    throw InputError(fmt::format("rigid body '{}': inertia tensor must be positive definite (smallest principal "
                                 "moment {} kg m^2)", body, moments(0)));
  }
  if (moments(2) > (moments(0) + moments(1)) * (1.0 + kRelativeRoundOff)) {
    throw InputError(fmt::format("rigid body '{}': principal moments {}, {}, {} kg m^2 violate the triangle "
                                 "inequality", body, moments(0), moments(1), moments(2)));
  }
}

void CheckMarkers(const std::string& body, const std::vector<RigidBodyMarker>& markers) {
  for (std::size_t k = 0; k < markers.size(); ++k) {
    const RigidBodyMarker& marker = markers[k];
    for (std::size_t l = 0; l < k; ++l) {
      if (markers[l].name == marker.name) {
        throw InputError(fmt::format("rigid body '{}': marker '{}' defined twice", body, marker.name));
      }
    }
    const Eigen::Matrix3d& R = marker.R_BM;
    if (!marker.p_BoM_B.allFinite() || !R.allFinite() ||
        (R.transpose() * R - Eigen::Matrix3d::Identity()).norm() > kRotationTolerance ||
        R.determinant() < 0.0) {
      throw InputError(fmt::format("rigid body '{}': marker '{}': position must be finite and orientation a "
                                   "rotation matrix", body, marker.name));
    }
  }
}

}  // namespace

RigidBody::RigidBody(std::string name, double mass, const Eigen::Vector3d& p_BoCm_B, const Eigen::Matrix3d& I_Cm_B,
                     std::vector<RigidBodyMarker> markers)
    : name_(std::move(name)), mass_(mass), p_BoCm_B_(p_BoCm_B), I_Cm_B_(I_Cm_B), markers_(std::move(markers)) {
  if (!(mass > 0.0) || !std::isfinite(mass)) {
    throw InputError(fmt::format("rigid body '{}': mass {} kg must be > 0", name_, mass));
  }
  if (!p_BoCm_B.allFinite()) throw InputError(fmt::format("rigid body '{}': centre of mass must be finite", name_));
  CheckInertia(name_, I_Cm_B);
  CheckMarkers(name_, markers_);
  const Eigen::Matrix3d c_tilde = Skew(p_BoCm_B_);
  I_Bo_B_ = I_Cm_B_ + mass_ * c_tilde.transpose() * c_tilde;
}

void RigidBody::MassMatrix(const ConstVectorRef& x, Eigen::Ref<Eigen::MatrixXd> M) const {
  const Eigen::Matrix3d R = RotationFromEulerParameters(x.segment<4>(3));
  const Eigen::Matrix3d mc_tilde = mass_ * Skew(p_BoCm_B_);
  M.topLeftCorner<3, 3>() = mass_ * Eigen::Matrix3d::Identity();
  M.topRightCorner<3, 3>() = R * mc_tilde.transpose();
  M.bottomLeftCorner<3, 3>() = mc_tilde * R.transpose();
  M.bottomRightCorner<3, 3>() = I_Bo_B_;
}

void RigidBody::Forces(double /*t*/, const ConstVectorRef& x, const ConstVectorRef& u, const Eigen::Vector3d& g_W,
                       Eigen::Ref<Eigen::VectorXd> h) const {
  const Eigen::Matrix3d R = RotationFromEulerParameters(x.segment<4>(3));
  const Eigen::Vector3d w = u.segment<3>(3);
  const Eigen::Vector3d mc = mass_ * p_BoCm_B_;
  h.head<3>() = mass_ * g_W - R * w.cross(w.cross(mc));
  h.tail<3>() = mc.cross(R.transpose() * g_W) - w.cross(I_Bo_B_ * w);
}

double RigidBody::KineticEnergy(const ConstVectorRef& x, const ConstVectorRef& u) const {
  Eigen::Matrix<double, 6, 6> M;
  MassMatrix(x, M);
  return 0.5 * u.dot(M * u);
}

double RigidBody::PotentialEnergy(const ConstVectorRef& x, const Eigen::Vector3d& g_W) const {
  const Eigen::Matrix3d R = RotationFromEulerParameters(x.segment<4>(3));
  return -mass_ * g_W.dot(x.head<3>() + R * p_BoCm_B_);
}

int RigidBody::FindMarker(std::string_view name) const {
  for (std::size_t k = 0; k < markers_.size(); ++k) {
    if (markers_[k].name == name) return static_cast<int>(k);
  }
  return -1;
}

MarkerKinematics RigidBody::Marker(int marker, const ConstVectorRef& x, const ConstVectorRef& u) const {
  FLEXMBS_CHECK(marker >= 0 && marker < static_cast<int>(markers_.size()),
                fmt::format("rigid body '{}': marker index {} out of range", name_, marker));
  const RigidBodyMarker& m = markers_[static_cast<std::size_t>(marker)];
  const Eigen::Matrix3d R = RotationFromEulerParameters(x.segment<4>(3));
  const Eigen::Vector3d w = u.segment<3>(3);
  MarkerKinematics k;
  k.p_WM_W = x.head<3>() + R * m.p_BoM_B;
  k.R_WM = R * m.R_BM;
  k.jacobian.setZero(6, 6);
  k.jacobian.topLeftCorner<3, 3>().setIdentity();
  k.jacobian.topRightCorner<3, 3>() = -R * Skew(m.p_BoM_B);
  k.jacobian.bottomRightCorner<3, 3>() = R;
  k.v_WM_W = u.head<3>() + R * w.cross(m.p_BoM_B);
  k.w_WM_W = R * w;
  k.bias.head<3>() = R * w.cross(w.cross(m.p_BoM_B));
  k.bias.tail<3>().setZero();
  return k;
}

}  // namespace flexmbs::mbs
