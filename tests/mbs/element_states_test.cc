// Force elements with states of their own (docs/mbs.md, "Force elements with states"): a Maxwell
// element (a spring in series with a dashpot, the junction's position its state) on a free mass,
// against the closed form of the damped oscillator it makes; its Jacobian blocks against central
// differences of the system's y'; and the methods that refuse states.
//
// The element, along W's x: the dashpot from the ground at x = 0 to the junction at z, the spring
// (free length 0) from the junction to the marker at x_M. F = k (x_M - z) pulls the marker
// towards the ground, c z' = F moves the junction. With w = x_M - z and the body's velocity v:
//   m v' = -k w,   w' = v - (k / c) w   =>   w'' + (k / c) w' + (k / m) w = 0,
// so from x_M = z = 0, v = v0: w = v0 / omega_d e^(-a t) sin(omega_d t) (a = k / (2 c),
// omega_d = sqrt(k / m - a^2)), v = v0 - (k / m) int_0^t w.
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <cmath>
#include <complex>
#include <algorithm>
#include <cstdio>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "mbs/force_element.h"
#include "mbs/multibody_system.h"
#include "mbs/rigid_body.h"
#include "mbs/simulation.h"
#include "mbs/system_jacobian.h"
#include "tests/input_error.h"

namespace flexmbs::mbs {
namespace {

using Eigen::Index;
using Eigen::MatrixXd;
using Eigen::Vector3d;
using Eigen::VectorXd;

/// The Maxwell element of the file comment between the ground and `marker`; state s = [z] [m].
class MaxwellElement final : public ForceElement {
 public:
  MaxwellElement(MarkerRef marker, double stiffness, double damping)
      : marker_(std::move(marker)), k_(stiffness), c_(damping) {}
  const std::string& name() const override { return name_; }
  Index num_states() const override { return 1; }
  void AddForces(double /*t*/, const MultibodySystem& system, const ConstVectorRef& y,
                 Eigen::Ref<VectorXd> h) const override {
    const MarkerKinematics m = system.MarkerState(marker_, y);
    system.AddMarkerLoad(marker_, m, -Tension(system, m, y) * Vector3d::UnitX(), Vector3d::Zero(), h);
  }
  void StateDerivatives(double /*t*/, const MultibodySystem& system, const ConstVectorRef& y,
                        Eigen::Ref<VectorXd> s_dot) const override {
    s_dot(0) = Tension(system, system.MarkerState(marker_, y), y) / c_;
  }
  /// Exact for a marker at the body's origin (the tests' one): x_M moves by the jacobian's v row.
  void AddForceJacobian(double /*t*/, const MultibodySystem& system, const ConstVectorRef& y,
                        Eigen::Ref<MatrixXd> dh_dx, Eigen::Ref<MatrixXd> /*dh_du*/) const override {
    const VelocityBlock& block = system.velocity_block(marker_.body);
    const VectorXd e = XRow(system, y).transpose();
    dh_dx.block(block.start, block.start, block.size, block.size) -= k_ * e * e.transpose();
  }
  void AddStateJacobian(double /*t*/, const MultibodySystem& system, const ConstVectorRef& y,
                        ElementStateJacobian& jacobian) const override {
    const VelocityBlock& block = system.velocity_block(marker_.body);
    const Eigen::RowVectorXd e = XRow(system, y);
    jacobian.ds_dx.block(0, block.start, 1, block.size) += k_ / c_ * e;
    jacobian.ds_ds(0, 0) -= k_ / c_;
    jacobian.dh_ds.block(block.start, 0, block.size, 1) += k_ * e.transpose();
  }

 private:
  double Tension(const MultibodySystem& system, const MarkerKinematics& m, const ConstVectorRef& y) const {
    return k_ * (m.p_WM_W.x() - system.ElementStates(y, *this)(0));
  }
  /// dx_M / du_b: the jacobian's first row.
  Eigen::RowVectorXd XRow(const MultibodySystem& system, const ConstVectorRef& y) const {
    return system.MarkerState(marker_, y).jacobian.row(0);
  }

  std::string name_ = "maxwell";
  MarkerRef marker_;
  double k_, c_;
};

constexpr double kMass = 2.0;      // [kg]
constexpr double kStiffness = 200.0;  // [N/m]: sqrt(k / m) = 10 rad/s
constexpr double kSpeed = 0.5;     // v0 [m/s]

/// A free rigid body (a unit-inertia sphere of kMass) moving along x at kSpeed, gravity off, the
/// Maxwell element of damping c on its origin.
struct MaxwellScene {
  MultibodySystem system{Vector3d::Zero()};
  VectorXd y0;

