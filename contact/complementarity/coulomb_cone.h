#pragma once

#include <Eigen/Core>

namespace flexmbs::contact {

/// Where a point lay relative to the Coulomb cone before ProjectOnCoulombCone moved it.
enum class ConeRegion { kInside, kBoundary, kPolar };

/// Projects x = (x_N, x_T) (x_T of size 1 or 2) onto the Coulomb cone
/// K_mu = {x : ||x_T|| <= mu x_N} in place, in the Euclidean norm; mu >= 0 (mu = 0: the half line
/// x_T = 0, x_N >= 0). Same branches and formulas as Siconos' projectionOnCone (Acary & Brogliato,
/// *Numerical Methods for Nonsmooth Dynamical Systems*, 2008, §13.5). Returns where x was.
ConeRegion ProjectOnCoulombCone(Eigen::Ref<Eigen::VectorXd> x, double mu);

}  // namespace flexmbs::contact
