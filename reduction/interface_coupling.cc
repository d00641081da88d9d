#include "reduction/interface_coupling.h"

#include <fmt/format.h>

#include <Eigen/Eigenvalues>
#include <Eigen/LU>
#include <Eigen/QR>
#include <algorithm>
#include <cmath>
#include <set>

#include "core/error.h"

namespace flexmbs::reduction {
namespace {

using Index = Eigen::Index;
using Triplet = Eigen::Triplet<double>;
using Matrix6 = Eigen::Matrix<double, 6, 6>;

// The 6 x 6 normal matrix of the rigid fit of nodes with positions r_n (from the marker) is
// singular when they lie on one line; with positions scaled to unit size, a smallest-to-largest
// eigenvalue ratio below this is "on one line" (a straight line of nodes gives exactly 0, any
// real spread gives >= 1e-4 or so).
constexpr double kCollinearRatio = 1e-10;

const char* const kAxisNames[3] = {"x", "y", "z"};
const char* const kMarkerDofNames[6] = {"tx", "ty", "tz", "rx", "ry", "rz"};

// The weight of the k-th node of an interface.
double WeightOf(const InterfaceSpec& interface, std::size_t k) {
  return interface.coupling == Coupling::kAveraging && !interface.weights.empty() ? interface.weights[k] : 1.0;
}

// The rigid fit of an interface: W_local (6 x 3 n_I, columns node by node, axis by axis), with
// A = sum w S^T S computed in scaled variables. Throws if the nodes lie on one line.
Eigen::MatrixXd LocalFit(const Eigen::Matrix3Xd& nodes, const InterfaceSpec& interface) {
  const Eigen::Vector3d marker = MarkerPosition(nodes, interface);
  const std::size_t count = interface.nodes.size();
  double length = 0.0;
  for (const int n : interface.nodes) length = std::max(length, (nodes.col(n) - marker).norm());
  if (!(length > 0.0)) length = 1.0;
  // With r = L r', S(r) = S(r') D, D = diag(1, 1, 1, L, L, L): A = D A' D, W = D^-1 A'^-1 [w S(r')^T].
  Matrix6 A_scaled = Matrix6::Zero();
  Eigen::MatrixXd rhs(6, 3 * static_cast<Index>(count));
  for (std::size_t k = 0; k < count; ++k) {
    const Eigen::Matrix<double, 3, 6> S = RigidMotionMatrix((nodes.col(interface.nodes[k]) - marker) / length);
    const double w = WeightOf(interface, k);
    A_scaled += w * S.transpose() * S;
    rhs.middleCols<3>(3 * static_cast<Index>(k)) = w * S.transpose();
  }
  const Eigen::SelfAdjointEigenSolver<Matrix6> eigen(A_scaled, Eigen::EigenvaluesOnly);
  if (!(eigen.eigenvalues()(0) > kCollinearRatio * eigen.eigenvalues()(5))) {
    throw InputError(fmt::format(
        "interface '{}': {} coupling needs nodes that are not all on one line: the marker's rotation about the "
        "line is undetermined ({} node{})", interface.name, CouplingName(interface.coupling), count,
        count == 1 ? "" : "s"));
  }
  Eigen::MatrixXd W = A_scaled.ldlt().solve(rhs);
  W.bottomRows<3>() /= length;
  return W;
}

void CheckNodeList(std::string_view what, const std::string& name, const std::vector<int>& list, Index num_nodes,
                   std::vector<int>* owner, int owner_id, const std::vector<std::string>& owner_names) {
  if (name.empty()) throw InputError(fmt::format("{} with an empty name", what));
  if (list.empty()) throw InputError(fmt::format("{} '{}': no nodes", what, name));
  for (const int n : list) {
    if (n < 0 || n >= num_nodes) {
      throw InputError(fmt::format("{} '{}': node {} is outside the mesh's node range [0, {})", what, name, n,
                                   num_nodes));
    }
    int& slot = (*owner)[static_cast<std::size_t>(n)];
    if (slot == owner_id) throw InputError(fmt::format("{} '{}': node {} is listed twice", what, name, n));
    if (slot >= 0) {
      throw InputError(fmt::format("{} '{}': node {} is also in {}: a node can belong to one interface or support "
                                   "only", what, name, n, owner_names[static_cast<std::size_t>(slot)]));
    }
    slot = owner_id;
  }
}

// Weights and marker of one interface (the node list is checked by CheckNodeList).
void ValidateWeightsAndMarker(const InterfaceSpec& i) {
  if (!i.weights.empty()) {
    if (i.coupling != Coupling::kAveraging) {
      throw InputError(fmt::format("interface '{}': weights are for averaging coupling only, not {}", i.name,
                                   CouplingName(i.coupling)));
    }
    if (i.weights.size() != i.nodes.size()) {
      throw InputError(fmt::format("interface '{}': {} weights for {} nodes", i.name, i.weights.size(),
                                   i.nodes.size()));
    }
    for (std::size_t k = 0; k < i.weights.size(); ++k) {
      if (!(std::isfinite(i.weights[k]) && i.weights[k] > 0.0)) {
        throw InputError(fmt::format("interface '{}': weight {} of node {} must be finite and > 0", i.name,
                                     i.weights[k], i.nodes[k]));
      }
    }
  }
  if (i.marker_position && !i.marker_position->allFinite()) {
    throw InputError(fmt::format("interface '{}': marker position is not finite", i.name));
  }
}

// One interface alone (for the public fit functions): node list and weights.
void ValidateInterface(Index num_nodes, const InterfaceSpec& i) {
  std::vector<int> owner(static_cast<std::size_t>(num_nodes), -1);
  CheckNodeList("interface", i.name, i.nodes, num_nodes, &owner, 0, {fmt::format("interface '{}'", i.name)});
  ValidateWeightsAndMarker(i);
}

}  // namespace

std::string_view CouplingName(Coupling coupling) {
  switch (coupling) {
    case Coupling::kNodes:
      return "nodes";
    case Coupling::kRigid:
      return "rigid";
    case Coupling::kAveraging:
      return "averaging";
  }
  return "?";
}

Eigen::Matrix<double, 3, 6> RigidMotionMatrix(const Eigen::Vector3d& r) {
  Eigen::Matrix<double, 3, 6> S;
  // theta x r = -r~ theta.
  S << 1, 0, 0, 0, r(2), -r(1),  //
      0, 1, 0, -r(2), 0, r(0),   //
      0, 0, 1, r(1), -r(0), 0;
  return S;
}

Eigen::Vector3d MarkerPosition(const Eigen::Matrix3Xd& nodes, const InterfaceSpec& interface) {
  if (interface.marker_position) return *interface.marker_position;
  ValidateInterface(nodes.cols(), interface);
  Eigen::Vector3d sum = Eigen::Vector3d::Zero();
  double total = 0.0;
  for (std::size_t k = 0; k < interface.nodes.size(); ++k) {
    const double w = WeightOf(interface, k);
    sum += w * nodes.col(interface.nodes[k]);
    total += w;
  }
  return total > 0.0 ? Eigen::Vector3d(sum / total) : Eigen::Vector3d::Zero();
}

Eigen::SparseMatrix<double> RigidFitOperator(const Eigen::Matrix3Xd& nodes, const InterfaceSpec& interface) {
  ValidateInterface(nodes.cols(), interface);
  const Eigen::MatrixXd W_local = LocalFit(nodes, interface);
  std::vector<Triplet> triplets;
  triplets.reserve(static_cast<std::size_t>(W_local.size()));
  for (std::size_t k = 0; k < interface.nodes.size(); ++k) {
    for (Index i = 0; i < 3; ++i) {
      const Index local = 3 * static_cast<Index>(k) + i;
      const Index dof = 3 * static_cast<Index>(interface.nodes[k]) + i;
      for (Index row = 0; row < 6; ++row) {
        if (W_local(row, local) != 0.0) triplets.emplace_back(row, dof, W_local(row, local));
      }
    }
  }
  Eigen::SparseMatrix<double> W(6, 3 * nodes.cols());
  W.setFromTriplets(triplets.begin(), triplets.end());
  return W;
}

Eigen::MatrixXd MarkerMotion(const Eigen::Matrix3Xd& nodes, const InterfaceSpec& interface,
                             const Eigen::MatrixXd& Phi) {
  if (interface.coupling == Coupling::kNodes) {
    throw InputError(fmt::format("interface '{}': a node-set interface has no marker", interface.name));
  }
  if (Phi.rows() != 3 * nodes.cols()) {
    throw InputError(fmt::format("interface '{}': the basis has {} rows, the mesh {} DOF", interface.name,
                                 Phi.rows(), 3 * nodes.cols()));
  }
  return RigidFitOperator(nodes, interface) * Phi;
}

std::string DescribeConditions(const BoundaryConditions& conditions) {
  auto list = [](const std::vector<std::string>& names) {
    std::string text;
    for (std::size_t k = 0; k < names.size(); ++k) {
      if (k > 0) text += k + 1 == names.size() ? " and " : ", ";
      text += "'" + names[k] + "'";
    }
    return text;
  };
  std::vector<std::string> interfaces, supports;
  for (const InterfaceSpec& i : conditions.interfaces) interfaces.push_back(i.name);
  for (const SupportSpec& s : conditions.supports) supports.push_back(s.name);
  std::string text;
  if (!interfaces.empty()) text = (interfaces.size() == 1 ? "interface " : "interfaces ") + list(interfaces);
  if (!supports.empty()) {
    if (!text.empty()) text += " and ";
    text += (supports.size() == 1 ? "support " : "supports ") + list(supports);
  }
  return text.empty() ? "no interface or support" : text;
}

namespace {

// Names, node lists and ownership of the conditions (one interface or support per node);
// InputError naming the first that breaks a rule.
void ValidateConditions(Index num_nodes, const BoundaryConditions& conditions) {
  std::vector<std::string> owner_names;
  std::set<std::string> names;
  auto claim_name = [&](std::string_view what, const std::string& name) {
    if (!name.empty() && !names.insert(name).second) {
      throw InputError(fmt::format("{} '{}': the name is used by another interface or support", what, name));
    }
    owner_names.push_back(fmt::format("{} '{}'", what, name));
  };
  // Supports may share nodes (a node in two holds the union of their components, as Nastran's
  // SPCs add up); a node of an interface belongs to that interface alone.
  std::vector<int> owner(static_cast<std::size_t>(num_nodes), -1);
  for (const SupportSpec& s : conditions.supports) {
    claim_name("support", s.name);
    if (std::none_of(s.components.begin(), s.components.end(), [](bool held) { return held; })) {
      throw InputError(fmt::format("support '{}': holds no component (give x, y and/or z)", s.name));
    }
    const int id = static_cast<int>(owner_names.size()) - 1;
    std::vector<int> own(static_cast<std::size_t>(num_nodes), -1);
    CheckNodeList("support", s.name, s.nodes, num_nodes, &own, id, owner_names);
    for (const int n : s.nodes) {
      if (owner[static_cast<std::size_t>(n)] < 0) owner[static_cast<std::size_t>(n)] = id;
    }
  }
  for (const InterfaceSpec& i : conditions.interfaces) {
    claim_name("interface", i.name);
    CheckNodeList("interface", i.name, i.nodes, num_nodes, &owner, static_cast<int>(owner_names.size()) - 1,
                  owner_names);
    ValidateWeightsAndMarker(i);
  }
}

// The DOF of `node` along `axis`.
Index DofOf(int node, Index axis) { return 3 * static_cast<Index>(node) + axis; }

// Builds a ConstraintTransform interface by interface: the roles of the DOF, the columns of B,
// and what the averaging interfaces add to G.
class TransformBuilder {
 public:
  explicit TransformBuilder(const Eigen::Matrix3Xd& nodes)
      : nodes_(nodes), num_dofs_(3 * nodes.cols()), role_(static_cast<std::size_t>(num_dofs_), kInterior) {}