  explicit MaxwellScene(double damping) {
    std::vector<RigidBodyMarker> markers{{"origin", Vector3d::Zero(), Eigen::Matrix3d::Identity()}};
    system.AddBody(std::make_unique<RigidBody>("mass", kMass, Vector3d::Zero(), Eigen::Matrix3d::Identity(),
                                               std::move(markers)));
    system.AddForceElement(std::make_unique<MaxwellElement>(system.Marker("mass", "origin"), kStiffness, damping));
    y0 = system.NeutralState();
    y0(system.num_positions()) = kSpeed;
  }
};

/// The closed form of the file comment at t: w = x_M - z and v, from the roots r_1,2 = -a +- sqrt(a^2 -
/// omega_0^2) of r^2 + (k / c) r + k / m (complex for light damping): w = v0 (e^(r1 t) - e^(r2 t)) /
/// (r1 - r2), v = v0 - (k / m) v0 / (r1 - r2) ((e^(r1 t) - 1) / r1 - (e^(r2 t) - 1) / r2).
struct MaxwellMotion {
  double w = 0.0, v = 0.0;
};
MaxwellMotion ClosedForm(double damping, double t) {
  const double a = kStiffness / (2.0 * damping);
  const std::complex<double> root = std::sqrt(std::complex<double>(a * a - kStiffness / kMass));
  const std::complex<double> r1 = -a + root, r2 = -a - root, e1 = std::exp(r1 * t), e2 = std::exp(r2 * t);
  const std::complex<double> w = kSpeed * (e1 - e2) / (r1 - r2);
  const std::complex<double> integral = kSpeed / (r1 - r2) * ((e1 - 1.0) / r1 - (e2 - 1.0) / r2);
  return {w.real(), kSpeed - kStiffness / kMass * integral.real()};
}

/// Runs the scene to 1 s with `method` and returns the largest errors of w and v against the
/// closed form over the outputs, relative to v0 / omega_0 and v0; and the steps.
struct RunErrors {
  double w = 0.0, v = 0.0;
  long steps = 0;
};
RunErrors RunMaxwell(double damping, OdeMethod method) {
  MaxwellScene scene(damping);
  SimulationOptions options;
  options.end_time = 1.0;
  options.output_interval = 0.05;
  options.integrator.method = method;
  options.integrator.relative_tolerance = 1e-10;
  options.integrator.absolute_tolerance = 1e-12;
  RunErrors errors;
  const Index nx = scene.system.num_positions();
  const double w_scale = kSpeed / std::sqrt(kStiffness / kMass);
  const SimulationStatistics statistics = Simulate(scene.system, options, scene.y0, [&](double t, const VectorXd& y,
                                                                                        const VectorXd&) {
    const MaxwellMotion exact = ClosedForm(damping, t);
    const double w = y(0) - y(scene.system.element_state_offset(0));
    ASSERT_TRUE(std::isfinite(exact.w) && std::isfinite(exact.v));
    errors.w = std::max(errors.w, std::abs(w - exact.w) / w_scale);
    errors.v = std::max(errors.v, std::abs(y(nx) - exact.v) / kSpeed);
  });
  errors.steps = statistics.integrator.steps;
  return errors;
}

TEST(ElementStates, LayoutAndInitialStates) {
  MaxwellScene scene(10.0);
  const MultibodySystem& system = scene.system;
  EXPECT_EQ(system.num_element_states(), 1);
  EXPECT_EQ(system.state_size(), 7 + 6 + 1);
  EXPECT_EQ(system.element_state_offset(0), 13);
  EXPECT_EQ(system.FirstElementWithStates(), 0);
  EXPECT_EQ(system.Velocities(scene.y0)(0), kSpeed);
  EXPECT_EQ(system.ElementStates(scene.y0, system.force_element(0))(0), 0.0);
}

// Lightly damped (zeta = a / omega_0 = 0.1): the explicit and the implicit method follow the
// closed form. Measured (rtol 1e-10): explicit w 4.1e-11, v 3.9e-11 (336 steps); implicit w
// 9.3e-9, v 8.8e-9 (514 steps).
TEST(ElementStates, MaxwellOscillatorMatchesClosedForm) {
  const double damping = kStiffness / (2.0 * 0.1 * 10.0);
  for (const auto& [method, bound] : {std::pair{OdeMethod::kExplicit, 4e-10}, std::pair{OdeMethod::kImplicit, 9e-8}}) {
    const RunErrors e = RunMaxwell(damping, method);
    std::printf("Maxwell zeta 0.1 %s: w %.2e, v %.2e, %ld steps\n", std::string(OdeMethodName(method)).c_str(),
                e.w, e.v, e.steps);
    EXPECT_LT(e.w, bound);
    EXPECT_LT(e.v, bound);
  }
}

// A stiff state: c = 0.02 N s/m puts the junction's time constant near c / k = 1e-4 s beside the
// slow motion (roots -1e4 and -0.01 1/s of w'' + (k/c) w' + (k/m) w). The implicit method, with the
// state's blocks in its Newton matrix, steps over it; the explicit one is held at its stability
// limit. Measured: implicit w 2.2e-12, v 1.2e-11 in 69 steps; explicit w 5.4e-9, v 5.4e-12 in
// 3079 steps.
TEST(ElementStates, StiffStateTakesTheImplicitMethod) {
  const double damping = 0.02;
  const RunErrors implicit = RunMaxwell(damping, OdeMethod::kImplicit);
  const RunErrors explicit_run = RunMaxwell(damping, OdeMethod::kExplicit);
  std::printf("Maxwell c/k = 1e-4 s: implicit w %.2e v %.2e in %ld steps; explicit w %.2e v %.2e in %ld steps\n",
              implicit.w, implicit.v, implicit.steps, explicit_run.w, explicit_run.v, explicit_run.steps);
  EXPECT_LT(implicit.w, 2e-11);
  EXPECT_LT(implicit.v, 1.2e-10);
  EXPECT_LT(explicit_run.w, 5e-8);
  EXPECT_LT(10 * implicit.steps, explicit_run.steps);
}

// SystemJacobian's state rows and columns against central differences of y' (increments 1e-6):
// the element is linear in x_M, z and the body's motion along x, so the blocks are exact.
// Measured: 4.6e-10 of the largest entry, 100 (k / m, k / c): 4.6e-12 relative.
TEST(ElementStates, JacobianBlocksMatchDifferences) {
  MaxwellScene scene(3.0);
  const MultibodySystem& system = scene.system;
  VectorXd y = scene.y0;
  y(0) = 0.02;                                // x_M [m]
  y(system.element_state_offset(0)) = -0.01;  // z [m]
  const Index n = system.state_size(), nx = system.num_positions();
  MatrixXd model(n, n);
  SystemJacobian(system, 0.0, y, model);
  const double increment = 1e-6;
  VectorXd plus(n), minus(n);
  double worst = 0.0;
  // The columns of p, v and s (the rotation's are the quaternion's, not differenced here).
  for (const Index column : {Index{0}, Index{1}, Index{2}, nx, nx + 1, nx + 2, system.element_state_offset(0)}) {
    VectorXd moved = y;
    moved(column) += increment;
    system.Derivative(0.0, moved, plus);
    moved(column) -= 2.0 * increment;
    system.Derivative(0.0, moved, minus);
    const VectorXd difference = (plus - minus) / (2.0 * increment);
    worst = std::max(worst, (model.col(column) - difference).cwiseAbs().maxCoeff());
  }
  std::printf("state Jacobian against differences: %.2e of %.3g\n", worst, model.cwiseAbs().maxCoeff());
  EXPECT_LT(worst, 5e-11 * model.cwiseAbs().maxCoeff());
  EXPECT_EQ(model(system.element_state_offset(0), system.element_state_offset(0)), -kStiffness / 3.0);
}

// Moreau-Jean and event-driven integrate bodies only, and the sparse Newton solve knows no
// states: each says so in one line naming the element.
TEST(ElementStates, MethodsWithoutStatesRefuse) {
  MaxwellScene scene(3.0);
  const auto refusal = [&](SimulationOptions options) {
    options.end_time = 0.01;
    return flexmbs::testing::InputErrorMessage(
        [&] { Simulate(scene.system, options, scene.y0, [](double, const VectorXd&, const VectorXd&) {}); });
  };
  SimulationOptions moreau_jean;
  moreau_jean.moreau_jean = MoreauJeanOptions{};
  EXPECT_EQ(refusal(moreau_jean), "simulation: force element 'maxwell' has states of its own, which only methods "
                                  "explicit and implicit integrate");
  SimulationOptions event_driven;
  event_driven.event_driven = EventDrivenOptions{};
  EXPECT_EQ(refusal(event_driven), refusal(moreau_jean));
  SimulationOptions sparse;
  sparse.integrator.method = OdeMethod::kImplicit;
  sparse.integrator.newton = OdeNewton::kSparse;
  EXPECT_EQ(refusal(sparse), "simulation: newton sparse does not take force element 'maxwell' with states of its "
                             "own; newton dense or auto");
}

}  // namespace
}  // namespace flexmbs::mbs
