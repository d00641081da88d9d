// The PETSc assembly from an element partition equals the serial assembly, on any number of
// ranks. Registered twice with CTest: on one rank and under `mpiexec -n 2`.
#include <gtest/gtest.h>
#include <petscmat.h>

#include <random>

#include "core/error.h"
#include "fem/assembly.h"
#include "fem/distributed_assembly.h"
#include "tests/fem/test_meshes.h"

namespace flexmbs::fem {
namespace {

// Serial and distributed values are sums of the same element terms in another order.
constexpr double kRoundOffTolerance = 1e-12;

// A distorted mixed hex20/wedge15 box: two element blocks, curved interior edges.
Mesh MixedBox() {
  std::mt19937 rng(7);
  testing::BoxMesh box = testing::StructuredBox(ElementType::kHex20, {5, 3, 2}, {0.5, 0.3, 0.2},
                                                ElementType::kWedge15, 3);
  testing::DistortInterior(&box, 0.2, 0.05, &rng);
  return box.mesh;
}

// The largest |A_dist(r, c) - A_serial(r, c)| over this rank's rows, relative to max |A|.
double MaxRelativeDifference(Mat distributed, const Eigen::SparseMatrix<double>& serial) {
  PetscInt begin = 0, end = 0;
  EXPECT_EQ(MatGetOwnershipRange(distributed, &begin, &end), 0);
  const Eigen::MatrixXd dense = Eigen::MatrixXd(serial);  // symmetric: row r = column r
  double max_difference = 0.0;
  for (PetscInt row = begin; row < end; ++row) {
    PetscInt count = 0;
    const PetscInt* cols = nullptr;
    const PetscScalar* values = nullptr;
    EXPECT_EQ(MatGetRow(distributed, row, &count, &cols, &values), 0);
    Eigen::VectorXd dist_row = Eigen::VectorXd::Zero(dense.cols());
    for (PetscInt k = 0; k < count; ++k) dist_row(cols[k]) = values[k];
    EXPECT_EQ(MatRestoreRow(distributed, row, &count, &cols, &values), 0);
    max_difference = std::max(max_difference, (dist_row - dense.col(row)).cwiseAbs().maxCoeff());
  }
  return max_difference / dense.cwiseAbs().maxCoeff();
}

TEST(EvenPartition, CoversEveryItemOnceInOrder) {
  for (int parts : {1, 2, 3, 7}) {
    Eigen::Index next = 0;
    for (int p = 0; p < parts; ++p) {
      const IndexRange r = EvenPartition(23, parts, p);
      EXPECT_EQ(r.begin, next);
      EXPECT_LE(r.end - r.begin, 23 / parts + 1);
      next = r.end;
    }
    EXPECT_EQ(next, 23);
  }
}

TEST(DistributedAssembly, EqualsSerialAssemblyOnEveryRank) {
  const Mesh mesh = MixedBox();
  for (MassMatrixKind kind : {MassMatrixKind::kConsistent, MassMatrixKind::kLumped}) {
    const SystemMatrices serial = AssembleSystem(mesh, kind);
    DistributedMatrices distributed = AssembleDistributed(mesh, kind);
    EXPECT_LT(MaxRelativeDifference(distributed.stiffness, serial.stiffness), kRoundOffTolerance);
    EXPECT_LT(MaxRelativeDifference(distributed.mass, serial.mass), kRoundOffTolerance);
    DestroyDistributed(&distributed);
  }
}

TEST(DistributedAssembly, InvertedElementOnOneRankStopsEveryRank) {
  Mesh mesh = MixedBox();
  // Invert the last element (in the last rank's part): swap two corner nodes.
  ElementBlock& last = mesh.blocks.back();
  const Eigen::Index e = last.num_elements() - 1;
  std::swap(last.connectivity(1, e), last.connectivity(2, e));
  EXPECT_THROW(AssembleDistributed(mesh, MassMatrixKind::kConsistent), InputError);
}

}  // namespace
}  // namespace flexmbs::fem

int main(int argc, char** argv) {
  ::testing::InitGoogleTest(&argc, argv);
  if (PetscInitializeNoArguments() != 0) return 1;
  int failed = RUN_ALL_TESTS() != 0 ? 1 : 0;
  MPI_Allreduce(MPI_IN_PLACE, &failed, 1, MPI_INT, MPI_MAX, PETSC_COMM_WORLD);
  PetscFinalize();
  return failed;
}
