#include "reduction/modal_basis.h"

#include <fmt/format.h>

#include <Eigen/Eigenvalues>
#include <Eigen/Geometry>
#include <cmath>

#include "core/error.h"
#include "fem/mass_properties.h"
#include "reduction/basis_algebra.h"
#include "reduction/interior_problem.h"

namespace flexmbs::reduction {
namespace {

using Index = Eigen::Index;

// The eigensolver, its InputErrors prefixed with what was being solved.
EigenSolution SolveOrExplain(const Eigensolver& solver, const Eigen::SparseMatrix<double>& K,
                             const Eigen::SparseMatrix<double>& M, const EigenOptions& options,
                             const std::string& what) {
  try {
    return solver.Solve(K, M, options);
  } catch (const InputError& e) {
    throw InputError(fmt::format("{}: {}", what, e.what()));
  }
}

void RequireSomeModes(const EigenOptions& eigen, const std::string& what) {
  if (eigen.num_modes < 0) throw InputError(fmt::format("{}: number of modes {} must be >= 0", what, eigen.num_modes));
  if (eigen.num_modes == 0 && !(eigen.max_frequency_hz > 0.0)) {
    throw InputError(fmt::format("{}: no modes asked for: set the number of modes or a maximum frequency", what));
  }
}

}  // namespace

std::string_view ModeKindName(ModeKind kind) {
  switch (kind) {
    case ModeKind::kRigid:
      return "rigid";
    case ModeKind::kNormal:
      return "normal";
    case ModeKind::kConstraint:
      return "constraint";
    case ModeKind::kStaticCorrection:
      return "static_correction";
  }
  return "?";
}

std::optional<ModeKind> ModeKindFromName(std::string_view name) {
  for (const ModeKind kind : {ModeKind::kRigid, ModeKind::kNormal, ModeKind::kConstraint, ModeKind::kStaticCorrection}) {
    if (ModeKindName(kind) == name) return kind;
  }
  return std::nullopt;
}

std::string FormatModeCounts(const ModeCounts& counts) {
  return fmt::format("{} rigid, {} normal, {} constraint, {} static_correction", counts.rigid, counts.normal,
                     counts.constraint, counts.static_correction);
}

ModeCounts ReducedBasis::Counts() const {
  ModeCounts counts;
  for (const ModeKind kind : kinds) {
    switch (kind) {
      case ModeKind::kRigid:
        ++counts.rigid;
        break;
      case ModeKind::kNormal:
        ++counts.normal;
        break;
      case ModeKind::kConstraint:
        ++counts.constraint;
        break;
      case ModeKind::kStaticCorrection:
        ++counts.static_correction;
        break;
    }
  }
  return counts;
}

EigensolverSummary SummarizeEigenSolution(const EigenSolution& solution) {
  EigensolverSummary summary;
  summary.seconds = solution.seconds;
  summary.factorization_seconds = solution.factorization_seconds;
  summary.sturm_seconds = solution.sturm_seconds;
  summary.krylov_seconds = solution.krylov_seconds;
  summary.factorizations = solution.factorizations;
  summary.operator_applications = solution.operator_applications;
  summary.krylov_runs = solution.krylov_runs;
  summary.restarts = solution.restarts;
  summary.missed_mode_check = solution.missed_mode_check;
  return summary;
}

void ValidateModel(const FeModel& model) {
  const Index n = 3 * model.nodes.cols();
  if (n == 0) throw InputError("model: the mesh has no nodes");
  if (model.K.rows() != n || model.K.cols() != n || model.M.rows() != n || model.M.cols() != n) {
    throw InputError(fmt::format("model: K is {} x {} and M is {} x {}, the mesh has {} nodes ({} DOF)", model.K.rows(),
                                 model.K.cols(), model.M.rows(), model.M.cols(), model.nodes.cols(), n));
  }
}

void ComputeReducedMatrices(const FeModel& model, ReducedBasis* basis) {
  basis->K_reduced = Symmetrized(basis->Phi.transpose() * (model.K * basis->Phi));
  basis->M_reduced = Symmetrized(basis->Phi.transpose() * (model.M * basis->Phi));
}

Eigen::MatrixXd MOrthonormalRigidModes(const FeModel& model) {
  ValidateModel(model);
  const fem::MassProperties mass = fem::MassPropertiesFromMassMatrix(model.M, model.nodes);
  if (!(mass.mass_kg > 0.0)) throw InputError(fmt::format("model: mass {} kg must be > 0", mass.mass_kg));
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> principal(mass.I_Cm_B);
  const Index n = model.nodes.cols();
  Eigen::MatrixXd R = Eigen::MatrixXd::Zero(3 * n, 6);
  for (Index v = 0; v < n; ++v) {
    const Eigen::Vector3d r = model.nodes.col(v) - mass.p_BoCm_B;
    R.block<3, 3>(3 * v, 0).setIdentity();
    for (Index k = 0; k < 3; ++k) R.block<3, 1>(3 * v, 3 + k) = principal.eigenvectors().col(k).cross(r);
  }
  return MOrthonormalized(model.M, R);
}

ReducedBasis FreeFreeModalBasis(const FeModel& model, const FreeFreeOptions& options, const Eigensolver& solver) {
  const std::string what = "free-free modal basis";
  ValidateModel(model);
  constexpr Index kRigid = 6;
  const Index n = model.K.rows();
  RequireSomeModes(options.eigen, what);
  if (options.eigen.num_modes > n - kRigid) {
    throw InputError(fmt::format("{}: {} elastic modes asked for, but the model has {} DOF ({} elastic modes)", what,
                                 options.eigen.num_modes, n, n - kRigid));
  }
  EigenOptions eigen = options.eigen;
  if (eigen.num_modes > 0) eigen.num_modes += kRigid;
  const EigenSolution s = SolveOrExplain(solver, model.K, model.M, eigen, what);

  const double zero = kZeroEigenvalue * model.K.diagonal().sum() / model.M.diagonal().sum();
  const Index num_zero = (s.eigenvalues.array().abs() <= zero).count();
  if (num_zero != kRigid) {
    throw InputError(fmt::format("{}: the body has {}{} zero-frequency modes, expected 6 rigid-body modes: {}", what,
                                 num_zero, num_zero == s.eigenvalues.size() ? " or more" : "",
                                 num_zero > kRigid ? "a part of the mesh is not connected to the rest, or a mechanism"
                                                   : "K is not singular; is the body supported?"));
  }
  const Index num_elastic = s.eigenvalues.size() - kRigid;
  if (num_elastic == 0) {
    EigenOptions next = options.eigen;
    next.num_modes = kRigid + 1;
    next.max_frequency_hz = 0.0;
    const EigenSolution lowest = SolveOrExplain(solver, model.K, model.M, next, what);
    throw InputError(fmt::format("{}: no elastic mode below max_frequency_hz = {:g} Hz: the lowest is at {:g} Hz", what,
                                 options.eigen.max_frequency_hz, FrequenciesHz(lowest.eigenvalues)(kRigid)));
  }

  ReducedBasis basis;
  basis.method = "free_free_modal";
  basis.eigensolver = s.backend;
  basis.eigensolver_summary = SummarizeEigenSolution(s);
  basis.Phi.resize(n, kRigid + num_elastic);
  basis.frequency_hz.resize(kRigid + num_elastic);
  basis.relative_residuals.resize(kRigid + num_elastic);
  basis.residual_floors.resize(kRigid + num_elastic);
  if (options.rigid_modes == RigidModes::kComputed) {
    basis.Phi = s.modes;
    basis.frequency_hz = FrequenciesHz(s.eigenvalues);
    basis.relative_residuals = s.relative_residuals;
    basis.residual_floors = s.residual_floors;
    for (Index k = 0; k < kRigid; ++k) basis.names.push_back(fmt::format("rigid_{}", k + 1));
  } else {
    const Eigen::MatrixXd R = MOrthonormalRigidModes(model);
    Eigen::MatrixXd E = s.modes.rightCols(num_elastic);
    MOrthogonalizeAgainst(model.M, R, &E);
    const RitzResult ritz = RayleighRitz(model.K, model.M, E);
    const PairResiduals rigid = ComputeResiduals(model.K, model.M, Eigen::VectorXd::Zero(kRigid), R, s.shift);
    const PairResiduals elastic = ComputeResiduals(model.K, model.M, ritz.values, ritz.vectors, s.shift);
    basis.Phi << R, ritz.vectors;
    basis.frequency_hz << Eigen::VectorXd::Zero(kRigid), FrequenciesHz(ritz.values);
    basis.relative_residuals << rigid.relative, elastic.relative;
    basis.residual_floors << rigid.floor, elastic.floor;
    for (const char* name : {"rigid_tx", "rigid_ty", "rigid_tz", "rigid_r1", "rigid_r2", "rigid_r3"}) {
      basis.names.push_back(name);
    }
  }
  basis.kinds.assign(static_cast<std::size_t>(kRigid), ModeKind::kRigid);
  basis.kinds.resize(static_cast<std::size_t>(kRigid + num_elastic), ModeKind::kNormal);
  for (Index k = 0; k < num_elastic; ++k) basis.names.push_back(fmt::format("normal_{}", k + 1));
  ComputeReducedMatrices(model, &basis);
  basis.description = fmt::format(
      "free-free normal modes: 6 rigid-body modes ({}), {} elastic modes up to {:.6g} Hz",
      options.rigid_modes == RigidModes::kExact ? "exact, principal axes" : "as computed", num_elastic,
      basis.frequency_hz(kRigid + num_elastic - 1));
  return basis;
}

ReducedBasis FixedInterfaceModalBasis(const FeModel& model, const BoundaryConditions& conditions,
                                      const EigenOptions& eigen, const Eigensolver& solver) {
  const std::string what = "fixed-interface modal basis";
  ValidateModel(model);
  if (conditions.empty()) {
    throw InputError(fmt::format("{}: no interface or support holds the body; use the free-free modal basis", what));
  }
  RequireSomeModes(eigen, what);
  const InteriorProblem interior = BuildInteriorProblem(model, conditions);
  const Index n_o = interior.K_oo.rows();
  const std::string held = fmt::format("{} held by {}", what, DescribeConditions(conditions));
  if (n_o == 0) throw InputError(fmt::format("{}: no DOF is left free", held));
  if (eigen.num_modes > n_o) {
    throw InputError(fmt::format("{}: {} modes asked for, but only {} interior DOF are free", held, eigen.num_modes, n_o));
  }
  // One factorisation of K_oo for the eigen-solve and the static solves after it, where the
  // eigensolver can use it; FactorHeldInterior then also checks that the conditions hold the body.
  const std::shared_ptr<const HeldFactorization> factor =
      SharesHeldFactorization(solver, eigen) ? FactorHeldBody(model, conditions, interior) : nullptr;
  const HeldModes modes = SolveHeldModes(solver, interior, factor.get(), eigen, held);
  const EigenSolution& s = modes.solution;
  const double zero = kZeroEigenvalue * interior.K_oo.diagonal().sum() / interior.M_oo.diagonal().sum();
  if (s.eigenvalues.size() > 0 && std::abs(s.eigenvalues(0)) <= zero) ThrowNotHeld(model, conditions);

  ReducedBasis basis;
  basis.method = "fixed_interface_modal";
  basis.eigensolver = s.backend;
  basis.eigensolver_summary = modes.summary;
  basis.held_factorization = factor;
  basis.held_by = conditions;
  basis.Phi = interior.transform.G * s.modes;
  basis.kinds.assign(static_cast<std::size_t>(s.modes.cols()), ModeKind::kNormal);
  for (Index k = 0; k < s.modes.cols(); ++k) basis.names.push_back(fmt::format("normal_{}", k + 1));
  basis.frequency_hz = FrequenciesHz(s.eigenvalues);
  basis.relative_residuals = s.relative_residuals;
  basis.residual_floors = s.residual_floors;
  ComputeReducedMatrices(model, &basis);
  basis.description = fmt::format("fixed-interface normal modes ({}): {} modes up to {:.6g} Hz",
                                  DescribeConditions(conditions), s.modes.cols(),
                                  basis.frequency_hz(basis.frequency_hz.size() - 1));
  return basis;
}

}  // namespace flexmbs::reduction
