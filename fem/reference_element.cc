#include "fem/reference_element.h"

#include <Eigen/LU>
#include <array>
#include <cmath>

#include "core/error.h"

namespace flexmbs::fem {
namespace {

// Reference node coordinates in gmsh order (gmsh::model::mesh::getElementProperties).
Eigen::Matrix3Xd Nodes(std::initializer_list<std::array<double, 3>> xyz) {
  Eigen::Matrix3Xd nodes(3, static_cast<Eigen::Index>(xyz.size()));
  Eigen::Index a = 0;
  for (const auto& p : xyz) nodes.col(a++) = Eigen::Vector3d(p[0], p[1], p[2]);
  return nodes;
}

// Monomial exponents, one column per basis monomial.
Eigen::Matrix3Xi Monomials(std::initializer_list<std::array<int, 3>> exps) {
  Eigen::Matrix3Xi e(3, static_cast<Eigen::Index>(exps.size()));
  Eigen::Index k = 0;
  for (const auto& p : exps) e.col(k++) = Eigen::Vector3i(p[0], p[1], p[2]);
  return e;
}

double Power(double x, int n) {
  double r = 1.0;
  for (int i = 0; i < n; ++i) r *= x;
  return r;
}

// Value and gradient of the monomial with exponents `e` at `xi`.
void Monomial(const Eigen::Vector3i& e, const Eigen::Vector3d& xi, double* value,
              Eigen::Vector3d* grad) {
  const Eigen::Vector3d p(Power(xi(0), e(0)), Power(xi(1), e(1)), Power(xi(2), e(2)));
  *value = p(0) * p(1) * p(2);
  for (int d = 0; d < 3; ++d) {
    double dp = e(d) == 0 ? 0.0 : e(d) * Power(xi(d), e(d) - 1);
    (*grad)(d) = dp * p((d + 1) % 3) * p((d + 2) % 3);
  }
}

const Eigen::Matrix3Xi kP1 = Monomials({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}});
const Eigen::Matrix3Xi kP2 = Monomials({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}, {2, 0, 0},
                                        {0, 2, 0}, {0, 0, 2}, {1, 1, 0}, {0, 1, 1}, {1, 0, 1}});
const Eigen::Matrix3Xi kQ1 = Monomials({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}, {1, 1, 0},
                                        {0, 1, 1}, {1, 0, 1}, {1, 1, 1}});
// Serendipity space of the 20-node brick: P2 plus the cubic and quartic terms that are at most
// linear in two of the three coordinates.
const Eigen::Matrix3Xi kS20 = Monomials(
    {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}, {2, 0, 0}, {0, 2, 0}, {0, 0, 2},
     {1, 1, 0}, {0, 1, 1}, {1, 0, 1}, {2, 1, 0}, {2, 0, 1}, {1, 2, 0}, {0, 2, 1},
     {1, 0, 2}, {0, 1, 2}, {1, 1, 1}, {2, 1, 1}, {1, 2, 1}, {1, 1, 2}});
// P1(triangle) x Q1(line).
const Eigen::Matrix3Xi kW6 =
    Monomials({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}, {1, 0, 1}, {0, 1, 1}});
// Serendipity wedge: P2(triangle) x Q1(line) plus zeta^2, xi zeta^2, eta zeta^2.
const Eigen::Matrix3Xi kW15 =
    Monomials({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {2, 0, 0}, {1, 1, 0}, {0, 2, 0}, {0, 0, 1},
               {1, 0, 1}, {0, 1, 1}, {2, 0, 1}, {1, 1, 1}, {0, 2, 1}, {0, 0, 2}, {1, 0, 2},
               {0, 1, 2}});

}  // namespace

