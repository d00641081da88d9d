#pragma once
// Force elements (docs/mbs.md, "Seams for contact"): applied loads that add generalised forces
// to h in M u' = h + G^T lambda, and the stiff part of their Jacobians dh/dx, dh/du for the
// implicit integrator (AddForceJacobian). Compliant contact laws plug in here.

#include <Eigen/Core>
#include <array>
#include <string>
#include <vector>

#include "mbs/body.h"
#include "mbs/contact_load.h"
#include "mbs/marker_ref.h"
#include "mbs/time_function.h"

namespace flexmbs::mbs {

class MultibodySystem;

/// The Jacobian blocks of a force element's own states s (ForceElement::AddStateJacobian), each
/// arriving zeroed: ds'/dx by velocity-space increments and ds'/du (num_states() x
/// num_velocities()), ds'/ds (num_states() square), dh/ds (num_velocities() x num_states()).
struct ElementStateJacobian {
  Eigen::Ref<Eigen::MatrixXd> ds_dx, ds_du, ds_ds, dh_ds;
};

/// An applied load. Immutable; reads the system's state through MultibodySystem::MarkerState.
/// An element may carry states of its own (docs/mbs.md, "Force elements with states"): first-order
/// equations s' = f_s(t, x, u, s) integrated with the bodies, held in y after their velocities
/// (MultibodySystem::ElementStates), e.g. a tooth's deflection behind its own dashpot.
class ForceElement {
 public:
  virtual ~ForceElement() = default;
  /// The element's name in the scene.
  virtual const std::string& name() const = 0;
  /// Adds the element's generalised forces at time t [s] and state y to h (the system's
  /// velocity space, size system.num_velocities()) [N, N m, ...].
  virtual void AddForces(double t, const MultibodySystem& system, const ConstVectorRef& y,
                         Eigen::Ref<Eigen::VectorXd> h) const = 0;
  /// The energy stored in the element [J]; 0 for loads without a potential.
  virtual double PotentialEnergy(double t, const MultibodySystem& system, const ConstVectorRef& y) const;
  /// Adds the stiff part of the element's dh/dx and dh/du (num_velocities() square each; x by
  /// velocity-space increments, MultibodySystem::DisplacePositions) for the implicit integrator's
  /// Newton matrix (mbs/system_jacobian.h); the default adds nothing.
  virtual void AddForceJacobian(double t, const MultibodySystem& system, const ConstVectorRef& y,
                                Eigen::Ref<Eigen::MatrixXd> dh_dx, Eigen::Ref<Eigen::MatrixXd> dh_du) const;
  /// The number of the element's own states (above); 0, the default, for a load of (x, u) alone.
  virtual Eigen::Index num_states() const { return 0; }
  /// The states at the start of a run (size num_states()); the default leaves the zeros s0 arrives with.
  virtual void InitialStates(Eigen::Ref<Eigen::VectorXd> s0) const;
  /// The states' rates s' (size num_states()) at time t [s] and state y. Called only when
  /// num_states() > 0; the default is for elements without states (FLEXMBS_CHECK).
  virtual void StateDerivatives(double t, const MultibodySystem& system, const ConstVectorRef& y,
                                Eigen::Ref<Eigen::VectorXd> s_dot) const;
  /// Adds the states' Jacobian blocks (ElementStateJacobian) at (t, y) for the implicit method's
  /// Newton matrix (mbs/system_jacobian.h); the default adds nothing.
  virtual void AddStateJacobian(double t, const MultibodySystem& system, const ConstVectorRef& y,
                                ElementStateJacobian& jacobian) const;
  /// Whether the element is a contact (its ContactLoads are drawn in the ParaView files).
  virtual bool is_contact() const { return false; }
  /// The loads at the element's contact points in contact at (t, y) (contact_id 0: the caller
  /// numbers them); none for a load that is not a contact (the default).
  virtual std::vector<ContactLoad> ContactLoads(double t, const MultibodySystem& system, const ConstVectorRef& y) const;
};

/// The frame of a point load's components.
enum class LoadFrame {
  kWorld,   ///< W
  kMarker,  ///< the marker's frame, turning with it (a follower load)
};

/// A force f [N] at the origin of a marker and a torque tau [N m] on its body, each component a
/// time function (a null function is 0).
class PointLoad final : public ForceElement {
 public:
  PointLoad(std::string name, MarkerRef at, std::array<TimeFunctionPtr, 3> force, std::array<TimeFunctionPtr, 3> torque,
            LoadFrame frame);
  const std::string& name() const override { return name_; }
  void AddForces(double t, const MultibodySystem& system, const ConstVectorRef& y,
                 Eigen::Ref<Eigen::VectorXd> h) const override;

