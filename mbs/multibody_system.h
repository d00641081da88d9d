#pragma once
// A multibody system (docs/mbs.md): bodies, joints, force elements and gravity, the layout of
// its state y = [x_1 .. x_B, u_1 .. u_B, s_1 .. s_E] (s_k force element k's own states, docs/mbs.md
// "Force elements with states"), and its equations of motion
//   M u' = h + G^T lambda,   G u' = gamma - 2 zeta omega_B (G u + g_t) - omega_B^2 g   (zeta = 1),
// solved at every evaluation by the Schur complement G M^-1 G^T (constraint_solver.h).

#include <Eigen/Core>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include "mbs/body.h"
#include "mbs/force_element.h"
#include "mbs/joint.h"
#include "mbs/marker_ref.h"
#include "mbs/unilateral_contact.h"

namespace flexmbs::mbs {

/// How the constraints are solved at every evaluation.
struct ConstraintSettings {
  /// omega_B [rad/s] of the Baumgarte terms (zeta = 1); 0: none.
  double baumgarte_frequency = 0.0;
  /// The Schur complement is rank deficient when a pivot of its pivoted LDL^T, scaled to unit
  /// diagonal, is below this: a constraint row within about sqrt(singular_pivot) rad (in the
  /// metric M^-1) of the span of the others.
  double singular_pivot = 1e-10;
};

/// All joints' equations stacked in joint order (JointEquations, assembled over the bodies).
struct SystemConstraints {
  Eigen::VectorXd g;      ///< m
  Eigen::VectorXd g_t;    ///< m
  Eigen::MatrixXd G;      ///< m x num_velocities()
  Eigen::VectorXd gamma;  ///< m
};

/// The load a joint puts on its body j, at the origin of marker J, in W.
struct JointLoad {
  Eigen::Vector3d f_W = Eigen::Vector3d::Zero();    ///< [N]
  Eigen::Vector3d tau_W = Eigen::Vector3d::Zero();  ///< [N m]
};

/// Body b's block of the system's velocities u: u_b = u.segment(start, size), and so its rows and
/// columns of h, M, G and every Jacobian over u. The one place the system's velocities are cut
/// per body (docs/mbs.md, "Planar scenes": a planar body's block will hold its in-plane
/// velocities only).
struct VelocityBlock {
  Eigen::Index start = 0;  ///< the body's first entry in u
  Eigen::Index size = 0;   ///< its number of velocities (6 + n)
};

/// A multibody system. Built once (Add*), then evaluated; all state is passed in.
class MultibodySystem {
 public:
  /// Gravity g_W [m/s^2].
  explicit MultibodySystem(const Eigen::Vector3d& g_W = Eigen::Vector3d(0.0, 0.0, -9.81));

  /// Adds a body; returns its index. Throws InputError if its name is taken.
  int AddBody(std::unique_ptr<Body> body);
  /// Adds a joint between bodies already added; returns its index. Throws InputError for a
  /// taken name or a body index out of range.
  int AddJoint(Joint joint);
  /// Adds a force element; returns its index. Throws InputError if its name is taken.
  int AddForceElement(std::unique_ptr<ForceElement> element);
  /// Adds a unilateral contact (mbs/unilateral_contact.h; Moreau-Jean time stepping only, the
  /// ODE integrators see none); returns its index. Throws InputError if its name is taken.
  int AddUnilateralContact(std::unique_ptr<UnilateralContact> contact);

  /// The index of body `name`, or -1.
  int FindBody(std::string_view name) const;
  /// Marker `marker` of body `body`; throws InputError naming both if either is unknown.
  MarkerRef Marker(std::string_view body, std::string_view marker) const;

  int num_bodies() const { return static_cast<int>(bodies_.size()); }
  const Body& body(int b) const { return *bodies_.at(static_cast<std::size_t>(b)); }
  int num_joints() const { return static_cast<int>(joints_.size()); }
  const Joint& joint(int k) const { return joints_.at(static_cast<std::size_t>(k)); }
  int num_force_elements() const { return static_cast<int>(force_elements_.size()); }
  const ForceElement& force_element(int k) const { return *force_elements_.at(static_cast<std::size_t>(k)); }
  int num_unilateral_contacts() const { return static_cast<int>(unilateral_contacts_.size()); }
  const UnilateralContact& unilateral_contact(int k) const {
    return *unilateral_contacts_.at(static_cast<std::size_t>(k));
  }
  const Eigen::Vector3d& gravity() const { return g_W_; }
  const ConstraintSettings& constraint_settings() const { return settings_; }
  void set_constraint_settings(const ConstraintSettings& settings) { settings_ = settings; }

