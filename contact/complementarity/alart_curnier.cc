#include "contact/complementarity/alart_curnier.h"

namespace flexmbs::contact {

AlartCurnierContact AlartCurnier(const LocalVector& r, const LocalVector& u, double mu, double rho) {
  const Eigen::Index d = r.size();
  const LocalVector x = r - rho * u;
  AlartCurnierContact c{r, LocalMatrix::Zero(d, d)};
  if (x(0) <= 0.0) return c;  // P = 0: separation
  c.phi(0) -= x(0);
  c.D(0, 0) = 1.0;
  const auto x_t = x.tail(d - 1);
  const double norm_t = x_t.norm();
  const double radius = mu * x(0);
  if (norm_t <= radius) {  // stick: P_T = x_T
    c.phi.tail(d - 1) -= x_t;
    c.D.bottomRightCorner(d - 1, d - 1).setIdentity();
    return c;
  }
  // slide: P_T = radius x_T / ||x_T||
  const LocalVector t = x_t / norm_t;
  c.phi.tail(d - 1) -= radius * t;
  c.D.bottomLeftCorner(d - 1, 1) = mu * t;
  c.D.bottomRightCorner(d - 1, d - 1) =
      (radius / norm_t) * (LocalMatrix::Identity(d - 1, d - 1) - t * t.transpose());
  return c;
}

double AlartCurnierRho(const Eigen::Ref<const Eigen::MatrixXd>& W_ii) {
  const double norm = W_ii.norm();
  return norm > 0.0 ? 1.0 / norm : 1.0;
}

}  // namespace flexmbs::contact
