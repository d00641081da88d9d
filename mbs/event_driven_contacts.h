#pragma once
// The contact algebra of event-driven integration (docs/contact.md, "Event-driven integration"):
// the system's contact points, the constrained system's response to contact forces (the joints
// holding), the closed points on acceleration level (an LCP in the normal accelerations and
// forces; with friction a friction-contact problem over the sticking points, the sliding points'
// friction along their sliding direction), the impact problem with Newton's restitution (and
// Coulomb friction), and the projection of closed gaps and sticking velocities.

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

/// How a closed point's tangential motion is held.
enum class Tangential {
  kFree,   ///< no friction (mu = 0): no tangential force
  kStick,  ///< U_T = 0 held by a friction force |lambda_T| <= mu lambda_N
  kSlide,  ///< lambda_T = -mu lambda_N s along the sliding direction s
};

/// A closed point: its index in EventDrivenContacts::points(), its tangential state and, when
/// sliding, the unit direction s of the slide in its tangent frame (t1, t2), set when the slide
/// begins and when its velocity turns through 90 degrees from it (EventDrivenContacts::Derivative).
struct ClosedPoint {
  int index = 0;
  Tangential tangential = Tangential::kFree;
  Eigen::Vector2d slide_direction = Eigen::Vector2d::UnitX();
};

/// The closed points on acceleration level at one state: u' with the contact forces, the normal
/// forces lambda_N [N] and gap accelerations g_N'' [m/s^2] (per closed point, in the order
/// given): W_NN lambda_N + w_N = g_N'' >= 0 _|_ lambda_N >= 0; with friction also the tangential
/// forces and accelerations in each point's frame (t1, t2).
struct ClosedContactForces {
  Eigen::VectorXd lambda_N;           ///< [N]
  Eigen::VectorXd gap_acceleration;   ///< g_N'' [m/s^2]
  Eigen::VectorXd delassus_diagonal;  ///< (W_NN)_ii [1/kg]
  Eigen::Matrix2Xd lambda_T;          ///< [N], 0 for frictionless points
  Eigen::Matrix2Xd tangential_acceleration;  ///< U_T' [m/s^2]
  /// The mean of (W_TT)_ii over a point's two tangents [1/kg] (0 without friction).
  Eigen::VectorXd tangential_delassus;
  /// The joints' multipliers with the contact forces (num_constraints(), 0 on dropped rows).
  Eigen::VectorXd joint_lambda;
  int lcp_iterations = 0;
  double lcp_error = 0.0;
};

/// The outcome of an impact problem over some points (in the order given).
struct ImpactResult {
  Eigen::VectorXd U_N_before, U_N_after;  ///< [m/s]
  Eigen::VectorXd P_N;                    ///< [N s] >= 0
  Eigen::Matrix2Xd U_T_after;             ///< [m/s] in each point's frame (t1, t2)
  Eigen::Matrix2Xd P_T;                   ///< [N s], 0 without friction
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
  /// evaluated once. In a planar scene each point's tangents are t1 = z x n (in the plane) and
  /// t2 = z (UsePlanarTangents), and the friction problems take d = 2 (W_N, W_T1).
  std::vector<UnilateralContactKinematics> Evaluate(double t, const ConstVectorRef& y,
                                                    const std::vector<int>& indices) const;
  /// All points' kinematics.
  std::vector<UnilateralContactKinematics> EvaluateAll(double t, const ConstVectorRef& y) const;

  /// Whether contact `contact` has friction (mu > 0).
  bool HasFriction(int contact) const;

  /// The velocity-independent part of the listed points' accelerations, w = W u'_free + (dW/dt) u
  /// per point's rows [N; T1; T2], needs (dW/dt) u: here the central difference quotient of the
  /// rows along the motion, (W(x + eps u) - W(x - eps u)) u / (2 eps) with eps = cbrt(machine
  /// eps) / max(1, |u|_inf) [s] (positions moved by MultibodySystem::DisplacePositions; truncation
  /// O(eps^2)). Column i holds point i's (dW_N/dt) u, (dW_T/dt) u. Exact zero for a body
  /// translating on a fixed plane.
  Eigen::Matrix3Xd AccelerationBias(double t, const ConstVectorRef& y, const std::vector<int>& indices) const;

  /// y_dot = [x'; u'] at (t, y) with the closed points on acceleration level: the system's
  /// Derivative (joints, Baumgarte) plus A_c^-1 W^T lambda from the LCP (no point with friction
  /// sticking or sliding) or from the friction-contact problem: a sticking point's reaction in its
  /// Coulomb cone against its acceleration (De Saxce's form: stick, or slip beginning with maximal
  /// dissipation), a sliding point's normal force acting through W_N - mu s^T W_T (s = U_T / |U_T|
  /// while U_T points ahead of its slide_direction and |U_T| > 1e-12 m/s, else slide_direction).
  /// Throws SimulationError at t when the problem is not solved.
  ClosedContactForces Derivative(double t, const ConstVectorRef& y, const std::vector<ClosedPoint>& closed,
                                 Eigen::Ref<Eigen::VectorXd> y_dot) const;

  /// The impact problem over `points` at (t, y) by options.impact_law. Newton's: U_N+ = U_N- +
  /// W_NN P_N, U_N+ + e min(U_N-, 0) >= 0 _|_ P_N >= 0 (e per contact; a touching point that
  /// already separates only keeps U_N+ >= 0; the joints hold: G u+ = G u-); where a point has
  /// friction, the friction-contact problem of the same velocities with P_T in the Coulomb cone
  /// against U_T+ (as a Moreau-Jean step without the step's forces). Poisson's (frictionless): the
  /// compression LCP U_C = U_N- + W_NN P_C >= 0 _|_ P_C >= 0, then the expansion LCP U_N+ = U_C +
  /// W_NN (e P_C + Lambda) >= 0 _|_ Lambda >= 0, P_N = P_C + e P_C + Lambda. y's velocities
  /// become u+. Throws SimulationError at t when a problem is not solved.
  ImpactResult Impact(double t, Eigen::Ref<Eigen::VectorXd> y, const std::vector<int>& points) const;

  /// Moves the positions of y onto g_N = 0 of the closed points (Gauss-Newton in the constrained
  /// mass metric, the joints projected between the steps, ProjectPositions) and the velocities onto
  /// W_N u = 0, W_T u = 0 of the sticking points and the joints' G u = -g_t. Throws
  /// SimulationError at t if the gaps do not reach options.gap_projection_tolerance in 10 steps.
  void ProjectClosed(double t, Eigen::Ref<Eigen::VectorXd> y, const std::vector<ClosedPoint>& closed,
                     const ProjectionOptions& projection) const;

  /// Process CPU time [s] of Derivative's and Impact's solves so far: the constrained response W
  /// and the LCP or friction-contact problem.
  double solve_cpu_seconds() const { return solve_cpu_seconds_; }

 private:
  const MultibodySystem& system_;
  EventDrivenOptions options_;
  std::vector<ContactPointRef> points_;
  mutable double solve_cpu_seconds_ = 0.0;  ///< a measurement, summed by the const solves
};

}  // namespace flexmbs::mbs
