#include "mbs/multibody_system.h"

#include <fmt/format.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <initializer_list>
#include <utility>

#include "core/error.h"
#include "mbs/constraint_solver.h"

namespace flexmbs::mbs {
namespace {

template <typename Items, typename NameOf>
void RequireNewName(const Items& items, const std::string& name, std::string_view kind, NameOf name_of) {
  for (const auto& item : items) {
    if (name_of(item) == name) throw InputError(fmt::format("{} '{}' defined twice", kind, name));
  }
}

/// Throws InputError "<kind> '<name>': body index <b> is not in the system" for a marker on a
/// body outside [0, num_bodies) (the ground is allowed).
void RequireBodiesInSystem(std::initializer_list<const MarkerRef*> markers, int num_bodies, std::string_view kind,
                           const std::string& name) {
  for (const MarkerRef* marker : markers) {
    if (marker->body != kGround && (marker->body < 0 || marker->body >= num_bodies)) {
      throw InputError(fmt::format("{} '{}': body index {} is not in the system", kind, name, marker->body));
    }
  }
}

}  // namespace

MultibodySystem::MultibodySystem(const Eigen::Vector3d& g_W) : g_W_(g_W) {}

int MultibodySystem::AddBody(std::unique_ptr<Body> body) {
  FLEXMBS_CHECK(body != nullptr, "MultibodySystem::AddBody: null body");
  RequireNewName(bodies_, body->name(), "body", [](const auto& b) { return b->name(); });
  // Positions of all bodies come first in y: the velocities move back by n_x of the new body.
  position_offsets_.push_back(num_positions_);
  velocity_blocks_.push_back({num_velocities_, body->num_velocities()});
  num_positions_ += body->num_positions();
  num_velocities_ += body->num_velocities();
  bodies_.push_back(std::move(body));
  return num_bodies() - 1;
}

int MultibodySystem::AddJoint(Joint joint) {
  RequireNewName(joints_, joint.name(), "joint", [](const Joint& j) { return j.name(); });
  RequireBodiesInSystem({&joint.marker_i(), &joint.marker_j()}, num_bodies(), "joint", joint.name());
  constraint_offsets_.push_back(num_constraints_);
  num_constraints_ += joint.num_equations();
  joints_.push_back(std::move(joint));
  return num_joints() - 1;
}

int MultibodySystem::AddForceElement(std::unique_ptr<ForceElement> element) {
  FLEXMBS_CHECK(element != nullptr, "MultibodySystem::AddForceElement: null element");
  RequireNewName(force_elements_, element->name(), "force element", [](const auto& e) { return e->name(); });
  element_state_starts_.push_back(num_element_states_);
  num_element_states_ += element->num_states();
  force_elements_.push_back(std::move(element));
  return num_force_elements() - 1;
}

int MultibodySystem::AddUnilateralContact(std::unique_ptr<UnilateralContact> contact) {
  FLEXMBS_CHECK(contact != nullptr, "MultibodySystem::AddUnilateralContact: null contact");
  RequireNewName(unilateral_contacts_, contact->name(), "contact", [](const auto& c) { return c->name(); });
  RequireBodiesInSystem({&contact->marker_a(), &contact->marker_b()}, num_bodies(), "contact", contact->name());
  unilateral_contacts_.push_back(std::move(contact));
  return num_unilateral_contacts() - 1;
}

int MultibodySystem::FindBody(std::string_view name) const {
  for (int b = 0; b < num_bodies(); ++b) {
    if (body(b).name() == name) return b;
  }
  return -1;
}

MarkerRef MultibodySystem::Marker(std::string_view body_name, std::string_view marker_name) const {
  const int b = FindBody(body_name);
  if (b < 0) throw InputError(fmt::format("marker '{}' of body '{}': no such body", marker_name, body_name));
  const int marker = body(b).FindMarker(marker_name);
  if (marker < 0) throw InputError(fmt::format("body '{}' has no marker '{}'", body_name, marker_name));
  return MarkerRef::OnBody(b, marker);
}

int MultibodySystem::FirstElementWithStates() const {
  for (int k = 0; k < num_force_elements(); ++k) {
    if (force_element(k).num_states() > 0) return k;
  }
  return -1;
}

int MultibodySystem::JointOfConstraint(Eigen::Index row) const {
  FLEXMBS_CHECK(row >= 0 && row < num_constraints_, "MultibodySystem::JointOfConstraint: row out of range");
  const auto after = std::upper_bound(constraint_offsets_.begin(), constraint_offsets_.end(), row);
  return static_cast<int>(after - constraint_offsets_.begin()) - 1;
}

std::string MultibodySystem::DescribeConstraintRow(Eigen::Index row) const {
  const int k = JointOfConstraint(row);
  return fmt::format("'{}' row {} of {}", joint(k).name(), row - constraint_offset(k) + 1, joint(k).num_equations());
}

void MultibodySystem::set_dropped_constraints(std::vector<Eigen::Index> rows) {
  for (std::size_t i = 0; i < rows.size(); ++i) {
    FLEXMBS_CHECK(rows[i] >= 0 && rows[i] < num_constraints_ && (i == 0 || rows[i] > rows[i - 1]),
                  "MultibodySystem::set_dropped_constraints: rows ascending, distinct and in range");
  }
  dropped_constraints_ = std::move(rows);
}

std::vector<Eigen::Index> MultibodySystem::KeptConstraints() const {
  std::vector<Eigen::Index> kept;
  kept.reserve(static_cast<std::size_t>(num_constraints_));
  auto dropped = dropped_constraints_.begin();
  for (Eigen::Index row = 0; row < num_constraints_; ++row) {
    if (dropped != dropped_constraints_.end() && *dropped == row) {
      ++dropped;
    } else {
      kept.push_back(row);
    }
  }
  return kept;
}

std::vector<Eigen::Index> MultibodySystem::KeptVelocities(int b) const {
  if (planar()) return kept_velocities_.at(static_cast<std::size_t>(b));
  std::vector<Eigen::Index> all(static_cast<std::size_t>(velocity_block(b).size));
  for (std::size_t i = 0; i < all.size(); ++i) all[i] = static_cast<Eigen::Index>(i);
  return all;
}

std::vector<Eigen::Index> MultibodySystem::KeptVelocities() const {
  std::vector<Eigen::Index> kept;
  kept.reserve(static_cast<std::size_t>(num_velocities_));
  for (int b = 0; b < num_bodies(); ++b) {
    for (const Eigen::Index column : KeptVelocities(b)) kept.push_back(velocity_block(b).start + column);
  }
  return kept;
}

void MultibodySystem::set_kept_velocities(std::vector<std::vector<Eigen::Index>> columns) {
  FLEXMBS_CHECK(columns.empty() || static_cast<int>(columns.size()) == num_bodies(),
                "MultibodySystem::set_kept_velocities: one list per body");
  for (std::size_t b = 0; b < columns.size(); ++b) {
    const std::vector<Eigen::Index>& kept = columns[b];
    for (std::size_t i = 0; i < kept.size(); ++i) {
      FLEXMBS_CHECK(kept[i] >= 0 && kept[i] < velocity_block(static_cast<int>(b)).size && (i == 0 || kept[i] > kept[i - 1]),
                    "MultibodySystem::set_kept_velocities: columns ascending, distinct and in the body's block");
    }
  }
  kept_velocities_ = std::move(columns);
}

Eigen::VectorXd MultibodySystem::NeutralState() const {
  Eigen::VectorXd y = Eigen::VectorXd::Zero(state_size());
  for (int b = 0; b < num_bodies(); ++b) y(position_offset(b) + 3) = 1.0;
  for (int k = 0; k < num_force_elements(); ++k) {
    force_element(k).InitialStates(y.segment(element_state_offset(k), force_element(k).num_states()));
  }
  return y;
}

Eigen::Map<const Eigen::VectorXd> MultibodySystem::ElementStates(const ConstVectorRef& y,
                                                                 const ForceElement& element) const {
  for (int k = 0; k < num_force_elements(); ++k) {
    if (&force_element(k) == &element) return {y.data() + element_state_offset(k), element.num_states()};
  }
  FLEXMBS_CHECK(false, fmt::format("MultibodySystem::ElementStates: '{}' is not in the system", element.name()));
  return {nullptr, 0};
}

Eigen::Map<const Eigen::VectorXd> MultibodySystem::BodyPositions(const ConstVectorRef& y, int b) const {
  return {y.data() + position_offset(b), body(b).num_positions()};
}

Eigen::Map<const Eigen::VectorXd> MultibodySystem::BodyVelocities(const ConstVectorRef& y, int b) const {
  const VelocityBlock& block = velocity_block(b);
  return {y.data() + num_positions_ + block.start, block.size};
}

void MultibodySystem::SetBodyState(int b, const ConstVectorRef& x_b, const ConstVectorRef& u_b,
                                   Eigen::Ref<Eigen::VectorXd> y) const {
  const VelocityBlock& block = velocity_block(b);
  FLEXMBS_CHECK(x_b.size() == body(b).num_positions() && u_b.size() == block.size,
                "MultibodySystem::SetBodyState: sizes do not match the body");
  y.segment(position_offset(b), x_b.size()) = x_b;
  y.segment(num_positions_ + block.start, block.size) = u_b;
}

MarkerKinematics MultibodySystem::MarkerState(const MarkerRef& marker, const ConstVectorRef& y) const {
  if (marker.is_ground()) {
    MarkerKinematics ground;
    ground.p_WM_W = marker.p_WM_W;
    ground.R_WM = marker.R_WM;
    ground.jacobian.resize(6, 0);
    return ground;
  }
  return body(marker.body).Marker(marker.marker, BodyPositions(y, marker.body), BodyVelocities(y, marker.body));
}

void MultibodySystem::AddMarkerLoad(const MarkerRef& marker, const MarkerKinematics& kinematics,
                                    const Eigen::Vector3d& f_W, const Eigen::Vector3d& tau_W,
                                    Eigen::Ref<Eigen::VectorXd> h) const {
  if (marker.is_ground()) return;
  const VelocityBlock& block = velocity_block(marker.body);
  h.segment(block.start, block.size) += GeneralizedForce(kinematics, f_W, tau_W);
}

Eigen::MatrixXd MultibodySystem::BodyMassMatrix(int b, const ConstVectorRef& y) const {
  const Eigen::Index n = velocity_block(b).size;
  Eigen::MatrixXd M(n, n);
  body(b).MassMatrix(BodyPositions(y, b), M);
  return M;
}

Eigen::VectorXd MultibodySystem::Forces(double t, const ConstVectorRef& y) const {
  Eigen::VectorXd h(num_velocities_);
  for (int b = 0; b < num_bodies(); ++b) {
    const VelocityBlock& block = velocity_block(b);
    body(b).Forces(t, BodyPositions(y, b), BodyVelocities(y, b), g_W_, h.segment(block.start, block.size));
  }
  for (const auto& element : force_elements_) element->AddForces(t, *this, y, h);
  return h;
}

SystemConstraints MultibodySystem::Constraints(double t, const ConstVectorRef& y) const {
  SystemConstraints c;
  c.g.resize(num_constraints_);
  c.g_t.resize(num_constraints_);
  c.gamma.resize(num_constraints_);
  c.G = Eigen::MatrixXd::Zero(num_constraints_, num_velocities_);
  for (int k = 0; k < num_joints(); ++k) {
    const Joint& j = joint(k);
    const JointEquations e = j.Evaluate(t, MarkerState(j.marker_i(), y), MarkerState(j.marker_j(), y));
    const Eigen::Index row = constraint_offset(k), m = j.num_equations();
    c.g.segment(row, m) = e.g;
    c.g_t.segment(row, m) = e.g_t;
    c.gamma.segment(row, m) = e.gamma;
    if (!j.marker_i().is_ground()) c.G.block(row, velocity_block(j.marker_i().body).start, m, e.G_i.cols()) += e.G_i;
    if (!j.marker_j().is_ground()) c.G.block(row, velocity_block(j.marker_j().body).start, m, e.G_j.cols()) += e.G_j;
  }
  return c;
}

bool MultibodySystem::AccelerationDependentForces(const ConstVectorRef& y, const ConstVectorRef& u_dot,
                                                  Eigen::Ref<Eigen::VectorXd> h) const {
  h.setZero();
  bool any = false;
  for (int b = 0; b < num_bodies(); ++b) {
    const VelocityBlock& block = velocity_block(b);
    any = body(b).AddAccelerationDependentForces(BodyPositions(y, b), BodyVelocities(y, b),
                                                 u_dot.segment(block.start, block.size),
                                                 h.segment(block.start, block.size)) ||
          any;
  }
  return any;
}

void MultibodySystem::Accelerations(double t, const ConstVectorRef& y, Eigen::Ref<Eigen::VectorXd> u_dot,
                                    Eigen::Ref<Eigen::VectorXd> lambda) const {
  const Eigen::VectorXd h = Forces(t, y);
  const SystemConstraints c = Constraints(t, y);
  const ConstraintSolver solver(*this, t, y, c.G);
  if (num_constraints_ > 0) solver.RequireFullRank(t, settings_.singular_pivot);
  // u' = M^-1 (r + G^T lambda) with G u' = target: lambda = S^-1 (target - G M^-1 r).
  const auto solve = [&](const Eigen::VectorXd& r, const Eigen::VectorXd& target, Eigen::Ref<Eigen::VectorXd> out,
                         Eigen::Ref<Eigen::VectorXd> multipliers) {
    out = solver.SolveMass(r);
    if (num_constraints_ == 0) return;
    multipliers = solver.SolveSchur(target - solver.constraint_jacobian() * out);
    out += solver.mass_inverse_G_transpose() * multipliers;
  };
  const double omega = settings_.baumgarte_frequency;
  const Eigen::VectorXd u = Velocities(y);
  // G u' = gamma - 2 omega (G u + g_t) - omega^2 g.
  const Eigen::VectorXd G_u = solver.constraint_jacobian() * u;
  const Eigen::VectorXd target = c.gamma - 2.0 * omega * (G_u + c.g_t) - omega * omega * c.g;
  solve(h, target, u_dot, lambda);
  // The corrector: the acceleration-dependent forces at the first u', solved with a zero target.
  Eigen::VectorXd h_a(num_velocities_);
  if (!AccelerationDependentForces(y, u_dot, h_a)) return;
  Eigen::VectorXd du(num_velocities_), dlambda(num_constraints_);
  solve(h_a, Eigen::VectorXd::Zero(num_constraints_), du, dlambda);
  u_dot += du;
  lambda += dlambda;
}

void MultibodySystem::Derivative(double t, const ConstVectorRef& y, Eigen::Ref<Eigen::VectorXd> y_dot) const {
  for (int b = 0; b < num_bodies(); ++b) {
    PositionDerivative(BodyPositions(y, b), BodyVelocities(y, b),
                       y_dot.segment(position_offset(b), body(b).num_positions()));
  }
  Eigen::VectorXd lambda(num_constraints_);
  Accelerations(t, y, y_dot.segment(num_positions_, num_velocities_), lambda);
  for (int k = 0; k < num_force_elements(); ++k) {
    const Eigen::Index n = force_element(k).num_states();
    if (n > 0) force_element(k).StateDerivatives(t, *this, y, y_dot.segment(element_state_offset(k), n));
  }
}

JointLoad MultibodySystem::ConstraintLoad(int k, double t, const ConstVectorRef& y, const ConstVectorRef& lambda) const {
  const Joint& j = joint(k);
  const JointEquations e = j.Evaluate(t, MarkerState(j.marker_i(), y), MarkerState(j.marker_j(), y));
  const Eigen::Matrix<double, 6, 1> load = e.D_J.transpose() * lambda.segment(constraint_offset(k), j.num_equations());
  return {load.head<3>(), load.tail<3>()};
}

void MultibodySystem::DisplacePositions(const ConstVectorRef& du, Eigen::Ref<Eigen::VectorXd> y) const {
  for (int b = 0; b < num_bodies(); ++b) {
    const Eigen::Index px = position_offset(b), pu = velocity_block(b).start, n = body(b).num_modes();
    y.segment<3>(px) += du.segment<3>(pu);
    const Eigen::Vector3d rotation = du.segment<3>(pu + 3);
    const Eigen::Quaterniond e(y(px + 3), y(px + 4), y(px + 5), y(px + 6));
    const double angle = rotation.norm();
    const Eigen::Quaterniond step =
        angle > 0.0 ? Eigen::Quaterniond(Eigen::AngleAxisd(angle, rotation / angle)) : Eigen::Quaterniond::Identity();
    const Eigen::Quaterniond moved = e * step;
    y.segment<4>(px + 3) << moved.w(), moved.x(), moved.y(), moved.z();
    y.segment(px + 7, n) += du.segment(pu + 6, n);
  }
}

double MultibodySystem::NormalizeEulerParameters(Eigen::Ref<Eigen::VectorXd> y) const {
  double worst = 0.0;
  for (int b = 0; b < num_bodies(); ++b) {
    auto e = y.segment<4>(position_offset(b) + 3);
    const double norm = e.norm();
    worst = std::max(worst, std::abs(norm - 1.0));
    e /= norm;
  }
  return worst;
}

double MultibodySystem::KineticEnergy(const ConstVectorRef& y) const {
  double energy = 0.0;
  for (int b = 0; b < num_bodies(); ++b) energy += body(b).KineticEnergy(BodyPositions(y, b), BodyVelocities(y, b));
  return energy;
}

double MultibodySystem::PotentialEnergy(double t, const ConstVectorRef& y) const {
  double energy = 0.0;
  for (int b = 0; b < num_bodies(); ++b) energy += body(b).PotentialEnergy(BodyPositions(y, b), g_W_);
  for (const auto& element : force_elements_) energy += element->PotentialEnergy(t, *this, y);
  return energy;
}

}  // namespace flexmbs::mbs
