// The substructured factorisation (eigensolvers/distributed/substructured_factor.h) against a MUMPS Cholesky of
// the same distributed matrix, on one rank (no interface) and on two (run by CTest both ways).

#include <gtest/gtest.h>
#include <petscmat.h>

#include <memory>
#include <random>
#include <vector>

#include "core/error.h"
#include "fem/distributed_assembly.h"
#include "fem/petsc_check.h"
#include "eigensolvers/distributed/slepc_pair_measures.h"
#include "eigensolvers/distributed/substructured_factor.h"
#include "tests/support/test_problems.h"

namespace flexmbs::eigensolvers {
namespace {

using testing::HexBox;
using testing::Steel;

// K - sigma M of a free two-material box (stiffness ratio 1e3: a hard case for the interface
// matrix, which couples the soft and the stiff part), distributed by the mesh order.
struct ShiftedBox {
  fem::DistributedMatrices matrices;
  Mat A = nullptr;
  explicit ShiftedBox(double sigma) {
    fem::IsotropicMaterial soft = Steel();
    soft.youngs_modulus_pa *= 1e-3;
    const fem::Mesh mesh = HexBox({16, 3, 3}, {1.6, 0.2, 0.2}, soft, Steel(), 0.8);
    matrices = fem::AssembleDistributed(mesh, fem::MassMatrixKind::kConsistent);
    FLEXMBS_PETSC(MatDuplicate(matrices.stiffness, MAT_COPY_VALUES, &A));
    FLEXMBS_PETSC(MatAXPY(A, -sigma, matrices.mass, SAME_NONZERO_PATTERN));
  }
  ~ShiftedBox() {
    MatDestroy(&A);
    fem::DestroyDistributed(&matrices);
  }
};

// A vector of A's row layout with entries uniform in [-1, 1], the same on any rank count.
Vec RandomVector(Mat A, unsigned seed) {
  Vec v;
  FLEXMBS_PETSC(MatCreateVecs(A, &v, nullptr));
  PetscInt n = 0, begin = 0, end = 0;
  FLEXMBS_PETSC(VecGetSize(v, &n));
  FLEXMBS_PETSC(VecGetOwnershipRange(v, &begin, &end));
  std::mt19937 random(seed);
  std::uniform_real_distribution<double> uniform(-1.0, 1.0);
  for (PetscInt i = 0; i < n; ++i) {
    const double value = uniform(random);
    if (i >= begin && i < end) FLEXMBS_PETSC(VecSetValue(v, i, value, INSERT_VALUES));
  }
  FLEXMBS_PETSC(VecAssemblyBegin(v));
  FLEXMBS_PETSC(VecAssemblyEnd(v));
  return v;
}

// ||x - y|| / ||y||.
double RelativeDifference(Vec x, Vec y) {
  Vec d;
  FLEXMBS_PETSC(VecDuplicate(x, &d));
  FLEXMBS_PETSC(VecWAXPY(d, -1.0, y, x));
  PetscReal nd = 0.0, ny = 0.0;
  FLEXMBS_PETSC(VecNorm(d, NORM_2, &nd));
  FLEXMBS_PETSC(VecNorm(y, NORM_2, &ny));
  FLEXMBS_PETSC(VecDestroy(&d));
  return nd / ny;
}

int Ranks() {
  PetscMPIInt size = 1;
  MPI_Comm_size(PETSC_COMM_WORLD, &size);
  return size;
}

TEST(SubstructuredFactor, SolvesAsMumpsDoesOnTheSameMatrix) {
  const ShiftedBox box(-1e4);
  const SubstructuredFactor factor(box.A);
  ASSERT_TRUE(factor.positive_definite());
  Mat mumps = MumpsCholesky(box.A, MumpsFactorization::kPositiveDefinite, "substructured_test_");
  ASSERT_TRUE(FactoredPositiveDefinite(mumps));
  Vec b = RandomVector(box.A, 7), x, reference;
  FLEXMBS_PETSC(VecDuplicate(b, &x));
  FLEXMBS_PETSC(VecDuplicate(b, &reference));
  factor.Solve(b, x);
  FLEXMBS_PETSC(MatSolve(mumps, b, reference));
  EXPECT_LT(RelativeDifference(x, reference), 1e-10);
  // And the residual of its own: ||A x - b|| / ||b||.
  Vec Ax;
  FLEXMBS_PETSC(VecDuplicate(b, &Ax));
  FLEXMBS_PETSC(MatMult(box.A, x, Ax));
  EXPECT_LT(RelativeDifference(Ax, b), 1e-9);
  for (Vec* v : {&b, &x, &reference, &Ax}) VecDestroy(v);
  MatDestroy(&mumps);
  if (Ranks() == 1) {
    EXPECT_EQ(factor.interface_rows(), 0);
  } else {
    PetscInt rows = 0;
    FLEXMBS_PETSC(MatGetSize(box.A, &rows, nullptr));
    EXPECT_GT(factor.interface_rows(), 0);
    // Two ranks: one of the box's four node layers across z (the mesh order halves it there).
    if (Ranks() == 2) {
      EXPECT_LE(factor.interface_rows(), rows / 4);
    }
  }
  EXPECT_GT(factor.flops(), 0.0);
}

TEST(SubstructuredFactor, ColumnsAtOnceEqualColumnsOneByOne) {
  const ShiftedBox box(-1e4);
  const SubstructuredFactor factor(box.A);
  PetscInt local = 0;
  FLEXMBS_PETSC(MatGetLocalSize(box.A, &local, nullptr));
  const int columns = 3;
  std::vector<double> B(static_cast<std::size_t>(local) * columns), X(B.size());
  std::vector<double> one_by_one(B.size());
  for (int c = 0; c < columns; ++c) {
    Vec b = RandomVector(box.A, 11 + static_cast<unsigned>(c));
    const PetscScalar* values = nullptr;
    FLEXMBS_PETSC(VecGetArrayRead(b, &values));
    std::copy(values, values + local, B.begin() + c * local);
    FLEXMBS_PETSC(VecRestoreArrayRead(b, &values));
    VecDestroy(&b);
    factor.SolveColumns(B.data() + c * local, one_by_one.data() + c * local, 1);
  }
  factor.SolveColumns(B.data(), X.data(), columns);
  double largest = 0.0, difference = 0.0;
  for (std::size_t i = 0; i < X.size(); ++i) {
    largest = std::max(largest, std::abs(one_by_one[i]));
    difference = std::max(difference, std::abs(X[i] - one_by_one[i]));
  }
  EXPECT_LE(difference, 1e-12 * largest);
  // In place (B and X the same array) as well.
  factor.SolveColumns(B.data(), B.data(), columns);
  for (std::size_t i = 0; i < X.size(); ++i) EXPECT_EQ(B[i], X[i]) << i;
}

TEST(SubstructuredFactor, AnInterfaceAboveTheLimitIsNotFactorised) {
  const ShiftedBox box(-1e4);
  const SubstructuredFactor reference(box.A);
  const std::int64_t rows = reference.interface_rows();
  // At the limit it is factorised (one rank: no interface); one row below it, not.
  const std::unique_ptr<SubstructuredFactor> at = SubstructuredFactor::IfInterfaceAtMost(box.A, rows);
  ASSERT_TRUE(at);
  EXPECT_EQ(at->interface_rows(), rows);
  EXPECT_TRUE(at->positive_definite());
  EXPECT_EQ(SubstructuredFactor::IfInterfaceAtMost(box.A, rows - 1), nullptr);
}

TEST(SubstructuredFactor, AnIndefiniteMatrixIsNotPositiveDefinite) {
  // Far above the lowest elastic eigenvalues K - sigma M is indefinite: an interior or S shows it.
  const ShiftedBox box(1e9);
  const SubstructuredFactor factor(box.A);
  EXPECT_FALSE(factor.positive_definite());
  Vec b = RandomVector(box.A, 3);
  EXPECT_THROW(factor.Solve(b, b), InternalError);
  VecDestroy(&b);
}

}  // namespace
}  // namespace flexmbs::eigensolvers
