#include "reduction/basis_comparison.h"

#include <Eigen/Eigenvalues>
#include <cmath>
#include <fmt/format.h>

#include "core/error.h"
#include "fem/mass_properties.h"
#include "eigensolvers/eigensolver.h"

namespace flexmbs::reduction {

Eigen::MatrixXd MacMatrix(const Eigen::MatrixXd& A, const Eigen::MatrixXd& B) {
  FLEXMBS_CHECK(A.rows() == B.rows(), "MAC needs shapes of the same length");
  const Eigen::MatrixXd cross = A.transpose() * B;
  const Eigen::VectorXd norm_a = A.colwise().squaredNorm().transpose();
  const Eigen::VectorXd norm_b = B.colwise().squaredNorm().transpose();
  return cross.array().square() / (norm_a * norm_b.transpose()).array();
}

Eigen::MatrixXd EffectiveModalMass(const Eigen::MatrixXd& participation, const Eigen::VectorXd& modal_mass) {
  FLEXMBS_CHECK(participation.rows() == modal_mass.size(), "one modal mass per mode");
  return participation.array().square().colwise() / modal_mass.array();
}

Eigen::MatrixXd EffectiveModalMass(const sid::ReducedBody& body) {
  return EffectiveModalMass(body.Ct.m0, body.Me.m0.diagonal());
}

ModeSet BasisModes(const sid::ReducedBody& body) {
  return {body.mode_names, body.phi, body.frequency_hz, body.Ct.m0, body.Me.m0.diagonal()};
}

ModeSet BasisModes(const ReducedBasis& basis, const FeModel& model) {
  const Eigen::MatrixXd M_t = model.mass().Times(fem::RigidBodyModes(model.nodes).leftCols<3>());
  return {basis.names, basis.Phi, basis.frequency_hz, basis.Phi.transpose() * M_t, basis.M_reduced.diagonal()};
}

ModeSet SystemModes(const sid::ReducedBody& body, double zero_eigenvalue) {
  const Eigen::Index n = body.num_modes();
  FLEXMBS_CHECK(body.Ke.m0.rows() == n && body.Me.m0.rows() == n && body.Ct.m0.rows() == n,
                "the reduced matrices have one row per mode");
  // Direct form K x = lambda M x: absolute eigenvalue error ~ eps lambda_max of the small system.
  const Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd> eigen(body.Ke.m0, body.Me.m0,
                                                                        Eigen::ComputeEigenvectors | Eigen::Ax_lBx);
  if (eigen.info() != Eigen::Success) {
    throw InputError("the reduced mass matrix Me is not positive definite: the body has no system modes");
  }
  const Eigen::VectorXd& lambda = eigen.eigenvalues();
  const Eigen::MatrixXd& X = eigen.eigenvectors();
  ModeSet out;
  out.shapes = body.phi * X;
  out.frequency_hz = eigensolvers::FrequenciesHz(lambda);
  out.participation = X.transpose() * body.Ct.m0;
  out.modal_mass = Eigen::VectorXd::Ones(n);
  int rigid = 0, normal = 0;
  for (Eigen::Index k = 0; k < n; ++k) {
    const bool is_rigid = std::abs(lambda(k)) <= zero_eigenvalue;
    if (is_rigid) out.frequency_hz(k) = 0.0;
    out.names.push_back(is_rigid ? fmt::format("reduced_rigid_{}", ++rigid) : fmt::format("reduced_normal_{}", ++normal));
  }
  return out;
}

BasisComparison CompareModes(const ModeSet& a, const ModeSet& b, ErrorReference reference) {
  BasisComparison out;
  out.mac = MacMatrix(a.shapes, b.shapes);
  out.effective_mass_a = EffectiveModalMass(a.participation, a.modal_mass);
  out.effective_mass_b = EffectiveModalMass(b.participation, b.modal_mass);
  for (Eigen::Index i = 0; i < a.size(); ++i) {
    if (!std::isfinite(a.frequency_hz(i))) continue;
    ModePair best;
    best.mac = -1.0;
    for (Eigen::Index j = 0; j < b.size(); ++j) {
      if (std::isfinite(b.frequency_hz(j)) && out.mac(i, j) > best.mac) {
        best = {i, j, a.frequency_hz(i), b.frequency_hz(j), 0.0, out.mac(i, j)};
      }
    }
    if (best.mac < 0.0) continue;
    // Exact rigid modes have frequency 0 on both sides: no error.
    const bool both_zero = best.frequency_a_hz == 0.0 && best.frequency_b_hz == 0.0;
    const bool of_a = reference == ErrorReference::kA;
    const double f_reference = of_a ? best.frequency_a_hz : best.frequency_b_hz;
    const double f_other = of_a ? best.frequency_b_hz : best.frequency_a_hz;
    best.relative_error = both_zero ? 0.0 : f_other / f_reference - 1.0;
    out.pairs.push_back(best);
  }
  return out;
}

void CheckSameMesh(const Eigen::Matrix3Xd& nodes_a, const Eigen::Matrix3Xd& nodes_b) {
  if (nodes_a.cols() != nodes_b.cols()) {
    throw InputError(fmt::format("the meshes differ ({} and {} nodes)", nodes_a.cols(), nodes_b.cols()));
  }
  const double size = (nodes_a.rowwise().maxCoeff() - nodes_a.rowwise().minCoeff()).norm();
  const double offset = (nodes_a - nodes_b).cwiseAbs().maxCoeff();
  if (offset > 1e-12 * size) {
    throw InputError(fmt::format("the meshes differ (nodes up to {:.3g} m apart)", offset));
  }
}

BasisComparison CompareBases(const sid::ReducedBody& a, const sid::ReducedBody& b) {
  try {
    CheckSameMesh(a.node_positions, b.node_positions);
  } catch (const InputError& e) {
    throw InputError(fmt::format("{}: compare bases of one mesh", e.what()));
  }
  return CompareModes(BasisModes(a), BasisModes(b), ErrorReference::kA);
}

}  // namespace flexmbs::reduction
