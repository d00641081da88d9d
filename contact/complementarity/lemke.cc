#include "contact/complementarity/lemke.h"

#include <cmath>
#include <string>
#include <vector>

#include <Eigen/LU>
#include <fmt/core.h>

namespace flexmbs::contact {
namespace {

// Variables of the tableau w - M z - e z0 = q: w_k is k, z_k is n + k, z0 is 2 n.
struct Tableau {
  Eigen::MatrixXd B_inv;    // the inverse of the basis matrix, n x n
  Eigen::VectorXd b;        // the basic variables' values, B^-1 q
  std::vector<int> basis;   // basis[i]: the variable basic in row i
  Eigen::VectorXd c;        // the entering variable's column B^-1 A_j
  Eigen::RowVectorXd pivot_row;  // scratch of Pivot
  std::vector<int> rows;    // scratch of LexicographicRow
};

// c = B^-1 A_j, the entering variable j's column of the updated tableau.
void EnteringColumn(Tableau& t, const Eigen::MatrixXd& M, int j) {
  const int n = static_cast<int>(M.rows());
  if (j < n) {
    t.c = t.B_inv.col(j);
  } else if (j < 2 * n) {
    t.c.noalias() = -t.B_inv * M.col(j - n);
  } else {
    t.c = -t.B_inv.rowwise().sum();
  }
}

// Gauss-Jordan pivot on row r with the entering column c (c(r) != 0).
void Pivot(Tableau& t, int r, int entering) {
  const double p = t.c(r);
  t.pivot_row = t.B_inv.row(r) / p;
  const double b_r = t.b(r) / p;
  t.B_inv.noalias() -= t.c * t.pivot_row;
  t.b -= b_r * t.c;
  t.B_inv.row(r) = t.pivot_row;
  t.b(r) = b_r;
  t.basis[r] = entering;
}

// The lexicographic minimum ratio test (Cottle, Pang & Stone 1992, §4.9): among rows with c_i
// above tol, the lexicographic minimum of (b_i, B^-1_i.) / c_i. -1 when no row blocks (a ray).
int LexicographicRow(Tableau& t, double tol) {
  std::vector<int>& rows = t.rows;
  rows.clear();
  for (int i = 0; i < t.c.size(); ++i) {
    if (t.c(i) > tol) rows.push_back(i);
  }
  if (rows.empty()) return -1;
  // Column -1 is b, then the columns of B^-1; keep the rows within round-off of the minimum.
  for (int k = -1; k < t.B_inv.cols() && rows.size() > 1; ++k) {
    const auto value = [&](int i) { return (k < 0 ? t.b(i) : t.B_inv(i, k)) / t.c(i); };
    double least = value(rows[0]);
    for (int i : rows) least = std::min(least, value(i));
    const double tie = 1e-12 * (1.0 + std::abs(least));
    std::erase_if(rows, [&](int i) { return value(i) > least + tie; });
  }
  return rows[0];
}

// z from the final basis: the basic z_k take their row's value (negative round-off clipped to 0).
Eigen::VectorXd BasicZ(const Tableau& t, int n) {
  Eigen::VectorXd z = Eigen::VectorXd::Zero(n);
  for (int i = 0; i < n; ++i) {
    if (t.basis[i] >= n && t.basis[i] < 2 * n) z(t.basis[i] - n) = std::max(0.0, t.b(i));
  }
  return z;
}

// z_J = -M_JJ^-1 q_J on the basic set J of z: the same solution without the tableau's round-off.
Eigen::VectorXd RefinedZ(const LcpProblem& problem, const Eigen::VectorXd& z_tableau, const Tableau& t) {
  const int n = static_cast<int>(problem.q.size());
  std::vector<int> J;
  for (int i = 0; i < n; ++i) {
    if (t.basis[i] >= n && t.basis[i] < 2 * n) J.push_back(t.basis[i] - n);
  }
  if (J.empty()) return z_tableau;
  const Eigen::MatrixXd M_JJ = problem.M(J, J);
  const Eigen::VectorXd z_J = M_JJ.partialPivLu().solve(-problem.q(J));
  Eigen::VectorXd z = Eigen::VectorXd::Zero(n);
  z(J) = z_J.cwiseMax(0.0);
  return z.allFinite() ? z : z_tableau;
}

// The solution z with its LcpError `error`.
LcpSolution Finish(const LcpProblem& problem, Eigen::VectorXd z, double error, int pivots,
                   const LemkeOptions& options, const std::string& how) {
  LcpSolution s;
  s.iterations = pivots;
  s.error = error;
  s.converged = s.error <= options.tolerance;
  s.message = s.converged ? how
                          : fmt::format("{}, but its error {:.3g} exceeds the tolerance {:.3g} (round-off on an "
                                        "ill-conditioned M)", how, s.error, options.tolerance);
  s.w = LcpVelocity(problem, z);
  s.z = std::move(z);
  return s;
}

}  // namespace

LcpSolution SolveLcpLemke(const LcpProblem& problem, const LemkeOptions& options) {
  CheckLcp(problem);
  const int n = static_cast<int>(problem.q.size());
  if (n == 0 || problem.q.minCoeff() >= 0.0) {
    return Finish(problem, Eigen::VectorXd::Zero(n), 0.0, 0, options, "q >= 0: z = 0 solves the LCP");
  }
  const int max_pivots = options.max_pivots > 0 ? options.max_pivots : 10 * (n + 1) * (n + 1);
  Tableau t{Eigen::MatrixXd::Identity(n, n), problem.q, std::vector<int>(n), Eigen::VectorXd(n),
            Eigen::RowVectorXd(n), {}};
  for (int i = 0; i < n; ++i) t.basis[i] = i;
  t.rows.reserve(n);

  // z0 enters at the most negative q_i; among ties the last row keeps the tableau lexico-positive.
  int r = 0;
  for (int i = 1; i < n; ++i) {
    if (problem.q(i) <= problem.q(r)) r = i;
  }
  const int z0 = 2 * n;
  int entering = z0;
  EnteringColumn(t, problem.M, z0);
  for (int pivots = 1; pivots <= max_pivots; ++pivots) {
    const int leaving = t.basis[r];
    Pivot(t, r, entering);
    if (leaving == z0) {
      Eigen::VectorXd z = BasicZ(t, n);
      double error = LcpError(problem, z);
      if (options.refine) {
        Eigen::VectorXd z_refined = RefinedZ(problem, z, t);
        const double refined_error = LcpError(problem, z_refined);
        if (refined_error < error) {
          z = std::move(z_refined);
          error = refined_error;
        }
      }
      return Finish(problem, std::move(z), error, pivots, options, "z0 left the basis: solution");
    }
    entering = leaving < n ? leaving + n : leaving - n;  // the complement of the leaving variable
    EnteringColumn(t, problem.M, entering);
    r = LexicographicRow(t, options.pivot_tolerance * t.c.cwiseAbs().maxCoeff());
    if (r < 0) {
      const Eigen::VectorXd z = BasicZ(t, n);
      LcpSolution s = Finish(problem, z, LcpError(problem, z), pivots, options, "");
      s.converged = false;
      s.message = fmt::format("Lemke: ray termination after {} pivots ({}[{}] can grow without bound): no "
                              "solution found; the LCP is infeasible or M is not copositive-plus",
                              pivots, entering < n ? "w" : "z", entering < n ? entering : entering - n);
      return s;
    }
  }
  const Eigen::VectorXd z = BasicZ(t, n);
  LcpSolution s = Finish(problem, z, LcpError(problem, z), max_pivots, options, "");
  s.converged = false;
  s.message = fmt::format("Lemke: no solution after the maximum of {} pivots", max_pivots);
  return s;
}

}  // namespace flexmbs::contact
