// Reference elements: nodal (Kronecker) property, partition of unity, reproduction of linear and
// quadratic fields, and agreement with gmsh's own Lagrange basis functions.

#include <gmsh.h>
#include <gtest/gtest.h>

#include <random>
#include <string>
#include <vector>

#include "fem/reference_element.h"
#include "tests/support/random_draws.h"

namespace flexmbs::fem {
namespace {

// Round-off on O(1) basis values built from a 20x20 inverse Vandermonde matrix: a few hundred
// machine epsilons.
constexpr double kBasisTol = 1e-12;

class ReferenceElementTest : public ::testing::TestWithParam<ElementType> {};

// Uniform random points inside the reference domain of `type`.
std::vector<Eigen::Vector3d> RandomPoints(ElementType type, int count, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  std::vector<Eigen::Vector3d> points;
  while (static_cast<int>(points.size()) < count) {
    const Eigen::Vector3d u = flexmbs::testing::DrawVector3(unit, rng);
    switch (type) {
      case ElementType::kTet4:
      case ElementType::kTet10:
        if (u.sum() <= 1.0) points.push_back(u);
        break;
      case ElementType::kHex8:
      case ElementType::kHex20:
        points.push_back(2.0 * u.array() - 1.0);
        break;
      case ElementType::kWedge6:
      case ElementType::kWedge15:
        if (u(0) + u(1) <= 1.0) points.emplace_back(u(0), u(1), 2.0 * u(2) - 1.0);
        break;
    }
  }
  return points;
}

TEST_P(ReferenceElementTest, ShapeFunctionsAreOneAtTheirNodeAndZeroAtTheOthers) {
  const ReferenceElement& ref = ReferenceElement::Of(GetParam());
  ASSERT_EQ(ref.num_nodes(), Traits(GetParam()).num_nodes);
  for (int b = 0; b < ref.num_nodes(); ++b) {
    Eigen::VectorXd N;
    ref.Evaluate(ref.nodes().col(b), &N, nullptr);
    for (int a = 0; a < ref.num_nodes(); ++a) {
      EXPECT_NEAR(N(a), a == b ? 1.0 : 0.0, kBasisTol) << "N_" << a << " at node " << b;
    }
  }
}

TEST_P(ReferenceElementTest, ShapeFunctionsSumToOneAndGradientsSumToZero) {
  const ReferenceElement& ref = ReferenceElement::Of(GetParam());
  for (const Eigen::Vector3d& xi : RandomPoints(GetParam(), 20, 1)) {
    Eigen::VectorXd N;
    Eigen::Matrix3Xd dN;
    ref.Evaluate(xi, &N, &dN);
    EXPECT_NEAR(N.sum(), 1.0, kBasisTol);
    EXPECT_LT(dN.rowwise().sum().norm(), kBasisTol);
  }
}

TEST_P(ReferenceElementTest, InterpolatesLinearFieldsExactly) {
  // sum_a N_a xi_a = xi and sum_a xi_a (x) grad N_a = I: the isoparametric map of the reference
  // element is the identity, so any linear displacement field is in the space.
  const ReferenceElement& ref = ReferenceElement::Of(GetParam());
  for (const Eigen::Vector3d& xi : RandomPoints(GetParam(), 20, 2)) {
    Eigen::VectorXd N;
    Eigen::Matrix3Xd dN;
    ref.Evaluate(xi, &N, &dN);
    EXPECT_LT((ref.nodes() * N - xi).norm(), kBasisTol);
    EXPECT_LT((ref.nodes() * dN.transpose() - Eigen::Matrix3d::Identity()).norm(), kBasisTol);
  }
}

class QuadraticElementTest : public ::testing::TestWithParam<ElementType> {};

TEST_P(QuadraticElementTest, InterpolatesCompleteQuadraticsExactly) {
  // P2 is inside each quadratic space (complete P2, the 20-node and 15-node serendipity spaces).
  const ReferenceElement& ref = ReferenceElement::Of(GetParam());
  // f(xi) = a quadratic with all ten coefficients non-zero, and its gradient.
  auto f = [](const Eigen::Vector3d& p) {
    const double x = p(0), y = p(1), z = p(2);
    return 0.3 - x + 2 * y + 0.5 * z + 1.5 * x * x - 0.7 * y * y + 0.9 * z * z + 1.1 * x * y -
           1.3 * y * z + 0.4 * x * z;
  };
  auto grad_f = [](const Eigen::Vector3d& p) {
    const double x = p(0), y = p(1), z = p(2);
    return Eigen::Vector3d(-1 + 3 * x + 1.1 * y + 0.4 * z, 2 - 1.4 * y + 1.1 * x - 1.3 * z,
                           0.5 + 1.8 * z - 1.3 * y + 0.4 * x);
  };
  Eigen::VectorXd f_nodes(ref.num_nodes());
  for (int a = 0; a < ref.num_nodes(); ++a) f_nodes(a) = f(ref.nodes().col(a));
  for (const Eigen::Vector3d& xi : RandomPoints(GetParam(), 20, 3)) {
    Eigen::VectorXd N;
    Eigen::Matrix3Xd dN;
    ref.Evaluate(xi, &N, &dN);
    EXPECT_NEAR(N.dot(f_nodes), f(xi), kBasisTol);
    EXPECT_LT((dN * f_nodes - grad_f(xi)).norm(), kBasisTol);
  }
}

// gmsh's library state: initialised once per process, never finalised (fem::ImportMesh shares it).
void EnsureGmsh() {
  static const bool initialized = [] {
    gmsh::initialize(0, nullptr, false);
    gmsh::option::setNumber("General.Terminal", 0);
    return true;
  }();
  (void)initialized;
}

TEST_P(ReferenceElementTest, NodesAreGmshReferenceNodesInGmshOrder) {
  EnsureGmsh();
  const ReferenceElement& ref = ReferenceElement::Of(GetParam());
  std::string name;
  int dim = 0, order = 0, num_nodes = 0, num_primary = 0;
  std::vector<double> local;
  gmsh::model::mesh::getElementProperties(Traits(GetParam()).gmsh_type, name, dim, order, num_nodes,
                                          local, num_primary);
  ASSERT_EQ(dim, 3);
  ASSERT_EQ(order, Traits(GetParam()).order);
  ASSERT_EQ(num_nodes, ref.num_nodes()) << name;
  for (int a = 0; a < num_nodes; ++a) {
    const Eigen::Vector3d gmsh_xi(local[3 * a], local[3 * a + 1], local[3 * a + 2]);
    EXPECT_LT((gmsh_xi - ref.nodes().col(a)).norm(), kBasisTol) << name << " node " << a;
  }
}

TEST_P(ReferenceElementTest, ShapeFunctionsAndGradientsEqualGmshLagrangeBasis) {
  // gmsh 4.8's "Lagrange" space of an element type is the nodal basis of that type's own
  // polynomial space: for hex20 (type 17) and wedge15 (type 18) that is the serendipity space
  // (checked: 20 and 15 functions, not the 27/18 of the complete hex27/wedge18), the same
  // spaces flexmbs uses, so every function is compared. A type whose basis size differed would
  // be a different space and is reported as a failure rather than silently skipped.
  EnsureGmsh();
  const ReferenceElement& ref = ReferenceElement::Of(GetParam());
  const std::vector<Eigen::Vector3d> points = RandomPoints(GetParam(), 6, 4);
  std::vector<double> local;
  for (const Eigen::Vector3d& p : points) local.insert(local.end(), {p(0), p(1), p(2)});
  int components = 0, orientations = 0;
  std::vector<double> values, gradients;
  const int gmsh_type = Traits(GetParam()).gmsh_type;
  gmsh::model::mesh::getBasisFunctions(gmsh_type, local, "Lagrange", components, values,
                                       orientations);
  ASSERT_EQ(components, 1);
  ASSERT_EQ(values.size(), points.size() * static_cast<std::size_t>(ref.num_nodes()))
      << "gmsh's space for type " << gmsh_type << " has a different dimension";
  gmsh::model::mesh::getBasisFunctions(gmsh_type, local, "GradLagrange", components, gradients,
                                       orientations);
  ASSERT_EQ(components, 3);
  ASSERT_EQ(gradients.size(), 3 * values.size());
  const auto n = static_cast<std::size_t>(ref.num_nodes());
  for (std::size_t g = 0; g < points.size(); ++g) {
    Eigen::VectorXd N;
    Eigen::Matrix3Xd dN;
    ref.Evaluate(points[g], &N, &dN);
    for (std::size_t a = 0; a < n; ++a) {
      const auto ai = static_cast<Eigen::Index>(a);
      EXPECT_NEAR(N(ai), values[g * n + a], kBasisTol) << "N_" << a << " at point " << g;
      for (std::size_t i = 0; i < 3; ++i) {
        EXPECT_NEAR(dN(static_cast<Eigen::Index>(i), ai), gradients[3 * (g * n + a) + i], kBasisTol)
            << "dN_" << a << "/dxi_" << i << " at point " << g;
      }
    }
  }
}

INSTANTIATE_TEST_SUITE_P(AllTypes, ReferenceElementTest,
                         ::testing::Values(ElementType::kTet4, ElementType::kTet10,
                                           ElementType::kHex8, ElementType::kHex20,
                                           ElementType::kWedge6, ElementType::kWedge15),
                         [](const auto& param_info) {
                           return std::string(Traits(param_info.param).name);
                         });
INSTANTIATE_TEST_SUITE_P(QuadraticTypes, QuadraticElementTest,
                         ::testing::Values(ElementType::kTet10, ElementType::kHex20,
                                           ElementType::kWedge15),
                         [](const auto& param_info) {
                           return std::string(Traits(param_info.param).name);
                         });

}  // namespace
}  // namespace flexmbs::fem