  /// Sizes: positions (sum of 7 + n), velocities (sum of 6 + n), the force elements' states, the
  /// state y, constraints m.
  Eigen::Index num_positions() const { return num_positions_; }
  Eigen::Index num_velocities() const { return num_velocities_; }
  Eigen::Index num_element_states() const { return num_element_states_; }
  Eigen::Index state_size() const { return num_positions_ + num_velocities_ + num_element_states_; }
  Eigen::Index num_constraints() const { return num_constraints_; }
  /// Where body b's x_b starts in y, where its u_b starts in u (y = [x; u]), and where joint k's
  /// equations start in the stacked constraints. velocity_offset(b) is velocity_block(b).start.
  Eigen::Index position_offset(int b) const { return position_offsets_.at(static_cast<std::size_t>(b)); }
  Eigen::Index velocity_offset(int b) const { return velocity_block(b).start; }
  /// Body b's block of u (VelocityBlock).
  const VelocityBlock& velocity_block(int b) const { return velocity_blocks_.at(static_cast<std::size_t>(b)); }
  Eigen::Index constraint_offset(int k) const { return constraint_offsets_.at(static_cast<std::size_t>(k)); }
  /// Where force element k's states start in y (after every body's positions and velocities).
  Eigen::Index element_state_offset(int k) const {
    return num_positions_ + num_velocities_ + element_state_starts_.at(static_cast<std::size_t>(k));
  }
  /// The first force element with states, or -1: the methods that do not integrate them name it.
  int FirstElementWithStates() const;
  /// The joint whose equations contain stacked constraint row `row`.
  int JointOfConstraint(Eigen::Index row) const;
  /// "'<joint>' row <i> of <m>" (i 1-based within the joint) for stacked row `row`.
  std::string DescribeConstraintRow(Eigen::Index row) const;

  /// The stacked constraint rows left out of the equations of motion and the projections,
  /// ascending: the rows found redundant at the start of a run (constraint_redundancy.h). Their
  /// multipliers are 0, so the joint loads are one particular solution of the redundant system.
  const std::vector<Eigen::Index>& dropped_constraints() const { return dropped_constraints_; }
  /// Sets dropped_constraints(); `rows` ascending, distinct and < num_constraints() (checked).
  void set_dropped_constraints(std::vector<Eigen::Index> rows);
  /// The stacked constraint rows not dropped, ascending.
  std::vector<Eigen::Index> KeptConstraints() const;

  /// True for a planar scene (mbs/planar.h, docs/mbs.md "Planar scenes"): the solves gather each
  /// body's kept velocity columns and scatter back zeros in the dropped ones.
  bool planar() const { return !kept_velocities_.empty(); }
  /// Body b's kept velocity columns, indices into its block of u, ascending: in a planar scene
  /// v_x, v_y, w_z and the in-plane modes; in a spatial one every column (0 .. size - 1).
  std::vector<Eigen::Index> KeptVelocities(int b) const;
  /// The kept columns of every body as indices into u, ascending (all of u in a spatial scene).
  std::vector<Eigen::Index> KeptVelocities() const;
  /// Makes the system planar with `columns[b]` the kept columns of body b (one list per body,
  /// ascending, distinct and inside the body's block: checked). mbs/planar.h's MakePlanar is the
  /// caller, after its checks; an empty `columns` makes the system spatial again.
  void set_kept_velocities(std::vector<std::vector<Eigen::Index>> columns);

  /// Every body at the origin of W, unrotated (e = (1, 0, 0, 0)), undeformed and at rest; the
  /// force elements' states at their InitialStates.
  Eigen::VectorXd NeutralState() const;
  /// The velocities u of all bodies in y.
  Eigen::Map<const Eigen::VectorXd> Velocities(const ConstVectorRef& y) const {
    return {y.data() + num_positions_, num_velocities_};
  }
  /// The states of `element` (one of this system's force elements; FLEXMBS_CHECK) in y.
  Eigen::Map<const Eigen::VectorXd> ElementStates(const ConstVectorRef& y, const ForceElement& element) const;
  /// Views of body b's positions x_b and velocities u_b in y.
  Eigen::Map<const Eigen::VectorXd> BodyPositions(const ConstVectorRef& y, int b) const;
  Eigen::Map<const Eigen::VectorXd> BodyVelocities(const ConstVectorRef& y, int b) const;
  /// Writes x_b and u_b of body b into y.
  void SetBodyState(int b, const ConstVectorRef& x_b, const ConstVectorRef& u_b, Eigen::Ref<Eigen::VectorXd> y) const;

