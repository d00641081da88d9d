#include "fem/element_integrator.h"

#include <Eigen/LU>
#include <limits>

#include "fem/quadrature.h"
#include "fem/reference_element.h"

namespace flexmbs::fem {

ElementIntegrator::Tabulation ElementIntegrator::Tabulate(ElementType type,
                                                         const QuadratureRule& rule) {
  const ReferenceElement& ref = ReferenceElement::Of(type);
  Tabulation tab;
  tab.weights = rule.weights;
  tab.N.resize(static_cast<std::size_t>(rule.weights.size()));
  tab.dN.resize(tab.N.size());
  for (std::size_t q = 0; q < tab.N.size(); ++q) {
    ref.Evaluate(rule.points.col(static_cast<Eigen::Index>(q)), &tab.N[q], &tab.dN[q]);
  }
  return tab;
}

ElementIntegrator::ElementIntegrator(ElementType type)
    : type_(type),
      num_nodes_(Traits(type).num_nodes),
      stiffness_tab_(Tabulate(type, StiffnessRule(type))),
      affine_stiffness_tab_(Tabulate(type, AffineStiffnessRule(type))),
      mass_tab_(Tabulate(type, MassRule(type))),
      grad_(3, Traits(type).num_nodes) {}

bool ElementIntegrator::IsAffineTet10(const Eigen::Matrix3Xd& X) const {
  if (type_ != ElementType::kTet10) return false;
  // Mid-edge node m of edge (a, b), gmsh order; "at the midpoint" to round-off of the edge.
  constexpr int kEdges[6][3] = {{4, 0, 1}, {5, 1, 2}, {6, 0, 2}, {7, 0, 3}, {8, 2, 3}, {9, 1, 3}};
  constexpr double kRelativeTolerance = 1e-12;
  for (const auto& [m, a, b] : kEdges) {
    const Eigen::Vector3d offset = X.col(m) - 0.5 * (X.col(a) + X.col(b));
    if (offset.norm() > kRelativeTolerance * (X.col(b) - X.col(a)).norm()) return false;
  }
  return true;
}

double ElementIntegrator::Stiffness(const Eigen::Matrix3Xd& X, const IsotropicMaterial& material,
                                    Eigen::MatrixXd* K_e) {
  const Tabulation& tab = IsAffineTet10(X) ? affine_stiffness_tab_ : stiffness_tab_;
  const int n = num_nodes_;
  const double lambda = material.LameLambdaPa();
  const double mu = material.ShearModulusPa();
  K_e->setZero(3 * n, 3 * n);
  double min_det = std::numeric_limits<double>::infinity();
  for (std::size_t q = 0; q < tab.N.size(); ++q) {
    const Eigen::Matrix3Xd& dN = tab.dN[q];
    const Eigen::Matrix3d J = dN * X.transpose();  // J(i, j) = dx_j / dxi_i
    const double det = J.determinant();
    min_det = std::min(min_det, det);
    grad_.noalias() = J.inverse() * dN;  // grad_(j, a) = dN_a / dx_j
    const double w = tab.weights(static_cast<Eigen::Index>(q)) * det;
    // K_ab(i, j) = lambda g_ai g_bj + mu g_aj g_bi + mu delta_ij g_a . g_b  (B^T D B, isotropic)
    for (int b = 0; b < n; ++b) {
      const Eigen::Vector3d gb = grad_.col(b);
      for (int a = 0; a < n; ++a) {
        const Eigen::Vector3d ga = grad_.col(a);
        Eigen::Matrix3d block = (w * lambda) * ga * gb.transpose();
        block.noalias() += (w * mu) * gb * ga.transpose();
        block.diagonal().array() += w * mu * ga.dot(gb);
        K_e->block<3, 3>(3 * a, 3 * b) += block;
      }
    }
  }
  return min_det;
}

double ElementIntegrator::ScalarMass(const Eigen::Matrix3Xd& X, double density_kg_m3,
                                     MassMatrixKind kind, Eigen::MatrixXd* m_e) {
  m_e->setZero(num_nodes_, num_nodes_);
  double min_det = std::numeric_limits<double>::infinity();
  for (std::size_t q = 0; q < mass_tab_.N.size(); ++q) {
    const double det = (mass_tab_.dN[q] * X.transpose()).determinant();
    min_det = std::min(min_det, det);
    const double w = mass_tab_.weights(static_cast<Eigen::Index>(q)) * det * density_kg_m3;
    m_e->noalias() += w * mass_tab_.N[q] * mass_tab_.N[q].transpose();
  }
  if (kind == MassMatrixKind::kLumped) {
    // HRZ: keep the diagonal, scaled so that the element mass is preserved.
    const Eigen::VectorXd diag = m_e->diagonal();
    const double element_mass = m_e->sum();
    *m_e = (diag * (element_mass / diag.sum())).asDiagonal();
  }
  return min_det;
}

double ElementIntegrator::VolumeMoments(const Eigen::Matrix3Xd& X, double density_kg_m3,
                                        double* mass, Eigen::Vector3d* first,
                                        Eigen::Matrix3d* second) {
  *mass = 0.0;
  first->setZero();
  second->setZero();
  double min_det = std::numeric_limits<double>::infinity();
  for (std::size_t q = 0; q < mass_tab_.N.size(); ++q) {
    const double det = (mass_tab_.dN[q] * X.transpose()).determinant();
    min_det = std::min(min_det, det);
    const double w = mass_tab_.weights(static_cast<Eigen::Index>(q)) * det * density_kg_m3;
    const Eigen::Vector3d x = X * mass_tab_.N[q];
    *mass += w;
    *first += w * x;
    *second += w * x * x.transpose();
  }
  return min_det;
}

}  // namespace flexmbs::fem
