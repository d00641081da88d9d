#include "fem/element_integrator.h"

#include <Eigen/LU>
#include <algorithm>
#include <limits>

#include "core/error.h"
#include "fem/quadrature.h"
#include "fem/reference_element.h"

namespace flexmbs::fem {
namespace {

// Conical (collapsed) product rule on the unit triangle: x = u, y = v (1 - u), dA = (1 - u)
// du dv, n-point Gauss in u and v. x^a y^b becomes u^a (1 - u)^(b + 1) v^b, integrated exactly
// while a + b + 1 <= 2 n - 1: the rule has degree 2 n - 2 (Stroud, "Approximate Calculation
// of Multiple Integrals", 1971, conical product rules).
std::vector<Eigen::Vector3d> CollapsedTriangle(int n) {  // (x, y, weight)
  const QuadratureRule line = GaussLine(n);
  std::vector<Eigen::Vector3d> points;
  for (Eigen::Index i = 0; i < line.weights.size(); ++i) {
    const double u = 0.5 * (line.points(0, i) + 1.0), wu = 0.5 * line.weights(i);
    for (Eigen::Index j = 0; j < line.weights.size(); ++j) {
      const double v = 0.5 * (line.points(0, j) + 1.0), wv = 0.5 * line.weights(j);
      points.emplace_back(u, v * (1.0 - u), wu * wv * (1.0 - u));
    }
  }
  return points;
}

// Tensor product of the collapsed `triangle_points`^2 triangle rule with `line_points`-point Gauss on the wedge's [-1, 1] axis.
QuadratureRule WedgeProduct(int triangle_points, int line_points) {
  const std::vector<Eigen::Vector3d> triangle = CollapsedTriangle(triangle_points);
  const QuadratureRule line = GaussLine(line_points);
  const auto count = static_cast<Eigen::Index>(triangle.size()) * line.weights.size();
  QuadratureRule rule{Eigen::Matrix3Xd(3, count), Eigen::VectorXd(count),
                      std::min(2 * triangle_points - 2, 2 * line_points - 1)};
  Eigen::Index q = 0;
  for (const Eigen::Vector3d& t : triangle) {
    for (Eigen::Index k = 0; k < line.weights.size(); ++k, ++q) {
      rule.points.col(q) = Eigen::Vector3d(t(0), t(1), line.points(0, k));
      rule.weights(q) = t(2) * line.weights(k);
    }
  }
  return rule;
}

// n x n x n Gauss on [-1, 1]^3.
QuadratureRule HexProduct(int n) {
  const QuadratureRule line = GaussLine(n);
  QuadratureRule rule{Eigen::Matrix3Xd(3, n * n * n), Eigen::VectorXd(n * n * n), 2 * n - 1};
  Eigen::Index q = 0;
  for (int k = 0; k < n; ++k) {
    for (int j = 0; j < n; ++j) {
      for (int i = 0; i < n; ++i, ++q) {
        rule.points.col(q) = Eigen::Vector3d(line.points(0, i), line.points(0, j), line.points(0, k));
        rule.weights(q) = line.weights(i) * line.weights(j) * line.weights(k);
      }
    }
  }
  return rule;
}

// The geometric-stiffness rule of `type` (ElementIntegrator::GeometricStiffnessPoints).
QuadratureRule GeometricStiffnessRule(ElementType type) {
  switch (type) {
    case ElementType::kTet4:
    case ElementType::kTet10:
    case ElementType::kHex8: return StiffnessRule(type);  // degree 1, 3 and tensor degree 3
    case ElementType::kHex20: return HexProduct(4);
    case ElementType::kWedge6: return WedgeProduct(3, 2);
    case ElementType::kWedge15: return WedgeProduct(4, 4);
  }
  throw InternalError("unknown element type");
}

}  // namespace

Eigen::Matrix3d LinearElasticStress(const Eigen::Matrix3d& grad_u, const IsotropicMaterial& material) {
  const Eigen::Matrix3d eps = 0.5 * (grad_u + grad_u.transpose());
  Eigen::Matrix3d sigma = (2.0 * material.ShearModulusPa()) * eps;
  sigma.diagonal().array() += material.LameLambdaPa() * eps.trace();
  return sigma;
}

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
      geometric_tab_(Tabulate(type, GeometricStiffnessRule(type))),
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

double ElementIntegrator::GeometricStiffnessPoints(const Eigen::Matrix3Xd& X, Eigen::VectorXd* weights,
                                                   std::vector<Eigen::Matrix3Xd>* gradients) {
  const Eigen::Index count = geometric_tab_.weights.size();
  weights->resize(count);
  gradients->resize(static_cast<std::size_t>(count));
  double min_det = std::numeric_limits<double>::infinity();
  for (Eigen::Index q = 0; q < count; ++q) {
    const Eigen::Matrix3Xd& dN = geometric_tab_.dN[static_cast<std::size_t>(q)];
    const Eigen::Matrix3d J = dN * X.transpose();  // J(i, j) = dx_j / dxi_i
    const double det = J.determinant();
    min_det = std::min(min_det, det);
    (*gradients)[static_cast<std::size_t>(q)].noalias() = J.inverse() * dN;
    (*weights)(q) = geometric_tab_.weights(q) * det;
  }
  return min_det;
}

template <class StressAt>
double ElementIntegrator::GeometricStiffnessOf(const Eigen::Matrix3Xd& X, StressAt stress_at,
                                               Eigen::MatrixXd* k_G) {
  const double min_det = GeometricStiffnessPoints(X, &point_weights_, &point_grads_);
  k_G->setZero(num_nodes_, num_nodes_);
  for (std::size_t q = 0; q < point_grads_.size(); ++q) {
    const Eigen::Matrix3Xd& g = point_grads_[q];
    const Eigen::Matrix3d sigma = stress_at(g);
    k_G->noalias() += point_weights_(static_cast<Eigen::Index>(q)) * g.transpose() * (sigma * g);
  }
  return min_det;
}

double ElementIntegrator::ScalarGeometricStiffness(const Eigen::Matrix3Xd& X,
                                                   const IsotropicMaterial& material,
                                                   const Eigen::Matrix3Xd& u_e, Eigen::MatrixXd* k_G) {
  return GeometricStiffnessOf(
      X, [&](const Eigen::Matrix3Xd& g) { return LinearElasticStress(u_e * g.transpose(), material); }, k_G);
}

double ElementIntegrator::ScalarGeometricStiffness(const Eigen::Matrix3Xd& X, const Eigen::Matrix3d& sigma,
                                                   Eigen::MatrixXd* k_G) {
  return GeometricStiffnessOf(X, [&](const Eigen::Matrix3Xd&) { return sigma; }, k_G);
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