ReferenceElement::ReferenceElement(ElementType type, Eigen::Matrix3Xd nodes,
                                   Eigen::Matrix3Xi exponents)
    : type_(type), nodes_(std::move(nodes)), exponents_(std::move(exponents)) {
  const Eigen::Index n = nodes_.cols();
  FLEXMBS_CHECK(exponents_.cols() == n, "basis size must equal the node count");
  // Vandermonde V(a, k) = monomial_k(node_a); N = P(xi)^T V^-1.
  Eigen::MatrixXd V(n, n);
  for (Eigen::Index a = 0; a < n; ++a) {
    for (Eigen::Index k = 0; k < n; ++k) {
      Eigen::Vector3d grad;
      Monomial(exponents_.col(k), nodes_.col(a), &V(a, k), &grad);
    }
  }
  Eigen::FullPivLU<Eigen::MatrixXd> lu(V);
  FLEXMBS_CHECK(lu.isInvertible(), "nodes must be unisolvent for the monomial basis");
  coefficients_ = lu.inverse();
}

const ReferenceElement& ReferenceElement::Of(ElementType type) {
  static const ReferenceElement kElements[] = {
      ReferenceElement(ElementType::kTet4, Nodes({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}}),
                       kP1),
      ReferenceElement(ElementType::kTet10,
                       Nodes({{0, 0, 0},
                              {1, 0, 0},
                              {0, 1, 0},
                              {0, 0, 1},
                              {0.5, 0, 0},
                              {0.5, 0.5, 0},
                              {0, 0.5, 0},
                              {0, 0, 0.5},
                              {0, 0.5, 0.5},
                              {0.5, 0, 0.5}}),
                       kP2),
      ReferenceElement(ElementType::kHex8,
                       Nodes({{-1, -1, -1},
                              {1, -1, -1},
                              {1, 1, -1},
                              {-1, 1, -1},
                              {-1, -1, 1},
                              {1, -1, 1},
                              {1, 1, 1},
                              {-1, 1, 1}}),
                       kQ1),
      ReferenceElement(ElementType::kHex20,
                       Nodes({{-1, -1, -1}, {1, -1, -1}, {1, 1, -1}, {-1, 1, -1}, {-1, -1, 1},
                              {1, -1, 1},   {1, 1, 1},   {-1, 1, 1},  {0, -1, -1},  {-1, 0, -1},
                              {-1, -1, 0},  {1, 0, -1},  {1, -1, 0},  {0, 1, -1},   {1, 1, 0},
                              {-1, 1, 0},   {0, -1, 1},  {-1, 0, 1},  {1, 0, 1},    {0, 1, 1}}),
                       kS20),
      ReferenceElement(
          ElementType::kWedge6,
          Nodes({{0, 0, -1}, {1, 0, -1}, {0, 1, -1}, {0, 0, 1}, {1, 0, 1}, {0, 1, 1}}), kW6),
      ReferenceElement(ElementType::kWedge15,
                       Nodes({{0, 0, -1},
                              {1, 0, -1},
                              {0, 1, -1},
                              {0, 0, 1},
                              {1, 0, 1},
                              {0, 1, 1},
                              {0.5, 0, -1},
                              {0, 0.5, -1},
                              {0, 0, 0},
                              {0.5, 0.5, -1},
                              {1, 0, 0},
                              {0, 1, 0},
                              {0.5, 0, 1},
                              {0, 0.5, 1},
                              {0.5, 0.5, 1}}),
                       kW15),
  };
  return kElements[static_cast<int>(type)];
}

void ReferenceElement::Evaluate(const Eigen::Vector3d& xi, Eigen::VectorXd* N,
                                Eigen::Matrix3Xd* dN) const {
  const Eigen::Index n = nodes_.cols();
  Eigen::VectorXd p(n);
  Eigen::Matrix3Xd dp(3, n);
  for (Eigen::Index k = 0; k < n; ++k) {
    Eigen::Vector3d grad;
    Monomial(exponents_.col(k), xi, &p(k), &grad);
    dp.col(k) = grad;
  }
  if (N != nullptr) *N = coefficients_.transpose() * p;
  if (dN != nullptr) *dN = dp * coefficients_;
}

}  // namespace flexmbs::fem
