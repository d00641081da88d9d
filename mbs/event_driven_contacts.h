#pragma once
// The contact algebra of event-driven integration (docs/contact.md, "Event-driven integration"):
// the system's contact points, the constrained system's response to contact forces (the joints
// holding), the closed points on acceleration level (an LCP in the normal accelerations and
// forces), the impact LCP with Newton's restitution, and the projection of closed gaps.

#include <Eigen/Core>
#include <vector>

#include "mbs/constraint_projection.h"
#include "mbs/event_driven.h"
#include "mbs/multibody_system.h"

namespace flexmbs::mbs {

/// A contact point of the system: point `point` of contact `contact`.
struct ContactPointRef {
  int contact = 0;
  int point = 0;
};

/// The closed points on acceleration level at one state: u' with the contact forces and the
/// LCP's normal forces lambda_N [N] and gap accelerations g_N'' [m/s^2] (per closed point, in the
/// order given): W_NN lambda_N + w_N = g_N'' >= 0 _|_ lambda_N >= 0.
struct ClosedContactForces {
  Eigen::VectorXd lambda_N;           ///< [N]
  Eigen::VectorXd gap_acceleration;   ///< g_N'' [m/s^2]
  Eigen::VectorXd delassus_diagonal;  ///< (W_NN)_ii [1/kg]
  /// The joints' multipliers with the contact forces (num_constraints(), 0 on dropped rows).
  Eigen::VectorXd joint_lambda;
  int lcp_iterations = 0;
  double lcp_error = 0.0;
};

/// The outcome of an impact LCP over some points (in the order given).
struct ImpactResult {
  Eigen::VectorXd U_N_before, U_N_after;  ///< [m/s]
  Eigen::VectorXd P_N;                    ///< [N s] >= 0
  double lcp_error = 0.0;
};

/// The contact points of a system and their algebra. Holds a reference to the system.
class EventDrivenContacts {
 public:
  EventDrivenContacts(const MultibodySystem& system, const EventDrivenOptions& options);

  /// Every point of every contact, contact by contact.
  const std::vector<ContactPointRef>& points() const { return points_; }
  int num_points() const { return static_cast<int>(points_.size()); }

  /// The kinematics of the listed points (indices into points()) at (t, y), each contact
  /// evaluated once.
  std::vector<UnilateralContactKinematics> Evaluate(double t, const ConstVectorRef& y,
                                                    const std::vector<int>& indices) const;
  /// All points' kinematics.
  std::vector<UnilateralContactKinematics> EvaluateAll(double t, const ConstVectorRef& y) const;

  /// The velocity-independent part w_N = W_N u'_free + (dW_N/dt) u of the closed points' gap
  /// accelerations needs (dW_N/dt) u: here the central difference quotient of W_N along the
  /// motion, (W_N(x + eps u) - W_N(x - eps u)) u / (2 eps) with eps = cbrt(machine eps) /
  /// max(1, |u|_inf) [s] (positions moved by MultibodySystem::DisplacePositions; truncation
  /// O(eps^2)). Exact zero for a body translating on a fixed plane.
  Eigen::VectorXd GapAccelerationBias(double t, const ConstVectorRef& y,
                                      const std::vector<int>& closed) const;

  /// y_dot = [x'; u'] at (t, y) with the closed points on acceleration level: the system's
  /// Derivative (joints, Baumgarte) plus A_c^-1 W_N^T lambda_N from the LCP. Throws
  /// SimulationError at t when the LCP does not converge.
  ClosedContactForces Derivative(double t, const ConstVectorRef& y, const std::vector<int>& closed,
                                 Eigen::Ref<Eigen::VectorXd> y_dot) const;

  /// The impact LCP over `points` at (t, y): U_N+ = U_N- + W_NN P_N, U_N+ + e min(U_N-, 0) >= 0
  /// _|_ P_N >= 0 (Newton's law on the approaching points, e per contact; a touching point that
  /// already separates only keeps U_N+ >= 0; the joints hold: G u+ = G u-); y's velocities
  /// become u+. Throws SimulationError at t when the LCP does not converge.
  ImpactResult Impact(double t, Eigen::Ref<Eigen::VectorXd> y,
                      const std::vector<int>& points) const;

  /// Moves the positions of y onto g_N = 0 of the closed points (Gauss-Newton in the constrained
  /// mass metric, the joints projected between the steps, ProjectPositions) and the velocities onto
  /// W_N u = 0 and the joints' G u = -g_t. Throws SimulationError at t if the gaps do not reach
  /// options.gap_projection_tolerance in 10 steps.
  void ProjectClosed(double t, Eigen::Ref<Eigen::VectorXd> y, const std::vector<int>& closed,
                     const ProjectionOptions& projection) const;

 private:
  const MultibodySystem& system_;
  EventDrivenOptions options_;
  std::vector<ContactPointRef> points_;
};

}  // namespace flexmbs::mbs
