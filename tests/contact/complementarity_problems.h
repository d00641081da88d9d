#pragma once

#include <Eigen/Core>

#include "contact/complementarity/friction_contact_problem.h"
#include "contact/complementarity/lcp_problem.h"

namespace flexmbs::contact::testing {

/// LCP with M = A A^T / n + 0.1 I (symmetric positive definite) and q ~ N(0, 1), A ~ N(0, 1).
LcpProblem RandomPositiveDefiniteLcp(int n, unsigned seed);

/// LCP with a non-symmetric P-matrix M = A A^T / n + 0.1 I + (B - B^T) (positive definite, hence P).
LcpProblem RandomPMatrixLcp(int n, unsigned seed);

/// LCP with M = Q diag(logspace(0, -log10(condition))) Q^T, Q a random orthogonal matrix.
LcpProblem IllConditionedLcp(int n, double condition, unsigned seed);

/// An LCP with a known, degenerate solution: of every three indices one has z > 0 = w, one
/// w > 0 = z and one z = w = 0. M is symmetric positive definite; z_star holds the solution.
struct KnownLcp {
  LcpProblem problem;
  Eigen::VectorXd z_star;
};
KnownLcp DegenerateLcp(int n, unsigned seed);

/// A friction-contact problem from a stack of rigid bodies on the ground: `bodies` bodies (3 DOF
/// planar, 6 spatial) of random mass and inertia; contact c sits under body c mod bodies, on the
/// ground for even c and on body c mod bodies + 1 (if any) for odd c, with its normal tilted up to 30 degrees from
/// vertical; W = G M^-1 G^T, q = G v_free with a free velocity pointing down and sideways. More
/// contact coordinates than DOF (d contacts > DOF) makes W rank-deficient. G and M are kept to
/// compare the generalised impulse G^T r. `order` picks the order a contact point's coordinates are
/// drawn in: two families of problems from the same seeds (kLastFirst is the original family).
struct GeometricProblem {
  FrictionContactProblem problem;
  Eigen::MatrixXd G;  ///< d n x DOF contact Jacobian
  Eigen::MatrixXd M;  ///< DOF x DOF block-diagonal mass matrix
};
/// The order RigidBodiesOnGround draws a contact point's coordinates in: last coordinate first (the
/// original family, as GCC evaluated the constructor's arguments) or first coordinate first (as
/// clang did; commit fcb6076). Each gives other valid problems from the same seed.
enum class DrawOrder { kLastFirst, kFirstFirst };
GeometricProblem RigidBodiesOnGround(int dimension, int bodies, int contacts, double mu, unsigned seed,
                                     DrawOrder order = DrawOrder::kLastFirst);

}  // namespace flexmbs::contact::testing
