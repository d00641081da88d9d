#include "reduction/interface_coupling.h"

#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>
#include <Eigen/Geometry>
#include <Eigen/LU>
#include <Eigen/QR>
#include <algorithm>
#include <cmath>
#include <cstdio>

#include "basis_test_support.h"
#include "core/error.h"
#include "reduction/craig_bampton.h"
#include "reduction/modal_basis.h"
#include "tests/support/test_problems.h"

namespace flexmbs::reduction {
namespace {

using fem::ElementType;
using testing::Body;

// Rigid coupling: node motion of a constraint mode is S(r) e_j with B's exact entries
// (measured 0; was 1e-14): a few ulps.
constexpr double kRigidExact = 1e-15;
// The rigid fit of a constraint mode against the unit marker motion: one 6 x 6 solve and one
// least-squares solve, round-off (measured 6.5e-14, the weights' W R = I; 5.3e-15 and below
// elsewhere; was 1e-11).
constexpr double kFitRoundOff = 5e-13;
// Against the dense Lagrange-multiplier / null-space references: round-off amplified by the
// condition of K (~1e8 here); measured 1.4e-13 (was 1e-8).
constexpr double kDenseAgreement = 1e-12;
// Sine of the largest principal angle (Davis-Kahan: residual over relative gaps >= 1e-2):
// measured 1.1e-13 (was 1e-6).
constexpr double kSubspaceAgreement = 1e-12;
// Relative residual of the held body's pairs: measured 5.4e-13 (was the contract's 1e-8).
constexpr double kResidualBound = 5e-12;
// Strain energy of a rigid motion in the held basis relative to max |K_reduced|: measured
// 1.2e-13 (was 1e-10).
constexpr double kRigidEnergy = 1e-12;

const fem::IsotropicMaterial kSteel = testing::Steel();

// A hex20 beam 0.4 x 0.05 x 0.04 m, clamped (support) at x = 0, with the tip face x = 0.4 as
// one interface of the given coupling, marker at the face centroid.
struct Beam {
  Body body;
  std::vector<int> root;
  std::vector<int> tip;
  BoundaryConditions With(Coupling coupling) const {
    BoundaryConditions c;
    c.supports.push_back({"root", root});
    c.interfaces.push_back({"tip", tip, coupling, std::nullopt, {}});
    return c;
  }
};
const Beam& TheBeam() {
  static const Beam beam = [] {
    Beam b{testing::MakeBox(ElementType::kHex20, {4, 1, 1}, {0.4, 0.05, 0.04}, kSteel), {}, {}};
    b.root = testing::NodesAt(b.body.mesh, 0, 0.0);
    b.tip = testing::NodesAt(b.body.mesh, 0, 0.4);
    return b;
  }();
  return beam;
}

// The least-squares rigid motion [t; theta] of the nodes' displacement in u, about `marker`,
// with unit weights, by a QR solve of the stacked S(r_n) (independent of RigidFitOperator).
Eigen::Matrix<double, 6, 1> FitRigid(const fem::Mesh& mesh, const std::vector<int>& nodes,
                                     const Eigen::Vector3d& marker, const Eigen::VectorXd& u) {
  Eigen::MatrixXd S(3 * static_cast<Eigen::Index>(nodes.size()), 6);
  Eigen::VectorXd y(S.rows());
  for (std::size_t k = 0; k < nodes.size(); ++k) {
    const Eigen::Vector3d r = mesh.nodes.col(nodes[k]) - marker;
    const auto row = 3 * static_cast<Eigen::Index>(k);
    S.middleRows<3>(row) << Eigen::Matrix3d::Identity(), Eigen::Matrix3d::Zero();
    // theta x r, written out.
    S.middleRows<3>(row).rightCols<3>() << 0, r(2), -r(1), -r(2), 0, r(0), r(1), -r(0), 0;
    y.segment<3>(row) = u.segment<3>(3 * nodes[k]);
  }
  return S.colPivHouseholderQr().solve(y);
}

TEST(RigidCoupling, ConstraintModesMoveTheInterfaceNodesRigidlyWithTheMarker) {
  const Beam& beam = TheBeam();
  const InterfaceSpec tip = beam.With(Coupling::kRigid).interfaces[0];
  const Eigen::Vector3d marker = MarkerPosition(beam.body.mesh.nodes, tip);
  EXPECT_LE((marker - Eigen::Vector3d(0.4, 0.025, 0.02)).norm(), kRigidExact);  // measured 5.6e-17
  eigensolvers::EigenOptions eigen;
  eigen.num_modes = 3;
  const ReducedBasis cb = CraigBamptonBasis(beam.body.model(), beam.With(Coupling::kRigid), eigen, testing::Spectra());
  ASSERT_EQ(cb.Counts(), (ModeCounts{0, 3, 6, 0}));
  double worst = 0.0;
  for (Eigen::Index j = 0; j < 6; ++j) {
    const Eigen::Matrix<double, 6, 1> q = Eigen::Matrix<double, 6, 1>::Unit(j);
    for (const int n : beam.tip) {
      const Eigen::Vector3d r = beam.body.mesh.nodes.col(n) - marker;
      const Eigen::Vector3d expected = q.head<3>() + q.tail<3>().cross(r);
      worst = std::max(worst, (cb.Phi.block<3, 1>(3 * n, j) - expected).cwiseAbs().maxCoeff());
    }
  }
  EXPECT_LE(worst, kRigidExact);
  // The marker motion recovered from the nodes is the unit motion; zero in the normal modes.
  const Eigen::MatrixXd motion = MarkerMotion(beam.body.mesh.nodes, tip, cb.Phi);
  EXPECT_LE((motion.leftCols(6) - Eigen::MatrixXd::Identity(6, 6)).cwiseAbs().maxCoeff(), kFitRoundOff);
  EXPECT_LE(motion.rightCols(3).cwiseAbs().maxCoeff(), kFitRoundOff);
  std::printf("[ numbers  ] rigid coupling: max deviation of node motion from t + theta x r: %.1e\n", worst);
}

TEST(AveragingCoupling, RigidFitOfEachConstraintModeIsTheUnitMarkerMotionAndTheFaceDeforms) {
  const Beam& beam = TheBeam();
  const BoundaryConditions conditions = beam.With(Coupling::kAveraging);
  const Eigen::Vector3d marker = MarkerPosition(beam.body.mesh.nodes, conditions.interfaces[0]);
  eigensolvers::EigenOptions eigen;
  eigen.num_modes = 3;
  const ReducedBasis cb = CraigBamptonBasis(beam.body.model(), conditions, eigen, testing::Spectra());
  ASSERT_EQ(cb.Counts(), (ModeCounts{0, 3, 6, 0}));
  double worst = 0.0, strain = 0.0;
  for (Eigen::Index j = 0; j < 9; ++j) {
    const Eigen::Matrix<double, 6, 1> fit = FitRigid(beam.body.mesh, beam.tip, marker, cb.Phi.col(j));
    Eigen::Matrix<double, 6, 1> expected = Eigen::Matrix<double, 6, 1>::Zero();
    if (j < 6) expected(j) = 1.0;
    worst = std::max(worst, (fit - expected).cwiseAbs().maxCoeff());
    // The face does not move rigidly: the nodes keep a deformation beyond the rigid fit.
    double face = 0.0, deviation = 0.0;
    for (const int n : beam.tip) {
      const Eigen::Vector3d r = beam.body.mesh.nodes.col(n) - marker;
      face = std::max(face, cb.Phi.block<3, 1>(3 * n, j).norm());
      deviation = std::max(deviation, (cb.Phi.block<3, 1>(3 * n, j) - fit.head<3>() - fit.tail<3>().cross(r)).norm());
    }
    strain = std::max(strain, deviation / face);
  }
  EXPECT_LE(worst, kFitRoundOff);
  EXPECT_GE(strain, 1e-3);
  std::printf("[ numbers  ] averaging coupling: max |fit - unit marker motion| %.1e; face deformation beyond the fit "
              "up to %.2f of the face motion\n", worst, strain);
}

TEST(AveragingCoupling, ConstraintModesAreSofterThanRigidCouplingForTheSameMarkerMotion) {
  const Beam& beam = TheBeam();
  const ReducedBasis rigid = CraigBamptonBasis(beam.body.model(), beam.With(Coupling::kRigid), {}, testing::Spectra());
  const ReducedBasis average =
      CraigBamptonBasis(beam.body.model(), beam.With(Coupling::kAveraging), {}, testing::Spectra());
  // Strain energy of unit marker motion q: q^T K_bb q / 2. Every RBE2 field satisfies the RBE3
  // constraint, so the RBE3 minimum is lower for every q: K_bb(RBE2) - K_bb(RBE3) >= 0.
  std::printf("[ numbers  ] strain energy of unit marker motion, averaging / rigid:");
  for (Eigen::Index j = 0; j < 6; ++j) {
    EXPECT_LT(average.K_reduced(j, j), rigid.K_reduced(j, j)) << "marker DOF " << j;
    std::printf(" %.3f", average.K_reduced(j, j) / rigid.K_reduced(j, j));
  }
  std::printf("\n");
  const Eigen::VectorXd difference =
      Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>(rigid.K_reduced - average.K_reduced).eigenvalues();
  EXPECT_GE(difference.minCoeff(), -1e-10 * rigid.K_reduced.cwiseAbs().maxCoeff());
}

// The dense reference of the averaging interface: free DOF selection, W on them, null space.
struct DenseAveraging {
  Eigen::MatrixXd S;  // free DOF (support clamped), num_dofs x f
  Eigen::MatrixXd W;  // 6 x f
  Eigen::MatrixXd N;  // null space of W, f x (f - 6)
};
DenseAveraging MakeDenseAveraging(const Beam& beam) {
  DenseAveraging d;
  d.S = testing::FreeDofSelection(beam.body.K.rows(), beam.root);
  d.W = Eigen::MatrixXd(RigidFitOperator(beam.body.mesh.nodes, beam.With(Coupling::kAveraging).interfaces[0])) * d.S;
  d.N = testing::NullSpace(d.W);
  return d;
}

TEST(AveragingCoupling, FixedInterfaceModesMatchADenseNullSpaceSolve) {
  const Beam& beam = TheBeam();
  const BoundaryConditions conditions = beam.With(Coupling::kAveraging);
  eigensolvers::EigenOptions eigen;
  eigen.num_modes = 8;
  const ReducedBasis basis = FixedInterfaceModalBasis(beam.body.model(), conditions, eigen, testing::Spectra());
  const DenseAveraging d = MakeDenseAveraging(beam);
  const testing::DenseModes dense = testing::DenseModesOn(beam.body.K, beam.body.M, d.S * d.N, 0.0);
  double worst = 0.0;
  for (Eigen::Index j = 0; j < 8; ++j) {
    worst = std::max(worst, std::abs(testing::Lambda(basis.frequency_hz(j)) / dense.values(j) - 1.0));
    EXPECT_LE(basis.relative_residuals(j), kResidualBound);
  }
  EXPECT_LE(worst, kDenseAgreement);
  const double sine = testing::LargestPrincipalAngleSine(beam.body.M, basis.Phi, dense.vectors.leftCols(8));
  EXPECT_LE(sine, kSubspaceAgreement);
  // The marker stays held: the rigid fit of every mode is zero.
  const Eigen::MatrixXd motion = MarkerMotion(beam.body.mesh.nodes, conditions.interfaces[0], basis.Phi);
  EXPECT_LE(motion.cwiseAbs().maxCoeff() / basis.Phi.cwiseAbs().maxCoeff(), kFitRoundOff);
  // Softer than holding the face: each frequency is at most the clamped face's.
  const ReducedBasis held = FixedInterfaceModalBasis(beam.body.model(), beam.With(Coupling::kRigid), eigen, testing::Spectra());
  for (Eigen::Index j = 0; j < 8; ++j) EXPECT_LE(basis.frequency_hz(j), held.frequency_hz(j) * (1.0 + 1e-12));
  std::printf("[ numbers  ] averaging fixed-interface modes vs dense null-space solve: eigenvalue %.1e, subspace sine "
              "%.1e; f1 %.2f Hz (face held: %.2f Hz)\n", worst, sine, basis.frequency_hz(0), held.frequency_hz(0));
}

TEST(AveragingCoupling, ConstraintModesMatchADenseLagrangeMultiplierSolve) {
  const Beam& beam = TheBeam();
  const ReducedBasis cb =
      CraigBamptonBasis(beam.body.model(), beam.With(Coupling::kAveraging), {}, testing::Spectra());
  const DenseAveraging d = MakeDenseAveraging(beam);
  const Eigen::MatrixXd K = d.S.transpose() * Eigen::MatrixXd(beam.body.K) * d.S;
  const Eigen::Index f = K.rows();
  // [K, a W^T; a W, 0] [u; lambda / a] = [0; a I], a = max |K| so the blocks are of one scale.
  const double a = K.cwiseAbs().maxCoeff();
  Eigen::MatrixXd kkt = Eigen::MatrixXd::Zero(f + 6, f + 6);
  kkt.topLeftCorner(f, f) = K;
  kkt.topRightCorner(f, 6) = a * d.W.transpose();
  kkt.bottomLeftCorner(6, f) = a * d.W;
  Eigen::MatrixXd rhs = Eigen::MatrixXd::Zero(f + 6, 6);
  rhs.bottomRows(6) = a * Eigen::MatrixXd::Identity(6, 6);
  const Eigen::MatrixXd solution = kkt.fullPivLu().solve(rhs);
  const Eigen::MatrixXd psi = d.S * solution.topRows(f);
  const double deviation = (cb.Phi - psi).cwiseAbs().maxCoeff() / psi.cwiseAbs().maxCoeff();
  EXPECT_LE(deviation, kDenseAgreement);
  std::printf("[ numbers  ] averaging constraint modes vs dense Lagrange solve: %.1e\n", deviation);
}

TEST(AveragingCoupling, OnAFreeBodyTheConstraintModesAreRigid) {
  const Beam& beam = TheBeam();
  BoundaryConditions free;
  free.interfaces.push_back({"tip", beam.tip, Coupling::kAveraging, std::nullopt, {}});
  const ReducedBasis cb = CraigBamptonBasis(beam.body.model(), free, {}, testing::Spectra());
  // Unit marker motion moves the whole body rigidly: no strain energy.
  const double energy = cb.K_reduced.cwiseAbs().maxCoeff();
  const ReducedBasis held = CraigBamptonBasis(beam.body.model(), beam.With(Coupling::kAveraging), {}, testing::Spectra());
  EXPECT_LE(energy, kRigidEnergy * held.K_reduced.cwiseAbs().maxCoeff());
}

TEST(RigidFitOperator, RecoversAnyRigidMotionWithAnyPositiveWeights) {
  const Beam& beam = TheBeam();
  InterfaceSpec tip{"tip", beam.tip, Coupling::kAveraging, Eigen::Vector3d(0.5, 0.1, -0.2), {}};
  for (std::size_t k = 0; k < tip.nodes.size(); ++k) tip.weights.push_back(1.0 + static_cast<double>(k % 3));
  const Eigen::SparseMatrix<double> W = RigidFitOperator(beam.body.mesh.nodes, tip);
  Eigen::MatrixXd rigid = Eigen::MatrixXd::Zero(beam.body.K.rows(), 6);
  for (const int n : tip.nodes) rigid.middleRows<3>(3 * n) = RigidMotionMatrix(beam.body.mesh.nodes.col(n) - *tip.marker_position);
  EXPECT_LE((W * rigid - Eigen::MatrixXd::Identity(6, 6)).cwiseAbs().maxCoeff(), kFitRoundOff);
}

TEST(InterfaceCouplingBadInput, GivesOneLineInputErrors) {
  const Beam& beam = TheBeam();
  const Eigen::Matrix3Xd& x = beam.body.mesh.nodes;
  const auto build = [&](const BoundaryConditions& c) { return [&x, c] { BuildConstraintTransform(x, c); }; };
  BoundaryConditions c;
  c.interfaces.push_back({"tip", {}, Coupling::kNodes, std::nullopt, {}});
  testing::ExpectInputError(build(c), {"interface 'tip': no nodes"});
  c.interfaces[0].nodes = {0, 100000};
  testing::ExpectInputError(build(c), {"interface 'tip': node 100000 is outside"});
  c.interfaces[0].nodes = {3, 3};
  testing::ExpectInputError(build(c), {"interface 'tip': node 3 is listed twice"});
  c.interfaces[0].nodes = beam.tip;
  c.interfaces[0].name = "";
  testing::ExpectInputError(build(c), {"interface with an empty name"});
  c.interfaces[0].name = "tip";
  c.supports.push_back({"tip", beam.root});
  testing::ExpectInputError(build(c), {"interface 'tip': the name is used"});
  c.supports[0] = {"clamp", {beam.tip[0]}};
  testing::ExpectInputError(build(c), {"interface 'tip': node", "is also in support 'clamp'"});
  c.supports.clear();
  // Nodes on one line: the marker rotation about it is undetermined.
  const std::vector<int> edge = testing::NodesWhere(beam.body.mesh, [](const Eigen::Vector3d& p) {
    return p(1) == 0.0 && p(2) == 0.0;
  });
  for (const Coupling coupling : {Coupling::kRigid, Coupling::kAveraging}) {
    c.interfaces[0] = {"edge", edge, coupling, std::nullopt, {}};
    testing::ExpectInputError(build(c), {"interface 'edge'", std::string(CouplingName(coupling)), "one line"});
  }
  c.interfaces[0] = {"tip", beam.tip, Coupling::kRigid, std::nullopt, {1.0}};
  testing::ExpectInputError(build(c), {"interface 'tip': weights are for averaging coupling only, not rigid"});
  c.interfaces[0].coupling = Coupling::kAveraging;
  testing::ExpectInputError(build(c), {"interface 'tip': 1 weights for"});
  c.interfaces[0].weights.assign(beam.tip.size(), 1.0);
  c.interfaces[0].weights[2] = -1.0;
  testing::ExpectInputError(build(c), {"interface 'tip': weight -1 of node", "must be finite and > 0"});
  c.interfaces[0].weights.clear();
  c.interfaces[0].marker_position = Eigen::Vector3d(0.0, std::nan(""), 0.0);
  testing::ExpectInputError(build(c), {"interface 'tip': marker position is not finite"});
  testing::ExpectInputError([&] { MarkerMotion(x, {"n", {0}, Coupling::kNodes, std::nullopt, {}}, Eigen::MatrixXd()); },
                            {"interface 'n': a node-set interface has no marker"});
}

}  // namespace
}  // namespace flexmbs::reduction
