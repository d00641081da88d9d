#include <cmath>
#include <cstdio>
#include <random>

#include <gtest/gtest.h>

#include "contact/complementarity/coulomb_cone.h"
#include "contact/complementarity/friction_contact_problem.h"
#include "contact/complementarity/lcp_problem.h"
#include "contact/complementarity/siconos_solvers.h"
#include "tests/contact/complementarity_problems.h"

namespace flexmbs::contact {
namespace {

// Sums and norms of a handful of O(1) numbers: a few ulps.
constexpr double kRoundOff = 1e-15;

TEST(LcpError, IsZeroAtTheSolutionAndTheNormalisedNaturalMapElsewhere) {
  // M = 2, q = -2: z = 1, w = 0.
  const LcpProblem lcp{Eigen::MatrixXd::Constant(1, 1, 2.0), Eigen::VectorXd::Constant(1, -2.0)};
  EXPECT_EQ(LcpError(lcp, Eigen::VectorXd::Constant(1, 1.0)), 0.0);
  // z = 0: w = -2, min(z, w) = -2, ||q|| = 2.
  EXPECT_NEAR(LcpError(lcp, Eigen::VectorXd::Zero(1)), 1.0, kRoundOff);
}

TEST(CoulombCone, ProjectsOntoTheBoundaryAlongTheNormalOfTheCone) {
  Eigen::VectorXd x(3);
  x << 0.0, 3.0, 4.0;  // ||x_T|| = 5, mu = 1: projection at x_N = 5/2 on the ray (1, 0.6, 0.8)
  EXPECT_EQ(ProjectOnCoulombCone(x, 1.0), ConeRegion::kBoundary);
  EXPECT_NEAR(x(0), 2.5, kRoundOff);
  EXPECT_NEAR(x.tail(2).norm(), 2.5, kRoundOff);
  Eigen::VectorXd polar(2);
  polar << -1.0, 0.5;
  EXPECT_EQ(ProjectOnCoulombCone(polar, 1.0), ConeRegion::kPolar);
  EXPECT_EQ(polar.norm(), 0.0);
}

TEST(FrictionContactError, IsZeroForStickSlideAndTakeOff) {
  FrictionContactProblem problem{3, Eigen::MatrixXd::Identity(3, 3), Eigen::VectorXd(3), Eigen::VectorXd(1)};
  problem.mu << 0.5;
  // Sliding: q = (-1, 2, 0), r = (1, -0.5, 0) gives u = (0, 1.5, 0) opposite to r_T on the cone.
  problem.q << -1.0, 2.0, 0.0;
  Eigen::VectorXd r(3);
  r << 1.0, -0.5, 0.0;
  EXPECT_NEAR(FrictionContactError(problem, r), 0.0, kRoundOff);
  // Take-off: q_N > 0, r = 0.
  problem.q << 1.0, 2.0, 0.0;
  EXPECT_NEAR(FrictionContactError(problem, Eigen::VectorXd::Zero(3)), 0.0, kRoundOff);
  // A wrong answer has a positive error.
  EXPECT_GT(FrictionContactError(problem, r), 0.1);
}

// |a - b| / b.
double Relative(double a, double b) { return std::abs(a - b) / b; }

// Our error measures are Siconos' formulas evaluated in another order: they agree to round-off.
constexpr double kSameFormula = 5e-15;  // measured 4.5e-16 (LCP), 1.6e-16 (2-D), 0 (3-D)

TEST(ErrorMeasures, AgreeWithSiconosAtArbitraryPoints) {
  std::mt19937 rng(2);
  std::normal_distribution<double> normal;
  double worst_lcp = 0.0, worst_fc[2] = {0.0, 0.0};
  for (int n : {1, 10, 100}) {
    const LcpProblem lcp = testing::RandomPositiveDefiniteLcp(n, 1);
    const Eigen::VectorXd z = Eigen::VectorXd::NullaryExpr(n, [&] { return normal(rng); });
    worst_lcp = std::max(worst_lcp, Relative(LcpError(lcp, z), SiconosLcpError(lcp, z)));
    for (int d : {2, 3}) {
      const FrictionContactProblem fc = testing::RigidBodiesOnGround(d, 3, n, 0.3, 1).problem;
      const Eigen::VectorXd r = Eigen::VectorXd::NullaryExpr(d * n, [&] { return normal(rng); });
      worst_fc[d - 2] = std::max(worst_fc[d - 2], Relative(FrictionContactError(fc, r), SiconosFrictionContactError(fc, r)));
    }
  }
  std::printf("[measured] error measures against Siconos': LCP %.3g, 2-D %.3g, 3-D %.3g\n", worst_lcp, worst_fc[0],
              worst_fc[1]);
  EXPECT_LT(worst_lcp, kSameFormula);
  EXPECT_LT(worst_fc[0], kSameFormula);
  EXPECT_LT(worst_fc[1], kSameFormula);
}

}  // namespace
}  // namespace flexmbs::contact
