#include "reduction/dof_constraints.h"

#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "core/error.h"

namespace flexmbs::reduction {
namespace {

Eigen::SparseMatrix<double> Dense5() {
  Eigen::MatrixXd A(5, 5);
  for (int i = 0; i < 5; ++i) {
    for (int j = 0; j < 5; ++j) A(i, j) = (i == j) ? 10.0 + i : (i + j) % 3 == 0 ? 0.0 : 1.0 + i + j;
  }
  return A.sparseView();
}

TEST(FreeDofMap, RestrictKeepsTheFreeRowsAndColumnsInOrder) {
  const std::vector<Eigen::Index> fixed = {3, 1, 3};
  const FreeDofMap map(5, fixed);
  EXPECT_EQ(map.num_free(), 3);
  EXPECT_EQ(map.num_fixed(), 2);
  EXPECT_EQ(map.free_dofs(), (std::vector<Eigen::Index>{0, 2, 4}));
  EXPECT_EQ(map.ReducedIndex(2), 1);
  EXPECT_TRUE(map.IsFixed(1));
  const Eigen::SparseMatrix<double> A = Dense5();
  const Eigen::MatrixXd R = Eigen::MatrixXd(map.Restrict(A));
  const Eigen::MatrixXd Ad = Eigen::MatrixXd(A);
  const int keep[3] = {0, 2, 4};
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j) EXPECT_EQ(R(i, j), Ad(keep[i], keep[j]));
  }
}

TEST(FreeDofMap, ExpandPutsZerosOnFixedDofsAndInvertsRestrict) {
  const std::vector<Eigen::Index> fixed = {0, 4};
  const FreeDofMap map(5, fixed);
  Eigen::MatrixXd reduced(3, 2);
  reduced << 1, 2, 3, 4, 5, 6;
  const Eigen::MatrixXd full = map.Expand(reduced);
  Eigen::MatrixXd expected(5, 2);
  expected << 0, 0, 1, 2, 3, 4, 5, 6, 0, 0;
  EXPECT_EQ(full, expected);
  EXPECT_EQ(map.RestrictVectors(full), reduced);
}

TEST(FreeDofMap, ClampNodesFixesAllThreeDofsOfEachNode) {
  const std::vector<int> nodes = {0, 2};
  const FreeDofMap map = FreeDofMap::ClampNodes(4, nodes);
  EXPECT_EQ(map.num_dofs(), 12);
  EXPECT_EQ(map.free_dofs(), (std::vector<Eigen::Index>{3, 4, 5, 9, 10, 11}));
}

TEST(FreeDofMap, OutOfRangeDofOrNodeIsAnInputError) {
  const std::vector<Eigen::Index> fixed = {5};
  EXPECT_THROW(FreeDofMap(5, fixed), InputError);
  const std::vector<int> nodes = {-1};
  EXPECT_THROW(FreeDofMap::ClampNodes(4, nodes), InputError);
  const FreeDofMap map(5);
  EXPECT_THROW(map.Expand(Eigen::MatrixXd::Zero(4, 1)), InputError);
  EXPECT_THROW(map.Restrict(Eigen::SparseMatrix<double>(4, 4)), InputError);
}

}  // namespace
}  // namespace flexmbs::reduction
