#pragma once

#include <Eigen/Core>

namespace flexmbs::contact {

/// One planar contact solved exactly: u = W r + q with W 2 x 2 symmetric positive definite, (u, r)
/// obeying Coulomb's law (Signorini normal, two-sided tangent). Enumerates the cases — take-off
/// (q_N >= 0: r = 0), stick (u = 0, r = -W^-1 q inside the cone), slide in either direction
/// (u_N = 0, r_T = -sign(u_T) mu r_N) — and returns the first that holds; when round-off lets
/// none hold exactly, the candidate with the least natural-map error (Acary & Brogliato 2008,
/// §13.3.3; the enumeration of Siconos' fc2d_enum for one contact).
Eigen::Vector2d SolvePlanarContact(const Eigen::Matrix2d& W, const Eigen::Vector2d& q, double mu);

/// Options of SolveSpatialContact.
struct SpatialContactOptions {
  double tolerance = 1e-14;  ///< stop when ||Phi|| <= tolerance (||r|| + rho ||q||)
  int max_iterations = 50;   ///< most Newton steps
};

/// One spatial contact: u = W r + q with W 3 x 3 symmetric positive definite, (u, r) obeying
/// Coulomb's law. Take-off and stick are tested exactly first; otherwise Alart-Curnier's function
/// is solved by a semi-smooth Newton method with Armijo backtracking on ||Phi||^2 from r
/// (Alart & Curnier 1991; Siconos' ONECONTACT_NSN). Where Newton stalls short of its tolerance (a
/// kink of ||Phi||^2 with no descent along the Newton direction), the sliding solutions are
/// enumerated instead: r = r_N (1, -mu t) with u_N = 0 fixes r_N for each direction t = (cos a,
/// sin a), and u_T parallel to t is a root in a, bracketed on 64 samples of [0, 2 pi) and bisected
/// to round-off; the root with the least natural-map error replaces r if it is better (the role
/// of the projection fallback in Siconos' ONECONTACT_NSN_GP_HYBRID). Returns whether the
/// tolerance was met; r is the last Newton iterate or the better sliding root either way.
bool SolveSpatialContact(const Eigen::Matrix3d& W, const Eigen::Vector3d& q, double mu, Eigen::Vector3d& r,
                         const SpatialContactOptions& options = {});

}  // namespace flexmbs::contact