  // Clamps the held components of the support's nodes (once, if another support holds them too).
  void AddSupport(const SupportSpec& s) {
    for (const int n : s.nodes) {
      for (Index a = 0; a < 3; ++a) {
        Role& role = role_[static_cast<std::size_t>(DofOf(n, a))];
        if (!s.components[static_cast<std::size_t>(a)] || role == kClamped) continue;
        role = kClamped;
        ++t_.num_support_dofs;
      }
    }
  }

  // The interface's boundary DOF: B's columns from next_boundary_ on.
  void AddInterface(const InterfaceSpec& i) {
    ConstraintTransform::InterfaceRange range{i.name, i.coupling, next_boundary_, 0};
    switch (i.coupling) {
      case Coupling::kNodes:
        range.count = AddNodeSet(i);
        break;
      case Coupling::kRigid:
        range.count = AddRigid(i);
        break;
      case Coupling::kAveraging:
        range.count = AddAveraging(i);
        break;
    }
    next_boundary_ += range.count;
    t_.interfaces.push_back(range);
  }

  // Interior DOF: every DOF not clamped, coupled or dependent, in DOF order; then B and G.
  ConstraintTransform Finish() {
    std::vector<Index> interior_index(static_cast<std::size_t>(num_dofs_), -1);
    Index num_interior = 0;
    for (Index dof = 0; dof < num_dofs_; ++dof) {
      if (role_[static_cast<std::size_t>(dof)] == kInterior) interior_index[static_cast<std::size_t>(dof)] = num_interior++;
    }
    std::vector<Triplet> g_triplets;
    g_triplets.reserve(static_cast<std::size_t>(num_interior));
    for (Index dof = 0; dof < num_dofs_; ++dof) {
      const Index o = interior_index[static_cast<std::size_t>(dof)];
      if (o >= 0) g_triplets.emplace_back(dof, o, 1.0);
    }
    for (const Averaging& a : averaging_) {
      for (Index row = 0; row < 6; ++row) {
        const Index dof = a.dofs[static_cast<std::size_t>(a.dependent[static_cast<std::size_t>(row)])];
        for (std::size_t k = 0; k < a.other.size(); ++k) {
          const double value = -a.Wd_inv_Wo(row, static_cast<Index>(k));
          if (value == 0.0) continue;
          const Index o = interior_index[static_cast<std::size_t>(a.dofs[static_cast<std::size_t>(a.other[k])])];
          FLEXMBS_CHECK(o >= 0, "averaging interface: an independent DOF is not interior");
          g_triplets.emplace_back(dof, o, value);
        }
      }
    }
    t_.B.resize(num_dofs_, next_boundary_);
    t_.B.setFromTriplets(b_triplets_.begin(), b_triplets_.end());
    t_.G.resize(num_dofs_, num_interior);
    t_.G.setFromTriplets(g_triplets.begin(), g_triplets.end());
    return std::move(t_);
  }

