// Element stiffness against an independent textbook formulation: the Voigt B matrix and the
// 6x6 isotropic D, integrated with the general (curved-exact) stiffness rule.
#include <gtest/gtest.h>

#include <Eigen/LU>
#include <random>

#include "fem/element_integrator.h"
#include "fem/quadrature.h"
#include "fem/reference_element.h"
#include "tests/fem/test_meshes.h"

namespace flexmbs::fem {
namespace {

// Both sides sum the same exact integrals in another order.
constexpr double kRoundOffTolerance = 1e-12;

// K_e = sum_q w det J B^T D B with B the 6 x 3n strain-displacement matrix
// (eps = [exx, eyy, ezz, 2exy, 2eyz, 2exz]) and D the isotropic Voigt matrix.
Eigen::MatrixXd VoigtStiffness(ElementType type, const Eigen::Matrix3Xd& X,
                               const IsotropicMaterial& m) {
  const double lambda = m.LameLambdaPa(), mu = m.ShearModulusPa();
  Eigen::Matrix<double, 6, 6> D = Eigen::Matrix<double, 6, 6>::Zero();
  D.topLeftCorner<3, 3>().setConstant(lambda);
  D.topLeftCorner<3, 3>().diagonal().array() += 2.0 * mu;
  D.bottomRightCorner<3, 3>().diagonal().setConstant(mu);
  const QuadratureRule& rule = StiffnessRule(type);
  const ReferenceElement& ref = ReferenceElement::Of(type);
  const auto n = X.cols();
  Eigen::MatrixXd K = Eigen::MatrixXd::Zero(3 * n, 3 * n);
  for (Eigen::Index q = 0; q < rule.weights.size(); ++q) {
    Eigen::VectorXd N;
    Eigen::Matrix3Xd dN;
    ref.Evaluate(rule.points.col(q), &N, &dN);
    const Eigen::Matrix3d J = dN * X.transpose();
    const Eigen::Matrix3Xd g = J.inverse() * dN;
    Eigen::MatrixXd B = Eigen::MatrixXd::Zero(6, 3 * n);
    for (Eigen::Index a = 0; a < n; ++a) {
      B(0, 3 * a) = g(0, a);
      B(1, 3 * a + 1) = g(1, a);
      B(2, 3 * a + 2) = g(2, a);
      B(3, 3 * a) = g(1, a), B(3, 3 * a + 1) = g(0, a);
      B(4, 3 * a + 1) = g(2, a), B(4, 3 * a + 2) = g(1, a);
      B(5, 3 * a) = g(2, a), B(5, 3 * a + 2) = g(0, a);
    }
    K += rule.weights(q) * J.determinant() * B.transpose() * D * B;
  }
  return K;
}

// The nodes of one reference element mapped by a random affine map, then (if `curve`) the
// mid-edge nodes moved off their edges.
Eigen::Matrix3Xd RandomElement(ElementType type, bool curve, std::mt19937* rng) {
  std::uniform_real_distribution<double> u(-0.1, 0.1);
  Eigen::Matrix3d A = Eigen::Matrix3d::Identity() * 0.02;
  for (int i = 0; i < 9; ++i) A.data()[i] += 0.02 * u(*rng);
  Eigen::Matrix3Xd X = A * ReferenceElement::Of(type).nodes();
  const int corners = Traits(type).order == 1 ? Traits(type).num_nodes
                      : type == ElementType::kTet10 ? 4 : type == ElementType::kHex20 ? 8 : 6;
  if (curve) {
    for (Eigen::Index a = corners; a < X.cols(); ++a) {
      X.col(a) += 0.002 * Eigen::Vector3d(u(*rng), u(*rng), u(*rng));
    }
  }
  return X;
}

TEST(ElementIntegrator, StiffnessEqualsVoigtFormulationForEveryTypeStraightAndCurved) {
  std::mt19937 rng(3);
  const IsotropicMaterial steel = testing::Steel();
  for (const ElementTraits& t : kElementTraits) {
    for (bool curve : {false, true}) {
      if (curve && t.order == 1) continue;
      const Eigen::Matrix3Xd X = RandomElement(t.type, curve, &rng);
      ElementIntegrator integrator(t.type);
      Eigen::MatrixXd K;
      ASSERT_GT(integrator.Stiffness(X, steel, &K), 0.0);
      const Eigen::MatrixXd reference = VoigtStiffness(t.type, X, steel);
      EXPECT_LT((K - reference).norm(), kRoundOffTolerance * reference.norm())
          << t.name << (curve ? " curved" : " straight");
    }
  }
}

}  // namespace
}  // namespace flexmbs::fem
