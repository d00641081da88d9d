#pragma once
// Moreau-Jean time stepping (docs/contact.md, "Moreau-Jean time stepping"; Moreau 1988,
// "Unilateral contact and dry friction in finite freedom dynamics"; Jean 1999, "The non-smooth
// contact dynamics method"; Acary & Brogliato 2008, "Numerical Methods for Nonsmooth Dynamical
// Systems", §10.1): a fixed step h on velocity level with the theta-method for the smooth forces,
// the joints as equalities G v_k+1 = -g_t with their impulses, and the unilateral contacts of
// the system (mbs/unilateral_contact.h) as impulses P from Newton's impact law and Coulomb
// friction, solved as an LCP (frictionless) or a friction-contact problem (contact/complementarity)
// at every step. No events: an accumulation of impacts is passed through, Zeno-safe.

#include <Eigen/Core>
#include <functional>
#include <vector>

#include "mbs/contact_load.h"
#include "mbs/multibody_system.h"

namespace flexmbs::mbs {

/// Where a step's contact law holds (docs/contact.md, "Impact on position level").
enum class ImpactLevel {
  /// Newton's law on the end velocity: 0 <= P_N _|_ U_N,k+1 + e U_N,k >= 0 (Moreau-Jean, Siconos).
  kVelocity,
  /// The gap the step's positions reach (theta = 1), 0 <= P_N _|_ g_N(x_k) + h U_N,k+1 >= 0
  /// (Stewart & Trinkle 1996): inelastic at the points, no penetration left behind.
  kPosition,
};

/// Settings of Moreau-Jean time stepping.
struct MoreauJeanOptions {
  double step = 0.0;    ///< h [s] > 0, fixed (a last step before an output time may be shorter)
  double theta = 0.5;   ///< in [0.5, 1]: 0.5 (Siconos' examples) conserves the smooth energy best
  double solver_tolerance = 1e-10;  ///< the contact solver's error (LcpError, FrictionContactError)
  int solver_max_iterations = 1000;  ///< NSGS sweeps before the Newton handover (Lemke: own limit)
  ImpactLevel impact_level = ImpactLevel::kVelocity;
};

/// Throws InputError "simulation: ..." unless step > 0 and finite, theta in [0.5, 1] (1 on
/// position level), solver_tolerance > 0 and solver_max_iterations >= 1.
void CheckMoreauJeanOptions(const MoreauJeanOptions& options);

/// One contact's outcome of a step [t_k, t_k+1], over its points (UnilateralContact::num_points).
struct ContactStepResult {
  bool active = false;    ///< a point in the step's index set: g_N(x_k) + h/2 U_N,k <= 0
  /// A point with friction sliding: pressed (P_N > 0) and slipping at the end of the step,
  /// |W_T v_k+1| > 1e-9 m/s.
  bool sliding = false;
  int active_points = 0;  ///< how many of its points were
  double g_N = 0.0;       ///< the smallest gap at the end of the step, g_N(x_k+1) [m]
  double U_N = 0.0;       ///< normal relative velocity at the end at that point, W_N(x_k) v_k+1 [m/s]
  double P_N = 0.0;       ///< normal impulse over the step, summed over the points [N s] (>= 0)
  /// Tangential impulses along t1_W, t2_W summed over the points [N s] (the points of a
  /// surface_plane contact share the plane's tangents).
  Eigen::Vector2d P_T = Eigen::Vector2d::Zero();
  /// Per point with an impulse: where, and the impulse over the step as a force on A, P / h [N]
  /// (event-driven: the closed points' contact forces at the output time).
  std::vector<ContactLoad> loads;
};

/// What one step did.
struct MoreauJeanStepReport {
  double time = 0.0;        ///< t_k+1 [s]
  int active_contacts = 0;  ///< size of the index set: contact points, summed over the contacts
  int solver_iterations = 0;  ///< Lemke pivots, or NSGS sweeps plus Newton steps (0 without active contacts)
  double solver_error = 0.0;  ///< the solver's error at its end
  std::vector<ContactStepResult> contacts;  ///< per contact of the system, in its order
  /// The joints' multipliers as the average force of the step, Lambda / h (num_constraints(), 0 on
  /// the dropped rows; MultibodySystem::ConstraintLoad turns them into loads).
  Eigen::VectorXd lambda;
};

/// Called at every output time with the report of the output interval that ended there
/// (SimulateMoreauJean; at the start: all contacts inactive, their gaps at y0).
using ContactOutputCallback = std::function<void(double t, const MoreauJeanStepReport& step)>;

/// Counters of a Moreau-Jean run.
struct MoreauJeanStatistics {
  long steps = 0;
  long contact_solves = 0;        ///< steps with a non-empty index set
  long solver_iterations = 0;     ///< summed over the steps
  int max_active_contacts = 0;
  double max_solver_error = 0.0;  ///< the largest error a converged solve ended with
  /// Process CPU time of the contact solves [s]: per step with active contacts the KKT solve for
  /// the Delassus operator W and the LCP or friction-contact solve (mbs/cpu_time.h).
  double contact_solve_cpu_seconds = 0.0;
};

/// The one-step map of Moreau-Jean time stepping for a system. Per step from (t_k, x_k, v_k),
/// with the stiff parts H_x, H_u of dh/dx, dh/du (Body::AddForceJacobian,
/// ForceElement::AddForceJacobian; one Newton step of the theta-method, Acary & Brogliato 2008,
/// §10.1.2), the kept joint rows G and the active contacts' H = [W_N; W_T] (at x_k):
///   A = M(x_k) - h theta H_u - h^2 theta^2 H_x,
///   A (v_k+1 - v_k) = h (h(t_k + theta h, x_k, v_k) + h theta H_x v_k) + G^T Lambda + H^T P,
///   G v_k+1 = -g_t(t_k+1, x_k),
///   active contacts: U_k+1 = H v_k+1, with Newton's law U_N,k+1 + e U_N,k >= 0 _|_ P_N >= 0
///   (velocity level; on position level g_N(x_k) + h U_N,k+1 >= 0, theta = 1) and
///   Coulomb's law on (U_T,k+1, P_T) (De Saxce's form; FrictionContactProblem),
///   x_k+1 = x_k + h (theta v_k+1 + (1 - theta) v_k)   (MultibodySystem::DisplacePositions),
/// the Euler parameters normalised. The KKT system [A G^T; G 0] is solved by KktFactor (dense
/// full-pivot LU, sparse LU for many bodies); the contacts see the Delassus operator W = H A_c^-1 H^T (A_c^-1 the velocity block of the
/// KKT inverse) and the free local velocity q = H v_free + (e U_N,k, 0, 0) (position level:
/// (g_N(x_k) / h, 0, 0), and the index set g_N(x_k) + h W_N v_free <= 0). Frictionless steps
/// solve the LCP (W_NN, q_N) by Lemke (as Siconos' LCP), and where Lemke misses the tolerance (a
/// singular W_NN from redundant contact points: its pivots lose accuracy) by the proximal Newton
/// solver with mu = 0; others SolveFrictionContact (d = 3; in a planar scene d = 2, the one
/// in-plane tangent, and the KKT matrix over the kept velocity columns, mbs/planar.h). The bodies' acceleration-dependent
/// forces (geometric stiffening) enter by one corrector of the
/// free velocity with u' = (v_free - v_k) / h (as MultibodySystem::Accelerations); the contact
/// impulses' own stiffening is left out.
class MoreauJeanStepper {
 public:
  /// Checks the options (CheckMoreauJeanOptions) and that every contact's law holds on the impact
  /// level (InputError naming the contact otherwise). The system must outlive the stepper.
  MoreauJeanStepper(const MultibodySystem& system, const MoreauJeanOptions& options);

  /// Advances y = [x; v] from t by h (0 < h <= (1 + 1e-9) options.step; the joints' drift is the caller's:
  /// ProjectPositions). Throws SimulationError naming the step, the time and the residual when
  /// the contact solver does not converge or the KKT matrix is singular.
  const MoreauJeanStepReport& Step(double t, double h, Eigen::Ref<Eigen::VectorXd> y);

  /// The report at y without a step (every contact inactive, its gap and normal velocity at y):
  /// what the first output records.
  MoreauJeanStepReport Initial(double t, const ConstVectorRef& y) const;

  const MoreauJeanStatistics& statistics() const { return statistics_; }

 private:
  const MultibodySystem& system_;
  MoreauJeanOptions options_;
  Eigen::VectorXd u_dot_;  ///< the last step's smooth acceleration (v_free - v_k) / h
  MoreauJeanStepReport report_;
  MoreauJeanStatistics statistics_;
};

}  // namespace flexmbs::mbs