 private:
  // Roles of the DOF: interior (default), clamped, coupled (node set / rigid), dependent (averaging).
  enum Role : char { kInterior, kClamped, kCoupled, kDependent };
  // An averaging interface's split of its DOF into 6 dependent and the others.
  struct Averaging {
    std::vector<Index> dofs;       // the interface's node DOF (local order)
    std::vector<Index> dependent;  // local indices of the 6 dependent DOF
    std::vector<Index> other;      // local indices of the others
    Eigen::MatrixXd Wd_inv;        // 6 x 6
    Eigen::MatrixXd Wd_inv_Wo;     // 6 x (3 n_I - 6)
  };

  // A node-set interface: each node DOF is a boundary DOF.
  Index AddNodeSet(const InterfaceSpec& i) {
    for (std::size_t k = 0; k < i.nodes.size(); ++k) {
      for (Index a = 0; a < 3; ++a) {
        const Index dof = DofOf(i.nodes[k], a);
        role_[static_cast<std::size_t>(dof)] = kCoupled;
        b_triplets_.emplace_back(dof, next_boundary_ + 3 * static_cast<Index>(k) + a, 1.0);
        t_.boundary_names.push_back(fmt::format("{}_n{}_{}", i.name, i.nodes[k], kAxisNames[a]));
      }
    }
    return 3 * static_cast<Index>(i.nodes.size());
  }

