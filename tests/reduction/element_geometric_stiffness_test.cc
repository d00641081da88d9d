// The element geometric stiffness K_G against exact integrals of polynomial fields: uniform
// stress, stress of a field of the element's own space, symmetry and rigid motions.
#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>
#include <Eigen/LU>
#include <array>
#include <cmath>
#include <cstdio>
#include <map>
#include <numbers>
#include <optional>
#include <random>
#include <span>
#include <vector>

#include "basis_test_support.h"
#include "core/error.h"
#include "fem/element_integrator.h"
#include "fem/geometric_stiffness.h"
#include "fem/mass_properties.h"
#include "fem/reference_element.h"
#include "reduction/dof_constraints.h"
#include "reduction/interior_problem.h"
#include "reduction/modal_basis.h"
#include "tests/fem/test_meshes.h"

namespace flexmbs {
namespace {

using fem::ElementType;
using Index = Eigen::Index;

// Quadrature against exact integrals of the same polynomial, or two orders of one sum: a few
// hundred roundings of O(1) terms.
constexpr double kRoundOff = 1e-12;

constexpr ElementType kAllTypes[] = {ElementType::kTet4,  ElementType::kTet10,  ElementType::kHex8,
                                     ElementType::kHex20, ElementType::kWedge6, ElementType::kWedge15};

const fem::IsotropicMaterial kSteel{"steel", 2.1e11, 0.3, 7850.0};

// ---- Polynomials in the reference coordinates, integrated exactly -------------------------

using Exponents = std::array<int, 3>;
using Polynomial = std::map<Exponents, double>;

Polynomial Product(const Polynomial& a, const Polynomial& b) {
  Polynomial p;
  for (const auto& [ea, ca] : a) {
    for (const auto& [eb, cb] : b) p[{ea[0] + eb[0], ea[1] + eb[1], ea[2] + eb[2]}] += ca * cb;
  }
  return p;
}

void AddScaled(const Polynomial& p, double s, Polynomial* sum) {
  for (const auto& [e, c] : p) (*sum)[e] += s * c;
}

Polynomial Derivative(const Polynomial& p, int axis) {
  Polynomial d;
  const auto k = static_cast<std::size_t>(axis);
  for (const auto& [e, c] : p) {
    if (e[k] == 0) continue;
    Exponents lowered = e;
    --lowered[k];
    d[lowered] += c * e[k];
  }
  return d;
}

double Evaluate(const Polynomial& p, const Eigen::Vector3d& xi) {
  double value = 0.0;
  for (const auto& [e, c] : p) value += c * std::pow(xi(0), e[0]) * std::pow(xi(1), e[1]) * std::pow(xi(2), e[2]);
  return value;
}

double Factorial(int n) { return n <= 1 ? 1.0 : n * Factorial(n - 1); }
// int_{-1}^{1} t^k dt.
double LineMoment(int k) { return k % 2 == 1 ? 0.0 : 2.0 / (k + 1); }

// The exact integral of xi^a eta^b zeta^c over the reference domain of `type` (reference_element.h):
// unit simplex a! b! c! / (a + b + c + 3)!; [-1, 1]^3; unit triangle a! b! / (a + b + 2)! x [-1, 1].
double MonomialIntegral(ElementType type, const Exponents& e) {
  switch (type) {
    case ElementType::kTet4:
    case ElementType::kTet10:
      return Factorial(e[0]) * Factorial(e[1]) * Factorial(e[2]) / Factorial(e[0] + e[1] + e[2] + 3);
    case ElementType::kHex8:
    case ElementType::kHex20: return LineMoment(e[0]) * LineMoment(e[1]) * LineMoment(e[2]);
    case ElementType::kWedge6:
    case ElementType::kWedge15:
      return Factorial(e[0]) * Factorial(e[1]) / Factorial(e[0] + e[1] + 2) * LineMoment(e[2]);
  }
  return 0.0;
}

double IntegrateReference(const Polynomial& p, ElementType type) {
  double sum = 0.0;
  for (const auto& [e, c] : p) sum += c * MonomialIntegral(type, e);
  return sum;
}

// The monomials that span each element's displacement space (reference_element.h).
std::vector<Exponents> Space(ElementType type) {
  const std::vector<Exponents> p1{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
  std::vector<Exponents> p2 = p1;
  p2.insert(p2.end(), {{2, 0, 0}, {0, 2, 0}, {0, 0, 2}, {1, 1, 0}, {0, 1, 1}, {1, 0, 1}});
  switch (type) {
    case ElementType::kTet4: return p1;
    case ElementType::kTet10: return p2;
    case ElementType::kHex8: {
      std::vector<Exponents> q1 = p1;
      q1.insert(q1.end(), {{1, 1, 0}, {0, 1, 1}, {1, 0, 1}, {1, 1, 1}});
      return q1;
    }
    case ElementType::kHex20: {
      std::vector<Exponents> s = p2;
      s.insert(s.end(), {{2, 1, 0}, {2, 0, 1}, {1, 2, 0}, {0, 2, 1}, {1, 0, 2}, {0, 1, 2}, {1, 1, 1}, {2, 1, 1},
                         {1, 2, 1}, {1, 1, 2}});
      return s;
    }
    case ElementType::kWedge6: {
      std::vector<Exponents> w = p1;
      w.insert(w.end(), {{1, 0, 1}, {0, 1, 1}});
      return w;
    }
    case ElementType::kWedge15: {
      std::vector<Exponents> w = p2;
      w.insert(w.end(), {{2, 0, 1}, {1, 1, 1}, {0, 2, 1}, {1, 0, 2}, {0, 1, 2}});
      return w;
    }
  }
  return {};
}

// A displacement field (three components) with random coefficients on `monomials`.
std::array<Polynomial, 3> RandomField(const std::vector<Exponents>& monomials, std::mt19937* rng) {
  std::uniform_real_distribution<double> coefficient(-1.0, 1.0);
  std::array<Polynomial, 3> u;
  for (Polynomial& component : u) {
    for (const Exponents& e : monomials) component[e] = 1e-3 * coefficient(*rng);
  }
  return u;
}

// An element x = A xi + x0 (an affine image of the reference element: straight-sided).
struct AffineElement {
  ElementType type;
  Eigen::Matrix3d A;
  Eigen::Matrix3Xd X;  // node coordinates
};

AffineElement RandomAffineElement(ElementType type, std::mt19937* rng) {
  std::uniform_real_distribution<double> u(-0.3, 0.3);
  AffineElement element{type, Eigen::Matrix3d::Identity(), {}};
  for (Index i = 0; i < 9; ++i) element.A.data()[i] += u(*rng);
  element.A *= 0.05;
  const Eigen::Vector3d x0(u(*rng), u(*rng), u(*rng));
  element.X = (element.A * fem::ReferenceElement::Of(type).nodes()).colwise() + x0;
  return element;
}

// The nodal values (3 x n) of a polynomial field.
Eigen::Matrix3Xd NodalValues(const AffineElement& element, const std::array<Polynomial, 3>& u) {
  const Eigen::Matrix3Xd& xi = fem::ReferenceElement::Of(element.type).nodes();
  Eigen::Matrix3Xd values(3, xi.cols());
  for (Index a = 0; a < xi.cols(); ++a) {
    for (int i = 0; i < 3; ++i) values(i, a) = Evaluate(u[static_cast<std::size_t>(i)], xi.col(a));
  }
  return values;
}

// H(i, k) = du_i/dx_k as polynomials in xi: du_i/dx_k = sum_j du_i/dxi_j (A^-1)(j, k).
using PolynomialMatrix = std::array<std::array<Polynomial, 3>, 3>;
PolynomialMatrix PhysicalGradient(const AffineElement& element, const std::array<Polynomial, 3>& u) {
  const Eigen::Matrix3d A_inv = element.A.inverse();
  PolynomialMatrix H;
  for (std::size_t i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j) {
      const Polynomial d = Derivative(u[i], j);
      for (std::size_t k = 0; k < 3; ++k) AddScaled(d, A_inv(j, static_cast<Index>(k)), &H[i][k]);
    }
  }
  return H;
}

// sigma = lambda tr(eps) I + 2 mu eps as polynomials.
PolynomialMatrix Stress(const PolynomialMatrix& H, const fem::IsotropicMaterial& material) {
  const double lambda = material.LameLambdaPa(), mu = material.ShearModulusPa();
  PolynomialMatrix sigma;
  for (std::size_t k = 0; k < 3; ++k) {
    for (std::size_t l = 0; l < 3; ++l) {
      AddScaled(H[k][l], mu, &sigma[k][l]);
      AddScaled(H[l][k], mu, &sigma[k][l]);
      if (k == l) {
        for (std::size_t m = 0; m < 3; ++m) AddScaled(H[m][m], lambda, &sigma[k][l]);
      }
    }
  }
  return sigma;
}

// int sum_i grad u_i . (sigma grad v_i) dV, exactly.
double ExactEnergy(const AffineElement& element, const PolynomialMatrix& Hu, const PolynomialMatrix& sigma,
                   const PolynomialMatrix& Hv) {
  Polynomial integrand;
  for (std::size_t i = 0; i < 3; ++i) {
    for (std::size_t k = 0; k < 3; ++k) {
      for (std::size_t l = 0; l < 3; ++l) AddScaled(Product(Product(Hu[i][k], sigma[k][l]), Hv[i][l]), 1.0, &integrand);
    }
  }
  return element.A.determinant() * IntegrateReference(integrand, element.type);
}

// u_e^T (k_G (x) I_3) v_e.
double DiscreteEnergy(const Eigen::MatrixXd& k_G, const Eigen::Matrix3Xd& u_e, const Eigen::Matrix3Xd& v_e) {
  return (u_e * k_G * v_e.transpose()).trace();
}

TEST(ElementGeometricStiffness, UniformStressGivesTheExactIntegralOfAQuadraticField) {
  std::mt19937 rng(17);
  for (const ElementType type : kAllTypes) {
    // A quadratic field where the element has one; else the element's own (bi/tri-linear) space.
    const std::vector<Exponents> monomials = fem::Traits(type).order == 2 ? Space(ElementType::kTet10) : Space(type);
    const AffineElement element = RandomAffineElement(type, &rng);
    const std::array<Polynomial, 3> u = RandomField(monomials, &rng), v = RandomField(monomials, &rng);
    Eigen::Matrix3d sigma0 = Eigen::Matrix3d::Random() * 1e8;
    sigma0 = (sigma0 + sigma0.transpose()).eval();
    PolynomialMatrix uniform;
    for (std::size_t k = 0; k < 3; ++k) {
      for (std::size_t l = 0; l < 3; ++l) uniform[k][l][{0, 0, 0}] = sigma0(static_cast<Index>(k), static_cast<Index>(l));
    }
    fem::ElementIntegrator integrator(type);
    Eigen::MatrixXd k_G;
    ASSERT_GT(integrator.ScalarGeometricStiffness(element.X, sigma0, &k_G), 0.0);
    const double exact = ExactEnergy(element, PhysicalGradient(element, u), uniform, PhysicalGradient(element, v));
    const double computed = DiscreteEnergy(k_G, NodalValues(element, u), NodalValues(element, v));
    EXPECT_NEAR(computed, exact, kRoundOff * std::abs(exact)) << fem::Traits(type).name;
  }
}

TEST(ElementGeometricStiffness, IsExactForTheStressOfAFieldOfTheElementsOwnSpace) {
  // On a straight-sided element the stress of a field w of the element's space and the
  // gradients of u, v of that space make a polynomial integrand of three gradient factors,
  // which the geometric-stiffness rule integrates exactly (element_integrator.h).
  std::mt19937 rng(29);
  for (const ElementType type : kAllTypes) {
    const std::vector<Exponents> monomials = Space(type);
    for (int trial = 0; trial < 2; ++trial) {
      const AffineElement element = RandomAffineElement(type, &rng);
      const std::array<Polynomial, 3> u = RandomField(monomials, &rng), v = RandomField(monomials, &rng),
                                      w = RandomField(monomials, &rng);
      fem::ElementIntegrator integrator(type);
      Eigen::MatrixXd k_G;
      ASSERT_GT(integrator.ScalarGeometricStiffness(element.X, kSteel, NodalValues(element, w), &k_G), 0.0);
      const double exact = ExactEnergy(element, PhysicalGradient(element, u),
                                       Stress(PhysicalGradient(element, w), kSteel), PhysicalGradient(element, v));
      const double computed = DiscreteEnergy(k_G, NodalValues(element, u), NodalValues(element, v));
      EXPECT_NEAR(computed, exact, kRoundOff * std::abs(exact)) << fem::Traits(type).name;
    }
  }
}

TEST(ElementGeometricStiffness, IsSymmetricAndRigidMotionsNeitherStressNorFeelIt) {
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> uniform(-1.0, 1.0);
  for (const ElementType type : kAllTypes) {
    const AffineElement element = RandomAffineElement(type, &rng);
    const Index n = element.X.cols();
    Eigen::Matrix3Xd u_e(3, n);
    for (Index i = 0; i < u_e.size(); ++i) u_e.data()[i] = 1e-4 * uniform(rng);
    fem::ElementIntegrator integrator(type);
    Eigen::MatrixXd k_G;
    integrator.ScalarGeometricStiffness(element.X, kSteel, u_e, &k_G);
    const double scale = k_G.cwiseAbs().maxCoeff();
    ASSERT_GT(scale, 0.0);
    EXPECT_LE((k_G - k_G.transpose()).cwiseAbs().maxCoeff(), kRoundOff * scale) << fem::Traits(type).name;
    // A rigid translation t: K_G,e (1 (x) t) = (k_G 1) (x) t, zero since sum_a grad N_a = 0.
    EXPECT_LE((k_G * Eigen::VectorXd::Ones(n)).cwiseAbs().maxCoeff(), kRoundOff * scale) << fem::Traits(type).name;
    // An infinitesimal rigid rotation theta x r has no strain, hence no stress.
    const Eigen::Vector3d theta(1e-3, -2e-3, 0.5e-3);
    Eigen::Matrix3Xd rotation(3, n);
    for (Index a = 0; a < n; ++a) rotation.col(a) = theta.cross(element.X.col(a));
    Eigen::MatrixXd k_rotation;
    integrator.ScalarGeometricStiffness(element.X, kSteel, rotation, &k_rotation);
    Eigen::MatrixXd k_strained;
    const Eigen::Matrix3d stretch = 1e-3 * Eigen::Matrix3d::Identity();
    integrator.ScalarGeometricStiffness(element.X, kSteel, stretch * element.X, &k_strained);
    EXPECT_LE(k_rotation.cwiseAbs().maxCoeff(), kRoundOff * k_strained.cwiseAbs().maxCoeff()) << fem::Traits(type).name;
  }
}

}  // namespace
}  // namespace flexmbs
