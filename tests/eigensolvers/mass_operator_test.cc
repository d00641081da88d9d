#include "eigensolvers/mass_operator.h"

#include <gtest/gtest.h>

#include <array>
#include <random>

#include "fem/assembly.h"
#include "reduction/dof_constraints.h"
#include "tests/support/test_problems.h"

namespace flexmbs::eigensolvers {
namespace {

using Eigen::MatrixXd;
using SparseMatrix = Eigen::SparseMatrix<double>;

// The products of M through M_s and of M itself differ only in summation order.
constexpr double kRoundOff = 1e-14;

MatrixXd RandomBlock(Eigen::Index rows, Eigen::Index cols) {
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> uniform(-1.0, 1.0);
  return MatrixXd::NullaryExpr(rows, cols, [&] { return uniform(rng); });
}

double RelativeError(const MatrixXd& A, const MatrixXd& B) { return (A - B).norm() / B.norm(); }

// A box of two materials (densities 7850 and 2700 kg/m^3), 4 x 3 x 2 hex8.
fem::SystemMatrices TwoMaterialBox(fem::MassMatrixKind kind) {
  const fem::IsotropicMaterial aluminium{"aluminium", 70e9, 0.33, 2700.0};
  const fem::Mesh mesh =
      testing::HexBox({4, 3, 2}, {0.4, 0.3, 0.2}, testing::Steel(), aluminium, 0.2);
  return fem::AssembleSystem(mesh, kind);
}

// M X and |M| X through the scalar mass equal Eigen's products of M itself.
void ExpectProductsOfM(const MassOperator& mass, const SparseMatrix& M) {
  const MatrixXd X = RandomBlock(M.rows(), 5);
  EXPECT_LT(RelativeError(mass.Times(X), M * X), kRoundOff);
  MatrixXd Y(M.rows(), 5);
  mass.Times(X.data(), Y.data(), X.cols());
  EXPECT_LT(RelativeError(Y, M * X), kRoundOff);
  EXPECT_LT(RelativeError(mass.AbsTimes(X), SparseMatrix(M.cwiseAbs()) * X), kRoundOff);
  EXPECT_EQ(mass.Diagonal(), M.diagonal());
}

TEST(MassOperator, MultipliesAnAssembledConsistentMassThroughItsScalarMass) {
  const fem::SystemMatrices system = TwoMaterialBox(fem::MassMatrixKind::kConsistent);
  const MassOperator mass(system.mass);
  EXPECT_TRUE(mass.uses_scalar_mass());
  ExpectProductsOfM(mass, system.mass);
}

TEST(MassOperator, MultipliesALumpedMassThroughItsScalarMass) {
  const fem::SystemMatrices system = TwoMaterialBox(fem::MassMatrixKind::kLumped);
  const MassOperator mass(system.mass);
  EXPECT_TRUE(mass.uses_scalar_mass());
  ExpectProductsOfM(mass, system.mass);
}

// A held body's M_oo (whole nodes removed) keeps the structure.
TEST(MassOperator, MultipliesTheMassOfAClampedBodyThroughItsScalarMass) {
  const fem::Mesh mesh = testing::HexBox({4, 3, 2}, {0.4, 0.3, 0.2}, testing::Steel());
  const fem::SystemMatrices system = fem::AssembleSystem(mesh, fem::MassMatrixKind::kConsistent);
  const reduction::FreeDofMap map =
      reduction::FreeDofMap::ClampNodes(mesh.num_nodes(), testing::NodesOnPlane(mesh, 0, 0.0));
  const SparseMatrix M_oo = map.Restrict(system.mass);
  const MassOperator mass(M_oo);
  EXPECT_TRUE(mass.uses_scalar_mass());
  ExpectProductsOfM(mass, M_oo);
}

// One DOF removed (a single fixed axis), an entry coupling two axes, unequal axes: M is no
// longer M_s (x) I_3 and is multiplied as it is.
TEST(MassOperator, MultipliesAnyOtherMassAsItIs) {
  const fem::SystemMatrices system = TwoMaterialBox(fem::MassMatrixKind::kConsistent);
  const double max_entry = system.mass.coeffs().cwiseAbs().maxCoeff();
  SparseMatrix coupled = system.mass;
  coupled.coeffRef(3, 4) += 1e-15 * max_entry;
  coupled.coeffRef(4, 3) += 1e-15 * max_entry;
  SparseMatrix unequal = system.mass;
  unequal.coeffRef(5, 5) *= 1.0 + 1e-15;
  const std::array<Eigen::Index, 1> fixed{7};
  const SparseMatrix one_dof_removed = reduction::FreeDofMap(system.mass.rows(), fixed).Restrict(system.mass);
  for (const SparseMatrix* M :
       std::array<const SparseMatrix*, 3>{&coupled, &unequal, &one_dof_removed}) {
    const MassOperator mass(*M);
    EXPECT_FALSE(mass.uses_scalar_mass());
    ExpectProductsOfM(mass, *M);
  }
}

TEST(SplitScalarMass, ReportsHowFarMIsFromTheKroneckerStructure) {
  const fem::SystemMatrices system = TwoMaterialBox(fem::MassMatrixKind::kConsistent);
  const std::optional<ScalarMassSplit> exact = SplitScalarMass(system.mass);
  ASSERT_TRUE(exact.has_value());
  EXPECT_EQ(exact->max_deviation, 0.0);
  EXPECT_EQ(exact->max_entry, system.mass.coeffs().cwiseAbs().maxCoeff());
  EXPECT_EQ(exact->M_s.rows(), system.mass.rows() / 3);
  // Each entry of M_s is stored 9 times in M (the pattern K and M share), 3 times nonzero.
  EXPECT_EQ(9 * exact->M_s.nonZeros(), system.mass.nonZeros());
  EXPECT_EQ(3 * exact->M_s.nonZeros(), SparseMatrix(system.mass.pruned()).nonZeros());

  SparseMatrix coupled = system.mass;
  coupled.coeffRef(3, 4) = 2.5;
  EXPECT_EQ(SplitScalarMass(coupled)->max_deviation, 2.5);

  EXPECT_FALSE(SplitScalarMass(SparseMatrix(4, 4)).has_value());
  EXPECT_FALSE(SplitScalarMass(SparseMatrix(6, 3)).has_value());
}

}  // namespace
}  // namespace flexmbs::eigensolvers
