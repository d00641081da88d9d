#include "reduction/full_model_modes.h"

#include <Eigen/SparseCore>
#include <algorithm>
#include <cmath>
#include <fmt/format.h>
#include <iterator>

#include "core/error.h"

namespace flexmbs::reduction {

namespace {

// Rigid-body modes of a free body.
constexpr Eigen::Index kRigidModes = 6;

// [B G] (num_dofs x (boundary + interior)): u for unit boundary coordinates and interior DOF.
Eigen::SparseMatrix<double> AdmissibleDisplacements(const ConstraintTransform& t) {
  std::vector<Eigen::Triplet<double>> entries;
  entries.reserve(static_cast<std::size_t>(t.B.nonZeros() + t.G.nonZeros()));
  for (Eigen::Index c = 0; c < t.B.outerSize(); ++c) {
    for (Eigen::SparseMatrix<double>::InnerIterator it(t.B, c); it; ++it) entries.emplace_back(it.row(), c, it.value());
  }
  for (Eigen::Index c = 0; c < t.G.outerSize(); ++c) {
    for (Eigen::SparseMatrix<double>::InnerIterator it(t.G, c); it; ++it) {
      entries.emplace_back(it.row(), t.num_boundary() + c, it.value());
    }
  }
  Eigen::SparseMatrix<double> T(t.num_dofs(), t.num_boundary() + t.num_interior());
  T.setFromTriplets(entries.begin(), entries.end());
  return T;
}

// The supports clamped and the rigid interfaces' nodes on their markers' motion.
BoundaryConditions RigidConditions(const FullModelConditions& conditions) {
  return {conditions.held.supports, conditions.rigid};
}

// The lowest `modes` modes of the model with rigid interfaces (FullModelModes).
ReducedBasis ModesWithRigidInterfaces(const FeModel& model, const FullModelConditions& conditions, Eigen::Index modes,
                                      const eigensolvers::Eigensolver& solver) {
  const Eigen::SparseMatrix<double> T = AdmissibleDisplacements(BuildConstraintTransform(model.nodes,
                                                                                         RigidConditions(conditions)));
  const Eigen::SparseMatrix<double> Tt = T.transpose();
  Eigen::SparseMatrix<double> K_T = Tt * (model.K() * T);
  Eigen::SparseMatrix<double> M_T = Tt * (model.M() * T);
  K_T.prune(0.0);
  M_T.prune(0.0);
  eigensolvers::EigenOptions eigen;
  eigen.num_modes = static_cast<int>(modes);
  const eigensolvers::EigenSolution s = solver.Solve(K_T, M_T, eigen);
  const double zero = eigensolvers::kZeroEigenvalue * model.K().diagonal().sum() / model.M().diagonal().sum();

  ReducedBasis basis;
  basis.method = "full_model";
  basis.eigensolver = s.backend;
  basis.eigensolver_summary = SummarizeEigenSolution(s);
  basis.held_by = RigidConditions(conditions);
  basis.Phi = T * s.modes;
  basis.frequency_hz = eigensolvers::FrequenciesHz(s.eigenvalues);
  basis.relative_residuals = s.relative_residuals;
  basis.residual_floors = s.residual_floors;
  int rigid = 0, normal = 0;
  for (Eigen::Index k = 0; k < s.eigenvalues.size(); ++k) {
    const bool is_rigid = std::abs(s.eigenvalues(k)) <= zero;
    if (is_rigid) basis.frequency_hz(k) = 0.0;
    basis.kinds.push_back(is_rigid ? ModeKind::kRigid : ModeKind::kNormal);
    basis.names.push_back(is_rigid ? fmt::format("rigid_{}", ++rigid) : fmt::format("normal_{}", ++normal));
  }
  ComputeReducedMatrices(model, &basis);
  basis.description = fmt::format("full model ({}): {} modes", conditions.Describe(), modes);
  return basis;
}

}  // namespace

std::optional<ReductionMethod> BasisReductionMethod(std::string_view basis_method) {
  if (basis_method.starts_with("free_free_modal")) return ReductionMethod::kFreeFree;
  if (basis_method.starts_with("fixed_interface_modal")) return ReductionMethod::kFixedInterface;
  if (basis_method.starts_with("craig_bampton")) return ReductionMethod::kCraigBampton;
  return std::nullopt;
}

std::string FullModelConditions::Describe() const {
  std::string text = held.empty() ? "free (no supports)" : DescribeConditions(held);
  for (const InterfaceSpec& i : rigid) text += fmt::format(", interface '{}' rigid (marker free)", i.name);
  return text;
}

FullModelConditions SystemModeConditions(ReductionMethod method, const BoundaryConditions& conditions) {
  FullModelConditions out;
  switch (method) {
    case ReductionMethod::kFreeFree:
      return out;
    case ReductionMethod::kFixedInterface:
      out.held = conditions;
      return out;
    case ReductionMethod::kCraigBampton:
      out.held.supports = conditions.supports;
      std::copy_if(conditions.interfaces.begin(), conditions.interfaces.end(), std::back_inserter(out.rigid),
                   [](const InterfaceSpec& i) { return i.coupling == Coupling::kRigid; });
      return out;
  }
  throw InternalError("unknown reduction method");
}

Eigen::Index AvailableModes(const FeModel& model, const FullModelConditions& conditions) {
  if (!conditions.rigid.empty()) {
    const ConstraintTransform t = BuildConstraintTransform(model.nodes, RigidConditions(conditions));
    return t.num_boundary() + t.num_interior();
  }
  if (conditions.held.empty()) return model.num_dofs();
  return BuildConstraintTransform(model.nodes, conditions.held).num_interior();
}

ReducedBasis FullModelModes(const FeModel& model, const FullModelConditions& conditions, Eigen::Index count,
                            const eigensolvers::Eigensolver& solver) {
  ValidateModel(model);
  const Eigen::Index modes = std::min(count, AvailableModes(model, conditions));
  if (conditions.held.empty() && modes <= kRigidModes) {
    throw InputError(fmt::format("the free full model needs more than its {} rigid-body modes: {} modes asked for",
                                 kRigidModes, count));
  }
  if (!conditions.rigid.empty()) return ModesWithRigidInterfaces(model, conditions, modes, solver);
  if (!conditions.held.empty()) {
    eigensolvers::EigenOptions eigen;
    eigen.num_modes = static_cast<int>(modes);
    return FixedInterfaceModalBasis(model, conditions.held, eigen, solver);
  }
  FreeFreeOptions options;
  options.eigen.num_modes = static_cast<int>(modes - kRigidModes);
  options.rigid_modes = RigidModes::kExact;
  return FreeFreeModalBasis(model, options, solver);
}

}  // namespace flexmbs::reduction
