#include "reduction/craig_bampton.h"

#include <fmt/format.h>

#include <cmath>
#include <limits>

#include "core/error.h"
#include "reduction/basis_algebra.h"
#include "reduction/interior_problem.h"
#include "reduction/mirror_modes.h"

namespace flexmbs::reduction {
namespace {

using Index = Eigen::Index;
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

}  // namespace

ReducedBasis CraigBamptonBasis(const FeModel& model, const BoundaryConditions& conditions,
                               const eigensolvers::EigenOptions& normal_modes, const eigensolvers::Eigensolver& solver) {
  ValidateModel(model);
  if (conditions.interfaces.empty()) {
    throw InputError("craig-bampton basis: no interface: Craig-Bampton needs at least one interface (use a "
                     "fixed-interface or free-free modal basis otherwise)");
  }
  if (normal_modes.num_modes < 0) {
    throw InputError(fmt::format("craig-bampton basis: number of normal modes {} must be >= 0", normal_modes.num_modes));
  }
  const InteriorProblem interior = BuildInteriorProblem(model, conditions);
  const ConstraintTransform& t = interior.transform;
  const Index n_o = t.num_interior();
  const std::string what = fmt::format("craig-bampton basis ({})", DescribeConditions(conditions));
  if (n_o == 0) throw InputError(fmt::format("{}: every DOF is an interface or support DOF: no interior is left", what));
  if (normal_modes.num_modes > n_o) {
    throw InputError(fmt::format("{}: {} fixed-interface modes asked for, but the interior has only {} DOF", what,
                                 normal_modes.num_modes, n_o));
  }

  // Constraint modes: Psi = B + G X, K_oo X = -G^T K B. The factor of K_oo serves the normal
  // modes (shift 0) and the static solves after the basis too.
  const std::shared_ptr<const HeldFactorization> factor = FactorHeldBody(model, conditions, interior);
  const Eigen::MatrixXd rhs = -(Eigen::SparseMatrix<double>(t.G.transpose()) * (model.K() * t.B));
  const Eigen::MatrixXd X = factor->factor.Solve(rhs);
  const Eigen::MatrixXd Psi = Eigen::MatrixXd(t.B) + t.G * X;

  // Fixed-interface normal modes (K_oo is known to be positive definite: shift 0 unless set).
  HeldModes modes;
  const bool want_normal = normal_modes.num_modes > 0 || normal_modes.max_frequency_hz > 0.0;
  if (want_normal) {
    eigensolvers::EigenOptions options = normal_modes;
    if (!options.shift_hz) options.shift_hz = 0.0;
    modes = SolveHeldModes(solver, interior, factor.get(), options, what + ": fixed-interface modes");
  }
  const eigensolvers::EigenSolution& s = modes.solution;
  const Index n_b = t.num_boundary();
  const Index n_n = s.modes.cols();

  ReducedBasis basis;
  basis.method = "craig_bampton";
  basis.eigensolver = want_normal ? s.backend : std::string();
  if (want_normal) basis.eigensolver_summary = modes.summary;
  basis.held_factorization = factor;
  basis.held_by = conditions;
  basis.Phi.resize(model.num_dofs(), n_b + n_n);
  basis.Phi.leftCols(n_b) = Psi;
  if (n_n > 0) basis.Phi.rightCols(n_n) = t.G * s.modes;
  basis.kinds.assign(static_cast<std::size_t>(n_b), ModeKind::kConstraint);
  basis.kinds.resize(static_cast<std::size_t>(n_b + n_n), ModeKind::kNormal);
  for (const std::string& name : t.boundary_names) basis.names.push_back("constraint_" + name);
  for (Index k = 0; k < n_n; ++k) basis.names.push_back(fmt::format("normal_{}", k + 1));
  basis.frequency_hz = Eigen::VectorXd::Constant(n_b + n_n, kNaN);
  basis.relative_residuals = Eigen::VectorXd::Constant(n_b + n_n, kNaN);
  basis.residual_floors = Eigen::VectorXd::Constant(n_b + n_n, kNaN);
  if (n_n > 0) {
    basis.frequency_hz.tail(n_n) = eigensolvers::FrequenciesHz(s.eigenvalues);
    basis.relative_residuals.tail(n_n) = s.relative_residuals;
    basis.residual_floors.tail(n_n) = s.residual_floors;
  }
  SplitEqualModesByMirror(model, &basis);
  ComputeReducedMatrices(model, &basis);
  basis.description =
      n_n > 0 ? fmt::format("Craig-Bampton ({}): {} constraint modes, {} fixed-interface normal modes up to {:.6g} Hz",
                            DescribeConditions(conditions), n_b, n_n, basis.frequency_hz(n_b + n_n - 1))
              : fmt::format("Craig-Bampton ({}): {} constraint modes, no normal modes (Guyan static condensation)",
                            DescribeConditions(conditions), n_b);
  return basis;
}

ReducedBasis OrthonormalizeBasis(const FeModel& model, const ReducedBasis& input) {
  ValidateModel(model);
  if (input.Phi.rows() != model.num_dofs()) {
    throw InputError(fmt::format("orthonormalise basis: the basis has {} rows, the model {} DOF", input.Phi.rows(),
                                 model.num_dofs()));
  }
  if (input.num_modes() == 0) throw InputError("orthonormalise basis: the basis has no columns");
  const RitzResult ritz = RayleighRitz(model.stiffness(), model.mass(), input.Phi);
  const double zero = eigensolvers::kZeroEigenvalue * model.stiffness().Diagonal().sum() / model.mass().Diagonal().sum();
  const Index n = input.num_modes();

  ReducedBasis basis;
  basis.method = input.method == "craig_bampton" ? "craig_bampton_orthonormalized" : input.method + "+orthonormalized";
  basis.eigensolver = input.eigensolver;
  basis.eigensolver_summary = input.eigensolver_summary;
  basis.held_factorization = input.held_factorization;
  basis.held_by = input.held_by;
  basis.Phi = ritz.vectors;
  basis.frequency_hz = eigensolvers::FrequenciesHz(ritz.values);
  basis.relative_residuals = Eigen::VectorXd::Constant(n, kNaN);
  basis.residual_floors = Eigen::VectorXd::Constant(n, kNaN);
  Index rigid = 0, normal = 0;
  for (Index k = 0; k < n; ++k) {
    const bool is_rigid = std::abs(ritz.values(k)) <= zero;
    basis.kinds.push_back(is_rigid ? ModeKind::kRigid : ModeKind::kNormal);
    basis.names.push_back(is_rigid ? fmt::format("reduced_rigid_{}", ++rigid) : fmt::format("reduced_normal_{}", ++normal));
  }
  basis.original_kinds = input.kinds;
  basis.original_names = input.names;
  basis.original_transform = ritz.transform;
  SplitEqualModesByMirror(model, &basis);
  ComputeReducedMatrices(model, &basis);
  const ModeCounts from = input.Counts();
  basis.description = fmt::format(
      "orthonormalised {}: {} normal modes of the reduced system ({} at zero frequency), each a mix of the original "
      "{}", input.method, n, rigid, FormatModeCounts(from));
  return basis;
}

}  // namespace flexmbs::reduction
