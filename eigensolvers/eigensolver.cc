#include "eigensolvers/eigensolver.h"

#include <algorithm>
#include <cmath>
#include <fmt/format.h>
#include <fmt/ranges.h>
#include <functional>
#include <limits>
#include <numbers>
#include <utility>

#include "core/error.h"
#include "eigensolvers/distributed/slepc_solver.h"
#include "eigensolvers/serial/spectra_eigensolver.h"

namespace flexmbs::eigensolvers {
namespace {

// The registered backends, in the order they are listed. A new backend (SLEPc) adds a line.
const std::vector<std::pair<std::string, std::function<std::unique_ptr<Eigensolver>()>>>& Backends() {
  static const std::vector<std::pair<std::string, std::function<std::unique_ptr<Eigensolver>()>>> backends = {
      {"spectra", &MakeSpectraEigensolver},
      {"slepc", &MakeSlepcEigensolver},
  };
  return backends;
}

}  // namespace

std::string_view MissedModeCheckName(MissedModeCheck check) {
  switch (check) {
    case MissedModeCheck::kNone:
      return "none";
    case MissedModeCheck::kSturmCount:
      return "sturm_count";
    case MissedModeCheck::kDeflatedLanczos:
      return "deflated_lanczos";
    case MissedModeCheck::kBlockKrylov:
      return "block_krylov";
    case MissedModeCheck::kAuto:
      return "auto";
  }
  return "?";
}

Eigen::VectorXd FrequenciesHz(const Eigen::VectorXd& eigenvalues) {
  return eigenvalues.unaryExpr([](double lambda) {
    const double f = std::sqrt(std::abs(lambda)) / (2.0 * std::numbers::pi);
    return lambda < 0.0 ? -f : f;
  });
}

Eigen::VectorXd FrequenciesHz(const EigenSolution& solution) { return FrequenciesHz(solution.eigenvalues); }

double ShiftFromHz(double shift_hz) {
  const double omega = 2.0 * std::numbers::pi * shift_hz;
  return shift_hz < 0.0 ? -omega * omega : omega * omega;
}

double FreeBodyShift(const Eigen::SparseMatrix<double>& K, const Eigen::SparseMatrix<double>& M) {
  // Relative distance of the shift below zero, as a fraction of trace(K)/trace(M).
  constexpr double kShiftFraction = 1e-6;
  const double trace_k = K.diagonal().sum();
  const double trace_m = M.diagonal().sum();
  if (!(trace_k > 0.0) || !(trace_m > 0.0) || !std::isfinite(trace_k / trace_m)) return -1.0;
  return -kShiftFraction * trace_k / trace_m;
}

EigenSolution Eigensolver::SolveFactorized(const Eigen::SparseMatrix<double>& K, const Eigen::SparseMatrix<double>& M,
                                           const EigenOptions& options, const ShiftedFactorization&) const {
  return Solve(K, M, options);
}

std::unique_ptr<Eigensolver> MakeEigensolver(std::string_view backend) {
  for (const auto& [name, make] : Backends()) {
    if (name == backend) return make();
  }
  throw InputError(fmt::format("unknown eigensolver backend '{}' (available: {})", backend,
                               fmt::join(AvailableEigensolvers(), ", ")));
}

std::vector<std::string> AvailableEigensolvers() {
  std::vector<std::string> names;
  for (const auto& entry : Backends()) names.push_back(entry.first);
  return names;
}

void ValidateEigenInputs(const Eigen::SparseMatrix<double>& K, const Eigen::SparseMatrix<double>& M,
                         const EigenOptions& options) {
  if (K.rows() != K.cols()) {
    throw InputError(fmt::format("eigenproblem: stiffness matrix K is {} x {}, must be square", K.rows(), K.cols()));
  }
  if (M.rows() != M.cols()) {
    throw InputError(fmt::format("eigenproblem: mass matrix M is {} x {}, must be square", M.rows(), M.cols()));
  }
  if (K.rows() != M.rows()) {
    throw InputError(fmt::format("eigenproblem: K is {0} x {0} but M is {1} x {1}, must be of equal size", K.rows(), M.rows()));
  }
  if (K.rows() == 0) throw InputError("eigenproblem: K and M are empty (0 DOF)");
  const Eigen::VectorXd k_diagonal = K.diagonal();
  const Eigen::VectorXd m_diagonal = M.diagonal();
  for (Eigen::Index i = 0; i < K.rows(); ++i) {
    if (!(m_diagonal(i) > 0.0) || !std::isfinite(m_diagonal(i))) {
      throw InputError(fmt::format("eigenproblem: mass matrix diagonal entry {} (DOF {} of node {}) is {:g}, must be "
                                   "> 0: a DOF without mass (a node in no element?)", i, i % 3, i / 3, m_diagonal(i)));
    }
    if (!std::isfinite(k_diagonal(i))) {
      throw InputError(fmt::format("eigenproblem: stiffness matrix diagonal entry {} is {:g}", i, k_diagonal(i)));
    }
  }
  const bool band = options.max_frequency_hz > 0.0;
  if (options.num_modes < 0) {
    throw InputError(fmt::format("eigenproblem: num_modes {} must be >= 0", options.num_modes));
  }
  if (!std::isfinite(options.max_frequency_hz) || options.max_frequency_hz < 0.0) {
    throw InputError(fmt::format("eigenproblem: max_frequency_hz {:g} must be >= 0 and finite (0 = unused)",
                                 options.max_frequency_hz));
  }
  if (!band && options.num_modes == 0) {
    throw InputError("eigenproblem: neither num_modes nor max_frequency_hz is set: say how many modes to compute");
  }
  if (options.num_modes > K.rows()) {
    throw InputError(fmt::format("eigenproblem: {} modes requested but the model has only {} DOF",
                                 options.num_modes, K.rows()));
  }
  if (options.shift_hz && !std::isfinite(*options.shift_hz)) {
    throw InputError(fmt::format("eigenproblem: shift_hz {:g} must be finite", *options.shift_hz));
  }
  if (!(options.tolerance > 0.0) || !(options.tolerance < 1.0)) {
    throw InputError(fmt::format("eigenproblem: tolerance {:g} must be in (0, 1)", options.tolerance));
  }
  if (!(options.residual_tolerance > 0.0) || !std::isfinite(options.residual_tolerance)) {
    throw InputError(fmt::format("eigenproblem: residual_tolerance {:g} must be > 0", options.residual_tolerance));
  }
  if (options.max_iterations <= 0) {
    throw InputError(fmt::format("eigenproblem: max_iterations {} must be > 0", options.max_iterations));
  }
  if (options.lanczos_block_size < 0) {
    throw InputError(fmt::format("eigenproblem: lanczos_block_size {} must be >= 0 (0 = automatic)",
                                 options.lanczos_block_size));
  }
}

PairResiduals ResidualsFromSums(const ResidualSums& sums, const Eigen::VectorXd& eigenvalues,
                                double sigma, double zero_eigenvalue) {
  FLEXMBS_CHECK(sums.cols() == eigenvalues.size(), "ResidualsFromSums: one column per eigenvalue");
  PairResiduals result{Eigen::VectorXd(eigenvalues.size()), Eigen::VectorXd(eigenvalues.size())};
  for (Eigen::Index j = 0; j < eigenvalues.size(); ++j) {
    const double lambda = eigenvalues(j);
    const double k_norm = std::sqrt(sums(0, j));
    const double m_norm = std::sqrt(sums(1, j));
    const double rigid_scale = std::abs(lambda) <= zero_eigenvalue ? std::abs(sigma) * m_norm : 0.0;
    const double scale = std::max({k_norm, std::abs(lambda) * m_norm, rigid_scale,
                                   std::numeric_limits<double>::min()});
    result.relative(j) = std::sqrt(sums(2, j)) / scale;
    result.floor(j) = std::numeric_limits<double>::epsilon() * std::sqrt(sums(3, j)) / scale;
  }
  return result;
}

PairResiduals ComputeResiduals(const SymmetricOperator& K, const SymmetricOperator& M,
                               const Eigen::VectorXd& eigenvalues, const Eigen::MatrixXd& modes, double sigma) {
  FLEXMBS_CHECK(modes.cols() == eigenvalues.size() && modes.rows() == K.rows(),
                "ComputeResiduals: modes and eigenvalues do not match");
  const Eigen::MatrixXd KX = K.Times(modes);
  const Eigen::MatrixXd MX = M.Times(modes);
  const Eigen::MatrixXd abs_modes = modes.cwiseAbs();
  const Eigen::MatrixXd abs_KX = K.AbsTimes(abs_modes);
  const Eigen::MatrixXd abs_MX = M.AbsTimes(abs_modes);
  ResidualSums sums(4, eigenvalues.size());
  for (Eigen::Index j = 0; j < eigenvalues.size(); ++j) {
    const double lambda = eigenvalues(j);
    sums(0, j) = KX.col(j).squaredNorm();
    sums(1, j) = MX.col(j).squaredNorm();
    sums(2, j) = (KX.col(j) - lambda * MX.col(j)).squaredNorm();
    sums(3, j) = (abs_KX.col(j) + std::abs(lambda) * abs_MX.col(j)).squaredNorm();
  }
  return ResidualsFromSums(sums, eigenvalues, sigma,
                           kZeroEigenvalue * K.Diagonal().sum() / M.Diagonal().sum());
}

PairResiduals ComputeResiduals(const Eigen::SparseMatrix<double>& K, const Eigen::SparseMatrix<double>& M,
                               const Eigen::VectorXd& eigenvalues, const Eigen::MatrixXd& modes, double sigma) {
  return ComputeResiduals(SparseOperator(K), SparseOperator(M), eigenvalues, modes, sigma);
}

double PairResiduals::WorstRatio(double tolerance, Eigen::Index* worst, double floor_factor) const {
  double worst_ratio = 0.0;
  for (Eigen::Index j = 0; j < relative.size(); ++j) {
    const double bound = std::max(tolerance, floor_factor * floor(j));
    double ratio = relative(j) / bound;
    if (std::isnan(ratio)) ratio = std::numeric_limits<double>::infinity();
    if (ratio > worst_ratio) {
      worst_ratio = ratio;
      if (worst != nullptr) *worst = j;
    }
  }
  return worst_ratio;
}

bool PairResiduals::Accepted(double tolerance, Eigen::Index* worst, double floor_factor) const {
  return WorstRatio(tolerance, worst, floor_factor) <= 1.0;
}

double MOrthonormalityError(const SymmetricOperator& M, const Eigen::MatrixXd& modes) {
  if (modes.cols() == 0) return 0.0;
  const Eigen::MatrixXd G = modes.transpose() * M.Times(modes);
  return (G - Eigen::MatrixXd::Identity(G.rows(), G.cols())).cwiseAbs().maxCoeff();
}

double MOrthonormalityError(const Eigen::SparseMatrix<double>& M, const Eigen::MatrixXd& modes) {
  return MOrthonormalityError(SparseOperator(M), modes);
}

Eigen::Index GuardPairs(Eigen::Index wanted) { return std::max<Eigen::Index>(5, wanted / 5); }

double SturmCutAfter(const Eigen::VectorXd& values, Eigen::Index wanted, double sigma) {
  const double last = values(wanted - 1);
  const double gap = kClusterGap * std::max(std::abs(last), std::abs(sigma));
  Eigen::Index next = wanted;
  while (next < values.size() && values(next) <= last + gap) ++next;
  return next < values.size() ? 0.5 * (last + values(next)) : last + gap;
}

}  // namespace flexmbs::eigensolvers
