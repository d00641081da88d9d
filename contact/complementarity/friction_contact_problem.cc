#include "contact/complementarity/friction_contact_problem.h"

#include <algorithm>
#include <cfloat>
#include <cmath>

#include "contact/complementarity/coulomb_cone.h"
#include "core/error.h"

namespace flexmbs::contact {

void CheckFrictionContact(const FrictionContactProblem& problem) {
  FLEXMBS_CHECK(problem.dimension == 2 || problem.dimension == 3,
                "friction contact: the dimension must be 2 or 3");
  const Eigen::Index n = problem.dimension * problem.mu.size();
  FLEXMBS_CHECK(problem.W.rows() == n && problem.W.cols() == n,
                "friction contact: W must be d n x d n for n = mu.size() contacts");
  FLEXMBS_CHECK(problem.q.size() == n, "friction contact: q must have d n rows");
  FLEXMBS_CHECK((problem.mu.array() >= 0.0).all(), "friction contact: every mu must be >= 0");
  FLEXMBS_CHECK(problem.W.allFinite() && problem.q.allFinite() && problem.mu.allFinite(),
                "friction contact: W, q and mu must be finite");
}

double ContactNaturalMapErrorSquared(const LocalVector& r_i, const LocalVector& u_i, double mu) {
  LocalVector x = r_i - u_i;
  x(0) -= mu * u_i.tail(u_i.size() - 1).norm();
  ProjectOnCoulombCone(x, mu);
  return (r_i - x).squaredNorm();
}

double FrictionContactError(const FrictionContactProblem& problem, const Eigen::VectorXd& r) {
  const int d = problem.dimension;
  const Eigen::VectorXd u = problem.W * r + problem.q;
  double sum = 0.0;
  for (int i = 0; i < problem.contacts(); ++i) {
    sum += ContactNaturalMapErrorSquared(r.segment(d * i, d), u.segment(d * i, d), problem.mu(i));
  }
  const double scale = std::max({problem.q.norm(), r.norm(), u.norm()});
  return scale > DBL_EPSILON ? std::sqrt(sum) / scale : std::sqrt(sum);
}

}  // namespace flexmbs::contact
