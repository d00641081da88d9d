#include "reduction/basis_comparison.h"

#include <cmath>
#include <fmt/format.h>

#include "core/error.h"

namespace flexmbs::reduction {

Eigen::MatrixXd MacMatrix(const Eigen::MatrixXd& A, const Eigen::MatrixXd& B) {
  FLEXMBS_CHECK(A.rows() == B.rows(), "MAC needs shapes of the same length");
  const Eigen::MatrixXd cross = A.transpose() * B;
  const Eigen::VectorXd norm_a = A.colwise().squaredNorm().transpose();
  const Eigen::VectorXd norm_b = B.colwise().squaredNorm().transpose();
  return cross.array().square() / (norm_a * norm_b.transpose()).array();
}

Eigen::MatrixXd EffectiveModalMass(const sid::ReducedBody& body) {
  const Eigen::VectorXd modal_mass = body.Me.m0.diagonal();
  return body.Ct.m0.array().square().colwise() / modal_mass.array();
}

BasisComparison CompareBases(const sid::ReducedBody& a, const sid::ReducedBody& b) {
  if (a.node_positions.cols() != b.node_positions.cols()) {
    throw InputError(fmt::format("the bodies have different meshes ({} and {} nodes): compare bases of one mesh",
                                 a.node_positions.cols(), b.node_positions.cols()));
  }
  const double size = (a.node_positions.rowwise().maxCoeff() - a.node_positions.rowwise().minCoeff()).norm();
  const double offset = (a.node_positions - b.node_positions).cwiseAbs().maxCoeff();
  if (offset > 1e-12 * size) {
    throw InputError(fmt::format("the bodies' meshes differ (nodes up to {:.3g} m apart): compare bases of one mesh", offset));
  }
  BasisComparison out;
  out.mac = MacMatrix(a.phi, b.phi);
  out.effective_mass_a = EffectiveModalMass(a);
  out.effective_mass_b = EffectiveModalMass(b);
  for (Eigen::Index i = 0; i < a.phi.cols(); ++i) {
    if (!std::isfinite(a.frequency_hz(i))) continue;
    ModePair best;
    best.mac = -1.0;
    for (Eigen::Index j = 0; j < b.phi.cols(); ++j) {
      if (std::isfinite(b.frequency_hz(j)) && out.mac(i, j) > best.mac) {
        best = {i, j, a.frequency_hz(i), b.frequency_hz(j), 0.0, out.mac(i, j)};
      }
    }
    if (best.mac < 0.0) continue;
    // Exact rigid modes have frequency 0 in both bases: no error.
    const bool both_zero = best.frequency_a_hz == 0.0 && best.frequency_b_hz == 0.0;
    best.relative_error = both_zero ? 0.0 : best.frequency_b_hz / best.frequency_a_hz - 1.0;
    out.pairs.push_back(best);
  }
  return out;
}

}  // namespace flexmbs::reduction
