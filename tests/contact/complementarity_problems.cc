#include "tests/contact/complementarity_problems.h"

#include <cmath>
#include <numbers>
#include <random>

#include <Eigen/Cholesky>
#include <Eigen/Geometry>
#include <Eigen/QR>

#include "core/skew.h"

namespace flexmbs::contact::testing {
namespace {

Eigen::MatrixXd Gaussian(int rows, int cols, std::mt19937& rng) {
  std::normal_distribution<double> normal;
  return Eigen::MatrixXd::NullaryExpr(rows, cols, [&] { return normal(rng); });
}

// k numbers from `unit`, drawn one by one: the last entry first or the first entry first.
template <int k>
Eigen::Matrix<double, k, 1> Draw(std::uniform_real_distribution<double>& unit, std::mt19937& rng, DrawOrder order) {
  Eigen::Matrix<double, k, 1> x;
  for (int j = 0; j < k; ++j) x(order == DrawOrder::kLastFirst ? k - 1 - j : j) = unit(rng);
  return x;
}

}  // namespace

LcpProblem RandomPositiveDefiniteLcp(int n, unsigned seed) {
  std::mt19937 rng(seed);
  const Eigen::MatrixXd A = Gaussian(n, n, rng);
  return {A * A.transpose() / n + 0.1 * Eigen::MatrixXd::Identity(n, n), Gaussian(n, 1, rng)};
}

LcpProblem RandomPMatrixLcp(int n, unsigned seed) {
  std::mt19937 rng(seed);
  const Eigen::MatrixXd A = Gaussian(n, n, rng);
  const Eigen::MatrixXd B = Gaussian(n, n, rng) / std::sqrt(n);
  return {A * A.transpose() / n + 0.1 * Eigen::MatrixXd::Identity(n, n) + B - B.transpose(), Gaussian(n, 1, rng)};
}

LcpProblem IllConditionedLcp(int n, double condition, unsigned seed) {
  std::mt19937 rng(seed);
  const Eigen::MatrixXd Q = Gaussian(n, n, rng).householderQr().householderQ();
  Eigen::VectorXd lambda(n);
  for (int i = 0; i < n; ++i) lambda(i) = std::pow(condition, -static_cast<double>(i) / std::max(1, n - 1));
  return {Q * lambda.asDiagonal() * Q.transpose(), Gaussian(n, 1, rng)};
}

KnownLcp DegenerateLcp(int n, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> positive(0.5, 2.0);
  const Eigen::MatrixXd A = Gaussian(n, n, rng);
  const Eigen::MatrixXd M = A * A.transpose() / n + 0.1 * Eigen::MatrixXd::Identity(n, n);
  Eigen::VectorXd z = Eigen::VectorXd::Zero(n);
  Eigen::VectorXd w = Eigen::VectorXd::Zero(n);
  for (int i = 0; i < n; ++i) {
    if (i % 3 == 0) z(i) = positive(rng);
    if (i % 3 == 1) w(i) = positive(rng);
  }
  return {{M, w - M * z}, z};
}

GeometricProblem RigidBodiesOnGround(int dimension, int bodies, int contacts, double mu, unsigned seed,
                                     DrawOrder order) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  std::uniform_real_distribution<double> mass(1.0, 10.0);
  const double max_tilt = std::numbers::pi / 6.0;
  const int body_dof = dimension == 2 ? 3 : 6;
  const int dof = body_dof * bodies;
  GeometricProblem g{{dimension, {}, {}, Eigen::VectorXd::Constant(contacts, mu)},
                     Eigen::MatrixXd::Zero(dimension * contacts, dof),
                     Eigen::MatrixXd::Zero(dof, dof)};
  for (int b = 0; b < bodies; ++b) {
    const double m = mass(rng);
    g.M.block(body_dof * b, body_dof * b, body_dof, body_dof).diagonal().head(dimension).setConstant(m);
    for (int k = dimension; k < body_dof; ++k) g.M(body_dof * b + k, body_dof * b + k) = m * (0.1 + 0.2 * (unit(rng) + 1.0));
  }
  for (int c = 0; c < contacts; ++c) {
    // Even contacts touch the ground; odd ones rest body a on body b = a + 1 (the last body on the
    // ground), which sees the same point one unit above its centre. No cycles: lifting body k at
    // speed bodies - k opens every contact, so the impact problem is feasible.
    const int a = c % bodies;
    const int b = c % 2 == 1 && a + 1 < bodies ? a + 1 : -1;
    const int row = dimension * c;
    if (dimension == 2) {
      // frame (n, t); point p below a's centre; planar velocity of p: v + w x p = v + w perp(p).
      const double tilt = max_tilt * unit(rng);
      const Eigen::Vector2d n(std::sin(tilt), std::cos(tilt));
      const Eigen::Vector2d t(n.y(), -n.x());
      // Drawn one by one: the order of a call's arguments is unspecified (GCC draws the last
      // first, clang the first: under clang these were other problems); `order` says which.
      const Eigen::Vector2d drawn = Draw<2>(unit, rng, order);
      const Eigen::Vector2d p(drawn.x(), -1.0 + 0.2 * drawn.y());
      Eigen::Matrix2d C;
      C << n, t;
      const auto point_rows = [&](const Eigen::Vector2d& x) {
        Eigen::Matrix<double, 2, 3> rows;
        rows << C.transpose(), C.transpose() * Eigen::Vector2d(-x.y(), x.x());
        return rows;
      };
      g.G.block(row, body_dof * a, 2, 3) += point_rows(p);
      if (b >= 0) g.G.block(row, body_dof * b, 2, 3) -= point_rows(p + Eigen::Vector2d(0.0, 1.0));
    } else {
      const double tilt = max_tilt * (unit(rng) + 1.0) / 2.0;
      const double azimuth = std::numbers::pi * unit(rng);
      const Eigen::Vector3d n(std::sin(tilt) * std::cos(azimuth), std::sin(tilt) * std::sin(azimuth), std::cos(tilt));
      const Eigen::Vector3d t1 = n.unitOrthogonal();
      Eigen::Matrix3d C;
      C << n, t1, n.cross(t1);
      const Eigen::Vector3d drawn = Draw<3>(unit, rng, order);  // one by one (see the planar case)
      const Eigen::Vector3d p(drawn.x(), drawn.y(), -1.0 + 0.2 * drawn.z());
      // velocity of the point x (from the centre): v + w x x = v - Skew(x) w
      const auto point_rows = [&](const Eigen::Vector3d& x) {
        Eigen::Matrix<double, 3, 6> rows;
        rows << C.transpose(), -C.transpose() * Skew(x);
        return rows;
      };
      g.G.block(row, body_dof * a, 3, 6) += point_rows(p);
      if (b >= 0) g.G.block(row, body_dof * b, 3, 6) -= point_rows(p + Eigen::Vector3d(0.0, 0.0, 1.0));
    }
  }
  Eigen::VectorXd v_free = Eigen::VectorXd::Zero(dof);
  for (int b = 0; b < bodies; ++b) {
    v_free.segment(body_dof * b, body_dof) = Eigen::VectorXd::NullaryExpr(body_dof, [&] { return unit(rng); });
    v_free(body_dof * b + dimension - 1) = -1.0 + 0.3 * unit(rng);  // down
  }
  const Eigen::MatrixXd M_inv_Gt = g.M.llt().solve(g.G.transpose());
  const Eigen::MatrixXd W = g.G * M_inv_Gt;
  g.problem.W = 0.5 * (W + W.transpose());  // symmetric to round-off already; exactly now
  g.problem.q = g.G * v_free;
  return g;
}

}  // namespace flexmbs::contact::testing
