// The small rotation 1/2 curl u at an FE node.
#include "fem/nodal_rotation.h"

#include <gtest/gtest.h>

#include <Eigen/LU>
#include <cmath>
#include <random>
#include <string>

#include "core/error.h"
#include "tests/fem/test_meshes.h"
#include "tests/input_error.h"

namespace flexmbs::fem {
namespace {

// Affine fields are in every element's space: the gradient at a node is exact up to the
// round-off of the Jacobian inverse on O(1) coordinates (a few hundred eps).
constexpr double kRoundOff = 1e-11;

// Columns of Phi: the affine displacement fields u = A_k x + t_k at every node.
Eigen::MatrixXd AffineFields(const Mesh& mesh, const std::vector<Eigen::Matrix3d>& A,
                             const std::vector<Eigen::Vector3d>& t) {
  Eigen::MatrixXd Phi(mesh.num_dofs(), static_cast<Eigen::Index>(A.size()));
  for (std::size_t k = 0; k < A.size(); ++k) {
    for (Eigen::Index n = 0; n < mesh.num_nodes(); ++n) {
      Phi.block<3, 1>(3 * n, static_cast<Eigen::Index>(k)) = A[k] * mesh.nodes.col(n) + t[k];
    }
  }
  return Phi;
}

// The axial vector of the skew part of A: (A - A^T) / 2 = w~.
Eigen::Vector3d AxialOfSkewPart(const Eigen::Matrix3d& A) {
  return 0.5 * Eigen::Vector3d(A(2, 1) - A(1, 2), A(0, 2) - A(2, 0), A(1, 0) - A(0, 1));
}

void ExpectExactForAffineFields(const Mesh& mesh, const std::vector<int>& nodes) {
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  auto random_matrix = [&] {
    return Eigen::Matrix3d::NullaryExpr([&](Eigen::Index, Eigen::Index) { return unit(rng); });
  };
  const Eigen::Vector3d theta(0.3, -0.7, 0.2);
  Eigen::Matrix3d rotation;  // u = theta x x
  rotation << 0, -theta(2), theta(1), theta(2), 0, -theta(0), -theta(1), theta(0), 0;
  const Eigen::Matrix3d R = random_matrix();
  const Eigen::Matrix3d strain = R + R.transpose();  // symmetric: no rotation
  const Eigen::Matrix3d general = random_matrix();
  const Eigen::MatrixXd Phi =
      AffineFields(mesh, {rotation, strain, general},
                   {Eigen::Vector3d(1, 2, 3), Eigen::Vector3d(-1, 0, 2), Eigen::Vector3d::Zero()});
  for (const int node : nodes) {
    const Eigen::MatrixXd psi = NodalRotation(mesh, node, Phi);
    ASSERT_EQ(psi.rows(), 3);
    ASSERT_EQ(psi.cols(), 3);
    EXPECT_LT((psi.col(0) - theta).norm(), kRoundOff) << "node " << node;
    EXPECT_LT(psi.col(1).norm(), kRoundOff) << "node " << node;
    EXPECT_LT((psi.col(2) - AxialOfSkewPart(general)).norm(), kRoundOff) << "node " << node;
  }
}

class NodalRotationOnBoxes : public ::testing::TestWithParam<ElementType> {};

TEST_P(NodalRotationOnBoxes, IsExactForRigidRotationsAndZeroForStrain) {
  testing::BoxMesh box = testing::StructuredBox(GetParam(), {2, 2, 2}, {0.4, 0.5, 0.6});
  std::mt19937 rng(3);
  testing::DistortInterior(&box, 0.2, 0.1, &rng);  // curved interior edges for quadratic types
  std::vector<int> nodes;  // corner, interior, mid-side and face nodes alike
  for (Eigen::Index n = 0; n < box.mesh.num_nodes(); n += 5) nodes.push_back(static_cast<int>(n));
  ExpectExactForAffineFields(box.mesh, nodes);
}

INSTANTIATE_TEST_SUITE_P(ElementTypes, NodalRotationOnBoxes,
                         ::testing::Values(ElementType::kTet4, ElementType::kTet10,
                                           ElementType::kHex8, ElementType::kHex20,
                                           ElementType::kWedge6, ElementType::kWedge15),
                         [](const ::testing::TestParamInfo<ElementType>& param_info) {
                           return std::string(Traits(param_info.param).name);
                         });

TEST(NodalRotation, IsExactForAffineFieldsOnACurvedTet10Cylinder) {
  const Mesh mesh = testing::GmshCylinder(0.1, 0.3, Eigen::Vector3d(0.1, 0.2, -0.1), 0.05);
  std::vector<int> nodes;
  for (Eigen::Index n = 0; n < mesh.num_nodes(); n += 17) nodes.push_back(static_cast<int>(n));
  ExpectExactForAffineFields(mesh, nodes);
}

// Two tet4 sharing node 1 with a field that is not affine across them: the node's rotation is
// the volume-weighted mean of the two elements' (constant) rotations, each computed here from
// the element's linear interpolant u = a + B x fitted to its four nodal values.
TEST(NodalRotation, AveragesElementRotationsWeightedByVolume) {
  Mesh mesh;
  mesh.nodes.resize(3, 5);
  mesh.nodes << 0, 1, 0, 0, 2,  //
      0, 0, 1, 0, 1.5,          //
      0, 0, 0, 1, 1.2;
  ElementBlock block;
  block.type = ElementType::kTet4;
  block.connectivity.resize(4, 2);
  block.connectivity << 0, 1, 1, 2, 2, 3, 3, 4;  // columns: (0, 1, 2, 3) and (1, 2, 3, 4)
  mesh.blocks.push_back(block);
  const Eigen::MatrixXd Phi = Eigen::MatrixXd::NullaryExpr(15, 1, [](Eigen::Index i, Eigen::Index) {
    return std::sin(1.0 + 0.7 * static_cast<double>(i * i));
  });

  Eigen::Vector3d weighted = Eigen::Vector3d::Zero();
  double total = 0.0;
  for (Eigen::Index e = 0; e < 2; ++e) {
    Eigen::Matrix4d P;  // rows [1, x^T] of the element's nodes
    Eigen::Matrix<double, 4, 3> U;
    for (int a = 0; a < 4; ++a) {
      const int n = block.connectivity(a, e);
      P.row(a) << 1.0, mesh.nodes.col(n).transpose();
      U.row(a) = Phi.block<3, 1>(3 * n, 0).transpose();
    }
    const Eigen::Matrix<double, 4, 3> coefficients = P.lu().solve(U);    // rows: a^T, then B^T
    const Eigen::Matrix3d B = coefficients.bottomRows<3>().transpose();  // B(i, k) = du_i/dx_k
    const double volume = std::abs(P.determinant()) / 6.0;
    ASSERT_GT(P.determinant(), 0.0) << "element " << e << " must have a positive Jacobian";
    weighted += volume * AxialOfSkewPart(B);
    total += volume;
  }
  const Eigen::MatrixXd psi = NodalRotation(mesh, 1, Phi);
  EXPECT_LT((psi.col(0) - weighted / total).norm(), kRoundOff);
}

TEST(NodalRotation, ANodeOfNoElementIsAnInputError) {
  testing::BoxMesh box = testing::StructuredBox(ElementType::kHex8, {1, 1, 1}, {1, 1, 1});
  box.mesh.nodes.conservativeResize(3, box.mesh.num_nodes() + 1);
  box.mesh.nodes.col(box.mesh.num_nodes() - 1) = Eigen::Vector3d(5, 5, 5);
  const int lonely = static_cast<int>(box.mesh.num_nodes() - 1);
  const std::string message = flexmbs::testing::InputErrorMessage(
      [&] { NodalRotation(box.mesh, lonely, Eigen::MatrixXd::Zero(box.mesh.num_dofs(), 1)); });
  EXPECT_EQ(message, "node 8: no element holds it: its rotation is undefined");
}

}  // namespace
}  // namespace flexmbs::fem
