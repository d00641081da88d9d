#include "reduction/correction_modes.h"

#include <gtest/gtest.h>

#include <Eigen/Cholesky>
#include <Eigen/SparseCholesky>
#include <algorithm>
#include <cmath>
#include <cstdio>

#include "basis_test_support.h"
#include "core/error.h"
#include "reduction/craig_bampton.h"
#include "reduction/dof_constraints.h"
#include "reduction/modal_basis.h"

namespace flexmbs::reduction {
namespace {

using fem::ElementType;
using testing::Body;

// A static deflection the basis spans is reproduced to round-off amplified by the condition of
// K (~1e8 for these beams): measured 6.5e-12 at most (was 1e-9).
constexpr double kStaticAgreement = 5e-11;
// Without correction modes the truncated modal basis misses the local deflection by far more.
constexpr double kTruncationError = 1e-4;
// max |Phi^T M Phi - I|: measured 1.6e-15 (was 1e-10).
constexpr double kOrthonormalityBound = 2e-14;
// The static solve's residual |K u - f| / |f| (measured 9.6e-13; was 1e-9) and its rigid part
// |R R^T M u| / |u| (measured 1.5e-16; was 1e-9).
constexpr double kStaticResidual = 1e-11;
constexpr double kRigidPart = 1e-15;

const fem::IsotropicMaterial kSteel = testing::Steel();

// The hex20 cantilever of the correction tests: 0.4 x 0.05 x 0.04 m.
const Body& TheBeam() {
  static const Body body = testing::MakeBox(ElementType::kHex20, {4, 1, 1}, {0.4, 0.05, 0.04}, kSteel);
  return body;
}

// The static deflection of the body clamped at `clamped` nodes under f (Eigen's sparse LDL^T,
// independent of CHOLMOD).
Eigen::MatrixXd ClampedStatic(const Body& b, const std::vector<int>& clamped, const Eigen::MatrixXd& f) {
  const FreeDofMap map = FreeDofMap::ClampNodes(b.mesh.num_nodes(), clamped);
  const Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> ldlt(map.Restrict(b.K));
  return map.Expand(ldlt.solve(map.RestrictVectors(f)));
}

// The static deflection in the reduced model: u = Phi K_r^-1 Phi^T f.
Eigen::MatrixXd ReducedStatic(const ReducedBasis& basis, const Eigen::MatrixXd& f) {
  return basis.Phi * basis.K_reduced.ldlt().solve(basis.Phi.transpose() * f);
}

double RelativeError(const Eigen::MatrixXd& approx, const Eigen::MatrixXd& exact) {
  return (approx - exact).norm() / exact.norm();
}

TEST(StaticCorrectionModes, HeldAtTheInterfaceTheBasisReproducesTheStaticDeflectionExactly) {
  const Body& b = TheBeam();
  const std::vector<int> root = testing::NodesAt(b.mesh, 0, 0.0);
  BoundaryConditions conditions;
  conditions.interfaces.push_back({"root", root, Coupling::kNodes, std::nullopt, {}});
  eigensolvers::EigenOptions eigen;
  eigen.num_modes = 4;
  const ReducedBasis modal = FixedInterfaceModalBasis(b.model(), conditions, eigen, testing::Spectra());
  const LoadSet tip{"tip", testing::NodesAt(b.mesh, 0, 0.4), Eigen::Vector3d(0.0, 0.3, 1.0),
                    LoadDistribution::kResultant, {}};
  const CorrectionResult corrected = AddStaticCorrectionModes(b.model(), modal, std::span(&tip, 1));
  EXPECT_EQ(corrected.added, 1);
  EXPECT_TRUE(corrected.dropped.empty());
  EXPECT_EQ(corrected.basis.Counts(), (ModeCounts{0, 4, 0, 1}));
  EXPECT_EQ(corrected.basis.names.back(), "static_correction_tip");
  EXPECT_EQ(corrected.basis.method, "fixed_interface_modal+static_correction");
  EXPECT_TRUE(std::isnan(corrected.basis.frequency_hz(4)));

  const Eigen::MatrixXd f = BuildLoadCases(b.mesh.num_nodes(), tip).F;
  EXPECT_NEAR(f.sum(), 1.3 / std::sqrt(1.09), 2e-15);  // unit resultant along the direction (measured 2.2e-16; was 1e-14)
  const Eigen::MatrixXd exact = ClampedStatic(b, root, f);
  const double with = RelativeError(ReducedStatic(corrected.basis, f), exact);
  const double without = RelativeError(ReducedStatic(modal, f), exact);
  EXPECT_LE(with, kStaticAgreement);
  EXPECT_GE(without, kTruncationError);
  EXPECT_LE((corrected.basis.M_reduced - Eigen::MatrixXd::Identity(5, 5)).cwiseAbs().maxCoeff(), kOrthonormalityBound);
  std::printf("[ numbers  ] held beam, tip load: static error %.1e with the correction mode, %.1e with 4 normal modes "
              "only\n", with, without);
}

TEST(StaticCorrectionModes, CraigBamptonWithCorrectionReproducesTheStaticDeflectionOfTheSupportedBody) {
  const Body& b = TheBeam();
  const std::vector<int> root = testing::NodesAt(b.mesh, 0, 0.0);
  BoundaryConditions conditions;
  conditions.supports.push_back({"root", root});
  conditions.interfaces.push_back({"tip", testing::NodesAt(b.mesh, 0, 0.4), Coupling::kNodes, std::nullopt, {}});
  eigensolvers::EigenOptions eigen;
  eigen.num_modes = 3;
  const ReducedBasis cb = CraigBamptonBasis(b.model(), conditions, eigen, testing::Spectra());
  // A pad on the top face at mid-span, loaded in x, y and z; and the interface face itself.
  const LoadSet loads[] = {
      {"pad", testing::NodesWhere(b.mesh, [](const Eigen::Vector3d& x) {
         return std::abs(x(2) - 0.04) < 1e-12 && x(0) > 0.15 && x(0) < 0.25;
       }), std::nullopt, LoadDistribution::kResultant, {}},
      {"tip", testing::NodesAt(b.mesh, 0, 0.4), Eigen::Vector3d::UnitZ(), LoadDistribution::kResultant, {}}};
  const CorrectionResult corrected = AddStaticCorrectionModes(b.model(), cb, loads);
  EXPECT_EQ(corrected.added, 3);
  ASSERT_EQ(corrected.dropped.size(), 1u);  // the tip load acts on interface DOF only
  EXPECT_NE(corrected.dropped[0].find("static_correction_tip: the load acts on support or interface DOF only"),
            std::string::npos) << corrected.dropped[0];
  const Eigen::Index n_b = cb.Counts().constraint;
  EXPECT_EQ(corrected.basis.Counts(), (ModeCounts{0, 3, n_b, 3}));
  // Correction modes stay interface-held, so the constraint modes keep their meaning.
  for (const int n : loads[1].nodes) {
    EXPECT_EQ(corrected.basis.Phi.block(3 * n, n_b + 3, 3, 3).cwiseAbs().maxCoeff(), 0.0);
  }
  Eigen::MatrixXd f(b.K.rows(), 4);
  f << BuildLoadCases(b.mesh.num_nodes(), loads[0]).F, BuildLoadCases(b.mesh.num_nodes(), loads[1]).F;
  const Eigen::MatrixXd exact = ClampedStatic(b, root, f);
  const double with = RelativeError(ReducedStatic(corrected.basis, f), exact);
  const double without = RelativeError(ReducedStatic(cb, f.leftCols(3)), exact.leftCols(3));
  EXPECT_LE(with, kStaticAgreement);
  EXPECT_GE(without, kTruncationError);
  std::printf("[ numbers  ] Craig-Bampton beam, pad load x/y/z + tip load: static error %.1e with corrections, "
              "%.1e without\n", with, without);
}

TEST(StaticCorrectionModes, FreeBodyInertiaReliefDeflectionLiesInTheCorrectedBasis) {
  const Body& b = TheBeam();
  FreeFreeOptions options;
  options.eigen.num_modes = 6;
  const ReducedBasis modal = FreeFreeModalBasis(b.model(), options, testing::Spectra());
  const LoadSet tip{"tip", testing::NodesAt(b.mesh, 0, 0.4), std::nullopt, LoadDistribution::kResultant, {}};
  const CorrectionResult corrected = AddStaticCorrectionModes(b.model(), modal, std::span(&tip, 1));
  EXPECT_EQ(corrected.basis.Counts(), (ModeCounts{6, 6, 0, 3}));
  const ReducedBasis& basis = corrected.basis;
  EXPECT_LE((basis.M_reduced - Eigen::MatrixXd::Identity(15, 15)).cwiseAbs().maxCoeff(), kOrthonormalityBound);

  // Independent inertia-relief solution: (K + c M R R^T M) u = f_e = f - M R R^T f with R the
  // M-orthonormal rigid modes and c = trace(K)/trace(M) (so the rigid directions are as stiff
  // as the mesh, not near-singular): R^T of it gives c R^T M u = 0, so K u = f_e with u
  // M-orthogonal to R. Dense Cholesky.
  const Eigen::MatrixXd f = BuildLoadCases(b.mesh.num_nodes(), tip).F;
  const Eigen::MatrixXd R = MOrthonormalRigidModes(b.model());
  const Eigen::MatrixXd MR = b.M * R;
  const double c = b.K.diagonal().sum() / b.M.diagonal().sum();
  const Eigen::MatrixXd A = Eigen::MatrixXd(b.K) + c * MR * MR.transpose();
  const Eigen::MatrixXd f_e = f - MR * (R.transpose() * f);
  const Eigen::MatrixXd u = A.llt().solve(f_e);
  EXPECT_LE((b.K * u - f_e).norm() / f.norm(), kStaticResidual);
  EXPECT_LE((R * (R.transpose() * (b.M * u))).norm(), kRigidPart * u.norm());
  // The M-orthogonal projection onto the basis reproduces u.
  const auto project = [&](const ReducedBasis& on) {
    return Eigen::MatrixXd(on.Phi * on.M_reduced.ldlt().solve(on.Phi.transpose() * (b.M * u)));
  };
  const double with = RelativeError(project(basis), u);
  const double without = RelativeError(project(modal), u);
  EXPECT_LE(with, kStaticAgreement);
  EXPECT_GE(without, kTruncationError);
  // And the reduced elastic problem gives it: K_e q = Phi_e^T f (the elastic block; the rigid
  // coordinates carry the inertia relief).
  const Eigen::MatrixXd Phi_e = basis.Phi.rightCols(9);
  const Eigen::MatrixXd reduced = Phi_e * basis.K_reduced.bottomRightCorner(9, 9).ldlt().solve(Phi_e.transpose() * f);
  const double solved = RelativeError(reduced, u);
  EXPECT_LE(solved, kStaticAgreement);
  std::printf("[ numbers  ] free beam, inertia relief under tip loads: projection error %.1e with corrections, %.1e "
              "without; reduced solve %.1e\n", with, without, solved);
}

TEST(StaticCorrectionModes, DependentModesAreDroppedAndCounted) {
  const Body& b = TheBeam();
  FreeFreeOptions options;
  options.eigen.num_modes = 4;
  const ReducedBasis modal = FreeFreeModalBasis(b.model(), options, testing::Spectra());
  const std::vector<int> tip = testing::NodesAt(b.mesh, 0, 0.4);
  const LoadSet loads[] = {{"a", tip, Eigen::Vector3d::UnitZ(), LoadDistribution::kResultant, {}},
                           {"b", tip, Eigen::Vector3d(0.0, 0.0, -2.0), LoadDistribution::kResultant, {}},
                           {"c", {tip[0], tip[1]}, std::nullopt, LoadDistribution::kPerNode, {}}};
  const CorrectionResult corrected = AddStaticCorrectionModes(b.model(), modal, loads);
  EXPECT_EQ(corrected.added, 7);  // a, then c: 2 nodes x 3 directions
  ASSERT_EQ(corrected.dropped.size(), 1u);
  EXPECT_NE(corrected.dropped[0].find("static_correction_b: linearly dependent on the basis"), std::string::npos)
      << corrected.dropped[0];
  EXPECT_EQ(corrected.basis.names[11], "static_correction_c_n" + std::to_string(tip[0]) + "_x");
  EXPECT_EQ(corrected.basis.Counts(), (ModeCounts{6, 4, 0, 7}));
  std::printf("[ numbers  ] dropped: %s\n", corrected.dropped[0].c_str());
}

TEST(StaticCorrectionModesBadInput, GivesOneLineInputErrors) {
  const Body b = testing::MakeBox(ElementType::kHex8, {2, 1, 1}, {0.2, 0.1, 0.1}, kSteel);
  FreeFreeOptions options;
  options.eigen.num_modes = 2;
  const ReducedBasis modal = FreeFreeModalBasis(b.model(), options, testing::Spectra());
  const auto add = [&](LoadSet load) {
    return [&b, &modal, load] { AddStaticCorrectionModes(b.model(), modal, std::span(&load, 1)); };
  };
  testing::ExpectInputError([&] { AddStaticCorrectionModes(b.model(), modal, {}); }, {"no load sets"});
  testing::ExpectInputError(add({"pad", {}, std::nullopt, LoadDistribution::kResultant, {}}),
                            {"load set 'pad': no nodes (empty load set)"});
  testing::ExpectInputError(add({"pad", {1, 99}, std::nullopt, LoadDistribution::kResultant, {}}),
                            {"load set 'pad': node 99 is outside"});
  testing::ExpectInputError(add({"pad", {1}, Eigen::Vector3d::Zero(), LoadDistribution::kResultant, {}}),
                            {"load set 'pad': direction (0, 0, 0) must be finite and non-zero"});
  testing::ExpectInputError(add({"pad", {1, 2}, std::nullopt, LoadDistribution::kPerNode, {1.0, 2.0}}),
                            {"load set 'pad': weights are for a resultant load only"});
  testing::ExpectInputError(add({"", {1}, std::nullopt, LoadDistribution::kResultant, {}}), {"empty name"});
  ReducedBasis wrong = modal;
  wrong.Phi.resize(5, 1);
  const LoadSet ok{"pad", {1}, std::nullopt, LoadDistribution::kResultant, {}};
  testing::ExpectInputError([&] { AddStaticCorrectionModes(b.model(), wrong, std::span(&ok, 1)); },
                            {"the basis has 5 rows, the model 36 DOF"});
  const LoadSet twice[] = {ok, ok};
  testing::ExpectInputError([&] { AddStaticCorrectionModes(b.model(), modal, twice); },
                            {"load set 'pad': mode name 'static_correction_pad_x' is already in the basis or made twice"});
}

}  // namespace
}  // namespace flexmbs::reduction
