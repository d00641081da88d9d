#include "reduction/correction_modes.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <set>
#include <vector>

#include "core/error.h"
#include "reduction/basis_algebra.h"
#include "reduction/static_response.h"

namespace flexmbs::reduction {
namespace {

using Index = Eigen::Index;
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
const char* const kAxisNames[3] = {"x", "y", "z"};

}  // namespace

LoadCases BuildLoadCases(Index num_nodes, const LoadSet& load) {
  if (load.name.empty()) throw InputError("load set with an empty name");
  const std::string what = fmt::format("load set '{}'", load.name);
  if (load.nodes.empty()) throw InputError(fmt::format("{}: no nodes (empty load set)", what));
  std::vector<bool> seen(static_cast<std::size_t>(num_nodes), false);
  for (const int n : load.nodes) {
    if (n < 0 || n >= num_nodes) {
      throw InputError(fmt::format("{}: node {} is outside the mesh's node range [0, {})", what, n, num_nodes));
    }
    if (seen[static_cast<std::size_t>(n)]) throw InputError(fmt::format("{}: node {} is listed twice", what, n));
    seen[static_cast<std::size_t>(n)] = true;
  }
  std::vector<Eigen::Vector3d> directions;
  std::vector<std::string> direction_names;
  if (load.direction) {
    const Eigen::Vector3d& d = *load.direction;
    const double norm = d.norm();
    if (!(std::isfinite(norm) && norm > 0.0)) {
      throw InputError(fmt::format("{}: direction ({:g}, {:g}, {:g}) must be finite and non-zero", what, d(0), d(1), d(2)));
    }
    directions.push_back(d / norm);
    direction_names.emplace_back();
  } else {
    for (Index axis = 0; axis < 3; ++axis) {
      directions.push_back(Eigen::Vector3d::Unit(axis));
      direction_names.emplace_back(std::string("_") + kAxisNames[axis]);
    }
  }
  std::vector<double> shares(load.nodes.size(), 1.0);
  if (!load.weights.empty()) {
    if (load.distribution != LoadDistribution::kResultant) {
      throw InputError(fmt::format("{}: weights are for a resultant load only, not per-node loads", what));
    }
    if (load.weights.size() != load.nodes.size()) {
      throw InputError(fmt::format("{}: {} weights for {} nodes", what, load.weights.size(), load.nodes.size()));
    }
    for (std::size_t k = 0; k < shares.size(); ++k) {
      if (!(std::isfinite(load.weights[k]) && load.weights[k] > 0.0)) {
        throw InputError(fmt::format("{}: weight {} of node {} must be finite and > 0", what, load.weights[k],
                                     load.nodes[k]));
      }
      shares[k] = load.weights[k];
    }
  }
  double total = 0.0;
  for (const double w : shares) total += w;

  LoadCases cases;
  const Index num_dofs = 3 * num_nodes;
  if (load.distribution == LoadDistribution::kResultant) {
    cases.F = Eigen::MatrixXd::Zero(num_dofs, static_cast<Index>(directions.size()));
    for (std::size_t d = 0; d < directions.size(); ++d) {
      for (std::size_t k = 0; k < load.nodes.size(); ++k) {
        cases.F.block<3, 1>(3 * static_cast<Index>(load.nodes[k]), static_cast<Index>(d)) =
            shares[k] / total * directions[d];
      }
      cases.names.push_back(load.name + direction_names[d]);
    }
  } else {
    cases.F = Eigen::MatrixXd::Zero(num_dofs, static_cast<Index>(directions.size() * load.nodes.size()));
    Index column = 0;
    for (const int n : load.nodes) {
      for (std::size_t d = 0; d < directions.size(); ++d) {
        cases.F.block<3, 1>(3 * static_cast<Index>(n), column++) = directions[d];
        cases.names.push_back(fmt::format("{}_n{}{}", load.name, n, direction_names[d]));
      }
    }
  }
  return cases;
}

namespace {

// Every load set's unit load cases side by side (n x cases) with their mode names
// ("static_correction_<case>"), refused when a name is in the basis or made twice.
struct NamedLoads {
  Eigen::MatrixXd F;
  std::vector<std::string> names;
};
NamedLoads StackLoadCases(Index num_nodes, Index n, const ReducedBasis& basis, std::span<const LoadSet> loads) {
  NamedLoads stacked;
  std::vector<Eigen::MatrixXd> blocks;
  std::set<std::string> taken(basis.names.begin(), basis.names.end());
  Index num_cases = 0;
  for (const LoadSet& load : loads) {
    LoadCases cases = BuildLoadCases(num_nodes, load);
    num_cases += cases.F.cols();
    for (std::string& name : cases.names) {
      stacked.names.push_back("static_correction_" + name);
      if (!taken.insert(stacked.names.back()).second) {
        throw InputError(fmt::format("load set '{}': mode name '{}' is already in the basis or made twice", load.name,
                                     stacked.names.back()));
      }
    }
    blocks.push_back(std::move(cases.F));
  }
  stacked.F.resize(n, num_cases);
  Index offset = 0;
  for (const Eigen::MatrixXd& block : blocks) {
    stacked.F.middleCols(offset, block.cols()) = block;
    offset += block.cols();
  }
  return stacked;
}

// The basis's modes other than its constraint modes (what correction modes are made
// M-orthogonal to).
Eigen::MatrixXd NonConstraintModes(const ReducedBasis& basis) {
  std::vector<Index> keep;
  for (Index j = 0; j < basis.num_modes(); ++j) {
    if (basis.kinds[static_cast<std::size_t>(j)] != ModeKind::kConstraint) keep.push_back(j);
  }
  Eigen::MatrixXd columns(basis.Phi.rows(), static_cast<Index>(keep.size()));
  for (std::size_t k = 0; k < keep.size(); ++k) columns.col(static_cast<Index>(k)) = basis.Phi.col(keep[k]);
  return columns;
}

// `basis` with the M-orthonormal correction modes `added` (named by `names` at `accepted`)
// appended: kinds, names, NaN frequencies and residuals, method and description, reduced matrices.
ReducedBasis AppendCorrectionModes(const FeModel& model, const ReducedBasis& basis, const Eigen::MatrixXd& added,
                                   const std::vector<Index>& accepted, const std::vector<std::string>& names,
                                   std::size_t dropped) {
  ReducedBasis out = basis;
  const Index n = model.num_dofs();
  const Index old = basis.num_modes();
  const Index k = added.cols();
  out.Phi.conservativeResize(n, old + k);
  out.Phi.rightCols(k) = added;
  for (const Index j : accepted) {
    out.kinds.push_back(ModeKind::kStaticCorrection);
    out.names.push_back(names[static_cast<std::size_t>(j)]);
  }
  auto extend = [&](Eigen::VectorXd* v) {
    v->conservativeResize(old + k);
    v->tail(k).setConstant(kNaN);
  };
  extend(&out.frequency_hz);
  extend(&out.relative_residuals);
  extend(&out.residual_floors);
  if (out.method.find("+static_correction") == std::string::npos) out.method += "+static_correction";
  out.description += fmt::format("; {} static correction modes ({}, {} dropped)", k,
                                 basis.held_by.empty() ? "inertia relief" : "held as the basis", dropped);
  ComputeReducedMatrices(model, &out);
  return out;
}

}  // namespace

CorrectionResult AddStaticCorrectionModes(const FeModel& model, const ReducedBasis& basis,
                                          std::span<const LoadSet> loads, const CorrectionOptions& options) {
  ValidateModel(model);
  const Index n = model.num_dofs();
  if (basis.Phi.rows() != n) {
    throw InputError(fmt::format("static correction modes: the basis has {} rows, the model {} DOF", basis.Phi.rows(), n));
  }
  if (loads.empty()) throw InputError("static correction modes: no load sets");
  if (!(options.dependency_tolerance > 0.0 && options.dependency_tolerance < 1.0)) {
    throw InputError(fmt::format("static correction modes: dependency_tolerance {} must be in (0, 1)",
                                 options.dependency_tolerance));
  }
  const NamedLoads loads_named = StackLoadCases(model.nodes.cols(), n, basis, loads);
  const std::vector<std::string>& names = loads_named.names;

  // Static responses of the body as the basis holds it.
  CorrectionResult result;
  const StaticResponses responses = SolveStaticResponses(model, basis.held_by, loads_named.F, "static correction modes",
                                                         basis.held_factorization.get());
  const Eigen::MatrixXd& X = responses.X;
  const std::vector<bool>& carried = responses.carried;  // no interior load at all

  // M-orthogonalise against the basis (not its constraint modes) and each other; drop the dependent.
  Eigen::MatrixXd Q = MOrthonormalized(model.mass(), NonConstraintModes(basis));
  std::vector<Index> accepted;
  Eigen::MatrixXd added(n, 0);
  for (Index j = 0; j < loads_named.F.cols(); ++j) {
    const std::string& name = names[static_cast<std::size_t>(j)];
    if (carried[static_cast<std::size_t>(j)]) {
      result.dropped.push_back(fmt::format("{}: the load acts on support or interface DOF only (carried by the "
                                           "constraint modes or the supports)", name));
      continue;
    }
    Eigen::MatrixXd x = X.col(j);
    const double before = std::sqrt(x.col(0).dot(model.mass().Times(x).col(0)));
    MOrthogonalizeAgainst(model.mass(), Q, &x);
    const double after = std::sqrt(std::max(x.col(0).dot(model.mass().Times(x).col(0)), 0.0));
    if (!(before > 0.0) || !(after > options.dependency_tolerance * before)) {
      result.dropped.push_back(fmt::format("{}: linearly dependent on the basis (M-norm left after orthogonalisation "
                                           "{:.2g} of the static response's)", name, before > 0.0 ? after / before : 0.0));
      continue;
    }
    x /= after;
    Q.conservativeResize(n, Q.cols() + 1);
    Q.col(Q.cols() - 1) = x.col(0);
    added.conservativeResize(n, added.cols() + 1);
    added.col(added.cols() - 1) = x.col(0);
    accepted.push_back(j);
  }
  result.added = added.cols();
  result.basis = AppendCorrectionModes(model, basis, added, accepted, names, result.dropped.size());
  return result;
}

}  // namespace flexmbs::reduction
