// Hertz impact through the multibody solver: a steel sphere (R = 10 mm, E = 210 GPa, nu = 0.3,
// rho = 7850 kg/m^3) at v = 1 m/s on a rigid flat and on a second, equal, free steel sphere,
// with the Hertz law built from the materials (contact/laws/hertz.h), against Hertz's impact
// theory (K. L. Johnson, Contact Mechanics, Cambridge 1985, sec. 11.4):
//   delta_max = (15 m* v^2 / (16 E* sqrt(R*)))^(2/5),  F_max = 4/3 E* sqrt(R*) delta_max^(3/2),
//   t_c = 2.9432 delta_max / v  (2 (2/5) B(2/5, 1/2) = 2.94324 ...),
// explicit (Dormand-Prince) and implicit (ESDIRK, model Jacobian) integrators.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <functional>
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

constexpr double kRadius = 0.01, kDensity = 7850.0, kSpeed = 1.0;  // [m], [kg/m^3], [m/s]
const contact::ElasticMaterial kSteel{210e9, 0.3};
const double kMass = 4.0 / 3.0 * std::numbers::pi * std::pow(kRadius, 3) * kDensity;  // 0.0329 kg
constexpr double kGap = 1e-6;  // [m] between the surfaces at t = 0

std::unique_ptr<RigidBody> Sphere(const char* name) {
  const double moment = 0.4 * kMass * kRadius * kRadius;
  return std::make_unique<RigidBody>(name, kMass, Vector3d::Zero(), Vector3d::Constant(moment).asDiagonal().toDenseMatrix(),
                                     std::vector<RigidBodyMarker>{{"centre", Vector3d::Zero(), Eigen::Matrix3d::Identity()}});
}

/// Hertz's impact of two bodies of effective mass m*, modulus E*, radius R* at speed v.
struct HertzTheory {
  double delta_max, force_max, duration;
};

HertzTheory Theory(double effective_mass, double effective_modulus, double effective_radius) {
  const double k = 4.0 / 3.0 * effective_modulus * std::sqrt(effective_radius);
  const double delta_max =
      std::pow(15.0 * effective_mass * kSpeed * kSpeed / (16.0 * effective_modulus * std::sqrt(effective_radius)), 0.4);
  const double factor = 2.0 * 0.4 * std::tgamma(0.4) * std::tgamma(0.5) / std::tgamma(0.9);  // 2.9432...
  return {delta_max, k * std::pow(delta_max, 1.5), factor * delta_max / kSpeed};
}

/// The measured impact: the first and last crossing of delta = 0 (linear interpolation between
/// output samples) and the peak of k delta^(3/2) (a parabola through the largest sample and its
/// neighbours).
struct Measured {
  double force_max = 0.0, duration = 0.0;
};

struct Impact {
  MultibodySystem system{Vector3d::Zero()};
  VectorXd y0;
  std::function<double(const VectorXd&)> penetration;
  double stiffness = 0.0;
  HertzTheory theory{};
};

Measured Run(Impact& setup, OdeMethod method) {
  SimulationOptions options;
  options.integrator.method = method;
  options.integrator.relative_tolerance = 1e-10;
  options.integrator.absolute_tolerance = 1e-14;
  options.end_time = 1.3 * setup.theory.duration + kGap / kSpeed;
  options.output_interval = setup.theory.duration / 2000.0;
  std::vector<double> t, delta;
  Simulate(setup.system, options, setup.y0, [&](double time, const VectorXd& y, const VectorXd&) {
    t.push_back(time);
    delta.push_back(setup.penetration(y));
  });
  Measured measured;
  std::size_t first = 0, last = 0, peak = 0;
  for (std::size_t k = 1; k < t.size(); ++k) {
    if (delta[k - 1] <= 0.0 && delta[k] > 0.0) first = k;
    if (delta[k - 1] > 0.0 && delta[k] <= 0.0) last = k;
    if (delta[k] > delta[peak]) peak = k;
  }
  EXPECT_GT(first, 0u);
  EXPECT_GT(last, first);
  const auto crossing = [&](std::size_t k) {
    return t[k - 1] + (t[k] - t[k - 1]) * delta[k - 1] / (delta[k - 1] - delta[k]);
  };
  measured.duration = crossing(last) - crossing(first);
  // Parabola through (-h, a), (0, b), (h, c): the peak is b + (c - a)^2 / (8 (2 b - a - c)).
  const double a = delta[peak - 1], b = delta[peak], c = delta[peak + 1];
  const double delta_max = b + (c - a) * (c - a) / (8.0 * (2.0 * b - a - c));
  measured.force_max = setup.stiffness * std::pow(delta_max, 1.5);
  return measured;
}