  // A rigid (RBE2-like) interface: the nodes follow the marker's six DOF rigidly.
  Index AddRigid(const InterfaceSpec& i) {
    LocalFit(nodes_, i);  // throws if the nodes are on one line
    const Eigen::Vector3d marker = MarkerPosition(nodes_, i);
    for (const int n : i.nodes) {
      const Eigen::Matrix<double, 3, 6> S = RigidMotionMatrix(nodes_.col(n) - marker);
      for (Index a = 0; a < 3; ++a) {
        const Index dof = DofOf(n, a);
        role_[static_cast<std::size_t>(dof)] = kCoupled;
        for (Index c = 0; c < 6; ++c) {
          if (S(a, c) != 0.0) b_triplets_.emplace_back(dof, next_boundary_ + c, S(a, c));
        }
      }
    }
    for (const char* dof_name : kMarkerDofNames) t_.boundary_names.push_back(fmt::format("{}_{}", i.name, dof_name));
    return 6;
  }

  // An averaging (RBE3-like) interface: the six best-conditioned columns of the rigid fit W
  // become dependent, u_d = W_d^-1 (q - W_o u_o); the others stay interior.
  Index AddAveraging(const InterfaceSpec& i) {
    const Eigen::MatrixXd W = LocalFit(nodes_, i);
    Averaging a;
    for (const int n : i.nodes) {
      for (Index axis = 0; axis < 3; ++axis) a.dofs.push_back(DofOf(n, axis));
    }
    const Eigen::ColPivHouseholderQR<Eigen::MatrixXd> qr(W);
    const auto& permutation = qr.colsPermutation().indices();
    std::vector<bool> is_dependent(a.dofs.size(), false);
    for (Index k = 0; k < 6; ++k) is_dependent[static_cast<std::size_t>(permutation(k))] = true;
    for (std::size_t k = 0; k < a.dofs.size(); ++k) {
      (is_dependent[k] ? a.dependent : a.other).push_back(static_cast<Index>(k));
    }
    Eigen::MatrixXd Wd(6, 6), Wo(6, static_cast<Index>(a.other.size()));
    for (Index k = 0; k < 6; ++k) Wd.col(k) = W.col(a.dependent[static_cast<std::size_t>(k)]);
    for (std::size_t k = 0; k < a.other.size(); ++k) Wo.col(static_cast<Index>(k)) = W.col(a.other[k]);
    const Eigen::FullPivLU<Eigen::MatrixXd> lu(Wd);
    FLEXMBS_CHECK(lu.isInvertible(), "averaging interface: dependent block of the rigid fit is singular");
    a.Wd_inv = lu.inverse();
    a.Wd_inv_Wo = lu.solve(Wo);
    for (const Index k : a.dependent) role_[static_cast<std::size_t>(a.dofs[static_cast<std::size_t>(k)])] = kDependent;
    for (Index row = 0; row < 6; ++row) {
      const Index dof = a.dofs[static_cast<std::size_t>(a.dependent[static_cast<std::size_t>(row)])];
      for (Index c = 0; c < 6; ++c) b_triplets_.emplace_back(dof, next_boundary_ + c, a.Wd_inv(row, c));
    }
    for (const char* dof_name : kMarkerDofNames) t_.boundary_names.push_back(fmt::format("{}_{}", i.name, dof_name));
    averaging_.push_back(std::move(a));
    return 6;
  }

  const Eigen::Matrix3Xd& nodes_;
  const Index num_dofs_;
  std::vector<Role> role_;
  ConstraintTransform t_;
  std::vector<Averaging> averaging_;
  std::vector<Triplet> b_triplets_;
  Index next_boundary_ = 0;
};

}  // namespace

ConstraintTransform BuildConstraintTransform(const Eigen::Matrix3Xd& nodes, const BoundaryConditions& conditions) {
  ValidateConditions(nodes.cols(), conditions);
  TransformBuilder builder(nodes);
  for (const SupportSpec& s : conditions.supports) builder.AddSupport(s);
  for (const InterfaceSpec& i : conditions.interfaces) builder.AddInterface(i);
  return builder.Finish();
}

}  // namespace flexmbs::reduction
