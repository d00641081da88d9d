// ConstraintSolver on a tree of many rigid bodies, where S = G M^-1 G^T is factorised by the
// sparse LDL^T: its sparse G and M^-1 G^T, its Schur solves and the accelerations against the
// dense saddle-point algebra formed here, and its smallest pivot near a singular configuration
// against the smallest eigenvalue of S formed here.
#include "mbs/constraint_solver.h"

#include <gtest/gtest.h>

#include <Eigen/Cholesky>
#include <Eigen/Eigenvalues>
#include <Eigen/Geometry>
#include <Eigen/LU>
#include <cmath>
#include <memory>
#include <random>
#include <string>
#include <vector>

#include "mbs/joint.h"
#include "mbs/multibody_system.h"
#include "mbs/rigid_body.h"
#include "mbs/simulation_error.h"
#include "rigid_test_support.h"

namespace flexmbs::mbs {
namespace {

using Eigen::Index;
using Eigen::MatrixXd;
using Eigen::VectorXd;
using testing::PoseFromMarker;
using testing::RandomRigidBody;
using testing::RandomRotation;
using testing::RandomVector;
using testing::RigidPositions;

// Bodies of the tree: 24 revolute joints and a spherical one, 123 rows, far above
// ConstraintSolver::kDenseSchurRows.
constexpr int kBodies = 24;
// Relative round-off of products and backward errors of factorisations of matrices of this size
// (a few hundred operations per entry, eps = 2.2e-16, mass blocks of condition ~ 10).
constexpr double kRoundOff = 1e-12;

// The smallest pivot of an LDL^T of a positive definite S is at least its smallest eigenvalue
// lambda_min (each pivot is 1 / (S_k^-1)_kk of a leading block S_k), and for a near-null vector
// v of S it is about lambda_min / v_p^2 at the row p where the dependency closes: 2 lambda_min for
// two dependent rows, more for a vector spread over many rows. Measured on the twisted tree
// below: the pivoted LDL^T 3.2-9.3 lambda_min; the sparse one 6.4 lambda_min at tilt 0.03 and 25
// at tilt 0.1, where the near-null vector is the loop's, spread over many rows (components 0.39,
// 0.32, 0.31, ...; the pivoted LDL^T 7.5 there).
constexpr double kPivotedSpread = 20.0;
constexpr double kSparseSpread = 50.0;
// Absolute round-off of pivots and eigenvalues of the unit-diagonal S (about 120 eps).
constexpr double kPivotRoundOff = 1e-14;
// The joint made singular in TwistedTree.
constexpr int kTwisted = 9;

/// A binary tree of random rigid bodies: body 0 on a revolute joint to the ground, body k > 0 on
/// a revolute joint "joint<k>" from marker m1 or m2 of body (k - 1) / 2 to its marker m0, and a
/// loop closed by a spherical joint between leaves 15 and 22 (fill in the sparse factor); random
/// poses and velocities (the joints do not hold: G is defined everywhere).
struct Tree {
  MultibodySystem system;
  VectorXd y;

  explicit Tree(unsigned seed) {
    std::mt19937 rng(seed);
    for (int k = 0; k < kBodies; ++k) system.AddBody(RandomRigidBody(rng, "body" + std::to_string(k), 3));
    for (int k = 0; k < kBodies; ++k) {
      MarkerRef parent;
      if (k == 0) {
        const Eigen::Vector3d p_WP_W = RandomVector(rng);
        parent = MarkerRef::Ground(p_WP_W, RandomRotation(rng));
      } else {
        parent = system.Marker("body" + std::to_string((k - 1) / 2), k % 2 == 1 ? "m1" : "m2");
      }
      system.AddJoint(Joint("joint" + std::to_string(k), JointType::kRevolute, parent,
                            system.Marker("body" + std::to_string(k), "m0")));
    }
    system.AddJoint(Joint("loop", JointType::kSpherical, system.Marker("body15", "m1"), system.Marker("body22", "m2")));
    y = system.NeutralState();
    for (int k = 0; k < kBodies; ++k) {
      VectorXd u(6);
      u << RandomVector(rng), RandomVector(rng);
      system.SetBodyState(k, RigidPositions(RandomVector(rng, 3.0), RandomRotation(rng)), u, y);
    }
  }
};

/// The dense algebra of a system at y, formed here.
struct DenseAlgebra {
  MatrixXd M, G, Minv_GT, S;

