#include <algorithm>
#include <cstdio>
#include <random>
#include <string>

#include <gtest/gtest.h>

#include "contact/complementarity/lcp_pgs.h"
#include "contact/complementarity/lcp_solver.h"
#include "contact/complementarity/lemke.h"
#include "contact/complementarity/siconos_solvers.h"
#include "tests/contact/complementarity_problems.h"

namespace flexmbs::contact {
namespace {

using testing::DegenerateLcp;
using testing::IllConditionedLcp;
using testing::RandomPMatrixLcp;
using testing::RandomPositiveDefiniteLcp;

// ||a - b|| / (1 + ||b||).
double Difference(const Eigen::VectorXd& a, const Eigen::VectorXd& b) { return (a - b).norm() / (1.0 + b.norm()); }

void Report(const char* what, double value) { std::printf("[measured] %s: %.3g\n", what, value); }

// Lemke's pivoting is exact up to round-off: tolerances of the iterative solvers are set tight
// so that the comparisons below measure the methods, not the stopping rule.
constexpr double kTolerance = 1e-12;

// Agreement bounds on Difference(), about 10x the largest value measured on this machine (the
// tests print each measurement as "[measured] ...").
constexpr double kPgsAgainstExact = 3e-11;       // measured 2.8e-12 (PGS stops at error 1e-12), 4.6e-13 hand-made
constexpr double kPivotingAgreement = 3e-14;     // measured 2.1e-15 (SPD), 1.6e-15 (P), 2.9e-15 (degenerate)
constexpr double kIllConditionedAgreement = 1.5e-10;  // measured 1.3e-11 at cond 1e8
constexpr double kIllConditionedError = 6e-11;   // measured LcpError 6.2e-12 (Siconos' Lemke: 3.9e-10)
constexpr double kSameAlgorithm = 3e-15;         // measured 3.1e-16: PGS against Siconos' PGS, same sweeps

PgsOptions Pgs(int max_iterations = 100000) {
  PgsOptions options;
  options.tolerance = kTolerance;
  options.max_iterations = max_iterations;
  return options;
}

SiconosOptions Siconos(int max_iterations = 100000, double tolerance = kTolerance) {
  SiconosOptions options;
  options.tolerance = tolerance;
  options.max_iterations = max_iterations;
  return options;
}

TEST(Lemke, SolvesHandMadeLcpsWithKnownSolutions) {
  // M = [2 1; 1 2]: q = (-1, -1) gives z = (1/3, 1/3), w = 0; q = (-1, 2) gives z = (1/2, 0), w = (0, 5/2).
  Eigen::MatrixXd M(2, 2);
  M << 2, 1, 1, 2;
  const LcpProblem both{M, Eigen::Vector2d(-1, -1)};
  const LcpProblem one{M, Eigen::Vector2d(-1, 2)};
  double worst = 0.0;
  for (const auto& [problem, z_star] : {std::pair{both, Eigen::VectorXd(Eigen::Vector2d(1.0 / 3, 1.0 / 3))},
                                        std::pair{one, Eigen::VectorXd(Eigen::Vector2d(0.5, 0))}}) {
    for (const LcpSolution& s : {SolveLcpLemke(problem), SolveLcpPgs(problem, Pgs()),
                                 SiconosLcpLemke(problem), SiconosLcpPgs(problem, Siconos())}) {
      EXPECT_TRUE(s.converged) << s.message;
      worst = std::max(worst, Difference(s.z, z_star));
    }
  }
  Report("hand-made LCPs, all solvers against the analytic z", worst);
  EXPECT_LT(worst, kPgsAgainstExact);
}

TEST(Lemke, AgreesWithSiconosOnRandomPositiveDefiniteAndPMatrixLcps) {
  double worst_pd = 0.0, worst_p = 0.0;
  for (int n : {1, 2, 5, 10, 20, 50, 100, 200}) {
    for (unsigned seed = 0; seed < 3; ++seed) {
      const LcpProblem pd = RandomPositiveDefiniteLcp(n, seed);
      const LcpSolution ours = SolveLcpLemke(pd);
      const LcpSolution theirs = SiconosLcpLemke(pd);
      ASSERT_TRUE(ours.converged) << ours.message;
      ASSERT_TRUE(theirs.converged) << theirs.message;
      worst_pd = std::max(worst_pd, Difference(ours.z, theirs.z));
      const LcpProblem p = RandomPMatrixLcp(n, seed);
      const LcpSolution ours_p = SolveLcpLemke(p);
      const LcpSolution theirs_p = SiconosLcpLemke(p);
      ASSERT_TRUE(ours_p.converged) << ours_p.message;
      ASSERT_TRUE(theirs_p.converged) << theirs_p.message;
      worst_p = std::max(worst_p, Difference(ours_p.z, theirs_p.z));
    }
  }
  Report("Lemke vs Siconos Lemke, SPD n <= 200", worst_pd);
  Report("Lemke vs Siconos Lemke, non-symmetric P n <= 200", worst_p);
  EXPECT_LT(worst_pd, kPivotingAgreement);
  EXPECT_LT(worst_p, kPivotingAgreement);
}

TEST(ProjectedGaussSeidel, AgreesWithLemkeAndSiconosPgsOnPositiveDefiniteLcps) {
  double worst_lemke = 0.0, worst_siconos = 0.0;
  for (int n : {1, 5, 20, 100, 200}) {
    const LcpProblem problem = RandomPositiveDefiniteLcp(n, 7);
    const LcpSolution exact = SolveLcpLemke(problem);
    const LcpSolution ours = SolveLcpPgs(problem, Pgs());
    const LcpSolution theirs = SiconosLcpPgs(problem, Siconos());
    ASSERT_TRUE(ours.converged) << ours.message;
    ASSERT_TRUE(theirs.converged) << theirs.message;
    worst_lemke = std::max(worst_lemke, Difference(ours.z, exact.z));
    worst_siconos = std::max(worst_siconos, Difference(ours.z, theirs.z));
  }
  Report("PGS vs Lemke, SPD", worst_lemke);
  Report("PGS vs Siconos PGS, SPD", worst_siconos);
  EXPECT_LT(worst_lemke, kPgsAgainstExact);
  EXPECT_LT(worst_siconos, kSameAlgorithm);
}

TEST(Lemke, FindsTheKnownSolutionOfDegenerateLcps) {
  double worst_ours = 0.0, worst_siconos = 0.0, worst_pgs = 0.0;
  for (int n : {3, 9, 30, 99}) {
    const testing::KnownLcp known = DegenerateLcp(n, 11);
    const LcpSolution ours = SolveLcpLemke(known.problem);
    const LcpSolution theirs = SiconosLcpLemke(known.problem);
    const LcpSolution pgs = SolveLcpPgs(known.problem, Pgs());
    ASSERT_TRUE(ours.converged) << ours.message;
    ASSERT_TRUE(theirs.converged) << theirs.message;
    ASSERT_TRUE(pgs.converged) << pgs.message;
    worst_ours = std::max(worst_ours, Difference(ours.z, known.z_star));
    worst_siconos = std::max(worst_siconos, Difference(theirs.z, known.z_star));
    worst_pgs = std::max(worst_pgs, Difference(pgs.z, known.z_star));
  }
  Report("degenerate: Lemke vs known z", worst_ours);
  Report("degenerate: Siconos Lemke vs known z", worst_siconos);
  Report("degenerate: PGS vs known z", worst_pgs);
  EXPECT_LT(worst_ours, kPivotingAgreement);
  EXPECT_LT(worst_siconos, kPivotingAgreement);
  EXPECT_LT(worst_pgs, kPgsAgainstExact);
}

TEST(Lemke, SolvesIllConditionedLcps) {
  double worst = 0.0, worst_error = 0.0, worst_siconos_error = 0.0;
  for (int n : {5, 20, 50}) {
    const LcpProblem problem = IllConditionedLcp(n, 1e8, 3);
    const LcpSolution ours = SolveLcpLemke(problem);
    const LcpSolution theirs = SiconosLcpLemke(problem, Siconos(100000, 1e-6));
    EXPECT_TRUE(ours.converged) << ours.message;
    worst = std::max(worst, Difference(ours.z, theirs.z));
    worst_error = std::max(worst_error, ours.error);
    worst_siconos_error = std::max(worst_siconos_error, theirs.error);
  }
  Report("cond 1e8: Lemke vs Siconos Lemke", worst);
  Report("cond 1e8: Lemke error", worst_error);
  Report("cond 1e8: Siconos Lemke error", worst_siconos_error);
  EXPECT_LT(worst, kIllConditionedAgreement);
  EXPECT_LT(worst_error, kIllConditionedError);
}

TEST(Lemke, ReportsRayTerminationOnAnInfeasibleLcp) {
  // M = -1, q = -1: w = -z - 1 < 0 for every z >= 0.
  const LcpProblem infeasible{Eigen::MatrixXd::Constant(1, 1, -1.0), Eigen::VectorXd::Constant(1, -1.0)};
  const LcpSolution ours = SolveLcpLemke(infeasible);
  EXPECT_FALSE(ours.converged);
  EXPECT_NE(ours.message.find("ray termination"), std::string::npos) << ours.message;
  const LcpSolution theirs = SiconosLcpLemke(infeasible);
  EXPECT_FALSE(theirs.converged) << theirs.message;
  std::printf("[measured] Siconos on M = -1, q = -1: %s\n", theirs.message.c_str());
  // Two unknowns, the ray after a pivot: w_2 = -z_2 - 1 < 0 for every z_2 >= 0.
  Eigen::MatrixXd M(2, 2);
  M << 1, 0, 0, -1;
  const LcpProblem later{M, Eigen::Vector2d(-1, -1)};
  const LcpSolution ours_later = SolveLcpLemke(later);
  EXPECT_FALSE(ours_later.converged);
  EXPECT_NE(ours_later.message.find("ray termination"), std::string::npos) << ours_later.message;
  const LcpSolution theirs_later = SiconosLcpLemke(later);
  EXPECT_FALSE(theirs_later.converged) << theirs_later.message;
  std::printf("[measured] ours on the 2 x 2: %s\n[measured] Siconos on the 2 x 2: %s\n", ours_later.message.c_str(),
              theirs_later.message.c_str());
}

TEST(ProjectedGaussSeidel, ReportsNonConvergence) {
  const LcpProblem problem = RandomPositiveDefiniteLcp(50, 5);
  const LcpSolution ours = SolveLcpPgs(problem, Pgs(3));
  EXPECT_FALSE(ours.converged);
  EXPECT_EQ(ours.iterations, 3);
  EXPECT_NE(ours.message.find("no convergence"), std::string::npos) << ours.message;
  const LcpSolution theirs = SiconosLcpPgs(problem, Siconos(3));
  EXPECT_FALSE(theirs.converged) << theirs.message;
  // A non-positive diagonal is refused, not iterated.
  const LcpProblem negative{Eigen::MatrixXd::Constant(1, 1, -1.0), Eigen::VectorXd::Constant(1, -1.0)};
  EXPECT_FALSE(SolveLcpPgs(negative).converged);
}

}  // namespace
}  // namespace flexmbs::contact

