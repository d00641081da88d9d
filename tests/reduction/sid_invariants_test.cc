// The SID inertia invariants (reduction/sid_invariants.h) against computations that share
// nothing with them but the mass matrix: the FE model's mass properties, products of the full
// M with the basis and the rigid-body fields, central differences of order-0 quantities of the
// deformed body, and the inertia terms of the equations of motion (docs/sid.md) evaluated node
// by node. Bodies: distorted, curved, rotated and shifted tet10, hex20 and wedge15 boxes; bases:
// M-orthonormal eigenvectors (six rigid and three elastic) and a random, non-orthonormal one.

#include "reduction/sid_invariants.h"

#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <array>
#include <cmath>
#include <map>
#include <random>
#include <string>
#include <utility>
#include <vector>

#include "core/error.h"
#include "core/skew.h"
#include "fem/assembly.h"
#include "fem/mass_properties.h"
#include "tests/fem/test_meshes.h"
#include "tests/support/test_problems.h"

namespace flexmbs::reduction {
namespace {

using Eigen::Matrix3d;
using Eigen::Matrix3Xd;
using Eigen::MatrixXd;
using Eigen::Vector3d;
using Eigen::VectorXd;
using fem::ElementType;

// Identities of exact integrals evaluated two ways in double precision: round-off of sums over
// a few hundred nodes, amplified up to ~30x by the offset of the body from Bo (the inertia about
// Bo is mostly m |c|^2). Measured below 1e-14.
constexpr double kRoundOff = 1e-12;
// Central differences of quantities exactly linear (mdCM, Cr, Gr, Oe) or quadratic (J) in q have
// no truncation error (the cubic and higher terms are zero), so what is left is the round-off of
// the order-0 values, ~1e-15 |X0| per evaluation, divided by the step. Asserted as
// |difference - m1| <= kDifferenceRoundOff |X0| / step.
constexpr double kDifferenceRoundOff = 1e-13;
// Largest nodal displacement of a difference step or a test configuration: a tenth (a
// twentieth) of the body's size, large so the round-off above stays small.
constexpr double kStepSize = 0.1;
constexpr double kConfigurationSize = 0.05;
const Vector3d kBoxSize(0.5, 0.3, 0.4);

// A DOF vector (3 node + axis) as 3 x N and back.
Matrix3Xd Nodal(const VectorXd& u) { return Eigen::Map<const Matrix3Xd>(u.data(), 3, u.size() / 3); }
VectorXd Dofs(const Matrix3Xd& x) { return Eigen::Map<const VectorXd>(x.data(), x.size()); }

double RelativeError(const MatrixXd& value, const MatrixXd& reference) {
  return (value - reference).norm() / reference.norm();
}

// The largest nodal displacement of a DOF vector [m].
double MaxDisplacement(const VectorXd& u) { return Nodal(u).colwise().norm().maxCoeff(); }

struct Body {
  fem::Mesh mesh;
  Eigen::SparseMatrix<double> K, M;
  const Matrix3Xd& nodes() const { return mesh.nodes; }
};

// A 3 x 2 x 2-cell box, interior corners moved and interior edges curved, rotated and moved off
// the origin (so the centre of mass and the inertia tensor have every component).
const Body& MakeBody(ElementType type) {
  static std::map<ElementType, Body> bodies;
  auto found = bodies.find(type);
  if (found != bodies.end()) return found->second;
  std::mt19937 rng(17);
  fem::testing::BoxMesh box = fem::testing::StructuredBox(type, Eigen::Vector3i(3, 2, 2), kBoxSize);
  fem::testing::DistortInterior(&box, 0.15, 0.1, &rng);
  fem::testing::Transform(&box.mesh, fem::testing::RandomRotation(&rng), Vector3d(0.8, -0.5, 0.6));
  fem::SystemMatrices system = fem::AssembleSystem(box.mesh, fem::MassMatrixKind::kConsistent);
  Body body{std::move(box.mesh), std::move(system.stiffness), std::move(system.mass)};
  return bodies.emplace(type, std::move(body)).first->second;
}

// The first nine M-orthonormal eigenvectors of a body (six rigid-body modes, three elastic):
// free-free, so K - sigma M is positive definite for any sigma < 0.
const MatrixXd& Eigenmodes(ElementType type) {
  static std::map<ElementType, MatrixXd> bases;
  auto found = bases.find(type);
  if (found != bases.end()) return found->second;
  const Body& body = MakeBody(type);
  return bases.emplace(type, testing::SolveDense(body.K, body.M, -1e4).vectors.leftCols(9)).first->second;
}

MatrixXd RandomMatrix(Eigen::Index rows, Eigen::Index cols, double scale, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> uniform(-scale, scale);
  return MatrixXd::NullaryExpr(rows, cols, [&] { return uniform(rng); });
}

struct Case {
  ElementType type;
  bool eigenmodes;  ///< the first 9 M-orthonormal eigenvectors (6 rigid), else a random basis
};
std::string CaseName(const Case& c) {
  return std::string(fem::Traits(c.type).name) + (c.eigenmodes ? "Eigenmodes" : "RandomBasis");
}
void PrintTo(const Case& c, std::ostream* os) { *os << CaseName(c); }

class InertiaInvariantsTest : public ::testing::TestWithParam<Case> {
 protected:
  void SetUp() override {
    const Case c = GetParam();
    body_ = &MakeBody(c.type);
    Phi_ = c.eigenmodes ? Eigenmodes(c.type) : RandomMatrix(body_->M.rows(), 5, 1e-3, 5);
    inv_ = ComputeInertiaInvariants(body_->M, body_->nodes(), Phi_);
  }
  const Eigen::SparseMatrix<double>& M() const { return body_->M; }
  const Matrix3Xd& nodes() const { return body_->nodes(); }
  Eigen::Index n() const { return Phi_.cols(); }
  // The node positions of the deformed body x + Phi q.
  Matrix3Xd Deformed(const VectorXd& q) const { return nodes() + Nodal(Phi_ * q); }

