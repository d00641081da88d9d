#pragma once
// A rigid body (docs/mbs.md with n = 0): mass, centre of mass and inertia in its body frame B,
// and named marker frames fixed in B.

#include <Eigen/Core>
#include <string>
#include <string_view>
#include <vector>

#include "mbs/body.h"

namespace flexmbs::mbs {

/// A marker frame M fixed in a rigid body: origin p_BoM_B [m] and orientation R_BM.
struct RigidBodyMarker {
  std::string name;
  Eigen::Vector3d p_BoM_B = Eigen::Vector3d::Zero();
  Eigen::Matrix3d R_BM = Eigen::Matrix3d::Identity();
};

/// A rigid body with x = [p_WBo_W, e] and u = [v_WBo_W, w_WB_B]. Its equations (Newton-Euler
/// about the body origin Bo, docs/mbs.md with mdCM = m c, c = p_BoCm_B):
///   [ m I       -m R c~ ] [v']   [ m g_W - R (w~ w~ m c)       ]
///   [ m c~ R^T   J_Bo   ] [w'] = [ m c~ R^T g_W - w~ J_Bo w   ],
/// J_Bo = J_Cm + m c~^T c~ (parallel axes), R = R_WB.
class RigidBody final : public Body {
 public:
  /// mass [kg] > 0; p_BoCm_B [m]; I_Cm_B [kg m^2] the inertia tensor about the centre of mass in
  /// B components (symmetric, positive definite, principal moments obeying the triangle
  /// inequality); marker names unique. Throws InputError naming the body and the bad value.
  RigidBody(std::string name, double mass, const Eigen::Vector3d& p_BoCm_B, const Eigen::Matrix3d& I_Cm_B,
            std::vector<RigidBodyMarker> markers = {});

  const std::string& name() const override { return name_; }
  Eigen::Index num_modes() const override { return 0; }
  double mass() const { return mass_; }
  const Eigen::Vector3d& p_BoCm_B() const { return p_BoCm_B_; }
  /// Inertia about the centre of mass and about the body origin Bo, in B [kg m^2].
  const Eigen::Matrix3d& inertia_about_cm() const { return I_Cm_B_; }
  const Eigen::Matrix3d& inertia_about_origin() const { return I_Bo_B_; }
  const std::vector<RigidBodyMarker>& markers() const { return markers_; }

  void MassMatrix(const ConstVectorRef& x, Eigen::Ref<Eigen::MatrixXd> M) const override;
  void Forces(double t, const ConstVectorRef& x, const ConstVectorRef& u, const Eigen::Vector3d& g_W,
              Eigen::Ref<Eigen::VectorXd> h) const override;
  double KineticEnergy(const ConstVectorRef& x, const ConstVectorRef& u) const override;
  /// -m g_W . p_WCm_W (zero at the origin of W).
  double PotentialEnergy(const ConstVectorRef& x, const Eigen::Vector3d& g_W) const override;
  int FindMarker(std::string_view name) const override;
  /// p_WM = p + R p_BoM, R_WM = R R_BM, [v_WM; w_WM] = [I, -R p~; 0, R] u and the bias
  /// [R w~ w~ p_BoM; 0] (w = w_WB_B, p = p_BoM_B).
  MarkerKinematics Marker(int marker, const ConstVectorRef& x, const ConstVectorRef& u) const override;

 private:
  std::string name_;
  double mass_;
  Eigen::Vector3d p_BoCm_B_;
  Eigen::Matrix3d I_Cm_B_, I_Bo_B_;
  std::vector<RigidBodyMarker> markers_;
};

}  // namespace flexmbs::mbs
