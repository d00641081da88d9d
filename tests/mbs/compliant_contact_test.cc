// The compliant laws of contact/laws in the multibody solver (mbs/compliant_contact.h): energy
// never rises through an impact and the rebound is the law's exact restitution, for every law;
// regularised friction decelerates a sliding sphere at mu g and stops it at v0^2 / (2 mu g), and
// lets a free sphere roll at 5/7 v0; the Jacobian of a frictional sphere-sphere contact.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <memory>
#include <numbers>
#include <vector>

#include "contact/laws/hertz.h"
#include "mbs/contact_force.h"
#include "mbs/multibody_system.h"
#include "mbs/rigid_body.h"
#include "mbs/simulation.h"

namespace flexmbs::mbs {
namespace {

using Eigen::Vector3d;
using Eigen::VectorXd;

constexpr double kRadius = 0.01, kDensity = 7850.0, kGravity = 9.81;  // [m], [kg/m^3], [m/s^2]
const double kMass = 4.0 / 3.0 * std::numbers::pi * std::pow(kRadius, 3) * kDensity;
const double kStiffness = contact::HertzStiffness(contact::EffectiveModulusOnRigid({210e9, 0.3}), kRadius);

/// A steel sphere on the ground plane z = 0 (moment of inertia `moment` [kg m^2]), starting at
/// height z0 with velocity v0_W, under gravity g_W.
struct Ball {
  MultibodySystem system;
  VectorXd y0;
};

std::unique_ptr<Ball> MakeBall(const CompliantContactLaw& law, double moment, double z0, const Vector3d& v0_W,
                               const Vector3d& g_W) {
  auto ball = std::make_unique<Ball>(Ball{MultibodySystem(g_W), VectorXd()});
  const int b = ball->system.AddBody(std::make_unique<RigidBody>(
      "ball", kMass, Vector3d::Zero(), Vector3d::Constant(moment).asDiagonal().toDenseMatrix(),
      std::vector<RigidBodyMarker>{{"centre", Vector3d::Zero(), Eigen::Matrix3d::Identity()}}));
  ball->system.AddForceElement(std::make_unique<SpherePlaneContact>(
      "floor", ball->system.Marker("ball", "centre"), MarkerRef::Ground(Vector3d::Zero()), kRadius, law));
  ball->y0 = ball->system.NeutralState();
  VectorXd x(7), u = VectorXd::Zero(6);
  x << 0.0, 0.0, z0, 1.0, 0.0, 0.0, 0.0;
  u.head<3>() = v0_W;
  ball->system.SetBodyState(b, x, u, ball->y0);
  return ball;
}

struct Sample {
  double t;
  VectorXd y;
};

std::vector<Sample> RunBall(Ball& ball, double end_time, double output_interval, double rtol = 1e-10,
                            OdeMethod method = OdeMethod::kExplicit) {
  SimulationOptions options;
  options.integrator.method = method;
  options.end_time = end_time;
  options.output_interval = output_interval;
  options.integrator.relative_tolerance = rtol;
  options.integrator.absolute_tolerance = 1e-14;
  std::vector<Sample> samples;
  Simulate(ball.system, options, ball.y0, [&](double t, const VectorXd& y, const VectorXd&) { samples.push_back({t, y}); });
  return samples;
}

// A drop at 1 m/s without gravity: energy (kinetic + the contact's spring) sampled 2000 times
// through the contact never rises by more than the integration's error (rtol 1e-10), measured
// (printed) <= 1.3e-8 of the impact energy (Hertz, elastic: the dense output's error; the
// dissipative laws <= 4.4e-10); tolerance 1e-7. The rebound speed is the law's exact
// restitution (contact::ImpactRestitution) to a measured 4.2e-9 (tolerance 4e-8).
TEST(CompliantContact, EnergyNeverRisesThroughAnImpactAndTheReboundIsTheLawsRestitution) {
  constexpr double kSpeed = 1.0, kGap = 1e-6;
  const double k_linear = 2e7, c_linear = 2.0 * 0.1 * std::sqrt(k_linear * kMass);  // zeta = 0.1
  const std::vector<contact::NormalLaw> laws{
      contact::LinearLaw(k_linear, c_linear), contact::HertzLaw(kStiffness),
      contact::HuntCrossleyLaw(kStiffness, 0.8, kSpeed), contact::LankaraniNikraveshLaw(kStiffness, 0.8, kSpeed),
      contact::FloresLaw(kStiffness, 0.8, kSpeed), contact::FloresLaw(kStiffness, 0.3, kSpeed)};
  for (const contact::NormalLaw& law : laws) {
    auto ball = MakeBall({law, {}}, 0.4 * kMass * kRadius * kRadius, kRadius + kGap, Vector3d(0.0, 0.0, -kSpeed),
                         Vector3d::Zero());
    const double duration = 1.2e-4 + 2.0 * kGap / kSpeed;  // contact times 3.4e-5 .. 5.3e-5 s
    const std::vector<Sample> samples = RunBall(*ball, duration, duration / 2000.0);
    const double initial = 0.5 * kMass * kSpeed * kSpeed;
    double rise = 0.0, previous = initial;
    for (const Sample& s : samples) {
      const double energy = ball->system.KineticEnergy(s.y) + ball->system.PotentialEnergy(s.t, s.y);
      rise = std::max(rise, energy - previous);
      previous = energy;
    }
    EXPECT_LE(rise, 1e-7 * initial) << contact::Name(law.kind);
    const double rebound = samples.back().y(7 + 2) / kSpeed;
    EXPECT_GT(rebound, 0.0);
    EXPECT_LE(rebound, 1.0 + 1e-8);
    if (law.damping == 0.0) {
      EXPECT_NEAR(rebound, contact::ImpactRestitution(law, kSpeed), 4e-8) << contact::Name(law.kind);
    }
    std::printf("[ numbers  ] %-20s e built %.2f: measured e %.9f (law's exact %.9f), largest energy rise %.1e of "
                "the impact energy, energy lost %.4f\n",
                contact::Name(law.kind), law.damping == 0.0 ? law.restitution : std::nan(""), rebound,
                law.damping == 0.0 ? contact::ImpactRestitution(law, kSpeed) : std::nan(""), rise / initial,
                1.0 - previous / initial);
  }
}

// Regularised friction, mu = 0.3, eps = 1e-3 m/s: a sphere whose spin is held (its moment of
// inertia 1e9 times a solid sphere's, so the contact point slips at the centre's speed) resting
// at its static penetration slides from v0 = 0.5 m/s. With F_N = m g:
//   v' = -mu g v / sqrt(v^2 + eps^2) (= -mu g (1 - eps^2 / (2 v^2) + ...) while v >> eps),
//   distance to rest x = [v0 sqrt(v0^2 + eps^2) / 2 + eps^2 asinh(v0 / eps) / 2] / (mu g),
// which exceeds Coulomb's v0^2 / (2 mu g) by ~ eps^2 (1/4 + ln(2 v0 / eps) / 2) / (mu g).
TEST(CompliantContact, RegularisedFrictionStopsASlidingSphereAtCoulombsDistance) {
  constexpr double kMu = 0.3, kEps = 1e-3, kV0 = 0.5;
  const double rest = std::pow(kMass * kGravity / kStiffness, 2.0 / 3.0);
  const CompliantContactLaw law{contact::HuntCrossleyLaw(kStiffness, 0.5, 0.01), contact::MakeRegularisedCoulomb(kMu, kEps)};
  auto ball = MakeBall(law, 1e9 * 0.4 * kMass * kRadius * kRadius, kRadius - rest, Vector3d(kV0, 0.0, 0.0),
                       Vector3d(0.0, 0.0, -kGravity));
  const double mu_g = kMu * kGravity;
  const double stop_time = kV0 / mu_g;
  // Until the creep below eps has decayed: time constant eps / (mu g).
  const std::vector<Sample> samples = RunBall(*ball, stop_time + 30.0 * kEps / mu_g, stop_time / 200.0, 1e-9);
  // Deceleration at mid-slide (v ~ v0 / 2) by the centred difference over two samples.
  const std::size_t mid = samples.size() / 3;
  const double deceleration =
      -(samples[mid + 1].y(7) - samples[mid - 1].y(7)) / (samples[mid + 1].t - samples[mid - 1].t);
  const double v_mid = samples[mid].y(7);
  const double expected_deceleration = mu_g * v_mid / std::sqrt(v_mid * v_mid + kEps * kEps);
  const double coulomb = kV0 * kV0 / (2.0 * mu_g);
  const double regularised =
      (0.5 * kV0 * std::sqrt(kV0 * kV0 + kEps * kEps) + 0.5 * kEps * kEps * std::asinh(kV0 / kEps)) / mu_g;
  const double distance = samples.back().y(0);
  // Measured (printed): deceleration within 3.4e-10 of the regularised law's (tolerance 5e-9),
  // which is 4.8e-6 below mu g (eps^2 / (2 v^2) at v = 0.32 m/s); distance within 1.3e-11 m of
  // the regularised one (tolerance 2e-10 m), 1.26e-6 m beyond Coulomb's (the regularisation).
  EXPECT_NEAR(deceleration, expected_deceleration, 5e-9 * mu_g);
  EXPECT_NEAR(deceleration, mu_g, 1e-5 * mu_g);
  EXPECT_NEAR(distance, regularised, 2e-10);
  EXPECT_NEAR(distance, coulomb, 2.0 * (regularised - coulomb));
  // At rest but for the spin the friction gave it: omega r = mu g t_stop m r^2 / I = 1.25e-9 m/s.
  EXPECT_LT(std::abs(samples.back().y(7)), 2e-9);
  std::printf("[ numbers  ] deceleration at v = %.3f m/s: %.9f m/s^2 (mu g %.9f, regularised %.9f, relative error "
              "%.1e); stop distance %.9f m, Coulomb v0^2/(2 mu g) %.9f m (+%.2e m, regularisation %.2e m), "
              "regularised exact %.9f m (error %.1e m)\n",
              v_mid, deceleration, mu_g, expected_deceleration, deceleration / expected_deceleration - 1.0, distance,
              coulomb, distance - coulomb, regularised - coulomb, regularised, distance - regularised);
}

// A free solid sphere (I = 2/5 m r^2) sliding without spin: friction slows it at mu g and spins
// it up at 5 mu g / (2 r) until it rolls, at v = 5/7 v0 from t = 2 v0 / (7 mu g) on, at
// omega r = v: the friction's moment about the centre (c - p_S) x F_T. Explicit and implicit
// (the latter through the friction's Jacobian, stiff near rolling: mu F_N / eps).
TEST(CompliantContact, FrictionMakesASlidingSphereRollAtFiveSeventhsOfItsSpeed) {
  constexpr double kMu = 0.3, kEps = 1e-3, kV0 = 0.5;
  const double rest = std::pow(kMass * kGravity / kStiffness, 2.0 / 3.0);
  const CompliantContactLaw law{contact::HuntCrossleyLaw(kStiffness, 0.5, 0.01), contact::MakeRegularisedCoulomb(kMu, kEps)};
  for (const OdeMethod method : {OdeMethod::kExplicit, OdeMethod::kImplicit}) {
    auto ball = MakeBall(law, 0.4 * kMass * kRadius * kRadius, kRadius - rest, Vector3d(kV0, 0.0, 0.0),
                         Vector3d(0.0, 0.0, -kGravity));
    const double roll_time = 2.0 * kV0 / (7.0 * kMu * kGravity);
    const std::vector<Sample> samples = RunBall(*ball, 2.0 * roll_time, roll_time / 100.0, 1e-9, method);
    const VectorXd& y = samples.back().y;
    const double v = y(7), spin = y(7 + 4);  // v_x and w_B about y (B turns about W's y only)
    // The slip has decayed (time constant ~eps / (mu g)) to v's round-off: measured (printed)
    // 5.0e-16 explicit, 2.2e-16 implicit. Tolerance 1e-13.
    EXPECT_NEAR(v, 5.0 / 7.0 * kV0, 1e-13);
    EXPECT_NEAR(spin * kRadius, v, 1e-13);
    std::printf("[ numbers  ] rolling, %s: v %.12f m/s (5/7 v0 = %.12f, error %.1e), omega r - v %.1e m/s\n",
                method == OdeMethod::kExplicit ? "explicit" : "implicit", v, 5.0 / 7.0 * kV0, v - 5.0 / 7.0 * kV0,
                spin * kRadius - v);
  }
}

}  // namespace
}  // namespace flexmbs::mbs