namespace flexmbs::contact {
namespace {

// A singular LCP as redundant contact points give it: M = B B^T (n x n of rank r < n, B random),
// with a known solution z* >= 0, w* >= 0, z*_i w*_i = 0 and q = w* - M z*. For a symmetric
// positive semi-definite M every solution has the same w = M z + q (the minimisers of the convex
// quadratic 1/2 z^T M z + q^T z over z >= 0 share M z).
LcpProblem SingularLcp(std::mt19937& rng, Eigen::Index n, Eigen::Index rank, Eigen::VectorXd* w_known) {
  std::normal_distribution<double> normal;
  std::bernoulli_distribution active(0.5);
  Eigen::MatrixXd B(n, rank);
  for (Eigen::Index i = 0; i < n; ++i) {
    for (Eigen::Index j = 0; j < rank; ++j) B(i, j) = normal(rng);
  }
  Eigen::VectorXd z = Eigen::VectorXd::Zero(n), w = Eigen::VectorXd::Zero(n);
  for (Eigen::Index i = 0; i < n; ++i) (active(rng) ? z(i) : w(i)) = std::abs(normal(rng));
  const Eigen::MatrixXd M = B * B.transpose();
  *w_known = w;
  return {M, w - M * z};
}

TEST(SolveLcp, SolvesSingularLcpsThatLemkeMissesAtItsDefaultTolerance) {
  std::mt19937 rng(17);
  int lemke_missed = 0;
  double worst_error = 0.0, worst_w = 0.0;
  for (int trial = 0; trial < 20; ++trial) {
    Eigen::VectorXd w_known;
    const LcpProblem problem = SingularLcp(rng, 40, 8, &w_known);
    const LcpSolution lemke = SolveLcpLemke(problem, LemkeOptions{0, 1e-12, true, 1e-10});
    lemke_missed += !lemke.converged;
    const LcpSolution solution = SolveLcp(problem, {1e-10});
    EXPECT_TRUE(solution.converged) << trial << ": " << solution.message;
    EXPECT_GE(solution.z.minCoeff(), 0.0);
    worst_error = std::max(worst_error, solution.error);
    worst_w = std::max(worst_w, Difference(problem.M * solution.z + problem.q, w_known));
  }
  Report("singular LCPs (40 points, rank 8): Lemke missed 1e-10 in trials", lemke_missed);
  Report("singular LCPs: SolveLcp's largest LcpError", worst_error);
  Report("singular LCPs: SolveLcp's w against the known w", worst_w);
  EXPECT_GT(lemke_missed, 0);  // the later stages are exercised (measured: 3 of 20)
  EXPECT_LE(worst_error, 3e-12);  // measured 2.6e-13 (Lemke at pivot tolerance 1e-9, refined)
  EXPECT_LT(worst_w, 1.5e-10);    // measured 1.2e-11
}

TEST(SolveLcp, IsLemkeOnPMatrices) {
  for (int seed = 0; seed < 5; ++seed) {
    const LcpProblem problem = RandomPositiveDefiniteLcp(30, static_cast<unsigned>(seed));
    const LcpSolution lemke = SolveLcpLemke(problem), solution = SolveLcp(problem);
    EXPECT_EQ(solution.z, lemke.z);
    EXPECT_EQ(solution.iterations, lemke.iterations);
  }
}

}  // namespace
}  // namespace flexmbs::contact
