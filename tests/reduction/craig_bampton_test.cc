#include "reduction/craig_bampton.h"

#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <span>

#include "basis_test_support.h"
#include "core/error.h"
#include "reduction/correction_modes.h"
#include "reduction/interior_problem.h"
#include "tests/support/test_problems.h"

namespace flexmbs::reduction {
namespace {

using fem::ElementType;
using testing::Body;

// Constraint-mode displacement at boundary DOF: B is an exact 0/1 selection and G is zero
// there, so the values are exact.
constexpr double kExact = 0.0;
// |K psi| on interior DOF relative to max |K psi|: the residual of one Cholesky solve, a few
// hundred round-offs times the condition of K_ii (measured 4.0e-15; was 1e-9).
constexpr double kInteriorForce = 5e-14;
// Rayleigh-Ritz bound lambda_j(CB) >= lambda_j(full), up to round-off relative to lambda_j
// (measured: below the full model's by 3e-12 at most, above the previous k's by 2.4e-15; was 1e-10).
constexpr double kRitzRoundOff = 3e-11;
// With all fixed-interface modes the CB space is the full space: equal eigenvalues (measured
// 3.5e-12; was 1e-8).
constexpr double kCompleteAgreement = 3e-11;
// The orthonormalisation keeps the CB eigenvalues: measured 9.5e-10 relative (was 1e-8).
constexpr double kOrthonormalizedAgreement = 5e-9;
// A basis computed with one shared factorisation and with two: the same CHOLMOD factor (it is
// deterministic) and the same Lanczos runs, so the same numbers (measured: 0, bit for bit; was
// 1e-13): a few ulps.
constexpr double kSameComputation = 1e-15;
// Orthonormalised CB: M_reduced = I to this (measured 4.4e-15; was 1e-10).
constexpr double kOrthonormalityBound = 5e-14;
// Off-diagonal of K_reduced relative to its largest diagonal: round-off (measured 4.2e-16; was 1e-10).
constexpr double kDiagonalBound = 5e-15;
// Phi' = Phi T of the orthonormalisation, relative to max |Phi'| (measured 4.7e-16; was 1e-10).
constexpr double kTransformRoundOff = 5e-15;

const fem::IsotropicMaterial kSteel = testing::Steel();

double Shift(const Body& b) { return eigensolvers::FreeBodyShift(b.K, b.M); }

// Eigenvalues of the reduced pair, ascending, in shift-invert form (accurate low eigenvalues).
Eigen::VectorXd ReducedEigenvalues(const ReducedBasis& basis, double sigma) {
  return testing::SolveDense(basis.K_reduced.sparseView(), basis.M_reduced.sparseView(), sigma).values;
}

InterfaceSpec NodeInterface(const std::string& name, std::vector<int> nodes) {
  return {name, std::move(nodes), Coupling::kNodes, std::nullopt, {}};
}

TEST(CraigBampton, ConstraintModesGiveUnitDisplacementAtTheirOwnBoundaryDofAndNoInteriorForce) {
  const Body b = testing::MakeBox(ElementType::kHex20, {3, 1, 1}, {0.3, 0.06, 0.05}, kSteel);
  BoundaryConditions conditions;
  const std::vector<int> face = testing::NodesAt(b.mesh, 0, 0.0);
  conditions.interfaces.push_back(NodeInterface("root", face));
  eigensolvers::EigenOptions eigen;
  eigen.num_modes = 4;
  const ReducedBasis cb = CraigBamptonBasis(b.model(), conditions, eigen, testing::Spectra());
  const Eigen::Index n_b = 3 * static_cast<Eigen::Index>(face.size());
  ASSERT_EQ(cb.Counts(), (ModeCounts{0, 4, n_b, 0}));
  EXPECT_EQ(cb.names[0], "constraint_root_n" + std::to_string(face[0]) + "_x");
  std::vector<bool> boundary(static_cast<std::size_t>(b.K.rows()), false);
  double max_off = 0.0;
  for (std::size_t k = 0; k < face.size(); ++k) {
    for (int a = 0; a < 3; ++a) {
      const Eigen::Index dof = 3 * face[k] + a;
      boundary[static_cast<std::size_t>(dof)] = true;
      for (Eigen::Index j = 0; j < n_b; ++j) {
        const double expected = j == 3 * static_cast<Eigen::Index>(k) + a ? 1.0 : 0.0;
        max_off = std::max(max_off, std::abs(cb.Phi(dof, j) - expected));
      }
      // Normal modes are fixed at the interface.
      EXPECT_EQ(cb.Phi.row(dof).tail(4).cwiseAbs().maxCoeff(), 0.0);
    }
  }
  EXPECT_LE(max_off, kExact);
  const Eigen::MatrixXd force = b.K * cb.Phi.leftCols(n_b);
  double interior = 0.0;
  for (Eigen::Index dof = 0; dof < b.K.rows(); ++dof) {
    if (!boundary[static_cast<std::size_t>(dof)]) interior = std::max(interior, force.row(dof).cwiseAbs().maxCoeff());
  }
  const double relative = interior / force.cwiseAbs().maxCoeff();
  EXPECT_LE(relative, kInteriorForce);
  // Hence K_reduced is block diagonal: constraint modes are K-orthogonal to the normal modes.
  const double coupling = cb.K_reduced.topRightCorner(n_b, 4).cwiseAbs().maxCoeff() / cb.K_reduced.cwiseAbs().maxCoeff();
  EXPECT_LE(coupling, kInteriorForce);
  std::printf("[ numbers  ] constraint modes: boundary deviation %.1e, interior force / max force %.1e, K_bn coupling "
              "%.1e\n", max_off, relative, coupling);
}

struct ConvergenceCase {
  const char* name;
  bool supported;  // clamp x = 0 as a support (else free-free)
};

class CraigBamptonConvergence : public ::testing::TestWithParam<ConvergenceCase> {};

TEST_P(CraigBamptonConvergence, FrequenciesApproachTheFullModelFromAboveAndEqualItWithAllFixedInterfaceModes) {
  const Body b = testing::MakeBox(ElementType::kHex8, {4, 2, 2}, {0.4, 0.1, 0.1}, kSteel);
  BoundaryConditions conditions;
  conditions.interfaces.push_back(NodeInterface("tip", testing::NodesAt(b.mesh, 0, 0.4)));
  std::vector<int> clamped;
  if (GetParam().supported) {
    clamped = testing::NodesAt(b.mesh, 0, 0.0);
    conditions.supports.push_back({"root", clamped});
  }
  const double sigma = Shift(b);
  const testing::DenseModes full = testing::DenseModesOn(b.K, b.M, testing::FreeDofSelection(b.K.rows(), clamped), sigma);
  const Eigen::Index first = GetParam().supported ? 0 : 6;  // the first elastic eigenvalue
  constexpr Eigen::Index kCompared = 8;
  const Eigen::Index n_interior = b.K.rows() - 27 - 3 * static_cast<Eigen::Index>(clamped.size());

  Eigen::VectorXd previous = Eigen::VectorXd::Constant(kCompared, std::numeric_limits<double>::infinity());
  std::printf("[ numbers  ] %s: f%td/f%td of CB with k fixed-interface modes over the full model's:", GetParam().name,
              first + 1, first + kCompared);
  for (const Eigen::Index k : {Eigen::Index{0}, Eigen::Index{2}, Eigen::Index{5}, Eigen::Index{10}, Eigen::Index{20},
                               n_interior}) {
    eigensolvers::EigenOptions eigen;
    eigen.num_modes = static_cast<int>(k);
    const ReducedBasis cb = CraigBamptonBasis(b.model(), conditions, eigen, testing::Spectra());
    ASSERT_EQ(cb.Counts(), (ModeCounts{0, k, 27, 0}));
    const Eigen::VectorXd lambda = ReducedEigenvalues(cb, sigma).segment(first, kCompared);
    const Eigen::VectorXd exact = full.values.segment(first, kCompared);
    for (Eigen::Index j = 0; j < kCompared; ++j) {
      EXPECT_GE(lambda(j), exact(j) * (1.0 - kRitzRoundOff)) << "k = " << k << ", mode " << first + j;
      EXPECT_LE(lambda(j), previous(j) * (1.0 + kRitzRoundOff)) << "k = " << k << ", mode " << first + j;
      if (k == n_interior) {
        EXPECT_NEAR(lambda(j) / exact(j), 1.0, kCompleteAgreement) << "mode " << first + j;
      }
    }
    std::printf(" k=%td: %.2e/%.2e", k, std::sqrt(lambda(0) / exact(0)) - 1.0,
                std::sqrt(lambda(kCompared - 1) / exact(kCompared - 1)) - 1.0);
    previous = lambda;
  }
  std::printf(" (relative excess)\n");
}

INSTANTIATE_TEST_SUITE_P(Bodies, CraigBamptonConvergence,
                         ::testing::Values(ConvergenceCase{"free-free", false}, ConvergenceCase{"clamped", true}),
                         [](const ::testing::TestParamInfo<ConvergenceCase>& param) {
                           return std::string(param.param.supported ? "Clamped" : "FreeFree");
                         });

TEST(CraigBampton, OrthonormalizedHasIdentityMassDiagonalStiffnessAndTheSameEigenvalues) {
  const Body b = testing::MakeBox(ElementType::kHex20, {3, 1, 1}, {0.3, 0.06, 0.05}, kSteel);
  BoundaryConditions conditions;
  conditions.interfaces.push_back(NodeInterface("root", testing::NodesAt(b.mesh, 0, 0.0)));
  conditions.interfaces.push_back({"tip", testing::NodesAt(b.mesh, 0, 0.3), Coupling::kRigid, std::nullopt, {}});
  eigensolvers::EigenOptions eigen;
  eigen.num_modes = 6;
  const ReducedBasis cb = CraigBamptonBasis(b.model(), conditions, eigen, testing::Spectra());
  const ReducedBasis orth = OrthonormalizeBasis(b.model(), cb);
  const Eigen::Index n = cb.num_modes();
  ASSERT_EQ(orth.num_modes(), n);
  EXPECT_EQ(orth.method, "craig_bampton_orthonormalized");
  const double orthonormality = (orth.M_reduced - Eigen::MatrixXd::Identity(n, n)).cwiseAbs().maxCoeff();
  EXPECT_LE(orthonormality, kOrthonormalityBound);
  Eigen::MatrixXd off = orth.K_reduced;
  off.diagonal().setZero();
  const double diagonal = off.cwiseAbs().maxCoeff() / orth.K_reduced.diagonal().cwiseAbs().maxCoeff();
  EXPECT_LE(diagonal, kDiagonalBound);
  // The free body: six zero-frequency columns (rigid motion lies in the span of the constraint modes).
  EXPECT_EQ(orth.Counts(), (ModeCounts{6, n - 6, 0, 0}));
  const double sigma = Shift(b);
  const Eigen::VectorXd before = ReducedEigenvalues(cb, sigma);
  const Eigen::VectorXd after = ReducedEigenvalues(orth, sigma);
  double worst = 0.0;
  for (Eigen::Index j = 6; j < n; ++j) worst = std::max(worst, std::abs(after(j) / before(j) - 1.0));
  EXPECT_LE(worst, kOrthonormalizedAgreement);
  // Phi' = Phi T, with the original kinds kept.
  EXPECT_EQ(orth.original_kinds, cb.kinds);
  EXPECT_EQ(orth.original_names, cb.names);
  EXPECT_LE((cb.Phi * orth.original_transform - orth.Phi).cwiseAbs().maxCoeff() / orth.Phi.cwiseAbs().maxCoeff(),
            kTransformRoundOff);
  std::printf("[ numbers  ] orthonormalised CB (%td columns): |M_r - I| %.1e, K_r off-diagonal %.1e, eigenvalue "
              "change %.1e\n", n, orthonormality, diagonal, worst);
}

TEST(CraigBampton, WithoutNormalModesIsGuyanStaticCondensation) {
  const Body b = testing::MakeBox(ElementType::kHex8, {2, 1, 1}, {0.2, 0.1, 0.1}, kSteel);
  BoundaryConditions conditions;
  conditions.interfaces.push_back({"end", testing::NodesAt(b.mesh, 0, 0.2), Coupling::kRigid, std::nullopt, {}});
  const ReducedBasis cb = CraigBamptonBasis(b.model(), conditions, eigensolvers::EigenOptions{}, testing::Spectra());
  EXPECT_EQ(cb.Counts(), (ModeCounts{0, 0, 6, 0}));
  EXPECT_EQ(cb.names[3], "constraint_end_rx");
  EXPECT_TRUE(cb.eigensolver.empty());
  EXPECT_FALSE(cb.eigensolver_summary.has_value());
  EXPECT_TRUE(std::isnan(cb.frequency_hz(0)));
}

TEST(CraigBampton, OneFactorisationOfTheHeldBodyServesConstraintModesNormalModesAndCorrectionModes) {
  // Two rigid end interfaces of a hex20 bar; the deflated Lanczos check, since a Sturm count
  // factorises K - cut M on its own.
  const Body b = testing::MakeBox(ElementType::kHex20, {6, 1, 1}, {0.6, 0.06, 0.05}, kSteel);
  BoundaryConditions conditions;
  conditions.interfaces.push_back({"root", testing::NodesAt(b.mesh, 0, 0.0), Coupling::kRigid, std::nullopt, {}});
  conditions.interfaces.push_back({"tip", testing::NodesAt(b.mesh, 0, 0.6), Coupling::kRigid, std::nullopt, {}});
  eigensolvers::EigenOptions eigen;
  eigen.num_modes = 6;
  eigen.check_missed_modes = eigensolvers::MissedModeCheck::kDeflatedLanczos;
  ReducedBasis shared, own;
  EXPECT_EQ(testing::FactorizationsDuring([&] { shared = CraigBamptonBasis(b.model(), conditions, eigen, testing::Spectra()); }), 1);
  ASSERT_TRUE(shared.eigensolver_summary.has_value());
  EXPECT_EQ(shared.eigensolver_summary->factorizations, 1);
  testing::ExpectConsistentSummary(*shared.eigensolver_summary);
  ASSERT_NE(shared.held_factorization, nullptr);
  EXPECT_TRUE(FactorizedFor(*shared.held_factorization, conditions));

  // Without sharing: the constraint modes' factorisation and the eigensolver's own.
  EXPECT_EQ(testing::FactorizationsDuring(
                [&] { own = CraigBamptonBasis(b.model(), conditions, eigen, testing::SpectraFactorisingItself()); }),
            2);
  EXPECT_EQ(own.eigensolver_summary->factorizations, 1);  // the eigensolver's, the only one it used
  // The same factor (CHOLMOD is deterministic) and the same Lanczos runs: the same basis.
  ASSERT_EQ(shared.Phi.cols(), own.Phi.cols());
  const double difference = (shared.Phi - own.Phi).cwiseAbs().maxCoeff() / own.Phi.cwiseAbs().maxCoeff();
  EXPECT_LE(difference, kSameComputation);
  EXPECT_LE((shared.frequency_hz.tail(6) - own.frequency_hz.tail(6)).cwiseAbs().maxCoeff(),
            kSameComputation * own.frequency_hz.tail(6).maxCoeff());

  // Correction modes of the basis, and of its orthonormalised form, solve with its factor.
  const LoadSet side{"side", testing::NodesAt(b.mesh, 1, 0.0), Eigen::Vector3d::UnitY(), LoadDistribution::kResultant, {}};
  CorrectionResult with_shared, with_own;
  EXPECT_EQ(testing::FactorizationsDuring([&] { with_shared = AddStaticCorrectionModes(b.model(), shared, std::span(&side, 1)); }), 0);
  EXPECT_EQ(testing::FactorizationsDuring(
                [&] { AddStaticCorrectionModes(b.model(), OrthonormalizeBasis(b.model(), shared), std::span(&side, 1)); }),
            0);
  own.held_factorization.reset();
  EXPECT_EQ(testing::FactorizationsDuring([&] { with_own = AddStaticCorrectionModes(b.model(), own, std::span(&side, 1)); }), 1);
  ASSERT_EQ(with_shared.added, 1);
  const double correction_difference = (with_shared.basis.Phi.rightCols(1) - with_own.basis.Phi.rightCols(1))
                                           .cwiseAbs().maxCoeff() / with_own.basis.Phi.rightCols(1).cwiseAbs().maxCoeff();
  EXPECT_LE(correction_difference, kSameComputation);
  std::printf("[ numbers  ] CB with one factorisation vs two: basis %.1e, correction mode %.1e apart; eigen-solve "
              "%.3f s (factorisation %.3f s)\n", difference, correction_difference, shared.eigensolver_summary->seconds,
              shared.eigensolver_summary->factorization_seconds);
}

TEST(CraigBamptonBadInput, GivesOneLineInputErrors) {
  const Body b = testing::MakeBox(ElementType::kHex8, {2, 1, 1}, {0.2, 0.1, 0.1}, kSteel);
  const FeModel model = b.model();
  const eigensolvers::Eigensolver& solver = testing::Spectra();
  eigensolvers::EigenOptions eigen;
  eigen.num_modes = 2;
  testing::ExpectInputError([&] { CraigBamptonBasis(model, {}, eigen, solver); }, {"craig-bampton", "no interface"});
  // A node set on one line of a free body: the body can still rotate about it.
  BoundaryConditions edge;
  edge.interfaces.push_back(NodeInterface("edge", testing::NodesWhere(b.mesh, [](const Eigen::Vector3d& x) {
    return x(1) == 0.0 && x(2) == 0.0;
  })));
  testing::ExpectInputError([&] { CraigBamptonBasis(model, edge, eigen, solver); },
                            {"interface 'edge' does not hold the body", "K_ii", "3 held nodes lie on one line"});
  // Two single nodes: together on one line.
  BoundaryConditions points;
  points.interfaces.push_back(NodeInterface("a", {0}));
  points.interfaces.push_back(NodeInterface("b", {11}));
  testing::ExpectInputError([&] { CraigBamptonBasis(model, points, eigen, solver); },
                            {"interfaces 'a' and 'b' do not hold the body", "lie on one line"});
  BoundaryConditions face;
  face.interfaces.push_back(NodeInterface("root", testing::NodesAt(b.mesh, 0, 0.0)));
  eigen.num_modes = 30;  // 24 interior DOF
  testing::ExpectInputError([&] { CraigBamptonBasis(model, face, eigen, solver); },
                            {"interface 'root'", "30 fixed-interface modes", "only 24 DOF"});
  eigen.num_modes = 0;
  eigen.max_frequency_hz = 1.0;
  testing::ExpectInputError([&] { CraigBamptonBasis(model, face, eigen, solver); },
                            {"fixed-interface modes", "no mode below max_frequency_hz = 1 Hz"});
  testing::ExpectInputError([&] { OrthonormalizeBasis(model, ReducedBasis{}); }, {"orthonormalise basis"});
}

}  // namespace
}  // namespace flexmbs::reduction
