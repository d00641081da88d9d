#include "eigensolvers/shifted_factorization.h"

#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>

#include "fem/assembly.h"
#include "reduction/dof_constraints.h"
#include "tests/support/test_problems.h"

namespace flexmbs::eigensolvers {
namespace {

using Method = ShiftedFactorization::Method;
using Status = ShiftedFactorization::Status;

// A clamped steel bar, 8 x 2 x 2 hex8 (216 free DOF): small enough for dense references; the
// section is not square, so its eigenvalues are distinct.
struct Bar {
  Eigen::SparseMatrix<double> K;
  Eigen::SparseMatrix<double> M;
};
Bar MakeBar() {
  const fem::Mesh mesh = testing::HexBox({8, 2, 2}, {0.4, 0.05, 0.035}, testing::Steel());
  const fem::SystemMatrices system = fem::AssembleSystem(mesh, fem::MassMatrixKind::kConsistent);
  const reduction::FreeDofMap map = reduction::FreeDofMap::ClampNodes(mesh.num_nodes(), testing::NodesOnPlane(mesh, 0, 0.0));
  return {map.Restrict(system.stiffness), map.Restrict(system.mass)};
}

// Backward-stable solves of these systems (condition <= 1e9 here) agree with a dense LU to
// cond * eps ~ 1e-7 relative; this allows a margin.
constexpr double kSolveAgreement = 1e-6;

TEST(ShiftedFactorization, CholeskyAndLdltSolveKMinusSigmaM) {
  const Bar bar = MakeBar();
  const double sigma = -1e5;
  const Eigen::MatrixXd A = Eigen::MatrixXd(bar.K) - sigma * Eigen::MatrixXd(bar.M);
  const Eigen::MatrixXd B = Eigen::MatrixXd::Random(A.rows(), 3);
  const Eigen::MatrixXd X_ref = A.lu().solve(B);
  for (const Method method : {Method::kSupernodalCholesky, Method::kSimplicialLdlt}) {
    ShiftedFactorization f;
    ASSERT_EQ(f.Factorize(bar.K, bar.M, sigma, method), Status::kOk);
    EXPECT_TRUE(f.ok());
    EXPECT_EQ(f.NegativePivots(), 0);
    EXPECT_GT(f.FactorNonzeros(), 0.0);
    const Eigen::MatrixXd X = f.Solve(B);
    EXPECT_LE((X - X_ref).norm(), kSolveAgreement * X_ref.norm());
  }
}

TEST(ShiftedFactorization, LdltNegativePivotsCountTheEigenvaluesBelowTheShift) {
  const Bar bar = MakeBar();
  const testing::DenseEigen dense = testing::SolveDense(bar.K, bar.M, 0.0);
  for (const Eigen::Index below : {0, 1, 5, 17}) {
    // A cut halfway between eigenvalue `below - 1` and eigenvalue `below`.
    const double cut = below == 0 ? 0.5 * dense.values(0) : 0.5 * (dense.values(below - 1) + dense.values(below));
    ShiftedFactorization f;
    ASSERT_EQ(f.Factorize(bar.K, bar.M, cut, Method::kSimplicialLdlt), Status::kOk);
    EXPECT_EQ(f.NegativePivots(), below) << "cut " << cut;
  }
}

TEST(ShiftedFactorization, CholeskyAboveTheLowestEigenvalueIsNotPositiveDefinite) {
  const Bar bar = MakeBar();
  const double lowest = testing::SolveDense(bar.K, bar.M, 0.0).values(0);
  ShiftedFactorization f;
  EXPECT_EQ(f.Factorize(bar.K, bar.M, 1.5 * lowest, Method::kSupernodalCholesky), Status::kNotPositiveDefinite);
  EXPECT_FALSE(f.ok());
  EXPECT_LT(f.FailedPivot(), bar.K.rows());
  // The same object refactorises at a new shift (reusing its symbolic analysis).
  EXPECT_EQ(f.Factorize(bar.K, bar.M, 0.5 * lowest, Method::kSupernodalCholesky), Status::kOk);
  EXPECT_TRUE(f.ok());
}

TEST(ShiftedFactorization, RefactorisingAtANewShiftGivesTheNewSolution) {
  const Bar bar = MakeBar();
  const Eigen::VectorXd b = Eigen::VectorXd::Random(bar.K.rows());
  ShiftedFactorization f;
  for (const double sigma : {0.0, -3e4, -7e6}) {
    ASSERT_EQ(f.Factorize(bar.K, bar.M, sigma, Method::kSupernodalCholesky), Status::kOk);
    const Eigen::MatrixXd A = Eigen::MatrixXd(bar.K) - sigma * Eigen::MatrixXd(bar.M);
    const Eigen::VectorXd x_ref = A.lu().solve(b);
    EXPECT_LE((f.Solve(Eigen::MatrixXd(b)) - x_ref).norm(), kSolveAgreement * x_ref.norm()) << sigma;
    EXPECT_EQ(f.sigma(), sigma);
  }
}

}  // namespace
}  // namespace flexmbs::eigensolvers
