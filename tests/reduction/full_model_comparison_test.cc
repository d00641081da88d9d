// A reduced body's system modes against its full FE model (`flexmbs compare A.sid.h5
// body.yaml`): the system modes of the file's reduced matrices, the full model held as the basis
// holds them, and the comparison, on small hex8 bars against dense solves.
#include "reduction/full_model_modes.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>

#include "basis_test_support.h"
#include "core/error.h"
#include "fem/mass_properties.h"
#include "reduction/basis_comparison.h"
#include "reduction/craig_bampton.h"
#include "reduction/sid_body_builder.h"
#include "tests/support/test_problems.h"

namespace flexmbs::reduction {
namespace {

using fem::ElementType;
using testing::Body;

// Rayleigh-Ritz bound f_j(reduced) >= f_j(full), up to round-off of the dense solve of the
// small system (direct form: absolute eigenvalue error ~ eps lambda_max of the reduced system,
// lambda_max / lambda_1 <= 1e5 on these bars) and of the Lanczos pairs (residuals 1e-8 ->
// eigenvalues to ~1e-14).
constexpr double kRitzRoundOff = 1e-10;
// Two computations of the same eigenpairs (a complete basis; the full model's own modes kept):
// frequencies and MAC, measured 6.7e-14 at most (the complete Craig-Bampton bar, clamped; the
// printouts; was 1e-8).
constexpr double kSameModes = 5e-13;
// The full model's Lanczos frequencies against the dense shift-invert solve: the eigensolver's
// residual tolerance 1e-8 bounds the eigenvalue error by ~1e-16 relative (quadratic in the
// residual) plus round-off; measured 1.1e-10 at most (the free bars' rigid-mode neighbours; was
// 1e-8).
constexpr double kAgainstDense = 1e-9;
// The lowest four system modes of the Craig-Bampton bar pair with MAC near 1: with 2 normal
// modes (measured 0.99999, 0.99999, 0.980 (its frequency 9 % too high), 0.998) and, converged, with
// 12 normal modes (measured >= 0.999998).
constexpr Eigen::Index kLowModes = 4;
constexpr double kLowModeMac = 0.97;
constexpr double kConvergedMac = 0.9999;
constexpr int kConvergedNormalModes = 12;
// Frequencies this close (relative) are one repeated eigenvalue (symmetry): single-mode MAC is
// ambiguous there (any basis of the eigenspace), so only the frequencies are compared.
constexpr double kCluster = 1e-8;
// Effective modal masses summed over a complete basis: round-off of the products.
constexpr double kMassRoundOff = 1e-10;

const fem::IsotropicMaterial kSteel = testing::Steel();

InterfaceSpec NodeInterface(const std::string& name, std::vector<int> nodes) {
  return {name, std::move(nodes), Coupling::kNodes, std::nullopt, {}};
}

// The `.sid.h5` content of `basis` (no stiffening: not needed here).
sid::ReducedBody Reduced(const Body& b, const ReducedBasis& basis) {
  SidSpec sid;
  sid.geometric_stiffening = false;
  return BuildReducedBody(b.mesh, b.model(), fem::MassMatrixKind::kConsistent, sid, basis);
}

// The zero-eigenvalue threshold of `compare`: kZeroEigenvalue trace(K) / trace(M).
double ZeroEigenvalue(const Body& b) { return eigensolvers::kZeroEigenvalue * b.K.diagonal().sum() / b.M.diagonal().sum(); }

// The admissible displacements of the full model, built directly: a unit vector per DOF of the
// nodes neither clamped nor on the rigid face, and the six rigid-body motions of the face's
// nodes (zero elsewhere), if there is a rigid face.
Eigen::MatrixXd AdmissibleBasis(const Body& b, const std::vector<int>& clamped, const std::vector<int>& rigid) {
  std::vector<int> fixed = clamped;
  fixed.insert(fixed.end(), rigid.begin(), rigid.end());
  const Eigen::MatrixXd free = testing::FreeDofSelection(b.K.rows(), fixed);
  if (rigid.empty()) return free;
  const Eigen::MatrixXd R = fem::RigidBodyModes(b.mesh.nodes);
  Eigen::MatrixXd N = Eigen::MatrixXd::Zero(b.K.rows(), free.cols() + 6);
  N.leftCols(free.cols()) = free;
  for (int node : rigid) N.block(3 * node, free.cols(), 3, 6) = R.middleRows(3 * node, 3);
  return N;
}

// The full model's frequencies [Hz] by the dense shift-invert solve on the admissible space.
Eigen::VectorXd DenseFrequencies(const Body& b, const std::vector<int>& clamped, const std::vector<int>& rigid = {}) {
  const testing::DenseModes dense =
      testing::DenseModesOn(b.K, b.M, AdmissibleBasis(b, clamped, rigid), eigensolvers::FreeBodyShift(b.K, b.M));
  return eigensolvers::FrequenciesHz(dense.values);
}

// Expects the full model's modes to have the dense solve's frequencies (elastic ones relative,
// rigid ones at 0); returns the largest relative difference.
double ExpectDenseFrequencies(const ModeSet& full, const Eigen::VectorXd& dense) {
  EXPECT_LE(full.size(), dense.size());
  double worst = 0.0;
  for (Eigen::Index j = 0; j < std::min(full.size(), dense.size()); ++j) {
    if (full.frequency_hz(j) == 0.0) continue;  // exact rigid mode: checked by the caller
    EXPECT_NEAR(full.frequency_hz(j) / dense(j), 1.0, kAgainstDense) << "full-model mode " << j;
    worst = std::max(worst, std::abs(full.frequency_hz(j) / dense(j) - 1.0));
  }
  return worst;
}

// Whether full-model mode j shares its frequency with a neighbour (kCluster).
bool InCluster(const ModeSet& full, Eigen::Index j) {
  auto same = [&](Eigen::Index i) {
    return i >= 0 && i < full.size() && std::abs(full.frequency_hz(i) / full.frequency_hz(j) - 1.0) <= kCluster;
  };
  return same(j - 1) || same(j + 1);
}

// A's system modes and the full model's, compared with B the reference.
struct SystemComparison {
  ModeSet system;
  ModeSet full;
  ReducedBasis full_basis;
  BasisComparison c;
};
SystemComparison CompareWithFullModel(const Body& b, ReductionMethod method, const BoundaryConditions& conditions,
                                      const ReducedBasis& basis, Eigen::Index extra_modes) {
  SystemComparison out;
  out.system = SystemModes(Reduced(b, basis), ZeroEigenvalue(b));
  out.full_basis = FullModelModes(b.model(), SystemModeConditions(method, conditions),
                                  out.system.size() + extra_modes, testing::Spectra());
  out.full = BasisModes(out.full_basis, b.model());
  out.c = CompareModes(out.system, out.full, ErrorReference::kB);
  return out;
}

TEST(BasisReductionMethod, ReadsEveryBasisNameFlexmbsWrites) {
  EXPECT_EQ(BasisReductionMethod("free_free_modal"), ReductionMethod::kFreeFree);
  EXPECT_EQ(BasisReductionMethod("free_free_modal+static_correction"), ReductionMethod::kFreeFree);
  EXPECT_EQ(BasisReductionMethod("fixed_interface_modal+orthonormalized"), ReductionMethod::kFixedInterface);
  EXPECT_EQ(BasisReductionMethod("craig_bampton"), ReductionMethod::kCraigBampton);
  EXPECT_EQ(BasisReductionMethod("craig_bampton_orthonormalized+static_correction"), ReductionMethod::kCraigBampton);
  EXPECT_EQ(BasisReductionMethod("guyan"), std::nullopt);
}

TEST(SystemModeConditions, CraigBamptonFreesTheInterfacesKeepingRigidOnesRigidAndFixedInterfaceHoldsThem) {
  BoundaryConditions conditions;
  conditions.supports.push_back({"root", {0, 1}});
  conditions.interfaces.push_back(NodeInterface("tip", {2, 3}));
  conditions.interfaces.push_back({"hub", {4, 5, 6}, Coupling::kRigid, std::nullopt, {}});
  const FullModelConditions free = SystemModeConditions(ReductionMethod::kFreeFree, conditions);
  EXPECT_TRUE(free.held.empty());
  EXPECT_TRUE(free.rigid.empty());
  EXPECT_EQ(free.Describe(), "free (no supports)");
  const FullModelConditions cb = SystemModeConditions(ReductionMethod::kCraigBampton, conditions);
  ASSERT_EQ(cb.held.supports.size(), 1u);
  EXPECT_EQ(cb.held.supports[0].name, "root");
  EXPECT_TRUE(cb.held.interfaces.empty());
  ASSERT_EQ(cb.rigid.size(), 1u);
  EXPECT_EQ(cb.rigid[0].name, "hub");
  EXPECT_EQ(cb.Describe(), "support 'root', interface 'hub' rigid (marker free)");
  const FullModelConditions fixed = SystemModeConditions(ReductionMethod::kFixedInterface, conditions);
  EXPECT_EQ(fixed.held.supports.size(), 1u);
  EXPECT_EQ(fixed.held.interfaces.size(), 2u);
  EXPECT_TRUE(fixed.rigid.empty());
}

TEST(CompareModes, MeasuresTheErrorAgainstTheReferenceSide) {
  // Two identical shapes, frequencies 10 Hz (A) and 8 Hz (B), and a rigid pair at 0 Hz.
  ModeSet a{{"a0", "a1"}, Eigen::MatrixXd::Identity(2, 2), Eigen::Vector2d(0.0, 10.0),
            Eigen::MatrixXd::Ones(2, 3), Eigen::VectorXd::Ones(2)};
  ModeSet b = a;
  b.frequency_hz(1) = 8.0;
  const BasisComparison against_b = CompareModes(a, b, ErrorReference::kB);
  ASSERT_EQ(against_b.pairs.size(), 2u);
  EXPECT_EQ(against_b.pairs[0].relative_error, 0.0);
  EXPECT_DOUBLE_EQ(against_b.pairs[1].relative_error, 10.0 / 8.0 - 1.0);
  EXPECT_DOUBLE_EQ(CompareModes(a, b, ErrorReference::kA).pairs[1].relative_error, 8.0 / 10.0 - 1.0);
}

TEST(FullModelModes, AFreeBodyNeedsAnElasticMode) {
  const Body b = testing::MakeBox(ElementType::kHex8, {2, 1, 1}, {0.2, 0.1, 0.07}, kSteel);
  EXPECT_THROW(FullModelModes(b.model(), FullModelConditions{}, 6, testing::Spectra()), InputError);
}

// (1) Craig-Bampton bar (clamped root support, node-set tip interface): every system frequency
// lies at or above the full model's of the same rank (Rayleigh-Ritz), the low modes pair with
// MAC near 1, and the frequencies fall as normal modes are added (nested bases).
TEST(FullModelComparison, CraigBamptonSystemModesBoundTheFullModelFromAboveAndConverge) {
  const Body b = testing::MakeBox(ElementType::kHex8, {4, 2, 2}, {0.4, 0.1, 0.07}, kSteel);
  const std::vector<int> root = testing::NodesAt(b.mesh, 0, 0.0);
  BoundaryConditions conditions;
  conditions.supports.push_back({"root", root});
  conditions.interfaces.push_back(NodeInterface("tip", testing::NodesAt(b.mesh, 0, 0.4)));
  const Eigen::VectorXd dense = DenseFrequencies(b, root);

  Eigen::VectorXd previous;
  std::printf("[ numbers  ] CB bar against its full model, f_A / f_B - 1 of modes 1 and %td:", kLowModes);
  for (const int k : {2, 6, 12}) {
    eigensolvers::EigenOptions eigen;
    eigen.num_modes = k;
    const ReducedBasis cb = CraigBamptonBasis(b.model(), conditions, eigen, testing::Spectra());
    const SystemComparison s = CompareWithFullModel(b, ReductionMethod::kCraigBampton, conditions, cb, 10);
    const Eigen::Index n = s.system.size();
    ASSERT_EQ(n, 27 + k);
    ASSERT_EQ(s.full.size(), n + 10);
    EXPECT_TRUE(s.full_basis.held_by.interfaces.empty());  // the node-set interface free, the support held
    ExpectDenseFrequencies(s.full, dense);
    for (Eigen::Index j = 0; j < n; ++j) {
      EXPECT_GE(s.system.frequency_hz(j), s.full.frequency_hz(j) * (1.0 - kRitzRoundOff)) << "k = " << k << ", " << j;
      if (previous.size() > j) {
        EXPECT_LE(s.system.frequency_hz(j), previous(j) * (1.0 + kRitzRoundOff)) << "k = " << k << ", " << j;
      }
    }
    ASSERT_EQ(s.c.pairs.size(), static_cast<std::size_t>(n));
    for (Eigen::Index j = 0; j < kLowModes; ++j) {
      const ModePair& p = s.c.pairs[static_cast<std::size_t>(j)];
      EXPECT_EQ(p.b, j) << "k = " << k;
      EXPECT_GE(p.mac, k >= kConvergedNormalModes ? kConvergedMac : kLowModeMac) << "k = " << k << ", mode " << j;
      EXPECT_GE(p.relative_error, -kRitzRoundOff) << "k = " << k << ", mode " << j;
      EXPECT_NEAR(p.relative_error, s.system.frequency_hz(j) / s.full.frequency_hz(j) - 1.0, 1e-15);
    }
    std::printf(" k=%d: %.2e/%.2e (MAC %.6f)", k, s.c.pairs[0].relative_error,
                s.c.pairs[kLowModes - 1].relative_error, s.c.pairs[kLowModes - 1].mac);
    previous = s.system.frequency_hz;
  }
  std::printf("\n");
}

// (2) A tiny bar with ALL interior modes kept: the Craig-Bampton space is the whole admissible
// space, so the system modes are the full model's modes; with a rigid (RBE2) tip interface the
// full model keeps the tip's nodes on a rigid motion of the free marker.
struct CompleteCase {
  const char* name;
  bool supported;
  Coupling tip;  ///< the tip interface's coupling
};
class CompleteCraigBampton : public ::testing::TestWithParam<CompleteCase> {};

TEST_P(CompleteCraigBampton, SystemModesEqualTheFullModel) {
  const Body b = testing::MakeBox(ElementType::kHex8, {2, 1, 1}, {0.2, 0.1, 0.07}, kSteel);
  BoundaryConditions conditions;
  std::vector<int> clamped;
  if (GetParam().supported) {
    clamped = testing::NodesAt(b.mesh, 0, 0.0);
    conditions.supports.push_back({"root", clamped});
  }
  const std::vector<int> tip = testing::NodesAt(b.mesh, 0, 0.2);
  const bool rigid_tip = GetParam().tip == Coupling::kRigid;
  conditions.interfaces.push_back({"tip", tip, GetParam().tip, std::nullopt, {}});
  // A rigid tip's 4 nodes (12 DOF) move with its marker's 6 DOF.
  const Eigen::Index boundary = rigid_tip ? 6 : 12;
  const Eigen::Index admissible = b.K.rows() - 3 * static_cast<Eigen::Index>(clamped.size()) - 12 + boundary;
  eigensolvers::EigenOptions eigen;
  eigen.num_modes = static_cast<int>(admissible - boundary);  // every interior mode
  const ReducedBasis cb = CraigBamptonBasis(b.model(), conditions, eigen, testing::Spectra());
  const SystemComparison s = CompareWithFullModel(b, ReductionMethod::kCraigBampton, conditions, cb, 6);
  ASSERT_EQ(s.system.size(), admissible);
  ASSERT_EQ(s.full.size(), admissible);  // the margin capped at what the model has
  const double against_dense =
      ExpectDenseFrequencies(s.full, DenseFrequencies(b, clamped, rigid_tip ? tip : std::vector<int>{}));

  const Eigen::Index rigid = GetParam().supported ? 0 : 6;
  double worst_frequency = 0.0, worst_mac = 0.0;
  int clustered = 0;  // modes of repeated frequencies: frequency only
  for (Eigen::Index j = 0; j < admissible; ++j) {
    const ModePair& p = s.c.pairs[static_cast<std::size_t>(j)];
    if (j < rigid) {  // round-off eigenvalues of the reduced system: 0 Hz, as the exact rigid modes
      EXPECT_EQ(s.system.frequency_hz(j), 0.0);
      EXPECT_EQ(s.full.frequency_hz(j), 0.0);
      EXPECT_EQ(p.relative_error, 0.0);
      continue;
    }
    worst_frequency = std::max(worst_frequency, std::abs(p.frequency_a_hz / s.full.frequency_hz(j) - 1.0));
    if (InCluster(s.full, j)) {
      ++clustered;
      continue;
    }
    EXPECT_EQ(p.b, j);
    worst_frequency = std::max(worst_frequency, std::abs(p.relative_error));
    worst_mac = std::max(worst_mac, 1.0 - p.mac);
  }
  EXPECT_LE(worst_frequency, kSameModes);
  EXPECT_LE(worst_mac, kSameModes);
  // Two complete bases of the same space carry the same effective mass along each axis.
  const Eigen::Vector3d sum_a = s.c.effective_mass_a.colwise().sum();
  const Eigen::Vector3d sum_b = s.c.effective_mass_b.colwise().sum();
  for (int d = 0; d < 3; ++d) EXPECT_NEAR(sum_a(d) / sum_b(d), 1.0, kMassRoundOff) << "axis " << d;
  std::printf("[ numbers  ] complete CB (%s, %td DOF): |f_A / f_B - 1| <= %.1e, 1 - MAC <= %.1e (%d modes of "
              "repeated frequencies: frequency only); full model against dense %.1e\n", GetParam().name, admissible,
              worst_frequency, worst_mac, clustered, against_dense);
}

INSTANTIATE_TEST_SUITE_P(Bars, CompleteCraigBampton,
                         ::testing::Values(CompleteCase{"Clamped", true, Coupling::kNodes},
                                           CompleteCase{"Free", false, Coupling::kNodes},
                                           CompleteCase{"ClampedRigidTip", true, Coupling::kRigid},
                                           CompleteCase{"FreeRigidTip", false, Coupling::kRigid}),
                         [](const ::testing::TestParamInfo<CompleteCase>& param) { return param.param.name; });

// (3) A free-free modal body: its system modes are its own modes, the full model's lowest.
TEST(FullModelComparison, FreeFreeModalSystemModesAreTheFullModelsModes) {
  const Body b = testing::MakeBox(ElementType::kHex8, {4, 2, 2}, {0.4, 0.1, 0.07}, kSteel);
  FreeFreeOptions options;
  options.eigen.num_modes = 8;
  const ReducedBasis modal = FreeFreeModalBasis(b.model(), options, testing::Spectra());
  const SystemComparison s = CompareWithFullModel(b, ReductionMethod::kFreeFree, {}, modal, 6);
  ASSERT_EQ(s.system.size(), 14);
  ASSERT_EQ(s.full.size(), 20);
  ExpectDenseFrequencies(s.full, DenseFrequencies(b, {}));
  double worst_frequency = 0.0, worst_mac = 0.0;
  for (Eigen::Index j = 0; j < 14; ++j) {
    const ModePair& p = s.c.pairs[static_cast<std::size_t>(j)];
    if (j < 6) {
      EXPECT_EQ(p.frequency_a_hz, 0.0);
      EXPECT_EQ(p.relative_error, 0.0);
      continue;
    }
    EXPECT_EQ(p.b, j);
    worst_frequency = std::max(worst_frequency, std::abs(p.relative_error));
    worst_mac = std::max(worst_mac, 1.0 - p.mac);
  }
  EXPECT_LE(worst_frequency, kSameModes);
  EXPECT_LE(worst_mac, kSameModes);
  // The rigid translations carry the whole mass on both sides.
  const double mass = fem::MassPropertiesFromMassMatrix(b.M, b.mesh.nodes).mass_kg;
  for (int d = 0; d < 3; ++d) {
    EXPECT_NEAR(s.c.effective_mass_a.col(d).sum() / mass, 1.0, kMassRoundOff) << "axis " << d;
    EXPECT_NEAR(s.c.effective_mass_b.col(d).sum() / mass, 1.0, kMassRoundOff) << "axis " << d;
  }
  std::printf("[ numbers  ] free-free modal: |f_A / f_B - 1| <= %.1e, 1 - MAC <= %.1e\n", worst_frequency, worst_mac);
}

// A fixed-interface modal body: the full model held by its support and its rigid interface,
// whose marker the basis holds fixed, so that the interface's nodes stay put. Independent
// reference: the dense solve with the root's and the tip's nodes clamped (the full model of
// `compare` runs the reduction's own constraint code; the dense solve does not).
TEST(FullModelComparison, FixedInterfaceSystemModesAreTheDenseModesOfTheBarClampedAtBothEnds) {
  const Body b = testing::MakeBox(ElementType::kHex8, {4, 2, 2}, {0.4, 0.1, 0.07}, kSteel);
  const std::vector<int> root = testing::NodesAt(b.mesh, 0, 0.0), tip = testing::NodesAt(b.mesh, 0, 0.4);
  BoundaryConditions conditions;
  conditions.supports.push_back({"root", root});
  conditions.interfaces.push_back({"tip", tip, Coupling::kRigid, std::nullopt, {}});
  eigensolvers::EigenOptions eigen;
  eigen.num_modes = 6;
  const ReducedBasis modal = FixedInterfaceModalBasis(b.model(), conditions, eigen, testing::Spectra());
  const SystemComparison s = CompareWithFullModel(b, ReductionMethod::kFixedInterface, conditions, modal, 6);
  EXPECT_EQ(s.full_basis.held_by.interfaces.size(), 1u);
  std::vector<int> both_ends = root;
  both_ends.insert(both_ends.end(), tip.begin(), tip.end());
  const Eigen::VectorXd dense = DenseFrequencies(b, both_ends);
  ASSERT_EQ(s.system.size(), 6);
  const double full_worst = ExpectDenseFrequencies(s.full, dense);
  const double system_worst = ExpectDenseFrequencies(s.system, dense);
  std::printf("[ numbers  ] fixed-interface modal against the dense bar clamped at both ends: full model %.1e, "
              "system modes %.1e\n", full_worst, system_worst);
  // And the comparison pairs each system mode with the full model's mode of its index.
  double worst = 0.0;
  for (const ModePair& p : s.c.pairs) {
    EXPECT_EQ(p.b, p.a);
    worst = std::max({worst, std::abs(p.relative_error), 1.0 - p.mac});
  }
  EXPECT_LE(worst, kSameModes);
}

}  // namespace
}  // namespace flexmbs::reduction
