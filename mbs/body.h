#pragma once
// A body of a multibody system (docs/mbs.md): its coordinates, mass matrix, forces and the
// kinematics of its markers. Rigid bodies (rigid_body.h) and floating-frame-of-reference
// flexible bodies (flexible_body.h) implement it.
//
// Positions x = [p_WBo_W (3), e (4 Euler parameters, scalar first), q (n)], velocities
// u = [v_WBo_W (3), w_WB_B (3), qdot (n)].

#include <Eigen/Core>
#include <string>
#include <string_view>

namespace flexmbs::mbs {

using ConstVectorRef = Eigen::Ref<const Eigen::VectorXd>;

/// The pose and velocity of a marker frame M on a body, and how they depend on the body's
/// velocities u: [v_WM_W; w_WM_W] = jacobian * u, and the part of the marker's acceleration
/// that does not depend on u̇: [a_WM_W; alpha_WM_W] = jacobian * u̇ + bias. A load [f_W; tau_W]
/// at the marker's origin has the generalised force jacobian^T [f_W; tau_W].
struct MarkerKinematics {
  Eigen::Vector3d p_WM_W = Eigen::Vector3d::Zero();      ///< position [m]
  Eigen::Matrix3d R_WM = Eigen::Matrix3d::Identity();    ///< orientation
  Eigen::Vector3d v_WM_W = Eigen::Vector3d::Zero();      ///< velocity [m/s]
  Eigen::Vector3d w_WM_W = Eigen::Vector3d::Zero();      ///< angular velocity [rad/s]
  Eigen::Matrix<double, 6, Eigen::Dynamic> jacobian;     ///< 6 x n_u
  Eigen::Matrix<double, 6, 1> bias = Eigen::Matrix<double, 6, 1>::Zero();  ///< [m/s^2; rad/s^2]
};

/// One body. Implementations are immutable after construction; all state is passed in.
class Body {
 public:
  virtual ~Body() = default;

  /// The body's name in the scene.
  virtual const std::string& name() const = 0;
  /// Number of modal coordinates n (0 for a rigid body).
  virtual Eigen::Index num_modes() const = 0;
  Eigen::Index num_positions() const { return 7 + num_modes(); }
  Eigen::Index num_velocities() const { return 6 + num_modes(); }

  /// The mass matrix M_b(x) (n_u x n_u, symmetric positive definite) [kg, kg m, kg m^2, ...].
  virtual void MassMatrix(const ConstVectorRef& x, Eigen::Ref<Eigen::MatrixXd> M) const = 0;
  /// The right-hand side h_b(t, x, u) of M_b u̇ = h_b: gravity g_W [m/s^2], velocity-dependent
  /// inertia forces, elastic and damping forces (docs/mbs.md), without joint or force-element forces
  /// and without the acceleration-dependent forces below.
  virtual void Forces(double t, const ConstVectorRef& x, const ConstVectorRef& u, const Eigen::Vector3d& g_W,
                      Eigen::Ref<Eigen::VectorXd> h) const = 0;
  /// Adds to h (size n_u) the forces that depend linearly on the accelerations u_dot but are
  /// left out of the symmetric M_b: a flexible body's geometric stiffening by the inertia loads
  /// of its frame's acceleration (docs/mbs.md, "Geometric stiffening"). The system solves with
  /// u_dot from a first solve without them (MultibodySystem::Accelerations). Returns whether the
  /// body has such forces (false: h is unchanged); the default has none.
  virtual bool AddAccelerationDependentForces(const ConstVectorRef& x, const ConstVectorRef& u,
                                              const ConstVectorRef& u_dot, Eigen::Ref<Eigen::VectorXd> h) const;
  /// Adds the stiff part of h_b's derivatives for the implicit integrator's Newton matrix
  /// (mbs/system_jacobian.h): dh_dx (n_u x n_u) with respect to the positions moved by a
  /// velocity-space increment (MultibodySystem::DisplacePositions: columns p, rotation in B, q)
  /// and dh_du (n_u x n_u) with respect to u, at (x, u) with gravity g_W [m/s^2] and the
  /// accelerations u_dot (size n_u) in the acceleration-dependent forces, held fixed. What a
  /// body includes is its own choice (an approximate Jacobian slows Newton, never the result);
  /// the default adds nothing.
  virtual void AddForceJacobian(const ConstVectorRef& x, const ConstVectorRef& u, const ConstVectorRef& u_dot,
                                const Eigen::Vector3d& g_W, Eigen::Ref<Eigen::MatrixXd> dh_dx,
                                Eigen::Ref<Eigen::MatrixXd> dh_du) const;
  /// Kinetic energy [J] and potential energy (elastic and gravity, g_W) [J].
  virtual double KineticEnergy(const ConstVectorRef& x, const ConstVectorRef& u) const = 0;
  virtual double PotentialEnergy(const ConstVectorRef& x, const Eigen::Vector3d& g_W) const = 0;

  /// The index of the marker `name`, or -1 if the body has none of that name.
  virtual int FindMarker(std::string_view name) const = 0;
  /// The kinematics of marker `marker` (an index from FindMarker).
  virtual MarkerKinematics Marker(int marker, const ConstVectorRef& x, const ConstVectorRef& u) const = 0;

  /// The generalised force [N, N m, N m/q] of a force f_W [N] and torque tau_W [N m] acting at
  /// marker `marker`: jacobian^T [f_W; tau_W] (MarkerKinematics).
  Eigen::VectorXd MarkerLoad(int marker, const ConstVectorRef& x, const Eigen::Vector3d& f_W,
                             const Eigen::Vector3d& tau_W) const;
};

/// The generalised force (size n_u) [N, N m, N m/q] of a force f_W [N] at the origin of a
/// marker with `kinematics` and a torque tau_W [N m]: jacobian^T [f_W; tau_W].
Eigen::VectorXd GeneralizedForce(const MarkerKinematics& kinematics, const Eigen::Vector3d& f_W,
                                 const Eigen::Vector3d& tau_W);

/// xdot = [v, 1/2 e (x) (0, w_B), qdot]: the time derivative of a body's positions.
void PositionDerivative(const ConstVectorRef& x, const ConstVectorRef& u, Eigen::Ref<Eigen::VectorXd> xdot);

}  // namespace flexmbs::mbs
