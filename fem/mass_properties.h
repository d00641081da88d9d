#pragma once

#include <Eigen/Core>
#include <Eigen/SparseCore>

#include "fem/mesh.h"

namespace flexmbs::fem {

/// Rigid-body mass properties of a body in its frame B.
struct MassProperties {
  double mass_kg = 0.0;
  Eigen::Vector3d p_BoCm_B = Eigen::Vector3d::Zero();  ///< centre of mass [m]
  /// Inertia tensor about the centre of mass, expressed in B [kg m^2]:
  /// int rho (|r|^2 I - r r^T) dV with r measured from the centre of mass.
  Eigen::Matrix3d I_Cm_B = Eigen::Matrix3d::Zero();
};

/// The six rigid-body displacement fields of the nodes (3 n x 6): columns 0-2 unit
/// translations along B's axes, columns 3-5 unit rotations about them through Bo
/// (u_n = e_i x p_BoN_B).
Eigen::MatrixXd RigidBodyModes(const Eigen::Matrix3Xd& nodes);

/// Mass properties from a global mass matrix M (DOF 3 n + i) and the node positions, from the
/// rigid-body projection R^T M R = [m I, m c~^T; m c~, J_Bo] (R = RigidBodyModes). Exact for
/// the consistent mass of an isoparametric mesh.
MassProperties MassPropertiesFromMassMatrix(const Eigen::SparseMatrix<double>& M,
                                            const Eigen::Matrix3Xd& nodes);

/// Mass properties from the rigid-body projection R^T M R (6 x 6, R = RigidBodyModes) of a mass
/// matrix, where M is known by its products only: MassPropertiesFromMassMatrix's second half.
MassProperties MassPropertiesFromRigidProjection(const Eigen::MatrixXd& Mrr);

/// Mass properties by quadrature of rho, rho x and rho x x^T over every element's volume,
/// independently of any assembled matrix.
MassProperties IntegrateMassProperties(const Mesh& mesh);

/// Mass properties from the total mass, the first moment int rho x dV and the second moment
/// int rho x x^T dV about B's origin.
MassProperties MassPropertiesFromMoments(double mass_kg, const Eigen::Vector3d& first_moment,
                                         const Eigen::Matrix3d& second_moment);

}  // namespace flexmbs::fem