  const Body* body_ = nullptr;
  MatrixXd Phi_;
  InertiaInvariants inv_;
};

TEST_P(InertiaInvariantsTest, BlocksHaveTheirShapesAndOrders) {
  const std::vector<std::pair<const sid::TaylorMatrix*, std::array<Eigen::Index, 3>>> expected = {
      {&inv_.mdCM, {3, 1, 1}},     {&inv_.J, {3, 3, 2}},  {&inv_.Ct, {n(), 3, 0}},     {&inv_.Cr, {n(), 3, 1}},
      {&inv_.Me, {n(), n(), 0}}, {&inv_.Gr, {3, 3 * n(), 1}}, {&inv_.Ge, {n(), 3 * n(), 0}}, {&inv_.Oe, {n(), 6, 1}}};
  for (const auto& [block, shape] : expected) {
    EXPECT_EQ(block->m0.rows(), shape[0]);
    EXPECT_EQ(block->m0.cols(), shape[1]);
    EXPECT_EQ(block->order(), shape[2]);
    EXPECT_TRUE(block->IsConsistent(n()));
  }
}

TEST_P(InertiaInvariantsTest, OrderZeroIsTheMassCentreOfMassAndInertiaOfTheFeModel) {
  for (const fem::MassProperties& props :
       {fem::MassPropertiesFromMassMatrix(M(), nodes()), fem::IntegrateMassProperties(body_->mesh)}) {
    const double m = props.mass_kg;
    const Vector3d& c = props.p_BoCm_B;
    const Matrix3d J_Bo = props.I_Cm_B + m * (c.squaredNorm() * Matrix3d::Identity() - c * c.transpose());
    EXPECT_LT(std::abs(inv_.mass - m) / m, kRoundOff);
    EXPECT_LT(RelativeError(inv_.mdCM.m0, m * c), kRoundOff);
    EXPECT_LT(RelativeError(inv_.J.m0, J_Bo), kRoundOff);
  }
}

TEST_P(InertiaInvariantsTest, OrderZeroBlocksAreProjectionsOfTheFullMassMatrix) {
  const MatrixXd R = fem::RigidBodyModes(nodes());  // translations, rotations about Bo
  const MatrixXd M_Phi = M() * Phi_;
  EXPECT_LT(RelativeError(inv_.Ct.m0, M_Phi.transpose() * R.leftCols(3)), kRoundOff);
  EXPECT_LT(RelativeError(inv_.Cr.m0, M_Phi.transpose() * R.rightCols(3)), kRoundOff);
  EXPECT_LT(RelativeError(inv_.Me.m0, Phi_.transpose() * M_Phi), kRoundOff);
  // int phi_j dm side by side (3 x n): one norm, as elastic free-free modes have none.
  MatrixXd mode_integrals(3, n());
  for (Eigen::Index j = 0; j < n(); ++j) mode_integrals.col(j) = inv_.mdCM.m1[static_cast<std::size_t>(j)];
  EXPECT_LT(RelativeError(mode_integrals, R.leftCols(3).transpose() * M_Phi), kRoundOff);
}

// The order-0 formulas applied to the deformed node positions x + Phi q with the SAME mass matrix
// give the invariants at q: the deformed position rho = r + u is interpolated by the same shape
// functions, and dm is the undeformed material's (the density rides with the material), so
// int f(rho) dm over the deformed body is the same quadrature of the same nodal fields; no mass
// matrix of the deformed mesh is involved. mdCM, J and Cr come from the full M and the rigid-body
// fields of the deformed nodes (independent of the code under test); Gr and Oe from the order-0
// part of ComputeInertiaInvariants, checked against M itself by the other tests.
struct OrderZeroAt {
  Vector3d mdCM;
  Matrix3d J;
  MatrixXd Cr, Gr, Oe;
};

TEST_P(InertiaInvariantsTest, OrderOneAndTwoTermsAreExactDifferencesOfTheDeformedBody) {
  const auto at = [&](const VectorXd& q) {
    const Matrix3Xd x = Deformed(q);
    const MatrixXd R = fem::RigidBodyModes(x);
    const MatrixXd RMR = R.transpose() * (M() * R);  // [m I, mdCM~^T; mdCM~, J]
    const InertiaInvariants deformed = ComputeInertiaInvariants(M(), x, Phi_);
    return OrderZeroAt{Axial(RMR.bottomLeftCorner<3, 3>()), RMR.bottomRightCorner<3, 3>(),
                       Phi_.transpose() * (M() * R.rightCols(3)), deformed.Gr.m0, deformed.Oe.m0};
  };
  // |(X(+) - X(-)) / (2 step) - m1| against the round-off bound of the two evaluations.
  const auto expect_difference = [](const MatrixXd& plus, const MatrixXd& minus, double step, const MatrixXd& m1,
                                    const char* what, Eigen::Index j) {
    const double bound = kDifferenceRoundOff * std::max(plus.norm(), minus.norm()) / step;
    EXPECT_LE(((plus - minus) / (2.0 * step) - m1).norm(), bound) << what << " mode " << j;
  };
  std::vector<double> steps;
  for (Eigen::Index j = 0; j < n(); ++j) {
    const auto sj = static_cast<std::size_t>(j);
    const double step = kStepSize * kBoxSize.maxCoeff() / MaxDisplacement(Phi_.col(j));
    steps.push_back(step);
    const VectorXd e_j = VectorXd::Unit(n(), j);
    const OrderZeroAt plus = at(step * e_j), minus = at(-step * e_j);
    expect_difference(plus.mdCM, minus.mdCM, step, inv_.mdCM.m1[sj], "mdCM", j);
    expect_difference(plus.J, minus.J, step, inv_.J.m1[sj], "J", j);
    expect_difference(plus.Cr, minus.Cr, step, inv_.Cr.m1[sj], "Cr", j);
    expect_difference(plus.Gr, minus.Gr, step, inv_.Gr.m1[sj], "Gr", j);
    expect_difference(plus.Oe, minus.Oe, step, inv_.Oe.m1[sj], "Oe", j);
  }
  // J is quadratic: J(s(e_j + e_k)) - J(s(e_j - e_k)) - J(s(-e_j + e_k)) + J(-s(e_j + e_k))
  // = 4 s^2 (m2[jk] + m2[kj]) = 8 s^2 m2[jk], the linear terms cancelling.
  const auto J_at = [&](const VectorXd& q) {
    const MatrixXd R = fem::RigidBodyModes(Deformed(q)).rightCols(3);
    return MatrixXd(R.transpose() * (M() * R));
  };
  for (Eigen::Index j = 0; j < n(); ++j) {
    for (Eigen::Index k = 0; k < n(); ++k) {
      const double s = std::min(steps[static_cast<std::size_t>(j)], steps[static_cast<std::size_t>(k)]);
      const VectorXd a = s * VectorXd::Unit(n(), j), b = s * VectorXd::Unit(n(), k);
      const MatrixXd Jpp = J_at(a + b), Jpm = J_at(a - b), Jmp = J_at(b - a), Jmm = J_at(-a - b);
      const double bound = kDifferenceRoundOff * 4.0 * Jpp.norm() / (8.0 * s * s);
      const MatrixXd m2 = inv_.J.m2[static_cast<std::size_t>(j * n() + k)];
      EXPECT_LE(((Jpp - Jpm - Jmp + Jmm) / (8.0 * s * s) - m2).norm(), bound) << "J m2 " << j << ", " << k;
    }
  }
}

// The velocity-dependent inertia terms of docs/sid.md against the virtual work of the inertia
// forces, node by node: with B = [I, -rho~, Phi] at the nodes (fem::RigidBodyModes of the
// deformed nodes, then Phi), the mass matrix is B^T M B and the terms are B^T M a_v with the
// nodal accelerations a_v = w~ w~ rho + 2 w~ Phi qdot.
TEST_P(InertiaInvariantsTest, EquationsOfMotionInertiaTermsEqualTheirNodewiseEvaluation) {
  const Eigen::Index nq = n();
  VectorXd q = RandomMatrix(nq, 1, 1.0, 21);
  q *= kConfigurationSize * kBoxSize.maxCoeff() / MaxDisplacement(Phi_ * q);
  const VectorXd qdot = RandomMatrix(nq, 1, 1.0, 22) / MaxDisplacement(Phi_ * q);
  const Vector3d w = RandomMatrix(3, 1, 10.0, 23);

  const Matrix3Xd rho = Deformed(q);
  const MatrixXd R = fem::RigidBodyModes(rho);
  const Vector3d mdCM = inv_.mdCM.Evaluate(q);
  const Matrix3d J = inv_.J.Evaluate(q);
  const MatrixXd Ct = inv_.Ct.Evaluate(q), Cr = inv_.Cr.Evaluate(q), Gr = inv_.Gr.Evaluate(q);

  // Mass matrix, block by block.
  MatrixXd B(R.rows(), 6 + nq);
  B << R, Phi_;
  const MatrixXd BMB = B.transpose() * (M() * B);
  EXPECT_LT(RelativeError(BMB.topLeftCorner<3, 3>(), inv_.mass * Matrix3d::Identity()), kRoundOff);
  EXPECT_LT(RelativeError(BMB.block<3, 3>(3, 0), Skew(mdCM)), kRoundOff);
  EXPECT_LT(RelativeError(BMB.block<3, 3>(3, 3), J), kRoundOff);
  EXPECT_LT(RelativeError(BMB.block(6, 0, nq, 3), Ct), kRoundOff);
  EXPECT_LT(RelativeError(BMB.block(6, 3, nq, 3), Cr), kRoundOff);
  EXPECT_LT(RelativeError(BMB.bottomRightCorner(nq, nq), inv_.Me.m0), kRoundOff);

  // Centrifugal and Coriolis terms, each on its own.
  const Matrix3d W = Skew(w);
  const VectorXd centrifugal = Dofs(W * W * rho);         // w~ w~ rho at every node
  const VectorXd coriolis = Dofs(2.0 * W * Nodal(Phi_ * qdot));  // 2 w~ Phi qdot at every node
  const MatrixXd BM = (M() * B).transpose();
  const VectorXd centrifugal_work = BM * centrifugal, coriolis_work = BM * coriolis;
  VectorXd Gr_term = Vector3d::Zero(), Ge_term = VectorXd::Zero(nq);
  for (Eigen::Index j = 0; j < nq; ++j) {
    Gr_term += Gr.block<3, 3>(0, 3 * j) * w * qdot(j);
    Ge_term += inv_.Ge.m0.block(0, 3 * j, nq, 3) * w * qdot(j);
  }
  EXPECT_LT(RelativeError(centrifugal_work.head<3>(), W * W * mdCM), kRoundOff);
  EXPECT_LT(RelativeError(coriolis_work.head<3>(), 2.0 * W * Ct.transpose() * qdot), kRoundOff);
  EXPECT_LT(RelativeError(centrifugal_work.segment<3>(3), W * J * w), kRoundOff);
  EXPECT_LT(RelativeError(coriolis_work.segment<3>(3), Gr_term), kRoundOff);
  EXPECT_LT(RelativeError(centrifugal_work.tail(nq), inv_.Oe.Evaluate(q) * AngularVelocityProducts(w)), kRoundOff);
  EXPECT_LT(RelativeError(coriolis_work.tail(nq), Ge_term), kRoundOff);
}

INSTANTIATE_TEST_SUITE_P(Boxes, InertiaInvariantsTest,
                         ::testing::Values(Case{ElementType::kTet10, true}, Case{ElementType::kTet10, false},
                                           Case{ElementType::kHex20, true}, Case{ElementType::kHex20, false},
                                           Case{ElementType::kWedge15, true}, Case{ElementType::kWedge15, false}),
                         [](const auto& param_info) { return CaseName(param_info.param); });

// A basis holding the six rigid-body fields: unit-mass translations T / sqrt(m), rotations about
// Bo, then random fields made M-orthogonal to them. The invariants must repeat the rigid-body
// mass matrix [m I, mdCM~^T; mdCM~, J] in Ct, Cr and Me and vanish where an elastic field meets a
// rigid one.
TEST(InertiaInvariantsRigidModes, RepeatTheRigidBodyMassMatrixAndVanishForOrthogonalFields) {
  const Body& body = MakeBody(ElementType::kTet10);
  const MatrixXd R = fem::RigidBodyModes(body.nodes());
  const double m = (R.leftCols(1).transpose() * (body.M * R.leftCols(1)))(0, 0);
  MatrixXd rigid = R;
  rigid.leftCols(3) /= std::sqrt(m);
  MatrixXd E = RandomMatrix(R.rows(), 4, 1.0, 31);
  for (int pass = 0; pass < 2; ++pass) {  // twice: the second removes the first's round-off
    const MatrixXd rigid_mass = rigid.transpose() * (body.M * rigid);
    E -= rigid * rigid_mass.ldlt().solve(rigid.transpose() * (body.M * E));
  }
  for (Eigen::Index i = 0; i < E.cols(); ++i) E.col(i) /= std::sqrt(E.col(i).dot(body.M * E.col(i)));
  MatrixXd Phi(R.rows(), 10);
  Phi << rigid, E;
  const InertiaInvariants inv = ComputeInertiaInvariants(body.M, body.nodes(), Phi);
  const Vector3d s = inv.mdCM.m0;
  const Matrix3d J0 = inv.J.m0;

  EXPECT_LT(RelativeError(inv.Ct.m0.topRows(3), std::sqrt(m) * Matrix3d::Identity()), kRoundOff);
  EXPECT_LT(RelativeError(inv.Ct.m0.middleRows(3, 3), Skew(s)), kRoundOff);
  EXPECT_LT(RelativeError(inv.Cr.m0.topRows(3), Skew(s).transpose() / std::sqrt(m)), kRoundOff);
  EXPECT_LT(RelativeError(inv.Cr.m0.middleRows(3, 3), J0), kRoundOff);
  EXPECT_LT(RelativeError(inv.Me.m0.topLeftCorner<3, 3>(), Matrix3d::Identity()), kRoundOff);
  EXPECT_LT(RelativeError(inv.Me.m0.block<3, 3>(3, 3), J0), kRoundOff);
  // Zero blocks, against their Cauchy-Schwarz bounds for unit-modal-mass fields:
  // |int phi dm| <= sqrt(m), |int r x phi dm| <= sqrt(tr int r r^T dm) = sqrt(tr J0 / 2),
  // |int phi_rigid . phi dm| <= sqrt(Me_rigid,rigid).
  EXPECT_LE(inv.Ct.m0.bottomRows(4).cwiseAbs().maxCoeff(), kRoundOff * std::sqrt(m));
  EXPECT_LE(inv.Cr.m0.bottomRows(4).cwiseAbs().maxCoeff(), kRoundOff * std::sqrt(0.5 * J0.trace()));
  EXPECT_LE(inv.Me.m0.bottomLeftCorner(4, 6).cwiseAbs().maxCoeff(),
            kRoundOff * std::sqrt(inv.Me.m0.topLeftCorner<6, 6>().diagonal().maxCoeff()));
}

// ComputeModeProducts works through the nodes in blocks of about 2^20 / (3 n) rows: a body of
// 4913 nodes with 100 modes takes two, against the whole product in one.
TEST(ModeProducts, InNodeBlocksEqualTheWholeProduct) {
  const fem::Mesh mesh =
      fem::testing::StructuredBox(ElementType::kTet10, Eigen::Vector3i(8, 8, 8), Vector3d(1.0, 1.0, 1.0)).mesh;
  const Eigen::SparseMatrix<double> M = fem::AssembleSystem(mesh, fem::MassMatrixKind::kConsistent).mass;
  const MatrixXd Phi = RandomMatrix(M.rows(), 100, 1.0, 51);
  const Eigen::SparseMatrix<double> M_s = ScalarMassMatrix(M);
  const ModeComponents S = SplitModeComponents(Phi);
  ASSERT_GT(S.rows(), (Eigen::Index{1} << 20) / S.cols());
  const MatrixXd P = ComputeModeProducts(M_s, S);
  const MatrixXd whole = MatrixXd(S.transpose()) * MatrixXd(M_s * S);
  EXPECT_LT(RelativeError(P, whole), kRoundOff);
  const MatrixXd Me = P.block(0, 0, 100, 100) + P.block(100, 100, 100, 100) + P.block(200, 200, 100, 100);
  EXPECT_LT(RelativeError(Me, Phi.transpose() * (M * Phi)), kRoundOff);
}

TEST(ScalarMassMatrix, ReproducesTheAssembledMatrixAsItsKroneckerProductWithI3) {
  const Body& body = MakeBody(ElementType::kHex20);
  const MatrixXd M_s = MatrixXd(ScalarMassMatrix(body.M));
  MatrixXd kron = MatrixXd::Zero(body.M.rows(), body.M.cols());
  for (Eigen::Index a = 0; a < 3; ++a) {
    Eigen::Map<MatrixXd, 0, Eigen::Stride<Eigen::Dynamic, 3>>(kron.data() + a * kron.rows() + a, M_s.rows(),
                                                              M_s.cols(), Eigen::Stride<Eigen::Dynamic, 3>(3 * kron.rows(), 3)) = M_s;
  }
  EXPECT_EQ((MatrixXd(body.M) - kron).cwiseAbs().maxCoeff(), 0.0);
}

TEST(ScalarMassMatrix, RejectsAMatrixThatCouplesAxesOrDiffersBetweenThem) {
  const Body& body = MakeBody(ElementType::kTet10);
  const double max_entry = body.M.coeffs().cwiseAbs().maxCoeff();
  Eigen::SparseMatrix<double> coupled = body.M;
  coupled.coeffRef(3, 4) += 1e-9 * max_entry;
  coupled.coeffRef(4, 3) += 1e-9 * max_entry;
  EXPECT_THROW(ScalarMassMatrix(coupled), InternalError);
  Eigen::SparseMatrix<double> unequal = body.M;
  unequal.coeffRef(5, 5) *= 1.0 + 1e-9;
  EXPECT_THROW(ScalarMassMatrix(unequal), InternalError);
}

// A lumped (HRZ) mass matrix stores only its diagonal: the same projections hold.
TEST(InertiaInvariantsLumpedMass, AreTheProjectionsOfTheLumpedMatrix) {
  const Body& body = MakeBody(ElementType::kTet10);
  const Eigen::SparseMatrix<double> M = fem::AssembleSystem(body.mesh, fem::MassMatrixKind::kLumped).mass;
  const MatrixXd Phi = RandomMatrix(M.rows(), 4, 1e-3, 41);
  const InertiaInvariants inv = ComputeInertiaInvariants(M, body.nodes(), Phi);
  const MatrixXd R = fem::RigidBodyModes(body.nodes());
  const MatrixXd M_Phi = M * Phi;
  EXPECT_LT(RelativeError(inv.Me.m0, Phi.transpose() * M_Phi), kRoundOff);
  EXPECT_LT(RelativeError(inv.Cr.m0, M_Phi.transpose() * R.rightCols(3)), kRoundOff);
  EXPECT_LT(RelativeError(inv.J.m0, R.rightCols(3).transpose() * (M * R.rightCols(3))), kRoundOff);
}

TEST(CentrifugalBasis, ExpandsTheSquaredSkewMatrixOfAnyAngularVelocity) {
  const Vector3d w(0.3, -1.7, 2.2);
  const Eigen::Matrix<double, 6, 1> w_q = AngularVelocityProducts(w);
  Matrix3d sum = Matrix3d::Zero();
  for (std::size_t l = 0; l < 6; ++l) sum += w_q(static_cast<Eigen::Index>(l)) * CentrifugalBasis()[l];
  EXPECT_LT(RelativeError(sum, Skew(w) * Skew(w)), kRoundOff);
}

}  // namespace
}  // namespace flexmbs::reduction
