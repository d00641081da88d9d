#include "mbs/kkt_newton_solver.h"

#include <fmt/format.h>

#include <Eigen/LU>
#include <Eigen/SparseLU>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <utility>

#include "core/error.h"
#include "mbs/simulation_error.h"
#include "mbs/system_jacobian.h"

namespace flexmbs::mbs {
namespace {

using Eigen::Index;
using Eigen::MatrixXd;
using Eigen::VectorXd;
using Triplet = Eigen::Triplet<double>;

/// Adds the seconds since `start` to `total` when it goes out of scope.
class ScopedTimer {
 public:
  explicit ScopedTimer(double& total) : total_(total), start_(std::chrono::steady_clock::now()) {}
  ~ScopedTimer() { total_ += std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count(); }
  ScopedTimer(const ScopedTimer&) = delete;
  ScopedTimer& operator=(const ScopedTimer&) = delete;

 private:
  double& total_;
  std::chrono::steady_clock::time_point start_;
};

/// The forward-difference increment of a velocity u_j [m/s, rad/s]: SystemJacobian's,
/// sqrt(eps) max(|u_j|, 1).
double VelocityIncrement(double u_j) {
  return std::sqrt(std::numeric_limits<double>::epsilon()) * std::max(std::abs(u_j), 1.0);
}

/// True if a and b (compressed) have the same nonzero pattern.
bool SamePattern(const Eigen::SparseMatrix<double>& a, const Eigen::SparseMatrix<double>& b) {
  if (a.rows() != b.rows() || a.cols() != b.cols() || a.nonZeros() != b.nonZeros()) return false;
  return std::equal(a.outerIndexPtr(), a.outerIndexPtr() + a.outerSize() + 1, b.outerIndexPtr()) &&
         std::equal(a.innerIndexPtr(), a.innerIndexPtr() + a.nonZeros(), b.innerIndexPtr());
}

/// Per velocity of u: true where a planar scene drops it (MultibodySystem::KeptVelocities); empty
/// for a spatial scene.
std::vector<char> DroppedVelocities(const MultibodySystem& system) {
  if (!system.planar()) return {};
  std::vector<char> dropped(static_cast<std::size_t>(system.num_velocities()), 1);
  for (const Index column : system.KeptVelocities()) dropped[static_cast<std::size_t>(column)] = 0;
  return dropped;
}

/// A planar scene's augmented matrix (docs/mbs.md, "Planar scenes"): the entries in a dropped
/// velocity's row or column are left out and its diagonal is 1, so that the kept block is the
/// in-plane system and du = r_u in the dropped velocities (Solve's right-hand side there).
void KeepPlanarColumns(const std::vector<char>& dropped, std::vector<Triplet>& entries) {
  const Index nu = static_cast<Index>(dropped.size());
  const auto is_dropped = [&](Index i) { return i < nu && dropped[static_cast<std::size_t>(i)] != 0; };
  entries.erase(std::remove_if(entries.begin(), entries.end(),
                               [&](const Triplet& e) { return is_dropped(e.row()) || is_dropped(e.col()); }),
                entries.end());
  for (Index i = 0; i < nu; ++i) {
    if (is_dropped(i)) entries.emplace_back(static_cast<int>(i), static_cast<int>(i), 1.0);
  }
}

}  // namespace

/// The sparse LU of the augmented matrix; its pattern analysis is redone only when the pattern
/// changes (a force element's Jacobian switching on or off).
struct KktNewtonSolver::Factor {
  Eigen::SparseLU<Eigen::SparseMatrix<double>, Eigen::COLAMDOrdering<int>> lu;
  Eigen::SparseMatrix<double> analysed;  // the pattern lu was analysed for
  bool have_pattern = false;
};

KktNewtonSolver::KktNewtonSolver(const MultibodySystem& system)
    : system_(system), factor_(std::make_unique<Factor>()) {
  FLEXMBS_CHECK(system.num_element_states() == 0,
                "KktNewtonSolver: force elements with states of their own are the dense solve's");
  bodies_.resize(static_cast<std::size_t>(system.num_bodies()));
  for (int b = 0; b < system.num_bodies(); ++b) {
    BodyBlocks& blocks = bodies_[static_cast<std::size_t>(b)];
    blocks.px = system.position_offset(b);
    blocks.pu = system.velocity_block(b).start;
    blocks.nu = system.velocity_block(b).size;
  }
}

KktNewtonSolver::~KktNewtonSolver() = default;

void KktNewtonSolver::EvaluateForceElements(double t, const Eigen::Ref<const VectorXd>& y) {
  element_dh_dx_.clear();
  element_dh_du_.clear();
  if (system_.num_force_elements() == 0) return;
  // ForceElement::AddForceJacobian writes into the system's whole velocity space: kept zero
  // between calls, scanned for the entries the elements set (O(n_u^2), with force elements only).
  const Index nu = system_.num_velocities();
  if (element_scratch_dx_.rows() != nu) {
    element_scratch_dx_ = MatrixXd::Zero(nu, nu);
    element_scratch_du_ = MatrixXd::Zero(nu, nu);
  }
  for (int k = 0; k < system_.num_force_elements(); ++k) {
    system_.force_element(k).AddForceJacobian(t, system_, y, element_scratch_dx_, element_scratch_du_);
  }
  for (auto [scratch, triplets] : {std::pair{&element_scratch_dx_, &element_dh_dx_},
                                   std::pair{&element_scratch_du_, &element_dh_du_}}) {
    for (Index j = 0; j < nu; ++j) {
      for (Index i = 0; i < nu; ++i) {
        double& value = (*scratch)(i, j);
        if (value == 0.0) continue;
        triplets->emplace_back(static_cast<int>(i), static_cast<int>(j), value);
        value = 0.0;
      }
    }
  }
}

void KktNewtonSolver::EvaluateGammaDifferences(double t, const Eigen::Ref<const VectorXd>& y,
                                               const std::vector<Index>& kept) {
  gamma_du_.clear();
  std::vector<Index> kept_position(static_cast<std::size_t>(system_.num_constraints()), -1);
  for (std::size_t i = 0; i < kept.size(); ++i) kept_position[static_cast<std::size_t>(kept[i])] = static_cast<Index>(i);
  for (int k = 0; k < system_.num_joints(); ++k) {
    const Joint& joint = system_.joint(k);
    const Index first = system_.constraint_offset(k), m = joint.num_equations();
    const MarkerKinematics I = system_.MarkerState(joint.marker_i(), y), J = system_.MarkerState(joint.marker_j(), y);
    const VectorXd gamma0 = joint.Evaluate(t, I, J).gamma;
    for (const bool moving_i : {true, false}) {
      const MarkerRef& marker = moving_i ? joint.marker_i() : joint.marker_j();
      if (marker.is_ground()) continue;
      const BodyBlocks& blocks = bodies_[static_cast<std::size_t>(marker.body)];
      const auto x_b = system_.BodyPositions(y, marker.body);
      const auto u_b = system_.BodyVelocities(y, marker.body);
      VectorXd u_moved = u_b;
      for (Index c = 0; c < 6; ++c) {
        const double increment = VelocityIncrement(u_b(c));
        u_moved(c) = u_b(c) + increment;
        const MarkerKinematics moved = system_.body(marker.body).Marker(marker.marker, x_b, u_moved);
        const VectorXd gamma1 = joint.Evaluate(t, moving_i ? moved : I, moving_i ? J : moved).gamma;
        u_moved(c) = u_b(c);
        for (Index r = 0; r < m; ++r) {
          const Index row = kept_position[static_cast<std::size_t>(first + r)];
          if (row < 0) continue;
          gamma_du_.emplace_back(static_cast<int>(row), static_cast<int>(blocks.pu + c),
                                 (gamma1(r) - gamma0(r)) / increment);
        }
      }
    }
  }
}

void KktNewtonSolver::EvaluateBodies(double t, const Eigen::Ref<const VectorXd>& y, const VectorXd& u_dot) {
  for (int b = 0; b < system_.num_bodies(); ++b) {
    const Body& body = system_.body(b);
    BodyBlocks& blocks = bodies_[static_cast<std::size_t>(b)];
    const auto x_b = system_.BodyPositions(y, b);
    const auto u_b = system_.BodyVelocities(y, b);
    const auto u_dot_b = u_dot.segment(blocks.pu, blocks.nu);
    blocks.M = system_.BodyMassMatrix(b, y);
    blocks.dh_dx = MatrixXd::Zero(blocks.nu, blocks.nu);
    blocks.dh_du = MatrixXd::Zero(blocks.nu, blocks.nu);
    body.AddForceJacobian(x_b, u_b, u_dot_b, system_.gravity(), blocks.dh_dx, blocks.dh_du);
    // The v and w_B columns: forward differences of the body's h (with the acceleration-dependent
    // forces at u_dot), as SystemJacobian's differences of u' see them.
    const auto body_forces = [&](const VectorXd& u, VectorXd& h) {
      body.Forces(t, x_b, u, system_.gravity(), h);
      body.AddAccelerationDependentForces(x_b, u, u_dot_b, h);
    };
    VectorXd u_moved = u_b, h0(blocks.nu), h1(blocks.nu);
    body_forces(u_moved, h0);
    for (Index k = 0; k < 6; ++k) {
      const double increment = VelocityIncrement(u_b(k));
      u_moved(k) = u_b(k) + increment;
      body_forces(u_moved, h1);
      blocks.dh_du.col(k) = (h1 - h0) / increment;
      u_moved(k) = u_b(k);
    }
    blocks.L = RateByAngularVelocity(x_b.segment<4>(3));
    blocks.L_plus = (blocks.L.transpose() * blocks.L).inverse() * blocks.L.transpose();
    const Eigen::Vector3d w_B = u_b.segment<3>(3);
    blocks.D = RateByEulerParameters(w_B);
    blocks.w_squared = w_B.squaredNorm();
  }
}

void KktNewtonSolver::EvaluateConstraints(double t, const Eigen::Ref<const VectorXd>& y) {
  // G over the kept rows, each row over the velocities of its joint's bodies (zeros included, so
  // the pattern does not depend on the pose).
  const SystemConstraints c = system_.Constraints(t, y);
  const std::vector<Index> kept = system_.KeptConstraints();
  std::vector<Triplet> g;
  for (std::size_t i = 0; i < kept.size(); ++i) {
    const Joint& joint = system_.joint(system_.JointOfConstraint(kept[i]));
    for (const MarkerRef* marker : {&joint.marker_i(), &joint.marker_j()}) {
      if (marker->is_ground()) continue;
      const BodyBlocks& blocks = bodies_[static_cast<std::size_t>(marker->body)];
      for (Index j = blocks.pu; j < blocks.pu + blocks.nu; ++j) {
        g.emplace_back(static_cast<int>(i), static_cast<int>(j), c.G(kept[i], j));
      }
    }
  }
  G_.resize(static_cast<Index>(kept.size()), system_.num_velocities());
  G_.setFromTriplets(g.begin(), g.end());
  EvaluateGammaDifferences(t, y, kept);
}

void KktNewtonSolver::Evaluate(double t, Eigen::Ref<const VectorXd> y) {
  ScopedTimer timer(times_.evaluate);
  const Index nu = system_.num_velocities();
  FLEXMBS_CHECK(y.size() == system_.state_size(),
                fmt::format("KktNewtonSolver: state of size {} for a system of {}", y.size(), system_.state_size()));
  t_ = t;
  omega_ = system_.constraint_settings().baumgarte_frequency;
  // The bodies' dh at the accelerations of (t, y), as SystemJacobian takes them.
  VectorXd u_dot(nu), lambda(system_.num_constraints());
  system_.Accelerations(t, y, u_dot, lambda);
  EvaluateBodies(t, y, u_dot);
  EvaluateForceElements(t, y);
  EvaluateConstraints(t, y);
  // dh/dx over the system (for the right-hand side): the bodies' blocks and the elements' entries.
  std::vector<Triplet> dh_dx(element_dh_dx_);
  for (const BodyBlocks& blocks : bodies_) {
    for (Index j = 0; j < blocks.nu; ++j) {
      for (Index i = 0; i < blocks.nu; ++i) {
        if (blocks.dh_dx(i, j) == 0.0) continue;
        dh_dx.emplace_back(static_cast<int>(blocks.pu + i), static_cast<int>(blocks.pu + j), blocks.dh_dx(i, j));
      }
    }
  }
  dh_dx_.resize(nu, nu);
  dh_dx_.setFromTriplets(dh_dx.begin(), dh_dx.end());
  evaluated_ = true;
  factorized_ = false;
  ++times_.evaluations;
}

void KktNewtonSolver::Factorize(double gamma) {
  ScopedTimer timer(times_.factorize);
  FLEXMBS_CHECK(evaluated_ && gamma > 0.0, fmt::format("KktNewtonSolver::Factorize(gamma = {}) before Evaluate "
                                                       "or with gamma <= 0",
                                                       gamma));
  gamma_ = gamma;
  const Index nu = system_.num_velocities(), m = G_.rows();
  // Per body E = (I4 - gamma D)^-1 = (I4 + gamma D) / (1 + gamma^2 |w|^2 / 4) (D skew with
  // D^2 = -|w|^2 / 4 I4), W = L^+ E L; and which body and local index each velocity has.
  std::vector<int> body_of(static_cast<std::size_t>(nu));
  for (std::size_t b = 0; b < bodies_.size(); ++b) {
    BodyBlocks& blocks = bodies_[b];
    blocks.E = (Eigen::Matrix4d::Identity() + gamma * blocks.D) / (1.0 + 0.25 * gamma * gamma * blocks.w_squared);
    blocks.W = blocks.L_plus * blocks.E * blocks.L;
    for (Index k = 0; k < blocks.nu; ++k) body_of[static_cast<std::size_t>(blocks.pu + k)] = static_cast<int>(b);
  }
  // Adds the entry (row, column, value) of a matrix times (scale_identity I + scale_w W~),
  // W~ = blkdiag(I3, W, I_n): an entry in a rotation column spreads over its body's three.
  std::vector<Triplet> entries;
  const auto add_times_w = [&](Index row, Index column, double value, double scale_identity, double scale_w) {
    const BodyBlocks& blocks = bodies_[static_cast<std::size_t>(body_of[static_cast<std::size_t>(column)])];
    const Index local = column - blocks.pu;
    if (local < 3 || local >= 6) {
      entries.emplace_back(static_cast<int>(row), static_cast<int>(column), (scale_identity + scale_w) * value);
      return;
    }
    for (Index k = 0; k < 3; ++k) {
      const double factor = (k == local - 3 ? scale_identity : 0.0) + scale_w * blocks.W(local - 3, k);
      entries.emplace_back(static_cast<int>(row), static_cast<int>(blocks.pu + 3 + k), factor * value);
    }
  };
  // M - gamma dh/du - gamma^2 dh/dx W~: the bodies' blocks dense (the pattern stays), then the
  // force elements' entries.
  for (const BodyBlocks& blocks : bodies_) {
    MatrixXd dh_dx_W = blocks.dh_dx;
    dh_dx_W.middleCols<3>(3) = blocks.dh_dx.middleCols<3>(3) * blocks.W;
    const MatrixXd top_left = blocks.M - gamma * blocks.dh_du - gamma * gamma * dh_dx_W;
    for (Index j = 0; j < blocks.nu; ++j) {
      for (Index i = 0; i < blocks.nu; ++i) {
        entries.emplace_back(static_cast<int>(blocks.pu + i), static_cast<int>(blocks.pu + j), top_left(i, j));
      }
    }
  }
  for (const Triplet& e : element_dh_du_) entries.emplace_back(e.row(), e.col(), -gamma * e.value());
  for (const Triplet& e : element_dh_dx_) add_times_w(e.row(), e.col(), e.value(), 0.0, -gamma * gamma);
  // G^T, and G ((1 + 2 gamma omega) I + gamma^2 omega^2 W~) - gamma dgamma_c/du.
  const double identity_part = 1.0 + 2.0 * gamma * omega_, w_part = gamma * gamma * omega_ * omega_;
  for (Index i = 0; i < m; ++i) {
    for (Eigen::SparseMatrix<double, Eigen::RowMajor>::InnerIterator it(G_, i); it; ++it) {
      entries.emplace_back(static_cast<int>(it.col()), static_cast<int>(nu + i), it.value());
      add_times_w(nu + i, it.col(), it.value(), identity_part, w_part);
    }
  }
  for (const Triplet& e : gamma_du_) entries.emplace_back(static_cast<int>(nu) + e.row(), e.col(), -gamma * e.value());
  dropped_ = DroppedVelocities(system_);
  if (!dropped_.empty()) KeepPlanarColumns(dropped_, entries);
  kkt_.resize(nu + m, nu + m);
  kkt_.setFromTriplets(entries.begin(), entries.end());
  kkt_.makeCompressed();

  Factor& f = *factor_;
  if (!f.have_pattern || !SamePattern(kkt_, f.analysed)) {
    f.lu.analyzePattern(kkt_);
    f.analysed = kkt_;
    f.have_pattern = true;
  }
  f.lu.factorize(kkt_);
  if (f.lu.info() != Eigen::Success) {
    throw SimulationError(t_, fmt::format("integration failed at t = {} s: the sparse Newton matrix (gamma = {} s) "
                                          "is singular: {}",
                                          t_, gamma, f.lu.lastErrorMessage()));
  }
  factorized_ = true;
  ++times_.factorizations;
}

VectorXd KktNewtonSolver::VelocitySpacePositionResidual(const Eigen::Ref<const VectorXd>& r_x) const {
  VectorXd rho(system_.num_velocities());
  for (const BodyBlocks& blocks : bodies_) {
    const Index n = blocks.nu - 6;
    rho.segment<3>(blocks.pu) = r_x.segment<3>(blocks.px);
    rho.segment<3>(blocks.pu + 3) = blocks.L_plus * blocks.E * r_x.segment<4>(blocks.px + 3);
    rho.segment(blocks.pu + 6, n) = r_x.segment(blocks.px + 7, n);
  }
  return rho;
}

void KktNewtonSolver::Solve(Eigen::Ref<VectorXd> r) {
  ScopedTimer timer(times_.solve);
  FLEXMBS_CHECK(factorized_ && r.size() == system_.state_size(),
                fmt::format("KktNewtonSolver::Solve: a vector of size {} (system {}) or no factorisation", r.size(),
                            system_.state_size()));
  const Index nx = system_.num_positions(), nu = system_.num_velocities(), m = G_.rows();
  const auto r_x = r.head(nx);
  const auto r_u = r.tail(nu);
  const VectorXd rho = VelocitySpacePositionResidual(r_x);
  VectorXd rhs(nu + m);
  for (const BodyBlocks& blocks : bodies_) {
    rhs.segment(blocks.pu, blocks.nu).noalias() = blocks.M * r_u.segment(blocks.pu, blocks.nu);
  }
  rhs.head(nu) += gamma_ * (dh_dx_ * rho);
  VectorXd constrained = r_u - gamma_ * omega_ * omega_ * rho;
  for (std::size_t i = 0; i < dropped_.size(); ++i) {
    if (dropped_[i] == 0) continue;
    rhs(static_cast<Index>(i)) = r_u(static_cast<Index>(i));
    constrained(static_cast<Index>(i)) = 0.0;
  }
  rhs.tail(m) = G_ * constrained;
  const VectorXd du = factor_->lu.solve(rhs).head(nu);
  for (const BodyBlocks& blocks : bodies_) {
    const Index n = blocks.nu - 6;
    auto dx = r.segment(blocks.px, blocks.nu + 1);
    dx.head<3>() += gamma_ * du.segment<3>(blocks.pu);
    dx.segment<4>(3) = blocks.E * (dx.segment<4>(3) + gamma_ * blocks.L * du.segment<3>(blocks.pu + 3));
    dx.tail(n) += gamma_ * du.segment(blocks.pu + 6, n);
  }
  r.tail(nu) = du;
  ++times_.solves;
}

}  // namespace flexmbs::mbs
