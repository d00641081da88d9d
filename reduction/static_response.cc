#include "reduction/static_response.h"

#include <fmt/format.h>

#include <Eigen/Geometry>
#include <array>
#include <memory>

#include "core/error.h"
#include "reduction/basis_algebra.h"
#include "reduction/dof_constraints.h"
#include "reduction/interior_problem.h"
#include "eigensolvers/shifted_factorization.h"

namespace flexmbs::reduction {
namespace {

using Index = Eigen::Index;

// Six DOF that hold a free body statically determinately (3-2-1): node A (farthest from the
// centroid) in x, y, z; node B (farthest from A) in the two axes other than AB's dominant one;
// node C (farthest from the line AB) along the dominant axis of the normal of ABC. Rigid
// motions with these six DOF zero vanish (A fixes translation, B the rotations across AB, C
// the rotation about AB), so no reaction arises for a self-equilibrated load.
std::array<Index, 6> DeterminateSupport(const Eigen::Matrix3Xd& nodes, std::string_view what) {
  const Eigen::Vector3d centre = nodes.rowwise().mean();
  Index a = 0, b = 0, c = 0;
  (nodes.colwise() - centre).colwise().squaredNorm().maxCoeff(&a);
  (nodes.colwise() - nodes.col(a)).colwise().squaredNorm().maxCoeff(&b);
  const Eigen::Vector3d d = nodes.col(b) - nodes.col(a);
  double best = -1.0;
  for (Index v = 0; v < nodes.cols(); ++v) {
    const double distance = d.cross(nodes.col(v) - nodes.col(a)).squaredNorm();
    if (distance > best) {
      best = distance;
      c = v;
    }
  }
  const Eigen::Vector3d normal = d.cross(nodes.col(c) - nodes.col(a));
  if (!(d.norm() > 0.0) || !(normal.norm() > 1e-9 * d.squaredNorm())) {
    throw InputError(fmt::format("{}: inertia relief: the mesh's nodes lie on one line", what));
  }
  Index d_axis = 0, n_axis = 0;
  d.cwiseAbs().maxCoeff(&d_axis);
  normal.cwiseAbs().maxCoeff(&n_axis);
  std::array<Index, 6> dofs{3 * a, 3 * a + 1, 3 * a + 2, 0, 0, 3 * c + n_axis};
  int k = 3;
  for (Index axis = 0; axis < 3; ++axis) {
    if (axis != d_axis) dofs[static_cast<std::size_t>(k++)] = 3 * b + axis;
  }
  return dofs;
}

// Inertia-relief static responses of a free body, M-orthogonal to the rigid modes.
Eigen::MatrixXd InertiaReliefResponses(const FeModel& model, const Eigen::MatrixXd& F, std::string_view what) {
  const Eigen::MatrixXd R = MOrthonormalRigidModes(model);
  const Eigen::MatrixXd MR = model.mass().Times(R);
  const Eigen::MatrixXd F_e = F - MR * (R.transpose() * F);
  const std::array<Index, 6> fixed = DeterminateSupport(model.nodes, what);
  Eigen::MatrixXd X;
  if (const eigensolvers::ModelOperators* operators = model.operators()) {
    // The free-free basis found exactly six zero-frequency modes, which the 3-2-1 support holds.
    X = operators->SolveFixed(fixed, F_e);
  } else {
    const FreeDofMap map(model.num_dofs(), fixed);
    const Eigen::SparseMatrix<double> K_ff = map.Restrict(model.K());
    const Eigen::SparseMatrix<double> M_ff = map.Restrict(model.M());
    eigensolvers::ShiftedFactorization factor;
    if (factor.Factorize(K_ff, M_ff, 0.0, eigensolvers::ShiftedFactorization::Method::kSupernodalCholesky) !=
            eigensolvers::ShiftedFactorization::Status::kOk ||
        HasZeroEnergyMode(factor, K_ff, M_ff)) {
      throw InputError(fmt::format("{}: inertia relief: the free body's stiffness is singular beyond its six "
                                   "rigid-body modes (a part of the mesh not connected to the rest, or a mechanism)",
                                   what));
    }
    X = map.Expand(factor.Solve(map.RestrictVectors(F_e)));
  }
  MOrthogonalizeAgainst(model.mass(), R, &X);
  return X;
}

// The static responses of a body known by its products (ModelOperators), held by whole clamped
// DOF: X = G K_oo^-1 G^T F for the selection G.
StaticResponses HeldResponses(const FeModel& model, const BoundaryConditions& held_by, const Eigen::MatrixXd& F) {
  const std::optional<std::vector<int>> clamped = ClampedDofs(model.nodes, held_by);
  FLEXMBS_CHECK(clamped.has_value(), "a body known by its products is held by whole clamped DOF only");
  const std::vector<Index> fixed(clamped->begin(), clamped->end());
  StaticResponses result;
  result.carried.assign(static_cast<std::size_t>(F.cols()), true);
  auto next = fixed.begin();
  for (Index dof = 0; dof < F.rows(); ++dof) {
    if (next != fixed.end() && *next == dof) {
      ++next;
      continue;
    }
    for (Index j = 0; j < F.cols(); ++j) {
      if (F(dof, j) != 0.0) result.carried[static_cast<std::size_t>(j)] = false;
    }
  }
  result.X = model.operators()->SolveFixed(fixed, F);
  return result;
}

}  // namespace

StaticResponses SolveStaticResponses(const FeModel& model, const BoundaryConditions& held_by,
                                     const Eigen::MatrixXd& F, std::string_view what,
                                     const HeldFactorization* held) {
  FLEXMBS_CHECK(F.rows() == model.num_dofs(), "one load row per DOF");
  StaticResponses result;
  result.carried.assign(static_cast<std::size_t>(F.cols()), false);
  if (held_by.empty()) {
    result.X = InertiaReliefResponses(model, F, what);
    return result;
  }
  if (!model.assembled()) return HeldResponses(model, held_by, F);
  std::shared_ptr<const HeldFactorization> own;
  if (held == nullptr) {
    own = FactorHeldBody(model, held_by, BuildInteriorProblem(model, held_by));
    held = own.get();
  }
  FLEXMBS_CHECK(FactorizedFor(*held, held_by) && held->transform.num_dofs() == model.num_dofs(),
                "SolveStaticResponses: the held factorisation belongs to other conditions or another model");
  const Eigen::SparseMatrix<double>& G = held->transform.G;
  const Eigen::MatrixXd rhs = Eigen::SparseMatrix<double>(G.transpose()) * F;
  for (Index j = 0; j < F.cols(); ++j) result.carried[static_cast<std::size_t>(j)] = rhs.col(j).isZero(0.0);
  result.X = G * held->factor.Solve(rhs);
  return result;
}

}  // namespace flexmbs::reduction
