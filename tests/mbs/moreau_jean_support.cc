#include "tests/mbs/moreau_jean_support.h"

#include <Eigen/Geometry>
#include <chrono>
#include <ctime>
#include <string>
#include <utility>

#include "core/rotation.h"
#include "mbs/rigid_body.h"
#include "mbs/simulation.h"
#include "mbs/unilateral_contact.h"

namespace flexmbs::mbs::testing {

using Eigen::Matrix3d;
using Eigen::Vector3d;
using Eigen::VectorXd;

/// prefix + k (built by += : GCC 12 warns falsely on operator+ of a literal and a temporary).
std::string Numbered(const char* prefix, int k) {
  std::string name = prefix;
  name += std::to_string(k);
  return name;
}

ContactScene BallOnFloor(double mass, double radius, double gap0, double g, double restitution, double friction,
                         const Vector3d& v0_W, const Vector3d& w0_W) {
  ContactScene scene{std::make_unique<MultibodySystem>(Vector3d(0.0, 0.0, -g)), VectorXd()};
  MultibodySystem& system = *scene.system;
  const Matrix3d inertia = Matrix3d::Identity() * (0.4 * mass * radius * radius);
  const int ball = system.AddBody(std::make_unique<RigidBody>(
      "ball", mass, Vector3d::Zero(), inertia,
      std::vector<RigidBodyMarker>{{"centre", Vector3d::Zero(), Matrix3d::Identity()}}));
  system.AddUnilateralContact(std::make_unique<SpherePlaneUnilateral>(
      "floor", system.Marker("ball", "centre"), MarkerRef::Ground(Vector3d::Zero()), radius,
      UnilateralLaw{restitution, friction}));
  scene.y0 = system.NeutralState();
  VectorXd x(7), u(6);
  x << 0.0, 0.0, radius + gap0, 1.0, 0.0, 0.0, 0.0;
  u << v0_W, w0_W;  // unrotated: w_WB_B = w_WB_W
  system.SetBodyState(ball, x, u, scene.y0);
  return scene;
}

ContactScene BlockOnIncline(double angle, double friction, double g, double restitution) {
  constexpr double kMass = 1.0, kLength = 0.2, kHeight = 0.1, kFoot = 0.01;
  // All four feet 1e-12 m into the plane, so that every one is in the first step's index set: at
  // a gap of exactly 0 the round-off of the tilted pose (+-1e-17 m) decides, and a foot found
  // above the plane is left out and the block rocks onto it.
  constexpr double kPenetration = 1e-12;
  ContactScene scene{std::make_unique<MultibodySystem>(Vector3d(0.0, 0.0, -g)), VectorXd()};
  MultibodySystem& system = *scene.system;
  const Matrix3d inertia =
      Vector3d(kMass / 12.0 * (kLength * kLength + kHeight * kHeight), kMass / 12.0 * (kLength * kLength + kHeight * kHeight),
               kMass / 12.0 * 2.0 * kLength * kLength)
          .asDiagonal();
  std::vector<RigidBodyMarker> feet;
  for (int k = 0; k < 4; ++k) {
    const double sx = (k & 1) ? 1.0 : -1.0, sy = (k & 2) ? 1.0 : -1.0;
    feet.push_back({Numbered("foot", k),
                    Vector3d(sx * kLength / 2.0, sy * kLength / 2.0, -kHeight / 2.0 + kFoot), Matrix3d::Identity()});
  }
  const int block = system.AddBody(std::make_unique<RigidBody>("block", kMass, Vector3d::Zero(), inertia, std::move(feet)));
  const Matrix3d R_WP = Eigen::AngleAxisd(angle, Vector3d::UnitY()).toRotationMatrix();
  for (int k = 0; k < 4; ++k) {
    system.AddUnilateralContact(std::make_unique<SpherePlaneUnilateral>(
        Numbered("c", k), system.Marker("block", Numbered("foot", k)),
        MarkerRef::Ground(Vector3d::Zero(), R_WP), kFoot, UnilateralLaw{restitution, friction}));
  }
  scene.y0 = system.NeutralState();
  VectorXd x(7);
  x << R_WP * Vector3d(0.0, 0.0, kHeight / 2.0 - kPenetration), EulerParametersFromRotation(R_WP);
  system.SetBodyState(block, x, VectorXd::Zero(6), scene.y0);
  return scene;
}

StepHistory RunMoreauJean(ContactScene& scene, double h, double end_time, double theta, ImpactLevel level) {
  SimulationOptions options;
  options.end_time = end_time;
  options.output_interval = h;
  options.moreau_jean = MoreauJeanOptions{h, theta};
  options.moreau_jean->impact_level = level;
  StepHistory history;
  const MultibodySystem& system = *scene.system;
  Simulate(
      *scene.system, options, scene.y0,
      [&](double t, const VectorXd& y, const VectorXd&) {
        history.t.push_back(t);
        history.y.push_back(y);
        history.energy.push_back(system.KineticEnergy(y) + system.PotentialEnergy(t, y));
      },
      [&](double, const MoreauJeanStepReport& step) { history.steps.push_back(step); });
  return history;
}

EventRun RunEventDriven(ContactScene& scene, double end_time, double output_interval, double rest_velocity,
                        double relative_tolerance, double absolute_tolerance) {
  SimulationOptions options;
  options.end_time = end_time;
  options.output_interval = output_interval;
  options.integrator.relative_tolerance = relative_tolerance;
  options.integrator.absolute_tolerance = absolute_tolerance;
  options.event_driven = EventDrivenOptions{};
  options.event_driven->rest_velocity = rest_velocity;
  EventRun run;
  MoreauJeanStepReport report;
  const MultibodySystem& system = *scene.system;
  const auto start = std::chrono::steady_clock::now();
  const std::clock_t cpu_start = std::clock();
  run.statistics = Simulate(
      *scene.system, options, scene.y0,
      [&](double t, const VectorXd& y, const VectorXd&) {
        run.t.push_back(t);
        run.y.push_back(y);
        run.contacts.push_back(report);
        run.energy.push_back(system.KineticEnergy(y) + system.PotentialEnergy(t, y));
      },
      [&](double, const MoreauJeanStepReport& step) { report = step; },
      [&](const ContactEvent& event) { run.events.push_back(event); });
  run.wall_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  run.cpu_seconds = static_cast<double>(std::clock() - cpu_start) / CLOCKS_PER_SEC;
  return run;
}

}  // namespace flexmbs::mbs::testing
