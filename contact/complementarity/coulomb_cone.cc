#include "contact/complementarity/coulomb_cone.h"

namespace flexmbs::contact {

ConeRegion ProjectOnCoulombCone(Eigen::Ref<Eigen::VectorXd> x, double mu) {
  const double norm_t = x.tail(x.size() - 1).norm();
  if (mu * norm_t <= -x(0)) {
    x.setZero();
    return ConeRegion::kPolar;
  }
  if (norm_t <= mu * x(0)) return ConeRegion::kInside;
  const double x_n = (mu * norm_t + x(0)) / (mu * mu + 1.0);
  x.tail(x.size() - 1) *= mu * x_n / norm_t;
  x(0) = x_n;
  return ConeRegion::kBoundary;
}

}  // namespace flexmbs::contact
