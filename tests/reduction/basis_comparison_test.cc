// MAC, effective modal mass and the comparison of two bases of one body.
#include "reduction/basis_comparison.h"

#include <gtest/gtest.h>

#include <numbers>

#include "core/error.h"
#include "fem/assembly.h"
#include "fem/mass_properties.h"
#include "tests/support/test_problems.h"

namespace flexmbs::reduction {
namespace {

constexpr double kRoundOff = 1e-10;

// A small box as a ReducedBody carrying ALL its modes (a complete M-orthonormal basis).
sid::ReducedBody CompleteBody() {
  const fem::Mesh mesh = testing::HexBox({3, 2, 2}, {0.3, 0.2, 0.1}, testing::Steel());
  const fem::SystemMatrices system = fem::AssembleSystem(mesh, fem::MassMatrixKind::kConsistent);
  const testing::DenseEigen dense = testing::SolveDense(system.stiffness, system.mass, -1e3);
  sid::ReducedBody body;
  body.mass = fem::MassPropertiesFromMassMatrix(system.mass, mesh.nodes).mass_kg;
  body.node_positions = mesh.nodes;
  body.phi = dense.vectors;
  body.frequency_hz = dense.values.cwiseAbs().cwiseSqrt() / (2.0 * std::numbers::pi);
  body.Me.m0 = dense.vectors.transpose() * (system.mass * dense.vectors);
  body.Ct.m0 = dense.vectors.transpose() * (system.mass * fem::RigidBodyModes(mesh.nodes).leftCols<3>());
  return body;
}

TEST(MacMatrix, IsOneForTheSameShapeAtAnyScaleAndZeroForOrthogonalShapes) {
  Eigen::MatrixXd A(4, 2);
  A << 1, 0, 2, 0, 0, 1, 0, 1;
  const Eigen::MatrixXd mac = MacMatrix(A, -3.0 * A);
  EXPECT_NEAR(mac(0, 0), 1.0, kRoundOff);
  EXPECT_NEAR(mac(1, 1), 1.0, kRoundOff);
  EXPECT_NEAR(mac(0, 1), 0.0, kRoundOff);
}

TEST(EffectiveModalMass, SumsToTheBodyMassAlongEachAxisForACompleteBasis) {
  // Phi Phi^T = M^-1 for a complete M-orthonormal basis, so sum_k (Phi_k^T M t)^2 = t^T M t = m.
  const sid::ReducedBody body = CompleteBody();
  const Eigen::Vector3d sums = EffectiveModalMass(body).colwise().sum();
  for (int d = 0; d < 3; ++d) EXPECT_NEAR(sums(d), body.mass, kRoundOff * body.mass);
}

TEST(CompareBases, ABasisAgainstItselfPairsEveryModeWithMacOneAndNoError) {
  const sid::ReducedBody body = CompleteBody();
  const BasisComparison c = CompareBases(body, body);
  ASSERT_EQ(c.pairs.size(), static_cast<std::size_t>(body.phi.cols()));
  for (const ModePair& p : c.pairs) {
    EXPECT_NEAR(p.mac, 1.0, kRoundOff);
    EXPECT_EQ(p.relative_error, 0.0);
  }
}

TEST(CompareBases, BasesOfDifferentMeshesAreAnInputError) {
  const sid::ReducedBody a = CompleteBody();
  sid::ReducedBody b = a;
  b.node_positions(0, 0) += 1e-3;
  EXPECT_THROW(CompareBases(a, b), InputError);
}

}  // namespace
}  // namespace flexmbs::reduction
