// Quadrature rules: exact monomial integrals on each reference domain up to the stated degree,
// sharpness of the tetrahedron degrees, and weights summing to the reference volume.

#include "fem/quadrature.h"

#include <gtest/gtest.h>

#include <cmath>
#include <string>

namespace flexmbs::fem {
namespace {

// Monomial integrals are O(1e-3 .. 1); a rule with tabulated 16-digit points is exact to a
// few machine epsilons. Dunavant's triangle points are tabulated to 15 digits only: 1e-14.
constexpr double kExactTol = 1e-14;
// A rule "misses" a monomial if its error is far above round-off.
constexpr double kMissTol = 1e-8;

// n! as a double.
double Factorial(int n) { return n <= 1 ? 1.0 : n * Factorial(n - 1); }

// int_{-1}^{1} t^a dt.
double LineIntegral(int a) { return a % 2 == 1 ? 0.0 : 2.0 / (a + 1); }

// Exact integral of xi^a eta^b zeta^c over the reference domain of `type`.
double ExactMonomialIntegral(ElementType type, int a, int b, int c) {
  switch (type) {
    case ElementType::kTet4:
    case ElementType::kTet10:  // unit simplex: a! b! c! / (a + b + c + 3)!
      return Factorial(a) * Factorial(b) * Factorial(c) / Factorial(a + b + c + 3);
    case ElementType::kHex8:
    case ElementType::kHex20:
      return LineIntegral(a) * LineIntegral(b) * LineIntegral(c);
    case ElementType::kWedge6:
    case ElementType::kWedge15:  // unit triangle a! b! / (a + b + 2)!, times [-1, 1]
      return Factorial(a) * Factorial(b) / Factorial(a + b + 2) * LineIntegral(c);
  }
  return NAN;
}

// The rule's approximation of the same integral.
double RuleMonomialIntegral(const QuadratureRule& rule, int a, int b, int c) {
  double sum = 0.0;
  for (Eigen::Index q = 0; q < rule.weights.size(); ++q) {
    sum += rule.weights(q) * std::pow(rule.points(0, q), a) * std::pow(rule.points(1, q), b) *
           std::pow(rule.points(2, q), c);
  }
  return sum;
}

bool IsHex(ElementType type) { return type == ElementType::kHex8 || type == ElementType::kHex20; }

// Whether the rule claims exactness for xi^a eta^b zeta^c: total degree for simplices and
// wedges, degree in each variable separately (tensor degree) for hexahedra.
bool Claimed(ElementType type, int degree, int a, int b, int c) {
  return IsHex(type) ? std::max({a, b, c}) <= degree : a + b + c <= degree;
}

struct RuleCase {
  ElementType type;
  bool mass;
};

// The case's test name suffix, e.g. "tet10Mass"; also how gtest prints it.
std::string CaseName(const RuleCase& c) {
  return std::string(Traits(c.type).name) + (c.mass ? "Mass" : "Stiffness");
}
void PrintTo(const RuleCase& c, std::ostream* os) { *os << CaseName(c); }

class QuadratureTest : public ::testing::TestWithParam<RuleCase> {
 protected:
  const QuadratureRule& rule() const {
    return GetParam().mass ? MassRule(GetParam().type) : StiffnessRule(GetParam().type);
  }
};

TEST_P(QuadratureTest, WeightsSumToReferenceVolume) {
  EXPECT_NEAR(rule().weights.sum(), ExactMonomialIntegral(GetParam().type, 0, 0, 0), kExactTol);
}

TEST_P(QuadratureTest, PointsLieInsideTheReferenceDomainWithPositiveWeights) {
  const ElementType type = GetParam().type;
  for (Eigen::Index q = 0; q < rule().weights.size(); ++q) {
    const Eigen::Vector3d p = rule().points.col(q);
    EXPECT_GT(rule().weights(q), 0.0);
    if (IsHex(type)) {
      EXPECT_LE(p.cwiseAbs().maxCoeff(), 1.0);
    } else if (type == ElementType::kTet4 || type == ElementType::kTet10) {
      EXPECT_GE(p.minCoeff(), 0.0);
      EXPECT_LE(p.sum(), 1.0);
    } else {
      EXPECT_GE(p.head<2>().minCoeff(), 0.0);
      EXPECT_LE(p(0) + p(1), 1.0);
      EXPECT_LE(std::abs(p(2)), 1.0);
    }
  }
}

TEST_P(QuadratureTest, IntegratesEveryMonomialUpToItsDegreeExactly) {
  const ElementType type = GetParam().type;
  const int degree = rule().degree;
  int checked = 0;
  for (int a = 0; a <= degree; ++a) {
    for (int b = 0; b <= degree; ++b) {
      for (int c = 0; c <= degree; ++c) {
        if (!Claimed(type, degree, a, b, c)) continue;
        ++checked;
        EXPECT_NEAR(RuleMonomialIntegral(rule(), a, b, c), ExactMonomialIntegral(type, a, b, c),
                    kExactTol)
            << "x^" << a << " y^" << b << " z^" << c;
      }
    }
  }
  EXPECT_GT(checked, 0);
}

TEST(QuadratureRules, TetrahedronDegreesAreSharp) {
  // Some monomial of total degree + 1 is not integrated exactly (the stated degree is the
  // rule's real degree, not an under-statement).
  for (ElementType type : {ElementType::kTet4, ElementType::kTet10}) {
    for (const QuadratureRule* rule : {&StiffnessRule(type), &MassRule(type)}) {
      const int d = rule->degree + 1;
      double worst = 0.0;
      for (int a = 0; a <= d; ++a) {
        for (int b = 0; a + b <= d; ++b) {
          worst = std::max(worst, std::abs(RuleMonomialIntegral(*rule, a, b, d - a - b) -
                                           ExactMonomialIntegral(type, a, b, d - a - b)));
        }
      }
      EXPECT_GT(worst, kMissTol) << Traits(type).name << ": degree " << d << " is also exact";
    }
  }
}

TEST(QuadratureRules, DegreesCoverTheElementIntegrandsAndCurvedJacobians) {
  // Mass: N_a N_b (total degree 2 order for tetrahedra, degree 2 order per variable for
  // hexahedra). Stiffness: grad N_a . grad N_b on an affine element, and det J of a curved
  // isoparametric element (what the patch test needs): cubic for tet10, per-variable degree
  // 1 + 1 + 0 = 2 for hex8 and 1 + 2 + 2 = 5 for hex20 (serendipity map). Wedges: see
  // WedgeRulesAreTensorProductsOfTriangleAndGaussRules.
  struct Need {
    ElementType type;
    int mass, stiffness;
  };
  for (const Need& n : {Need{ElementType::kTet4, 2, 0}, Need{ElementType::kTet10, 4, 3},
                        Need{ElementType::kHex8, 2, 2}, Need{ElementType::kHex20, 4, 5}}) {
    EXPECT_GE(MassRule(n.type).degree, n.mass) << Traits(n.type).name;
    EXPECT_GE(StiffnessRule(n.type).degree, n.stiffness) << Traits(n.type).name;
  }
}

// Wedge rules: exact for xi^a eta^b zeta^c with a + b <= triangle degree and c <= line degree
// (2 x Gauss points - 1), as stated in quadrature.h: wedge6 3-point triangle (degree 2) x 2
// Gauss points, wedge15 6-point triangle (degree 4) x 3 Gauss points. That is what N_a N_b
// needs (in-plane degree 2 order, axial 2 or 4) and what det J of a curved wedge needs
// (in-plane 1 or 4, axial 2 or 5).
TEST(QuadratureRules, WedgeRulesAreTensorProductsOfTriangleAndGaussRules) {
  struct Case {
    ElementType type;
    int triangle_degree, line_degree;
  };
  for (const Case& k : {Case{ElementType::kWedge6, 2, 3}, Case{ElementType::kWedge15, 4, 5}}) {
    for (const QuadratureRule* rule : {&StiffnessRule(k.type), &MassRule(k.type)}) {
      for (int a = 0; a <= k.triangle_degree; ++a) {
        for (int b = 0; a + b <= k.triangle_degree; ++b) {
          for (int c = 0; c <= k.line_degree; ++c) {
            EXPECT_NEAR(RuleMonomialIntegral(*rule, a, b, c),
                        ExactMonomialIntegral(k.type, a, b, c), kExactTol)
                << Traits(k.type).name << " x^" << a << " y^" << b << " z^" << c;
          }
        }
      }
    }
  }
}

TEST(QuadratureRules, GaussLineIntegratesUpToDegreeTwoNMinusOne) {
  for (int n = 1; n <= 4; ++n) {
    const QuadratureRule rule = GaussLine(n);
    ASSERT_EQ(rule.degree, 2 * n - 1);
    for (int a = 0; a <= 2 * n; ++a) {
      const double error = std::abs(RuleMonomialIntegral(rule, a, 0, 0) - LineIntegral(a));
      if (a <= 2 * n - 1) {
        EXPECT_LT(error, kExactTol) << n << " points, t^" << a;
      } else {
        EXPECT_GT(error, kMissTol) << n << " points, t^" << a;
      }
    }
  }
}

INSTANTIATE_TEST_SUITE_P(
    AllRules, QuadratureTest,
    ::testing::Values(RuleCase{ElementType::kTet4, false}, RuleCase{ElementType::kTet4, true},
                      RuleCase{ElementType::kTet10, false}, RuleCase{ElementType::kTet10, true},
                      RuleCase{ElementType::kHex8, false}, RuleCase{ElementType::kHex8, true},
                      RuleCase{ElementType::kHex20, false}, RuleCase{ElementType::kHex20, true},
                      RuleCase{ElementType::kWedge6, false}, RuleCase{ElementType::kWedge6, true},
                      RuleCase{ElementType::kWedge15, false},
                      RuleCase{ElementType::kWedge15, true}),
    [](const auto& param_info) { return CaseName(param_info.param); });

}  // namespace
}  // namespace flexmbs::fem