  DenseAlgebra(const MultibodySystem& system, const VectorXd& y) {
    const Index nu = system.num_velocities();
    M = MatrixXd::Zero(nu, nu);
    for (int b = 0; b < system.num_bodies(); ++b) {
      const Index n = system.body(b).num_velocities();
      M.block(system.velocity_offset(b), system.velocity_offset(b), n, n) = system.BodyMassMatrix(b, y);
    }
    G = system.Constraints(0.0, y).G;
    Minv_GT = M.llt().solve(G.transpose());
    S = G * Minv_GT;
  }
  /// S over `rows`, scaled to unit diagonal.
  MatrixXd ScaledSchur(const std::vector<Index>& rows) const {
    const VectorXd inverse_scale = S(rows, rows).diagonal().cwiseSqrt().cwiseInverse();
    return inverse_scale.asDiagonal() * S(rows, rows) * inverse_scale.asDiagonal();
  }
};

/// 0 .. m - 1 for the m rows of G.
std::vector<Index> AllRows(const DenseAlgebra& dense) {
  std::vector<Index> rows(static_cast<std::size_t>(dense.G.rows()));
  for (std::size_t k = 0; k < rows.size(); ++k) rows[k] = static_cast<Index>(k);
  return rows;
}

double RelativeError(const MatrixXd& value, const MatrixXd& reference) {
  return (value - reference).norm() / reference.norm();
}

TEST(ConstraintSolver, SparseProductsAndSolvesMatchTheDenseAlgebra) {
  const Tree tree(7);
  const DenseAlgebra dense(tree.system, tree.y);
  const ConstraintSolver solver(tree.system, 0.0, tree.y, dense.G);
  ASSERT_FALSE(solver.pivoted());  // the sparse LDL^T is what is tested
  EXPECT_GT(solver.smallest_relative_pivot(), ConstraintSolver::kPivotedCheckBelow);
  EXPECT_LE(solver.smallest_relative_pivot(), 1.0);

  EXPECT_EQ((MatrixXd(solver.constraint_jacobian()) - dense.G).cwiseAbs().maxCoeff(), 0.0);
  EXPECT_LT(RelativeError(MatrixXd(solver.mass_inverse_G_transpose()), dense.Minv_GT), kRoundOff);
  EXPECT_LT(RelativeError(solver.scaled_schur(), dense.ScaledSchur(AllRows(dense))), kRoundOff);

  // S x = r: the backward error of the sparse solve (independent of S's condition).
  std::mt19937 rng(3);
  const MatrixXd R = MatrixXd::NullaryExpr(dense.G.rows(), 3, [&] { return std::normal_distribution<double>()(rng); });
  MatrixXd X(R.rows(), R.cols());
  for (Index j = 0; j < R.cols(); ++j) X.col(j) = solver.SolveSchur(R.col(j));
  EXPECT_LT((dense.S * X - R).norm() / (dense.S.norm() * X.norm()), kRoundOff);
  // M^-1 H body by body, with a column that is zero in all bodies but one.
  MatrixXd H = MatrixXd::Random(dense.M.rows(), 4);
  H.col(3).setZero();
  H(5, 3) = 1.0;
  EXPECT_LT(RelativeError(solver.SolveMassColumns(H), dense.M.llt().solve(H)), kRoundOff);
}

TEST(ConstraintSolver, DroppedRowsAreLeftOutOfTheSparseSchurComplement) {
  Tree tree(11);
  const std::vector<Index> dropped{3, 40, 41, 119};
  tree.system.set_dropped_constraints(dropped);
  const DenseAlgebra dense(tree.system, tree.y);
  const ConstraintSolver solver(tree.system, 0.0, tree.y, dense.G);
  ASSERT_FALSE(solver.pivoted());
  const std::vector<Index> kept = tree.system.KeptConstraints();
  EXPECT_EQ(solver.rows(), kept);
  EXPECT_LT(RelativeError(solver.scaled_schur(), dense.ScaledSchur(kept)), kRoundOff);
  const VectorXd r = VectorXd::Random(dense.G.rows());
  const VectorXd x = solver.SolveSchur(r);
  for (const Index row : dropped) EXPECT_EQ(x(row), 0.0);
  const MatrixXd S_kept = dense.S(kept, kept);
  EXPECT_LT((S_kept * x(kept) - r(kept)).norm() / (S_kept.norm() * x.norm()), kRoundOff);
}

TEST(ConstraintSolver, AccelerationsSolveTheSaddlePointSystem) {
  Tree tree(5);
  tree.system.set_constraint_settings({30.0, 1e-10});
  const DenseAlgebra dense(tree.system, tree.y);
  const Index nu = tree.system.num_velocities(), m = tree.system.num_constraints();
  VectorXd u_dot(nu), lambda(m);
  tree.system.Accelerations(0.0, tree.y, u_dot, lambda);
  // [M -G^T; G 0] [u'; lambda] = [h; gamma - 2 omega (G u + g_t) - omega^2 g], solved densely.
  const SystemConstraints c = tree.system.Constraints(0.0, tree.y);
  const double omega = 30.0;
  MatrixXd K = MatrixXd::Zero(nu + m, nu + m);
  K.topLeftCorner(nu, nu) = dense.M;
  K.topRightCorner(nu, m) = -dense.G.transpose();
  K.bottomLeftCorner(m, nu) = dense.G;
  VectorXd rhs(nu + m);
  rhs << tree.system.Forces(0.0, tree.y),
      c.gamma - 2.0 * omega * (c.G * tree.y.tail(nu) + c.g_t) - omega * omega * c.g;
  const VectorXd reference = K.fullPivLu().solve(rhs);
  EXPECT_LT((u_dot - reference.head(nu)).norm(), 1e-9 * reference.head(nu).norm());
  EXPECT_LT((lambda - reference.tail(m)).norm(), 1e-9 * reference.tail(m).norm());
}

/// The tree with joint 9's marker J turned against its marker I by R_IJ: x_J = z_I and z_J at 45
/// degrees between x_I and y_I, then z_J tilted by `tilt` [rad] towards z_I. At tilt 0 the
/// revolute joint's two axis rows (x_I . z_J, y_I . z_J, gradients x_I x z_J and y_I x z_J, both
/// along z_I) are dependent: S is singular in that joint alone.
Tree TwistedTree(double tilt) {
  Tree tree(13);
  const MarkerKinematics I = tree.system.MarkerState(tree.system.joint(kTwisted).marker_i(), tree.y);
  Eigen::Matrix3d R_IJ;
  R_IJ.col(0) = Eigen::Vector3d::UnitZ();
  R_IJ.col(1) = Eigen::Vector3d(1.0, -1.0, 0.0) / std::sqrt(2.0);
  R_IJ.col(2) = Eigen::Vector3d(1.0, 1.0, 0.0) / std::sqrt(2.0);
  // About (x_I - y_I) / sqrt(2): z_J turns towards z_I.
  R_IJ = Eigen::AngleAxisd(tilt, Eigen::Vector3d(1.0, -1.0, 0.0).normalized()).toRotationMatrix() * R_IJ;
  const auto& body = dynamic_cast<const RigidBody&>(tree.system.body(kTwisted));
  const VectorXd x = PoseFromMarker(body.markers()[0], I.p_WM_W, I.R_WM * R_IJ);
  tree.system.SetBodyState(kTwisted, x, tree.system.BodyVelocities(tree.y, kTwisted), tree.y);
  return tree;
}

TEST(ConstraintSolver, SmallestPivotBoundsTheSmallestEigenvalueAndIsPivotedNearRankDeficiency) {
  bool sparse_seen = false, pivoted_seen = false;
  for (const double tilt : {0.0, 1e-6, 1e-5, 1e-4, 1e-3, 1e-2, 3e-2, 1e-1}) {
    const Tree tree = TwistedTree(tilt);
    const DenseAlgebra dense(tree.system, tree.y);
    const ConstraintSolver solver(tree.system, 0.0, tree.y, dense.G);
    const double pivot = solver.smallest_relative_pivot();
    const double lambda_min =
        Eigen::SelfAdjointEigenSolver<MatrixXd>(dense.ScaledSchur(AllRows(dense))).eigenvalues()(0);
    SCOPED_TRACE(::testing::Message() << "tilt " << tilt << ": smallest pivot " << pivot << ", eigenvalue "
                                      << lambda_min << (solver.pivoted() ? " (pivoted)" : " (sparse)"));
    EXPECT_EQ(solver.pivoted(), pivot < ConstraintSolver::kPivotedCheckBelow);
    (solver.pivoted() ? pivoted_seen : sparse_seen) = true;
    EXPECT_GE(pivot, lambda_min - kPivotRoundOff);
    EXPECT_LE(pivot, (solver.pivoted() ? kPivotedSpread : kSparseSpread) * lambda_min + kPivotRoundOff);
    // Near rank deficiency (the limits of the run and of a failure's diagnosis) it is the pivoted one.
    if (lambda_min < 1e-6) {
      EXPECT_TRUE(solver.pivoted());
    }
    for (const double limit : {1e-10, 1e-6}) {
      if (kPivotedSpread * lambda_min < limit) {
        EXPECT_THROW(solver.RequireFullRank(0.0, limit), SimulationError) << "limit " << limit;
        EXPECT_EQ(solver.DependentJoints(limit), std::vector<int>{kTwisted});
      } else if (lambda_min >= limit) {
        EXPECT_NO_THROW(solver.RequireFullRank(0.0, limit)) << "limit " << limit;
      }
    }
  }
  EXPECT_TRUE(sparse_seen && pivoted_seen);
}

}  // namespace
}  // namespace flexmbs::mbs
