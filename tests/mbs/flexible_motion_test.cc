// A free-floating flexible body without forces (no gravity, no joints, no damping), integrated
// by the multibody step loop (mbs/simulation.h) with the explicit method from a spinning,
// translating, deformed and vibrating state: linear and angular momentum (both exact invariants
// of the FFR equations, which are the FE model's Galerkin projection) and energy must stay.
// Bodies: the Craig-Bampton beam (a clamped basis, floating) and the free-free beam's elastic
// modes, both with Ke scaled by 1e-4: the same mode shapes for a material with E = 21 MPa (the
// modes of a homogeneous isotropic body do not depend on E), so that the elastic periods
// (10 ... 100 ms) and the spin (0.3 s) share a time scale.

#include <gtest/gtest.h>

#include <cmath>
#include <iostream>
#include <memory>
#include <random>

#include "mbs/flexible_body.h"
#include "mbs/mode_selection.h"
#include "mbs/multibody_system.h"
#include "mbs/simulation.h"
#include "tests/mbs/flexible_test_bodies.h"

namespace flexmbs::mbs {
namespace {

using Eigen::Index;
using Eigen::Vector3d;
using Eigen::VectorXd;

constexpr double kSoftening = 1e-4;
// The explicit Dormand-Prince 5(4) at relative tolerance 1e-12 (absolute 1e-14 on every state
// entry): its local errors (<= 1e-12 of each entry) add up over 1e5 steps to a global error of
// ~1e-8 of the state in the worst case, below it where they do not accumulate. P and L are not
// invariants of the Runge-Kutta map (they depend on R(e) and q nonlinearly), so they drift by
// the same global error projected on them, relative over 1.02e5 steps: measured 2.5e-13 (P) and
// 1.3e-12 (L), the largest of the two bodies (issue 22: was 1e-10 for both).
constexpr double kRelativeTolerance = 1e-12;
constexpr double kLinearMomentumTolerance = 3e-12;
constexpr double kAngularMomentumTolerance = 1e-11;
// The energy holds to the global error too: measured 5.8e-12 relative (was asserted at the
// bound of the accumulated local errors, 1e5 steps x 1e-12 = 1e-7).
constexpr double kEnergyTolerance = 5e-11;
constexpr long kMinimumSteps = 100000;

struct Drift {
  long steps = 0;
  double P_drift = 0.0, L_drift = 0.0, E_drift = 0.0;
};

// Integrates `data` (restricted to its elastic modes, softened, undamped) for `end_time` [s].
Drift FloatFreely(const testing::FeReducedBody& fe, double end_time) {
  sid::ReducedBody data = RestrictModes(fe.body, testing::ElasticColumns(fe.basis));
  data.Ke.m0 *= kSoftening;
  data.De.m0.setZero();
  const Index n = data.num_modes();
  MultibodySystem system(Vector3d::Zero());
  system.AddBody(std::make_unique<FlexibleBody>("beam", std::move(data), false));
  const FlexibleBody& body = dynamic_cast<const FlexibleBody&>(system.body(0));

  // Spinning about an axis off the principal ones, translating, deformed by 2 cm and vibrating
  // with nodal velocities of 1 m/s.
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> uniform(-1.0, 1.0);
  const auto random = [&](Index size) { return VectorXd(VectorXd::NullaryExpr(size, [&] { return uniform(rng); })); };
  const Eigen::MatrixXd Phi = fe.basis.Phi(Eigen::all, testing::ElasticColumns(fe.basis));
  const auto largest_displacement = [&](const VectorXd& q) {
    return Eigen::Map<const Eigen::Matrix3Xd>(VectorXd(Phi * q).data(), 3, Phi.rows() / 3).colwise().norm().maxCoeff();
  };
  VectorXd q = random(n), qdot = random(n);
  q *= 0.02 / largest_displacement(q);
  qdot *= 1.0 / largest_displacement(qdot);
  VectorXd x(7 + n), u(6 + n);
  x << 0.1, -0.2, 0.3, Eigen::Vector4d(0.9, 0.1, -0.3, 0.2).normalized(), q;
  u << 0.5, -0.3, 0.2, 3.0, -20.0, 5.0, qdot;
  VectorXd y0 = system.NeutralState();
  system.SetBodyState(0, x, u, y0);

  const Momentum start = body.ComputeMomentum(x, u);
  const double E0 = system.KineticEnergy(y0) + system.PotentialEnergy(0.0, y0);
  SimulationOptions options;
  options.integrator.method = OdeMethod::kExplicit;
  options.integrator.relative_tolerance = kRelativeTolerance;
  options.integrator.absolute_tolerance = 1e-2 * kRelativeTolerance;
  options.integrator.max_steps_per_call = 1000000;
  options.end_time = end_time;
  options.output_interval = end_time / 20.0;
  Drift run;
  const auto output = [&](double t, const VectorXd& y, const VectorXd&) {
    const Momentum now = body.ComputeMomentum(system.BodyPositions(y, 0), system.BodyVelocities(y, 0));
    run.P_drift = std::max(run.P_drift, (now.linear_W - start.linear_W).norm() / start.linear_W.norm());
    run.L_drift = std::max(run.L_drift, (now.angular_Wo_W - start.angular_Wo_W).norm() / start.angular_Wo_W.norm());
    run.E_drift = std::max(run.E_drift, std::abs(system.KineticEnergy(y) + system.PotentialEnergy(t, y) - E0) / E0);
  };
  run.steps = Simulate(system, options, y0, output).integrator.steps;
  return run;
}

TEST(FreeFloatingFlexibleBody, KeepsMomentumAndEnergyOverAHundredThousandSteps) {
  struct Case {
    const char* name;
    const testing::FeReducedBody& (*fe)();
    double end_time;  ///< [s]: about 1.1e5 steps at the tolerance (measured), a margin for the
                      ///< step count's dependence on the round-off of the basis
  };
  for (const Case& c : {Case{"Craig-Bampton", &testing::CraigBamptonBeam, 1.0},
                        Case{"free-free", &testing::FreeFreeBeam, 4.6}}) {
    const Drift run = FloatFreely(c.fe(), c.end_time);
    std::cout << c.name << ": " << run.steps << " steps, drift P " << run.P_drift << ", L " << run.L_drift << ", E "
              << run.E_drift << "\n";
    EXPECT_GE(run.steps, kMinimumSteps) << c.name;
    EXPECT_LT(run.P_drift, kLinearMomentumTolerance) << c.name;
    EXPECT_LT(run.L_drift, kAngularMomentumTolerance) << c.name;
    EXPECT_LT(run.E_drift, kEnergyTolerance) << c.name;
  }
}

}  // namespace
}  // namespace flexmbs::mbs