  /// The kinematics of a marker (the ground: its fixed frame, at rest, a 6 x 0 jacobian).
  MarkerKinematics MarkerState(const MarkerRef& marker, const ConstVectorRef& y) const;
  /// Adds force f_W [N] at the origin of `marker` and torque tau_W [N m] to h (size
  /// num_velocities()), with `kinematics` = MarkerState(marker, y): GeneralizedForce, which
  /// includes the stiffening of a flexible body by a load at its node; nothing for the ground.
  void AddMarkerLoad(const MarkerRef& marker, const MarkerKinematics& kinematics, const Eigen::Vector3d& f_W,
                     const Eigen::Vector3d& tau_W, Eigen::Ref<Eigen::VectorXd> h) const;

  /// The block-diagonal mass matrix's block of body b at y.
  Eigen::MatrixXd BodyMassMatrix(int b, const ConstVectorRef& y) const;
  /// h(t, y): the bodies' forces (gravity, inertia, elastic) and the force elements.
  Eigen::VectorXd Forces(double t, const ConstVectorRef& y) const;
  /// The joints' equations at (t, y).
  SystemConstraints Constraints(double t, const ConstVectorRef& y) const;
  /// u' and lambda (size num_constraints(), 0 on the dropped rows) at (t, y), with Baumgarte terms per
  /// constraint_settings(). The bodies' acceleration-dependent forces h_a(u') (geometric
  /// stiffening, Body::AddAccelerationDependentForces) enter by one corrector step: u'_0 solves
  /// the system without them, u' the system with h_a(u'_0) (the same factorisations). With
  /// h_a = -N u' and A the constrained solution operator, u' - u'_exact = -(A N)^2 u'_exact:
  /// of second order in the deformation (|A N| grows with q, about as the elastic rotations;
  /// docs/mbs.md, "Geometric stiffening"); exact when joints prescribe the frames' motion.
  /// Throws SimulationError at t naming the joints when G M^-1 G^T over the kept rows is rank
  /// deficient (a closed loop in a singular configuration, or redundant rows not dropped).
  void Accelerations(double t, const ConstVectorRef& y, Eigen::Ref<Eigen::VectorXd> u_dot,
                     Eigen::Ref<Eigen::VectorXd> lambda) const;
  /// The bodies' acceleration-dependent forces (size num_velocities()) at y for the
  /// accelerations u_dot (size num_velocities()); returns false (and zeros) if no body has any.
  bool AccelerationDependentForces(const ConstVectorRef& y, const ConstVectorRef& u_dot,
                                   Eigen::Ref<Eigen::VectorXd> h) const;
  /// y' = [x'; u'; s'] (x' from body.h's PositionDerivative, s' the force elements' StateDerivatives).
  void Derivative(double t, const ConstVectorRef& y, Eigen::Ref<Eigen::VectorXd> y_dot) const;
  /// The load of joint k on its body j at marker J from the multipliers lambda of Accelerations.
  JointLoad ConstraintLoad(int k, double t, const ConstVectorRef& y, const ConstVectorRef& lambda) const;

  /// Moves the positions in y by the velocity-space increment du (size num_velocities()):
  /// p += du_v, e = e (x) exp(du_w / 2) (a rotation by du_w in B), q += du_q.
  void DisplacePositions(const ConstVectorRef& du, Eigen::Ref<Eigen::VectorXd> y) const;
  /// Scales every body's Euler parameters to unit norm; returns the largest | |e| - 1 | before.
  double NormalizeEulerParameters(Eigen::Ref<Eigen::VectorXd> y) const;

  /// Kinetic energy [J]; potential energy [J]: gravity and elastic energy of the bodies and the
  /// force elements' stored energy.
  double KineticEnergy(const ConstVectorRef& y) const;
  double PotentialEnergy(double t, const ConstVectorRef& y) const;

 private:
  Eigen::Vector3d g_W_;
  ConstraintSettings settings_;
  std::vector<std::unique_ptr<Body>> bodies_;
  std::vector<Joint> joints_;
  std::vector<std::unique_ptr<ForceElement>> force_elements_;
  std::vector<std::unique_ptr<UnilateralContact>> unilateral_contacts_;
  std::vector<Eigen::Index> position_offsets_, constraint_offsets_, element_state_starts_;
  std::vector<VelocityBlock> velocity_blocks_;
  std::vector<Eigen::Index> dropped_constraints_;
  std::vector<std::vector<Eigen::Index>> kept_velocities_;  // per body; empty: spatial
  Eigen::Index num_positions_ = 0, num_velocities_ = 0, num_element_states_ = 0, num_constraints_ = 0;
};

}  // namespace flexmbs::mbs
