#include "fem/mass_properties.h"

#include "core/error.h"
#include "fem/element_integrator.h"

namespace flexmbs::fem {

MassProperties MassPropertiesFromMoments(double mass_kg, const Eigen::Vector3d& first_moment,
                                         const Eigen::Matrix3d& second_moment) {
  FLEXMBS_CHECK(mass_kg > 0.0, "mass must be positive");
  MassProperties props;
  props.mass_kg = mass_kg;
  props.p_BoCm_B = first_moment / mass_kg;
  // Second moment about the centre of mass, then I = tr(S) 1 - S.
  const Eigen::Matrix3d S =
      second_moment - mass_kg * props.p_BoCm_B * props.p_BoCm_B.transpose();
  props.I_Cm_B = S.trace() * Eigen::Matrix3d::Identity() - S;
  return props;
}

Eigen::MatrixXd RigidBodyModes(const Eigen::Matrix3Xd& nodes) {
  const Eigen::Index n = nodes.cols();
  Eigen::MatrixXd R = Eigen::MatrixXd::Zero(3 * n, 6);
  for (Eigen::Index v = 0; v < n; ++v) {
    const Eigen::Vector3d x = nodes.col(v);
    R.block<3, 3>(3 * v, 0).setIdentity();
    // e_i x x as column i: the transpose of skew(x).
    R.block<3, 3>(3 * v, 3) << 0, x(2), -x(1), -x(2), 0, x(0), x(1), -x(0), 0;
  }
  return R;
}

MassProperties MassPropertiesFromMassMatrix(const Eigen::SparseMatrix<double>& M,
                                            const Eigen::Matrix3Xd& nodes) {
  FLEXMBS_CHECK(M.rows() == 3 * nodes.cols() && M.cols() == M.rows(), "M must be 3 n x 3 n");
  const Eigen::MatrixXd R = RigidBodyModes(nodes);
  return MassPropertiesFromRigidProjection(R.transpose() * (M * R));
}

MassProperties MassPropertiesFromRigidProjection(const Eigen::MatrixXd& Mrr) {
  FLEXMBS_CHECK(Mrr.rows() == 6 && Mrr.cols() == 6, "R^T M R must be 6 x 6");
  const double mass = Mrr.topLeftCorner<3, 3>().trace() / 3.0;
  // Lower-left block m c~: c = (c~(2,1), c~(0,2), c~(1,0)).
  const Eigen::Matrix3d mc_skew = Mrr.bottomLeftCorner<3, 3>();
  const Eigen::Vector3d first(mc_skew(2, 1), mc_skew(0, 2), mc_skew(1, 0));
  // J_Bo = tr(S) 1 - S with S the second moment about Bo: S = tr(J)/2 1 - J.
  const Eigen::Matrix3d J_Bo = Mrr.bottomRightCorner<3, 3>();
  const Eigen::Matrix3d second = 0.5 * J_Bo.trace() * Eigen::Matrix3d::Identity() - J_Bo;
  return MassPropertiesFromMoments(mass, first, second);
}

MassProperties IntegrateMassProperties(const Mesh& mesh) {
  double mass = 0.0;
  Eigen::Vector3d first = Eigen::Vector3d::Zero();
  Eigen::Matrix3d second = Eigen::Matrix3d::Zero();
  Eigen::Matrix3Xd X;
  for (const ElementBlock& block : mesh.blocks) {
    ElementIntegrator integrator(block.type);
    X.resize(3, integrator.num_nodes());
    for (Eigen::Index e = 0; e < block.num_elements(); ++e) {
      for (int a = 0; a < integrator.num_nodes(); ++a) {
        X.col(a) = mesh.nodes.col(block.connectivity(a, e));
      }
      double m_e;
      Eigen::Vector3d f_e;
      Eigen::Matrix3d s_e;
      integrator.VolumeMoments(X, block.material.density_kg_m3, &m_e, &f_e, &s_e);
      mass += m_e;
      first += f_e;
      second += s_e;
    }
  }
  return MassPropertiesFromMoments(mass, first, second);
}

}  // namespace flexmbs::fem
