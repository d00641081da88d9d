#pragma once
// Scenes of the Moreau-Jean and event-driven tests (tests/mbs/moreau_jean_test.cc,
// moreau_jean_friction_test.cc, event_driven_test.cc, event_driven_friction_test.cc): a ball above
// the ground plane and a block on an incline, built in the library, and runs that keep every
// output's state and contact report.

#include <Eigen/Core>
#include <memory>
#include <vector>

#include "mbs/event_driven.h"
#include "mbs/moreau_jean.h"
#include "mbs/multibody_system.h"
#include "mbs/simulation.h"

namespace flexmbs::mbs::testing {

/// A system and its initial state.
struct ContactScene {
  std::unique_ptr<MultibodySystem> system;
  Eigen::VectorXd y0;
};

/// A ball (mass [kg], radius [m], solid-sphere inertia) whose lowest point is `gap0` [m] above
/// the plane z = 0 (unilateral contact "floor", restitution e, friction mu), moving with v0_W
/// [m/s] and spinning with w0_W [rad/s]; gravity (0, 0, -g).
ContactScene BallOnFloor(double mass, double radius, double gap0, double g, double restitution, double friction,
                         const Eigen::Vector3d& v0_W = Eigen::Vector3d::Zero(),
                         const Eigen::Vector3d& w0_W = Eigen::Vector3d::Zero());

/// A block of mass 1 kg, 0.2 x 0.2 x 0.1 m, at rest on (1e-12 m into) a plane through W's origin tilted
/// by `angle` [rad] about W's y axis, on four small spheres (radius 0.01 m) at its bottom corners
/// (contacts "c0".."c3", the given restitution, friction mu); gravity (0, 0, -g). Down the slope
/// is (cos a, 0, -sin a).
ContactScene BlockOnIncline(double angle, double friction, double g, double restitution = 0.0);

/// Every step of a Moreau-Jean run: time, state and contact report.
struct StepHistory {
  std::vector<double> t;
  std::vector<Eigen::VectorXd> y;
  std::vector<MoreauJeanStepReport> steps;  ///< steps[0]: the initial report
  std::vector<double> energy;               ///< kinetic + potential [J]
};

/// Runs `scene` to end_time by steps of h (theta, impact level) with an output at every step.
StepHistory RunMoreauJean(ContactScene& scene, double h, double end_time, double theta = 0.5,
                          ImpactLevel level = ImpactLevel::kVelocity);

/// The outputs and events of an event-driven run.
struct EventRun {
  std::vector<double> t;
  std::vector<Eigen::VectorXd> y;
  std::vector<MoreauJeanStepReport> contacts;  ///< the report of the interval ending at t
  std::vector<double> energy;                  ///< kinetic + potential [J]
  std::vector<ContactEvent> events;
  SimulationStatistics statistics;
  double wall_seconds = 0.0;
  double cpu_seconds = 0.0;  ///< the process's CPU time over the run (steadier than wall on a loaded machine)
};

/// Runs `scene` event-driven to end_time with an output every output_interval [s], the given
/// rest_velocity [m/s] and ARKODE tolerances.
EventRun RunEventDriven(ContactScene& scene, double end_time, double output_interval, double rest_velocity,
                        double relative_tolerance = 1e-10, double absolute_tolerance = 1e-12);

}  // namespace flexmbs::mbs::testing
