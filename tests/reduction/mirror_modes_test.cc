// Equal-frequency mode pairs of a square beam centred on z = 0, split by its mirror plane
// (reduction/mirror_modes.h, issue 16).

#include "reduction/mirror_modes.h"

#include <gtest/gtest.h>

#include <cstdio>
#include <memory>
#include <numbers>
#include <string>
#include <vector>

#include "basis_test_support.h"
#include "mbs/flexible_body.h"
#include "mbs/multibody_system.h"
#include "mbs/planar.h"
#include "reduction/craig_bampton.h"
#include "reduction/sid_body_builder.h"
#include "tests/input_error.h"
#include "tests/support/test_problems.h"

namespace flexmbs::reduction {
namespace {

using fem::ElementType;
using testing::Body;
using Index = Eigen::Index;

// A mode's departure from its reflection or its negative after the split, of its norm:
// measured 2.8e-13 (free-free), 6.6e-13 (clamped, Craig-Bampton).
constexpr double kSplitBound = 7e-12;
// The raw solver's pairs are mixed (departures 0.28 .. 1.1 below); a mode counts as mixed above this.
constexpr double kMixed = 1e-2;
// Frequencies of the split modes (their Ritz values) against the solver's, relative: measured
// 3.5e-13 (free-free), 1.3e-11 (clamped): the solver's own accuracy, its eigenvalues off the raw
// modes' Rayleigh quotients by as much (2.1e-11 below).
constexpr double kFrequencyBound = 1.3e-10;
// |M_reduced - I|: measured 1.3e-15, 2.7e-15 (the raw bases' 1.3e-15).
constexpr double kOrthonormalityBound = 3e-14;
// K_reduced's largest off-diagonal entry of its largest diagonal one: measured 6e-15,
// 5.4e-14 (the raw bases' 4.2e-15, 4.8e-14).
constexpr double kDiagonalBound = 5e-13;
// |K_reduced(j, j) - (2 pi f_j)^2| / K_reduced(j, j): measured 1.5e-13, 4.5e-12 (the raw
// bases' 1.2e-13, 2.1e-11: their frequencies are the solver's eigenvalues, the split ones Ritz values).
constexpr double kRayleighBound = 5e-11;

// A hex20 beam 0.4 m long of square section 0.04 m, 8 x 2 x 2 cells, its cross-section centred
// on y = z = 0 (centred) or in [0, 0.04]^2 (as the box is built): same K and M.
Body SquareBeam(bool centred) {
  Body body = testing::MakeBox(ElementType::kHex20, {8, 2, 2}, {0.4, 0.04, 0.04}, testing::Steel());
  if (centred) body.mesh.nodes.bottomRows(2).array() -= 0.02;
  return body;
}

// P Phi, P the reflection z -> -z (the mirror node's u_x, u_y, -u_z) with the mirror nodes found
// by brute force (1e-12 m), independent of the library's pairing.
Eigen::MatrixXd Reflected(const Eigen::Matrix3Xd& nodes, const Eigen::MatrixXd& Phi) {
  Eigen::MatrixXd reflected(Phi.rows(), Phi.cols());
  for (Index n = 0; n < nodes.cols(); ++n) {
    const Eigen::Vector3d image(nodes(0, n), nodes(1, n), -nodes(2, n));
    Index m = 0;
    while (m + 1 < nodes.cols() && (nodes.col(m) - image).norm() > 1e-12) ++m;
    EXPECT_LE((nodes.col(m) - image).norm(), 1e-12) << "node " << n << " has no mirror image";
    reflected.row(3 * n) = Phi.row(3 * m);
    reflected.row(3 * n + 1) = Phi.row(3 * m + 1);
    reflected.row(3 * n + 2) = -Phi.row(3 * m + 2);
  }
  return reflected;
}

// Per column: the least of |P phi - phi| and |P phi + phi|, of |phi|.
Eigen::VectorXd MirrorDepartures(const Eigen::Matrix3Xd& nodes, const Eigen::MatrixXd& Phi) {
  const Eigen::MatrixXd reflected = Reflected(nodes, Phi);
  Eigen::VectorXd departure(Phi.cols());
  for (Index j = 0; j < Phi.cols(); ++j) {
    departure(j) = std::min((reflected.col(j) - Phi.col(j)).norm(), (reflected.col(j) + Phi.col(j)).norm()) /
                   Phi.col(j).norm();
  }
  return departure;
}

// The largest |M_r - I| and K_r's largest off-diagonal entry of its largest diagonal one, over
// the columns from `first` on, and the largest |K_r(j, j) - (2 pi f_j)^2| / K_r(j, j).
struct ReducedMatrixErrors {
  double orthonormality = 0.0, off_diagonal = 0.0, frequency = 0.0;
};
ReducedMatrixErrors ReducedErrors(const ReducedBasis& basis, Index first) {
  const Index n = basis.num_modes() - first;
  const Eigen::MatrixXd K = basis.K_reduced.bottomRightCorner(n, n), M = basis.M_reduced.bottomRightCorner(n, n);
  ReducedMatrixErrors e;
  e.orthonormality = (M - Eigen::MatrixXd::Identity(n, n)).cwiseAbs().maxCoeff();
  e.off_diagonal = (K - Eigen::MatrixXd(K.diagonal().asDiagonal())).cwiseAbs().maxCoeff() / K.diagonal().maxCoeff();
  for (Index j = 0; j < n; ++j) {
    e.frequency = std::max(e.frequency, std::abs(K(j, j) - std::pow(2.0 * std::numbers::pi * basis.frequency_hz(first + j), 2)) / K(j, j));
  }
  return e;
}

// Checks the split basis against the raw one (same K and M, no symmetry to split by): the normal
// columns [first, end) even or odd where the raw ones of each pair were mixed, frequencies
// unchanged, single modes bit for bit, the reduced matrices orthonormal and diagonal. Returns
// the number of pairs.
int ExpectSplit(const Eigen::Matrix3Xd& nodes, const ReducedBasis& split, const ReducedBasis& raw, Index first, Index end) {
  const Eigen::VectorXd after = MirrorDepartures(nodes, split.Phi).segment(first, end - first);
  const Eigen::VectorXd before = MirrorDepartures(nodes, raw.Phi).segment(first, end - first);
  std::printf("[ numbers  ] departure from the reflection or its negative after the split: max %.2g (before %.2g)\n",
              after.maxCoeff(), before.maxCoeff());
  EXPECT_LE(after.maxCoeff(), kSplitBound);
  int pairs = 0;
  double frequency_change = 0.0;
  const auto equal = [&](Index i, Index j) {
    return i >= first && j < raw.num_modes() && std::abs(raw.frequency_hz(i) - raw.frequency_hz(j)) <= 1e-9 * raw.frequency_hz(j);
  };
  for (Index j = first; j < split.num_modes(); ++j) {
    frequency_change = std::max(frequency_change, std::abs(split.frequency_hz(j) - raw.frequency_hz(j)) / raw.frequency_hz(j));
    if (!equal(j - 1, j) && !equal(j, j + 1)) {
      EXPECT_TRUE(split.Phi.col(j) == raw.Phi.col(j)) << "single mode " << j << " changed";
      EXPECT_EQ(split.frequency_hz(j), raw.frequency_hz(j));
    } else if (equal(j, j + 1)) {
      ++pairs;
      EXPECT_GT(std::max(before(j - first), before(j + 1 - first)), kMixed) << "the pair at " << raw.frequency_hz(j) << " Hz came out split";
    }
  }
  std::printf("[ numbers  ] frequencies changed by %.2g relative\n", frequency_change);
  EXPECT_LE(frequency_change, kFrequencyBound);
  const ReducedMatrixErrors e = ReducedErrors(split, first), r = ReducedErrors(raw, first);
  std::printf("[ numbers  ] split (raw): |M_r - I| %.2g (%.2g), K_r off-diagonal %.2g (%.2g), K_r(j, j) against "
              "(2 pi f)^2 %.2g (%.2g)\n", e.orthonormality, r.orthonormality, e.off_diagonal, r.off_diagonal, e.frequency, r.frequency);
  EXPECT_LE(e.orthonormality, kOrthonormalityBound);
  EXPECT_LE(e.off_diagonal, kDiagonalBound);
  EXPECT_LE(e.frequency, kRayleighBound);
  return pairs;
}

TEST(MirrorModes, FreeFreePairsOfASquareBeamComeOutEvenOrOddAndTheRestBitForBit) {
  const Body centred = SquareBeam(true), corner = SquareBeam(false);
  FreeFreeOptions options;
  options.eigen.num_modes = 10;
  options.rigid_modes = RigidModes::kComputed;  // Phi is the solver's output: comparable bit for bit
  const ReducedBasis split = FreeFreeModalBasis(centred.model(), options, testing::Spectra());
  const ReducedBasis raw = FreeFreeModalBasis(corner.model(), options, testing::Spectra());
  // Without the symmetry the basis is the solver's, bit for bit.
  const eigensolvers::EigenSolution s = testing::Spectra().Solve(corner.K, corner.M, [&] {
    eigensolvers::EigenOptions e = options.eigen;
    e.num_modes += 6;
    return e;
  }());
  EXPECT_TRUE(raw.Phi == s.modes);
  // Ten elastic modes cut the fifth pair (9572 Hz): its half in the basis is a single mode, left
  // as it is (mixed; the planar check refuses it, one more mode mends it).
  EXPECT_EQ(ExpectSplit(centred.mesh.nodes, split, raw, 6, 15), 3);
  EXPECT_GT(MirrorDepartures(centred.mesh.nodes, split.Phi)(15), kMixed);
  // The rigid modes (kind kRigid) are never touched.
  EXPECT_TRUE(split.Phi.leftCols(6) == raw.Phi.leftCols(6));
  // A split basis is left as it is: its clusters are already even or odd (C diagonal).
  ReducedBasis again = split;
  SplitEqualModesByMirror(centred.model(), &again);
  EXPECT_TRUE(again.Phi == split.Phi);
  EXPECT_TRUE(again.frequency_hz == split.frequency_hz);
  EXPECT_TRUE(again.relative_residuals == split.relative_residuals);
  // A cluster the reflection does not map onto itself is left as it is: an even mode and the
  // mixture of another even and an odd one, given one frequency (C's eigenvalues off +-1).
  std::vector<Index> even, odd;
  for (Index j = 6; j < 15; ++j) {
    const Eigen::VectorXd reflected = Reflected(centred.mesh.nodes, split.Phi.col(j));
    ((reflected - split.Phi.col(j)).norm() <= kSplitBound * split.Phi.col(j).norm() ? even : odd).push_back(j);
  }
  ASSERT_GE(even.size(), 2u);
  ASSERT_GE(odd.size(), 1u);
  ReducedBasis skewed = split;
  skewed.Phi.resize(split.Phi.rows(), 2);
  skewed.Phi << split.Phi.col(even[0]), (split.Phi.col(even[1]) + split.Phi.col(odd[0])) / std::sqrt(2.0);
  skewed.kinds.assign(2, ModeKind::kNormal);
  skewed.names = {"a", "b"};
  skewed.frequency_hz = Eigen::VectorXd::Constant(2, split.frequency_hz(even[0]));
  skewed.relative_residuals = skewed.residual_floors = Eigen::VectorXd::Zero(2);
  const Eigen::MatrixXd skewed_Phi = skewed.Phi;
  SplitEqualModesByMirror(centred.model(), &skewed);
  EXPECT_TRUE(skewed.Phi == skewed_Phi);
}

TEST(MirrorModes, ClampedPairsAndCraigBamptonNormalModesSplit) {
  const Body centred = SquareBeam(true), corner = SquareBeam(false);
  eigensolvers::EigenOptions eigen;
  eigen.num_modes = 8;
  const auto held = [](const Body& b) {
    BoundaryConditions conditions;
    conditions.supports.push_back({"root", testing::NodesAt(b.mesh, 0, 0.0)});
    return conditions;
  };
  const ReducedBasis split = FixedInterfaceModalBasis(centred.model(), held(centred), eigen, testing::Spectra());
  const ReducedBasis raw = FixedInterfaceModalBasis(corner.model(), held(corner), eigen, testing::Spectra());
  EXPECT_EQ(ExpectSplit(centred.mesh.nodes, split, raw, 0, 8), 3);

  BoundaryConditions tip;
  tip.interfaces.push_back({"root", testing::NodesAt(centred.mesh, 0, 0.0), Coupling::kRigid, std::nullopt, {}});
  const ReducedBasis cb = CraigBamptonBasis(centred.model(), tip, eigen, testing::Spectra());
  const Eigen::VectorXd departures = MirrorDepartures(centred.mesh.nodes, cb.Phi).tail(8);
  // The orthonormalised form's normal modes (of the reduced system, by a dense eigen-solve) too;
  // the off-centre beam's are mixed.
  const auto orthonormal_departures = [&](const Body& b) {
    tip.interfaces[0].nodes = testing::NodesAt(b.mesh, 0, 0.0);
    const ReducedBasis orthonormal = OrthonormalizeBasis(b.model(), CraigBamptonBasis(b.model(), tip, eigen, testing::Spectra()));
    const Index normal = orthonormal.Counts().normal;
    EXPECT_EQ(normal, 8);
    return Eigen::VectorXd(MirrorDepartures(centred.mesh.nodes, orthonormal.Phi).tail(normal));
  };
  const Eigen::VectorXd orthonormal = orthonormal_departures(centred), orthonormal_raw = orthonormal_departures(corner);
  std::printf("[ numbers  ] Craig-Bampton normal modes: departure max %.2g; orthonormalised: %.2g (before %.2g)\n",
              departures.maxCoeff(), orthonormal.maxCoeff(), orthonormal_raw.maxCoeff());
  EXPECT_LE(departures.maxCoeff(), kSplitBound);
  EXPECT_LE(orthonormal.maxCoeff(), kSplitBound);
  EXPECT_GT(orthonormal_raw.maxCoeff(), kMixed);
}

// The planar check (mbs::MakePlanar, a free-free body in a scene's xy plane) keeps the split
// beam's even modes, found here by the brute-force reflection, and refuses the raw basis's first
// mode, half of a mixed pair, as it refused case 06's beam.
TEST(MirrorModes, APlanarSceneKeepsTheSplitSquareBeamsEvenModesAndRefusesTheRawPairs) {
  const Body centred = SquareBeam(true), corner = SquareBeam(false);
  FreeFreeOptions options;
  options.eigen.num_modes = 9;  // whole pairs (a tenth cuts one, see above)
  const ReducedBasis split = FreeFreeModalBasis(centred.model(), options, testing::Spectra());
  const ReducedBasis raw = FreeFreeModalBasis(corner.model(), options, testing::Spectra());
  const auto kept_columns = [&](const ReducedBasis& free_free) {
    // The elastic columns (the floating frame carries the rigid motion).
    ReducedBasis basis = free_free;
    basis.Phi = free_free.Phi.rightCols(9);
    basis.kinds.erase(basis.kinds.begin(), basis.kinds.begin() + 6);
    basis.names.erase(basis.names.begin(), basis.names.begin() + 6);
    basis.frequency_hz = free_free.frequency_hz.tail(9);
    basis.relative_residuals = free_free.relative_residuals.tail(9);
    basis.residual_floors = free_free.residual_floors.tail(9);
    ComputeReducedMatrices(centred.model(), &basis);
    SidSpec sid;
    sid.geometric_stiffening = false;
    const fem::SystemMatrices views{centred.K, centred.M};
    sid::ReducedBody data = BuildReducedBody({centred.mesh, views, fem::MassMatrixKind::kConsistent, sid}, basis);
    data.name = "beam";
    mbs::MultibodySystem system(Eigen::Vector3d::Zero());
    const int b = system.AddBody(std::make_unique<mbs::FlexibleBody>("beam", std::move(data), false));
    mbs::MakePlanar(system, system.NeutralState());
    return system.KeptVelocities(b);
  };
  const Eigen::MatrixXd elastic = split.Phi.rightCols(9);
  const Eigen::MatrixXd reflected = Reflected(centred.mesh.nodes, elastic);
  std::vector<Index> expected = {0, 1, 5};  // v_x, v_y, w_z, then the even modes' columns
  for (Index j = 0; j < 9; ++j) {
    if ((reflected.col(j) - elastic.col(j)).norm() <= kSplitBound * elastic.col(j).norm()) expected.push_back(6 + j);
  }
  EXPECT_EQ(expected.size(), 3u + 4u);  // one of each of the 3 pairs, one of the 3 single modes
  EXPECT_EQ(kept_columns(split), expected);
  const std::string refusal = testing::InputErrorMessage([&] { kept_columns(raw); });
  EXPECT_NE(refusal.find("body 'beam' mode 1 'normal_1': neither in-plane nor out-of-plane"), std::string::npos) << refusal;
}

}  // namespace
}  // namespace flexmbs::reduction
