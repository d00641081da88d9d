// Rigid-body modes and the free-free eigenproblem K phi = lambda M phi: exactly six zero
// eigenvalues, well separated from the first elastic one, whose eigenvectors span the rigid-body
// fields.

#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>
#include <random>
#include <string>

#include "fem/assembly.h"
#include "fem/mass_properties.h"
#include "tests/fem/test_meshes.h"

namespace flexmbs::fem {
namespace {

// A rigid-body eigenvalue is round-off, ~eps * lambda_max ~ eps * lambda_7 * (L / h)^2 * 10;
// measured max |lambda_1..6| / lambda_7 = 1e-14 .. 1e-12 on these meshes. 1e-8 leaves margin
// and still separates sharply.
constexpr double kZeroEigenvalueRatio = 1e-8;
// Eigenvectors from Eigen's dense solver of a <= 525 x 525 problem: M-orthonormal and
// residual-free to ~1e-12 relative; 1e-9 for the projections that involve cond(M) ~ 1e2.
constexpr double kEigenTol = 1e-9;

TEST(RigidBodyModes, ColumnsAreUnitTranslationsAndRotationsAboutTheAxes) {
  Eigen::Matrix3Xd nodes(3, 2);
  nodes << 0.3, -1.0, 2.0, 0.5, -0.7, 4.0;
  const Eigen::MatrixXd R = RigidBodyModes(nodes);
  ASSERT_EQ(R.rows(), 6);
  ASSERT_EQ(R.cols(), 6);
  for (int v = 0; v < 2; ++v) {
    for (int i = 0; i < 3; ++i) {
      const Eigen::Vector3d e = Eigen::Vector3d::Unit(i);
      EXPECT_EQ((R.block<3, 1>(3 * v, i) - e).norm(), 0.0);
      EXPECT_EQ((R.block<3, 1>(3 * v, 3 + i) - e.cross(nodes.col(v))).norm(), 0.0);
    }
  }
}

struct FreeFreeCase {
  ElementType type;
  bool distorted;  ///< interior nodes moved (and, for quadratic types, edges curved)
  ElementType second_type = type;  ///< a mixed mesh: the cells with x index >= 1 are of this type
};

// Test name suffix of a case: "hex20Distorted", "hex8AndWedge6Distorted".
std::string CaseName(const FreeFreeCase& c) {
  std::string name(Traits(c.type).name);
  if (c.second_type != c.type) name += "And" + std::string(Traits(c.second_type).name);
  return name + (c.distorted ? "Distorted" : "");
}
// gtest prints a case by its name rather than its bytes.
void PrintTo(const FreeFreeCase& c, std::ostream* os) { *os << CaseName(c); }

class FreeFreeTest : public ::testing::TestWithParam<FreeFreeCase> {};

TEST_P(FreeFreeTest, HasExactlySixRigidBodyModesWellSeparatedFromTheFirstElasticMode) {
  std::mt19937 rng(3);
  testing::BoxMesh box =
      testing::StructuredBox(GetParam().type, Eigen::Vector3i(3, 2, 2),
                             Eigen::Vector3d(0.6, 0.3, 0.25), GetParam().second_type, 1);
  if (GetParam().distorted) testing::DistortInterior(&box, 0.2, 0.08, &rng);
  testing::Transform(&box.mesh, testing::RandomRotation(&rng), Eigen::Vector3d(0.4, 0.1, -0.3));
  ASSERT_LE(box.mesh.num_dofs(), 1500);
  const SystemMatrices system = AssembleSystem(box.mesh, MassMatrixKind::kConsistent);
  const Eigen::MatrixXd K(system.stiffness), M(system.mass);

  const Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd> solver(K, M);
  ASSERT_EQ(solver.info(), Eigen::Success);
  const Eigen::VectorXd& lambda = solver.eigenvalues();  // ascending
  const double lambda_7 = lambda(6);
  int zero_count = 0;
  for (Eigen::Index k = 0; k < lambda.size(); ++k) {
    if (std::abs(lambda(k)) < kZeroEigenvalueRatio * lambda_7) ++zero_count;
  }
  const double ratio = lambda.head(6).cwiseAbs().maxCoeff() / lambda_7;
  std::printf("  %s (%ld dof): max |lambda_1..6| / lambda_7 = %.2e, lambda_7 = %.4g 1/s^2\n",
              CaseName(GetParam()).c_str(), static_cast<long>(K.rows()), ratio, lambda_7);
  EXPECT_EQ(zero_count, 6);
  EXPECT_GT(lambda_7, 0.0);
  EXPECT_LT(ratio, kZeroEigenvalueRatio);

  // The first seven eigenpairs: M-orthonormal, with small residuals relative to ||K||.
  const Eigen::MatrixXd Phi = solver.eigenvectors().leftCols(7);
  EXPECT_LT((Phi.transpose() * M * Phi - Eigen::MatrixXd::Identity(7, 7)).norm(), kEigenTol);
  const double K_norm = K.norm();
  for (int k = 0; k < 7; ++k) {
    const Eigen::VectorXd r = K * Phi.col(k) - lambda(k) * (M * Phi.col(k));
    EXPECT_LT(r.norm() / (K_norm * Phi.col(k).norm()), kEigenTol) << "eigenpair " << k;
  }

  // The zero-eigenvalue space is the rigid-body space: the M-orthogonal projection of each
  // rigid-body field onto the six eigenvectors leaves nothing.
  const Eigen::MatrixXd R = RigidBodyModes(box.mesh.nodes);
  const Eigen::MatrixXd Phi0 = Phi.leftCols(6);
  const Eigen::MatrixXd rest = R - Phi0 * (Phi0.transpose() * M * R);
  EXPECT_LT(rest.norm() / R.norm(), kEigenTol);
}

INSTANTIATE_TEST_SUITE_P(
    AllTypes, FreeFreeTest,
    ::testing::Values(
        FreeFreeCase{ElementType::kTet4, false}, FreeFreeCase{ElementType::kTet4, true},
        FreeFreeCase{ElementType::kTet10, false}, FreeFreeCase{ElementType::kTet10, true},
        FreeFreeCase{ElementType::kHex8, false}, FreeFreeCase{ElementType::kHex8, true},
        FreeFreeCase{ElementType::kHex20, false}, FreeFreeCase{ElementType::kHex20, true},
        FreeFreeCase{ElementType::kWedge6, false}, FreeFreeCase{ElementType::kWedge6, true},
        FreeFreeCase{ElementType::kWedge15, false}, FreeFreeCase{ElementType::kWedge15, true},
        FreeFreeCase{ElementType::kHex8, true, ElementType::kWedge6},
        FreeFreeCase{ElementType::kHex20, true, ElementType::kWedge15}),
    [](const auto& param_info) { return CaseName(param_info.param); });

}  // namespace
}  // namespace flexmbs::fem
