#include "reduction/modal_basis.h"

#include <fmt/format.h>

#include <Eigen/Eigenvalues>
#include <Eigen/Geometry>
#include <cmath>

#include "core/error.h"
#include "fem/mass_properties.h"
#include "reduction/basis_algebra.h"
#include "reduction/interior_problem.h"
#include "reduction/mirror_modes.h"

namespace flexmbs::reduction {
namespace {

using Index = Eigen::Index;

// The eigensolver, its InputErrors prefixed with what was being solved.
eigensolvers::EigenSolution SolveOrExplain(const eigensolvers::Eigensolver& solver, const Eigen::SparseMatrix<double>& K,
                             const Eigen::SparseMatrix<double>& M, const eigensolvers::EigenOptions& options,
                             const std::string& what) {
  try {
    return solver.Solve(K, M, options);
  } catch (const InputError& e) {
    throw InputError(fmt::format("{}: {}", what, e.what()));
  }
}

void RequireSomeModes(const eigensolvers::EigenOptions& eigen, const std::string& what) {
  if (eigen.num_modes < 0) throw InputError(fmt::format("{}: number of modes {} must be >= 0", what, eigen.num_modes));
  if (eigen.num_modes == 0 && !(eigen.max_frequency_hz > 0.0)) {
    throw InputError(fmt::format("{}: no modes asked for: set the number of modes or a maximum frequency", what));
  }
}

constexpr Index kRigid = 6;

// Checks the model and the options of a free-free basis; the eigensolver's options (the six
// rigid-body modes on top of the elastic ones).
eigensolvers::EigenOptions FreeFreeEigenOptions(const FeModel& model, const FreeFreeOptions& options, const std::string& what) {
  ValidateModel(model);
  RequireSomeModes(options.eigen, what);
  const Index n = model.num_dofs();
  if (options.eigen.num_modes > n - kRigid) {
    throw InputError(fmt::format("{}: {} elastic modes asked for, but the model has {} DOF ({} elastic modes)", what,
                                 options.eigen.num_modes, n, n - kRigid));
  }
  eigensolvers::EigenOptions eigen = options.eigen;
  if (eigen.num_modes > 0) eigen.num_modes += kRigid;
  return eigen;
}

// The number of elastic modes of a free-free solution; throws unless exactly six are at zero.
Index CheckRigidModeCount(const FeModel& model, const eigensolvers::EigenSolution& s, const std::string& what) {
  const double zero = eigensolvers::kZeroEigenvalue * model.stiffness().Diagonal().sum() / model.mass().Diagonal().sum();
  const Index num_zero = (s.eigenvalues.array().abs() <= zero).count();
  if (num_zero != kRigid) {
    throw InputError(fmt::format("{}: the body has {}{} zero-frequency modes, expected 6 rigid-body modes: {}", what,
                                 num_zero, num_zero == s.eigenvalues.size() ? " or more" : "",
                                 num_zero > kRigid ? "a part of the mesh is not connected to the rest, or a mechanism"
                                                   : "K is not singular; is the body supported?"));
  }
  return s.eigenvalues.size() - kRigid;
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

EigensolverSummary SummarizeEigenSolution(const eigensolvers::EigenSolution& solution) {
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
  summary.factorization = solution.factorization;
  summary.lanczos_block_size = solution.lanczos_block_size;
  return summary;
}

const Eigen::SparseMatrix<double>& FeModel::K() const {
  FLEXMBS_CHECK(assembled(), "this step needs K assembled, and the model is known by its products only");
  return K_->matrix();
}

const Eigen::SparseMatrix<double>& FeModel::M() const {
  FLEXMBS_CHECK(assembled(), "this step needs M assembled, and the model is known by its products only");
  return M_->matrix();
}

void ValidateModel(const FeModel& model) {
  const Index n = 3 * model.nodes.cols();
  if (n == 0) throw InputError("model: the mesh has no nodes");
  // An operator is square by definition; assembled matrices may not be.
  const Index K_cols = model.assembled() ? model.K().cols() : model.stiffness().rows();
  const Index M_cols = model.assembled() ? model.M().cols() : model.mass().rows();
  if (model.stiffness().rows() != n || K_cols != n || model.mass().rows() != n || M_cols != n) {
    throw InputError(fmt::format("model: K is {} x {} and M is {} x {}, the mesh has {} nodes ({} DOF)",
                                 model.stiffness().rows(), K_cols, model.mass().rows(), M_cols, model.nodes.cols(), n));
  }
}

void ComputeReducedMatrices(const FeModel& model, ReducedBasis* basis) {
  basis->K_reduced = Symmetrized(basis->Phi.transpose() * model.stiffness().Times(basis->Phi));
  basis->M_reduced = Symmetrized(basis->Phi.transpose() * model.mass().Times(basis->Phi));
}

Eigen::MatrixXd MOrthonormalRigidModes(const FeModel& model) {
  ValidateModel(model);
  const fem::MassProperties mass = eigensolvers::MassPropertiesOf(model.mass(), model.nodes);
  if (!(mass.mass_kg > 0.0)) throw InputError(fmt::format("model: mass {} kg must be > 0", mass.mass_kg));
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> principal(mass.I_Cm_B);
  const Index n = model.nodes.cols();
  Eigen::MatrixXd R = Eigen::MatrixXd::Zero(3 * n, 6);
  for (Index v = 0; v < n; ++v) {
    const Eigen::Vector3d r = model.nodes.col(v) - mass.p_BoCm_B;
    R.block<3, 3>(3 * v, 0).setIdentity();
    for (Index k = 0; k < 3; ++k) R.block<3, 1>(3 * v, 3 + k) = principal.eigenvectors().col(k).cross(r);
  }
  return MOrthonormalized(model.mass(), R);
}

namespace {

// The free-free basis of the eigenpairs `s` (6 rigid-body modes, then num_elastic elastic ones).
ReducedBasis FreeFreeBasisFrom(const FeModel& model, const FreeFreeOptions& options, const eigensolvers::EigenSolution& s,
                               Index num_elastic) {
  ReducedBasis basis;
  basis.method = "free_free_modal";
  basis.eigensolver = s.backend;
  basis.eigensolver_summary = SummarizeEigenSolution(s);
  basis.Phi.resize(model.num_dofs(), kRigid + num_elastic);
  basis.frequency_hz.resize(kRigid + num_elastic);
  basis.relative_residuals.resize(kRigid + num_elastic);
  basis.residual_floors.resize(kRigid + num_elastic);
  if (options.rigid_modes == RigidModes::kComputed) {
    basis.Phi = s.modes;
    basis.frequency_hz = eigensolvers::FrequenciesHz(s.eigenvalues);
    basis.relative_residuals = s.relative_residuals;
    basis.residual_floors = s.residual_floors;
    for (Index k = 0; k < kRigid; ++k) basis.names.push_back(fmt::format("rigid_{}", k + 1));
  } else {
    const Eigen::MatrixXd R = MOrthonormalRigidModes(model);
    Eigen::MatrixXd E = s.modes.rightCols(num_elastic);
    MOrthogonalizeAgainst(model.mass(), R, &E);
    const RitzResult ritz = RayleighRitz(model.stiffness(), model.mass(), E);
    const eigensolvers::PairResiduals rigid =
        eigensolvers::ComputeResiduals(model.stiffness(), model.mass(), Eigen::VectorXd::Zero(kRigid), R, s.shift);
    const eigensolvers::PairResiduals elastic = eigensolvers::ComputeResiduals(model.stiffness(), model.mass(), ritz.values, ritz.vectors, s.shift);
    basis.Phi << R, ritz.vectors;
    basis.frequency_hz << Eigen::VectorXd::Zero(kRigid), eigensolvers::FrequenciesHz(ritz.values);
    basis.relative_residuals << rigid.relative, elastic.relative;
    basis.residual_floors << rigid.floor, elastic.floor;
    for (const char* name : {"rigid_tx", "rigid_ty", "rigid_tz", "rigid_r1", "rigid_r2", "rigid_r3"}) {
      basis.names.push_back(name);
    }
  }
  basis.kinds.assign(static_cast<std::size_t>(kRigid), ModeKind::kRigid);
  basis.kinds.resize(static_cast<std::size_t>(kRigid + num_elastic), ModeKind::kNormal);
  for (Index k = 0; k < num_elastic; ++k) basis.names.push_back(fmt::format("normal_{}", k + 1));
  SplitEqualModesByMirror(model, &basis);
  ComputeReducedMatrices(model, &basis);
  basis.description = fmt::format(
      "free-free normal modes: 6 rigid-body modes ({}), {} elastic modes up to {:.6g} Hz",
      options.rigid_modes == RigidModes::kExact ? "exact, principal axes" : "as computed", num_elastic,
      basis.frequency_hz(kRigid + num_elastic - 1));
  return basis;
}

}  // namespace

ReducedBasis FreeFreeModalBasis(const FeModel& model, const FreeFreeOptions& options, const eigensolvers::Eigensolver& solver) {
  const std::string what = "free-free modal basis";
  const eigensolvers::EigenOptions eigen = FreeFreeEigenOptions(model, options, what);
  const eigensolvers::EigenSolution s = SolveOrExplain(solver, model.K(), model.M(), eigen, what);
  const Index num_elastic = CheckRigidModeCount(model, s, what);
  if (num_elastic == 0) {
    eigensolvers::EigenOptions next = options.eigen;
    next.num_modes = kRigid + 1;
    next.max_frequency_hz = 0.0;
    const eigensolvers::EigenSolution lowest = SolveOrExplain(solver, model.K(), model.M(), next, what);
    throw InputError(fmt::format("{}: no elastic mode below max_frequency_hz = {:g} Hz: the lowest is at {:g} Hz", what,
                                 options.eigen.max_frequency_hz, eigensolvers::FrequenciesHz(lowest.eigenvalues)(kRigid)));
  }
  return FreeFreeBasisFrom(model, options, s, num_elastic);
}

ReducedBasis FreeFreeModalBasis(const FeModel& model, const FreeFreeOptions& options, const eigensolvers::EigenSolution& solution) {
  const std::string what = "free-free modal basis";
  const eigensolvers::EigenOptions eigen = FreeFreeEigenOptions(model, options, what);
  if (solution.modes.rows() != model.num_dofs() || solution.modes.cols() != solution.eigenvalues.size()) {
    throw InputError(fmt::format("{}: the eigenpairs given have {} rows and {} modes for {} eigenvalues, the model {} "
                                 "DOF", what, solution.modes.rows(), solution.modes.cols(),
                                 solution.eigenvalues.size(), model.num_dofs()));
  }
  if (eigen.max_frequency_hz <= 0.0 && solution.eigenvalues.size() != eigen.num_modes) {
    throw InputError(fmt::format("{}: {} eigenpairs given, {} asked for (6 rigid-body modes included)", what,
                                 solution.eigenvalues.size(), eigen.num_modes));
  }
  const Index num_elastic = CheckRigidModeCount(model, solution, what);
  if (num_elastic == 0) {
    throw InputError(fmt::format("{}: no elastic mode below max_frequency_hz = {:g} Hz", what,
                                 options.eigen.max_frequency_hz));
  }
  return FreeFreeBasisFrom(model, options, solution, num_elastic);
}

namespace {

// Checks a fixed-interface request (a valid model, some conditions, some modes) and returns its
// description for errors: "fixed-interface modal basis held by <conditions>".
std::string ValidateHeldRequest(const FeModel& model, const BoundaryConditions& conditions, const eigensolvers::EigenOptions& eigen) {
  const std::string what = "fixed-interface modal basis";
  ValidateModel(model);
  if (conditions.empty()) {
    throw InputError(fmt::format("{}: no interface or support holds the body; use the free-free modal basis", what));
  }
  RequireSomeModes(eigen, what);
  return fmt::format("{} held by {}", what, DescribeConditions(conditions));
}

// Throws InputError `held`: ... when no interior DOF is free or fewer than the modes asked for.
void RequireFreeDofs(const std::string& held, Index n_o, const eigensolvers::EigenOptions& eigen) {
  if (n_o == 0) throw InputError(fmt::format("{}: no DOF is left free", held));
  if (eigen.num_modes > n_o) {
    throw InputError(fmt::format("{}: {} modes asked for, but only {} interior DOF are free", held, eigen.num_modes, n_o));
  }
}

// The fixed-interface basis of the held body's eigenpairs `s`, Phi their modes on all DOF.
ReducedBasis FixedInterfaceBasisFrom(const FeModel& model, const BoundaryConditions& conditions,
                                     const eigensolvers::EigenSolution& s, Eigen::MatrixXd Phi, const EigensolverSummary& summary,
                                     std::shared_ptr<const HeldFactorization> factor) {
  ReducedBasis basis;
  basis.method = "fixed_interface_modal";
  basis.eigensolver = s.backend;
  basis.eigensolver_summary = summary;
  basis.held_factorization = std::move(factor);
  basis.held_by = conditions;
  basis.Phi = std::move(Phi);
  basis.kinds.assign(static_cast<std::size_t>(s.modes.cols()), ModeKind::kNormal);
  for (Index k = 0; k < s.modes.cols(); ++k) basis.names.push_back(fmt::format("normal_{}", k + 1));
  basis.frequency_hz = eigensolvers::FrequenciesHz(s.eigenvalues);
  basis.relative_residuals = s.relative_residuals;
  basis.residual_floors = s.residual_floors;
  SplitEqualModesByMirror(model, &basis);
  ComputeReducedMatrices(model, &basis);
  basis.description = fmt::format("fixed-interface normal modes ({}): {} modes up to {:.6g} Hz",
                                  DescribeConditions(conditions), s.modes.cols(),
                                  basis.frequency_hz(basis.frequency_hz.size() - 1));
  return basis;
}

}  // namespace

ReducedBasis FixedInterfaceModalBasis(const FeModel& model, const BoundaryConditions& conditions,
                                      const eigensolvers::EigenOptions& eigen, const eigensolvers::Eigensolver& solver) {
  const std::string held = ValidateHeldRequest(model, conditions, eigen);
  const InteriorProblem interior = BuildInteriorProblem(model, conditions);
  RequireFreeDofs(held, interior.K_oo.rows(), eigen);
  // One factorisation of K_oo for the eigen-solve and the static solves after it, where the
  // eigensolver can use it; FactorHeldInterior then also checks that the conditions hold the body.
  const std::shared_ptr<const HeldFactorization> factor =
      SharesHeldFactorization(solver, eigen) ? FactorHeldBody(model, conditions, interior) : nullptr;
  const HeldModes modes = SolveHeldModes(solver, interior, factor.get(), eigen, held);
  const eigensolvers::EigenSolution& s = modes.solution;
  const double zero = eigensolvers::kZeroEigenvalue * interior.K_oo.diagonal().sum() / interior.M_oo.diagonal().sum();
  if (s.eigenvalues.size() > 0 && std::abs(s.eigenvalues(0)) <= zero) ThrowNotHeld(model, conditions);
  return FixedInterfaceBasisFrom(model, conditions, s, interior.transform.G * s.modes, modes.summary, factor);
}

ReducedBasis FixedInterfaceModalBasis(const FeModel& model, const BoundaryConditions& conditions,
                                      const eigensolvers::EigenOptions& eigen, const eigensolvers::EigenSolution& solution) {
  const std::string held = ValidateHeldRequest(model, conditions, eigen);
  const std::optional<std::vector<int>> clamped = ClampedDofs(model.nodes, conditions);
  if (!clamped) {
    throw InputError(fmt::format("{}: eigenpairs computed elsewhere need conditions that clamp whole node DOF (no "
                                 "averaging interface)", held));
  }
  const Index n = model.num_dofs();
  RequireFreeDofs(held, n - static_cast<Index>(clamped->size()), eigen);
  if (solution.modes.rows() != n || solution.modes.cols() != solution.eigenvalues.size() ||
      (eigen.max_frequency_hz <= 0.0 && solution.eigenvalues.size() != eigen.num_modes)) {
    throw InputError(fmt::format("{}: the eigenpairs given have {} rows and {} modes for {} eigenvalues; the model has "
                                 "{} DOF and {} modes were asked for", held, solution.modes.rows(),
                                 solution.modes.cols(), solution.eigenvalues.size(), n, eigen.num_modes));
  }
  // K_oo's and M_oo's traces: the diagonals at the interior DOF, summed in ascending order.
  const Eigen::VectorXd K_diagonal = model.stiffness().Diagonal(), M_diagonal = model.mass().Diagonal();
  double trace_k = 0.0, trace_m = 0.0;
  auto next = clamped->begin();
  for (Index dof = 0; dof < n; ++dof) {
    if (next != clamped->end() && *next == dof) {
      if (!solution.modes.row(dof).isZero(0.0)) {
        throw InputError(fmt::format("{}: the eigenpairs given move the held DOF {}", held, dof));
      }
      ++next;
      continue;
    }
    trace_k += K_diagonal(dof);
    trace_m += M_diagonal(dof);
  }
  const double zero = eigensolvers::kZeroEigenvalue * trace_k / trace_m;
  if (solution.eigenvalues.size() > 0 && std::abs(solution.eigenvalues(0)) <= zero) ThrowNotHeld(model, conditions);
  return FixedInterfaceBasisFrom(model, conditions, solution, solution.modes, SummarizeEigenSolution(solution), nullptr);
}

}  // namespace flexmbs::reduction
