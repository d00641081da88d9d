#include "reduction/interior_problem.h"

#include <fmt/format.h>

#include <Eigen/SVD>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <random>
#include <vector>

#include "core/error.h"
#include "reduction/dof_constraints.h"

namespace flexmbs::reduction {
namespace {

// Held nodes lie on one line when the second singular value of their centred positions is
// below this fraction of the first (exactly collinear positions give round-off).
constexpr double kCollinearFraction = 1e-9;

bool SameSupport(const SupportSpec& a, const SupportSpec& b) {
  return a.name == b.name && a.nodes == b.nodes && a.components == b.components;
}

bool SameInterface(const InterfaceSpec& a, const InterfaceSpec& b) {
  return a.name == b.name && a.nodes == b.nodes && a.coupling == b.coupling &&
         a.marker_position.has_value() == b.marker_position.has_value() &&
         (!a.marker_position || *a.marker_position == *b.marker_position) && a.weights == b.weights;
}

}  // namespace

InteriorProblem BuildInteriorProblem(const FeModel& model, const BoundaryConditions& conditions) {
  ValidateModel(model);
  InteriorProblem p;
  p.transform = BuildConstraintTransform(model.nodes, conditions);
  const Eigen::SparseMatrix<double>& G = p.transform.G;
  const bool averaging = std::any_of(conditions.interfaces.begin(), conditions.interfaces.end(),
                                     [](const InterfaceSpec& i) { return i.coupling == Coupling::kAveraging; });
  if (!averaging) {
    // G selects the interior DOF (ascending, like FreeDofMap): restrict without sparse products.
    std::vector<bool> interior(static_cast<std::size_t>(G.rows()), false);
    for (Eigen::Index o = 0; o < G.outerSize(); ++o) {
      for (Eigen::SparseMatrix<double>::InnerIterator it(G, o); it; ++it) interior[static_cast<std::size_t>(it.row())] = true;
    }
    std::vector<Eigen::Index> fixed;
    for (Eigen::Index dof = 0; dof < G.rows(); ++dof) {
      if (!interior[static_cast<std::size_t>(dof)]) fixed.push_back(dof);
    }
    const FreeDofMap map(G.rows(), fixed);
    p.K_oo = map.Restrict(model.K());
    p.M_oo = map.Restrict(model.M());
    return p;
  }
  const Eigen::SparseMatrix<double> Gt = G.transpose();
  p.K_oo = Gt * (model.K() * G);
  p.M_oo = Gt * (model.M() * G);
  p.K_oo.prune(0.0);
  p.M_oo.prune(0.0);
  return p;
}

bool HasZeroEnergyMode(const eigensolvers::ShiftedFactorization& factor, const Eigen::SparseMatrix<double>& K,
                       const Eigen::SparseMatrix<double>& M) {
  constexpr Eigen::Index kProbeVectors = 2;
  constexpr int kSteps = 3;
  const Eigen::Index n = K.rows();
  if (n == 0) return false;
  const double scale = K.diagonal().sum() / M.diagonal().sum();
  std::mt19937_64 rng(0x48656c64u);
  std::uniform_real_distribution<double> uniform(-0.5, 0.5);
  Eigen::MatrixXd X(n, kProbeVectors);
  for (Eigen::Index i = 0; i < X.size(); ++i) X.data()[i] = uniform(rng);
  for (int step = 0; step < kSteps; ++step) {
    X = factor.Solve(Eigen::MatrixXd(M * X));
    if (!X.allFinite()) return true;
    X.colwise().normalize();
  }
  const Eigen::MatrixXd KX = K * X;
  const Eigen::MatrixXd MX = M * X;
  for (Eigen::Index j = 0; j < kProbeVectors; ++j) {
    const double rayleigh = X.col(j).dot(KX.col(j)) / X.col(j).dot(MX.col(j));
    if (!(rayleigh > eigensolvers::kZeroEigenvalue * scale)) return true;
  }
  return false;
}

std::optional<std::vector<int>> ClampedDofs(const Eigen::Matrix3Xd& nodes, const BoundaryConditions& conditions) {
  const ConstraintTransform transform = BuildConstraintTransform(nodes, conditions);
  const Eigen::SparseMatrix<double, Eigen::RowMajor> G = transform.G;
  std::vector<int> clamped;
  for (Eigen::Index dof = 0; dof < G.rows(); ++dof) {
    const Eigen::Index count = G.outerIndexPtr()[dof + 1] - G.outerIndexPtr()[dof];
    if (count == 0) {
      clamped.push_back(static_cast<int>(dof));
    } else if (count != 1 || G.valuePtr()[G.outerIndexPtr()[dof]] != 1.0) {
      return std::nullopt;
    }
  }
  // A selection: each interior coordinate is one free DOF, in ascending order.
  if (G.cols() != G.rows() - static_cast<Eigen::Index>(clamped.size())) return std::nullopt;
  Eigen::Index expected = 0;
  for (Eigen::Index dof = 0; dof < G.rows(); ++dof) {
    if (G.outerIndexPtr()[dof + 1] == G.outerIndexPtr()[dof]) continue;
    if (G.innerIndexPtr()[G.outerIndexPtr()[dof]] != expected++) return std::nullopt;
  }
  return clamped;
}

eigensolvers::ShiftedFactorization FactorHeldInterior(const FeModel& model, const BoundaryConditions& conditions,
                                        const InteriorProblem& interior) {
  eigensolvers::ShiftedFactorization factor;
  if (interior.K_oo.rows() == 0) return factor;
  const auto status = factor.Factorize(interior.K_oo, interior.M_oo, 0.0,
                                       eigensolvers::ShiftedFactorization::Method::kSupernodalCholesky);
  if (status != eigensolvers::ShiftedFactorization::Status::kOk || HasZeroEnergyMode(factor, interior.K_oo, interior.M_oo)) {
    ThrowNotHeld(model, conditions);
  }
  return factor;
}

std::shared_ptr<const HeldFactorization> FactorHeldBody(const FeModel& model, const BoundaryConditions& conditions,
                                                        const InteriorProblem& interior) {
  const auto start = std::chrono::steady_clock::now();
  auto held = std::make_shared<HeldFactorization>();
  held->factor = FactorHeldInterior(model, conditions, interior);
  held->seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  held->conditions = conditions;
  held->transform = interior.transform;
  return held;
}

bool FactorizedFor(const HeldFactorization& held, const BoundaryConditions& conditions) {
  return std::ranges::equal(held.conditions.supports, conditions.supports, SameSupport) &&
         std::ranges::equal(held.conditions.interfaces, conditions.interfaces, SameInterface);
}

bool SharesHeldFactorization(const eigensolvers::Eigensolver& solver, const eigensolvers::EigenOptions& options) {
  return solver.UsesGivenFactorization() && (!options.shift_hz || *options.shift_hz == 0.0);
}

HeldModes SolveHeldModes(const eigensolvers::Eigensolver& solver, const InteriorProblem& interior, const HeldFactorization* held,
                         const eigensolvers::EigenOptions& options, std::string_view what) {
  const bool shared = held != nullptr && SharesHeldFactorization(solver, options);
  HeldModes modes;
  try {
    modes.solution = shared ? solver.SolveFactorized(interior.K_oo, interior.M_oo, options, held->factor)
                            : solver.Solve(interior.K_oo, interior.M_oo, options);
  } catch (const InputError& e) {
    throw InputError(fmt::format("{}: {}", what, e.what()));
  }
  modes.summary = SummarizeEigenSolution(modes.solution);
  if (shared) {
    ++modes.summary.factorizations;
    modes.summary.factorization_seconds += held->seconds;
    modes.summary.seconds += held->seconds;
  }
  return modes;
}

void ThrowNotHeld(const FeModel& model, const BoundaryConditions& conditions) {
  const std::string who = DescribeConditions(conditions);
  const std::size_t count = conditions.supports.size() + conditions.interfaces.size();
  bool has_averaging = false;
  std::vector<int> held;
  for (const SupportSpec& s : conditions.supports) held.insert(held.end(), s.nodes.begin(), s.nodes.end());
  for (const InterfaceSpec& i : conditions.interfaces) {
    if (i.coupling == Coupling::kAveraging) has_averaging = true;
    held.insert(held.end(), i.nodes.begin(), i.nodes.end());
  }
  const bool partial = std::any_of(conditions.supports.begin(), conditions.supports.end(), [](const SupportSpec& s) {
    return std::find(s.components.begin(), s.components.end(), false) != s.components.end();
  });
  std::string reason;
  if (conditions.empty()) {
    reason = "nothing holds it";
  } else if (partial) {
    reason = "supports that hold only some components leave a rigid motion free (hold the others somewhere too)";
  } else if (!has_averaging) {
    Eigen::Matrix3Xd x(3, static_cast<Eigen::Index>(held.size()));
    for (std::size_t k = 0; k < held.size(); ++k) x.col(static_cast<Eigen::Index>(k)) = model.nodes.col(held[k]);
    const Eigen::Vector3d centre = x.rowwise().mean();
    x.colwise() -= centre;
    // min(3, held nodes) singular values; those of fewer than three nodes are zero beyond.
    const Eigen::VectorXd computed = Eigen::JacobiSVD<Eigen::MatrixXd>(x).singularValues();
    Eigen::Vector3d s = Eigen::Vector3d::Zero();
    s.head(computed.size()) = computed;
    if (!(s(0) > 0.0)) {
      reason = fmt::format("{} held node{} at one point, about which the body can still rotate",
                           held.size() == 1 ? "its only" : "all its", held.size() == 1 ? " is" : "s are");
    } else if (s(1) <= kCollinearFraction * s(0)) {
      reason = fmt::format("its {} held nodes lie on one line, about which the body can still rotate", held.size());
    }
  }
  if (reason.empty()) {
    reason = "a zero-energy motion remains with them held (a part of the mesh not connected to them, or a mechanism)";
  }
  throw InputError(fmt::format("{} {} not hold the body: the interior stiffness K_ii (interface DOF held) is singular: {}",
                               who, count == 1 ? "does" : "do", reason));
}

}  // namespace flexmbs::reduction