// Relative errors against the theory, measured (printed; 2000 samples per contact, rtol 1e-10):
// peak force 1.2e-10 / 1.5e-11 explicit, 3.8e-8 / 1.5e-7 implicit (flat / sphere); duration
// 1.6e-11 / 1.7e-12 explicit, 7.7e-10 / 7.8e-10 implicit. Tolerances ~10x the worst: far inside
// the 2 % that is asked.
constexpr double kForceTolerance = 2e-6, kDurationTolerance = 1e-8;

void ExpectHertz(Impact& setup, const char* what) {
  for (const OdeMethod method : {OdeMethod::kExplicit, OdeMethod::kImplicit}) {
    const Measured measured = Run(setup, method);
    const double force_error = measured.force_max / setup.theory.force_max - 1.0;
    const double time_error = measured.duration / setup.theory.duration - 1.0;
    EXPECT_LE(std::abs(force_error), kForceTolerance) << what;
    EXPECT_LE(std::abs(time_error), kDurationTolerance) << what;
    std::printf("[ numbers  ] %s, %s: F_max %.6f N (theory %.6f N, error %+.1e), t_c %.6e s (theory %.6e s, "
                "error %+.1e)\n",
                what, method == OdeMethod::kExplicit ? "explicit" : "implicit", measured.force_max,
                setup.theory.force_max, force_error, measured.duration, setup.theory.duration, time_error);
  }
}

TEST(HertzImpact, SteelSphereOnARigidFlatMatchesHertzTheory) {
  Impact setup;
  const int ball = setup.system.AddBody(Sphere("ball"));
  const double modulus = contact::EffectiveModulusOnRigid(kSteel);
  setup.stiffness = contact::HertzStiffness(modulus, kRadius);
  setup.theory = Theory(kMass, modulus, kRadius);
  setup.system.AddForceElement(std::make_unique<SpherePlaneContact>(
      "floor", setup.system.Marker("ball", "centre"), MarkerRef::Ground(Vector3d::Zero()), kRadius,
      CompliantContactLaw{contact::HertzLaw(setup.stiffness), {}}));
  setup.y0 = setup.system.NeutralState();
  VectorXd x(7), u = VectorXd::Zero(6);
  x << 0.0, 0.0, kRadius + kGap, 1.0, 0.0, 0.0, 0.0;
  u(2) = -kSpeed;
  setup.system.SetBodyState(ball, x, u, setup.y0);
  const MarkerRef centre = setup.system.Marker("ball", "centre");
  setup.penetration = [&setup, centre](const VectorXd& y) {
    return kRadius - setup.system.MarkerState(centre, y).p_WM_W.z();
  };
  ExpectHertz(setup, "sphere on rigid flat");
}

TEST(HertzImpact, SteelSphereOnAnEqualFreeSphereMatchesHertzTheory) {
  Impact setup;
  const int one = setup.system.AddBody(Sphere("one"));
  const int two = setup.system.AddBody(Sphere("two"));
  const double modulus = contact::EffectiveModulus(kSteel, kSteel);
  const double radius = contact::EffectiveRadius(kRadius, kRadius);
  setup.stiffness = contact::HertzStiffness(modulus, radius);
  setup.theory = Theory(0.5 * kMass, modulus, radius);  // m* = m m / (m + m)
  const MarkerRef c1 = setup.system.Marker("one", "centre"), c2 = setup.system.Marker("two", "centre");
  setup.system.AddForceElement(std::make_unique<SphereSphereContact>(
      "pair", c1, c2, kRadius, kRadius, CompliantContactLaw{contact::HertzLaw(setup.stiffness), {}}));
  setup.y0 = setup.system.NeutralState();
  VectorXd x(7), u = VectorXd::Zero(6);
  x << 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0;
  setup.system.SetBodyState(two, x, u, setup.y0);
  x(0) = -(2.0 * kRadius + kGap);
  u(0) = kSpeed;  // sphere one closes on sphere two, at rest
  setup.system.SetBodyState(one, x, u, setup.y0);
  setup.penetration = [&setup, c1, c2](const VectorXd& y) {
    return 2.0 * kRadius - (setup.system.MarkerState(c1, y).p_WM_W - setup.system.MarkerState(c2, y).p_WM_W).norm();
  };
  ExpectHertz(setup, "sphere on free sphere");
}

}  // namespace
}  // namespace flexmbs::mbs
