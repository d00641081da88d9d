#include "mbs/body.h"

#include "core/rotation.h"

namespace flexmbs::mbs {

Eigen::VectorXd Body::MarkerLoad(int marker, const ConstVectorRef& x, const Eigen::Vector3d& f_W,
                                 const Eigen::Vector3d& tau_W) const {
  const MarkerKinematics kinematics = Marker(marker, x, Eigen::VectorXd::Zero(num_velocities()));
  return GeneralizedForce(kinematics, f_W, tau_W);
}

bool Body::AddAccelerationDependentForces(const ConstVectorRef& /*x*/, const ConstVectorRef& /*u*/,
                                          const ConstVectorRef& /*u_dot*/, Eigen::Ref<Eigen::VectorXd> /*h*/) const {
  return false;
}

void Body::AddForceJacobian(const ConstVectorRef& /*x*/, const ConstVectorRef& /*u*/, const ConstVectorRef& /*u_dot*/,
                            const Eigen::Vector3d& /*g_W*/, Eigen::Ref<Eigen::MatrixXd> /*dh_dx*/,
                            Eigen::Ref<Eigen::MatrixXd> /*dh_du*/) const {}

Eigen::VectorXd GeneralizedForce(const MarkerKinematics& kinematics, const Eigen::Vector3d& f_W,
                                 const Eigen::Vector3d& tau_W) {
  Eigen::Matrix<double, 6, 1> load;
  load << f_W, tau_W;
  return kinematics.jacobian.transpose() * load;
}

void PositionDerivative(const ConstVectorRef& x, const ConstVectorRef& u, Eigen::Ref<Eigen::VectorXd> xdot) {
  const Eigen::Index n = x.size() - 7;
  xdot.head<3>() = u.head<3>();
  xdot.segment<4>(3) = EulerParameterRate(x.segment<4>(3), u.segment<3>(3));
  xdot.tail(n) = u.tail(n);
}

}  // namespace flexmbs::mbs