 private:
  std::string name_;
  MarkerRef at_;
  std::array<TimeFunctionPtr, 3> force_, torque_;
  LoadFrame frame_;
};

/// A linear spring-damper between the origins of markers A and B: tension
/// F = k (l - free_length) + c dl/dt along the line from A to B (pulling B towards A for F > 0);
/// potential energy k (l - free_length)^2 / 2. Throws SimulationError if the two points meet
/// (no direction).
class SpringDamper final : public ForceElement {
 public:
  /// free_length [m] >= 0, stiffness k [N/m] >= 0, damping c [N s/m] >= 0; InputError otherwise.
  SpringDamper(std::string name, MarkerRef a, MarkerRef b, double free_length, double stiffness, double damping);
  const std::string& name() const override { return name_; }
  void AddForces(double t, const MultibodySystem& system, const ConstVectorRef& y,
                 Eigen::Ref<Eigen::VectorXd> h) const override;
  double PotentialEnergy(double t, const MultibodySystem& system, const ConstVectorRef& y) const override;
  /// The load's derivative by the relative motion of the two points through the markers'
  /// jacobians: d(F e)/dd = k e e^T + F / l (I - e e^T) + c e dl/dt' (I - e e^T) / l,
  /// d(F e)/d(v_B - v_A) = c e e^T (e the unit vector A -> B, l the length). Exact in u; in x
  /// without the change of the marker jacobians (the load times the lever's rotation).
  void AddForceJacobian(double t, const MultibodySystem& system, const ConstVectorRef& y,
                        Eigen::Ref<Eigen::MatrixXd> dh_dx, Eigen::Ref<Eigen::MatrixXd> dh_du) const override;

 private:
  std::string name_;
  MarkerRef a_, b_;
  double free_length_, stiffness_, damping_;
};

/// A bushing between marker frames I and J, for small relative rotations: with the offset
/// d = R_WI^T (p_WJ - p_WI) and the rotation vector theta of R_WI^T R_WJ (both in I), and their
/// rates (relative to I), the load on J is
///   f_I = -(K_t d + C_t d'),  tau_I = -(K_r theta + C_r w_IJ_I)
/// (diagonal K = diag(stiffness), C = diag(damping), translations first), and body i carries
/// the opposite load at the same point. Potential (d^T K_t d + theta^T K_r theta) / 2, exact for
/// the translations; the torque is the potential's gradient to first order in theta.
class Bushing final : public ForceElement {
 public:
  /// stiffness [N/m x3, N m/rad x3] >= 0, damping [N s/m x3, N m s/rad x3] >= 0; InputError
  /// otherwise.
  Bushing(std::string name, MarkerRef marker_i, MarkerRef marker_j, const Eigen::Matrix<double, 6, 1>& stiffness,
          const Eigen::Matrix<double, 6, 1>& damping);
  const std::string& name() const override { return name_; }
  void AddForces(double t, const MultibodySystem& system, const ConstVectorRef& y,
                 Eigen::Ref<Eigen::VectorXd> h) const override;
  double PotentialEnergy(double t, const MultibodySystem& system, const ConstVectorRef& y) const override;
  /// The load's derivative by the relative motion (d, theta in W components) through the markers'
  /// jacobians: blkdiag(R_WI K_t R_WI^T, R_WI K_r R_WI^T), and the same with C for the rates.
  /// Exact in u; in x at theta = 0 and up to the load times the rotation of I and of the levers.
  void AddForceJacobian(double t, const MultibodySystem& system, const ConstVectorRef& y,
                        Eigen::Ref<Eigen::MatrixXd> dh_dx, Eigen::Ref<Eigen::MatrixXd> dh_du) const override;

 private:
  std::string name_;
  MarkerRef marker_i_, marker_j_;
  Eigen::Matrix<double, 6, 1> stiffness_, damping_;
};

}  // namespace flexmbs::mbs
