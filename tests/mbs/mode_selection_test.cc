// Which modes a scene keeps (mbs/mode_selection.h): the selections, their one-line errors, the
// restriction against a body reduced from the kept columns directly, and the refusal of modes
// that move the body rigidly.

#include "mbs/mode_selection.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <iostream>
#include <utility>
#include <string>
#include <vector>

#include "mbs/flexible_body.h"
#include "tests/input_error.h"
#include "tests/mbs/flexible_test_bodies.h"

namespace flexmbs::mbs {
namespace {

using Eigen::Index;
using Eigen::MatrixXd;
using flexmbs::testing::InputErrorMessage;
using testing::CraigBamptonBeam;
using testing::FreeFreeBeam;

// The restricted blocks and those of a re-reduction are the same exact integrals, summed in
// another order (the reduction's blocks of nodes and modes): round-off. The stiffening matrices
// come from static solves of the same loads: the same round-off. Measured: at most 6e-16.
constexpr double kRoundOff = 1e-12;

std::vector<Index> Range(Index first, Index last) {
  std::vector<Index> out;
  for (Index i = first; i <= last; ++i) out.push_back(i);
  return out;
}

TEST(SelectModes, KeepsEveryModeButTheRigidOnesWithoutFilters) {
  EXPECT_EQ(SelectModes(CraigBamptonBeam().body, {}, "beam"), Range(0, 9));
  EXPECT_EQ(SelectModes(FreeFreeBeam().body, {}, "beam"), Range(6, 10));
}

TEST(SelectModes, ByIndexAndNameInTheBodysOrder) {
  const sid::ReducedBody& body = CraigBamptonBeam().body;
  ModeSelection selection;
  selection.modes = std::vector<ModeId>{std::string("normal_2"), Index{9}, std::string("constraint_tip_tx"), Index{3}};
  EXPECT_EQ(body.mode_names[7], "normal_2") << "the Craig-Bampton beam's mode names changed";
  EXPECT_EQ(SelectModes(body, selection, "beam"), (std::vector<Index>{0, 3, 7, 9}));
}

TEST(SelectModes, ByKindAndFrequencyCutOff) {
  const sid::ReducedBody& body = CraigBamptonBeam().body;  // 6 constraint, then normal_1 .. normal_4
  ModeSelection normal;
  normal.kinds = std::vector<std::string>{"normal"};
  EXPECT_EQ(SelectModes(body, normal, "beam"), Range(6, 9));
  ModeSelection constraint;
  constraint.kinds = std::vector<std::string>{"constraint"};
  EXPECT_EQ(SelectModes(body, constraint, "beam"), Range(0, 5));
  // A cut-off between normal_2 and normal_3 keeps the constraint modes (no frequency) and two.
  ModeSelection band;
  band.max_frequency_hz = 0.5 * (body.frequency_hz(7) + body.frequency_hz(8));
  EXPECT_EQ(SelectModes(body, band, "beam"), Range(0, 7));
  band.kinds = normal.kinds;
  EXPECT_EQ(SelectModes(body, band, "beam"), Range(6, 7));
}

TEST(SelectModes, ErrorsAreOneLineAndNameTheBodyAndTheItem) {
  const sid::ReducedBody& cb = CraigBamptonBeam().body;
  const sid::ReducedBody& free = FreeFreeBeam().body;
  const auto listed = [](std::vector<ModeId> ids) {
    ModeSelection s;
    s.modes = std::move(ids);
    return s;
  };
  const auto kinds = [](std::vector<std::string> names) {
    ModeSelection s;
    s.kinds = std::move(names);
    return s;
  };
  const auto band = [](double hz) {
    ModeSelection s;
    s.max_frequency_hz = hz;
    return s;
  };
  ModeSelection both = listed({Index{1}});
  both.kinds = std::vector<std::string>{"normal"};
  ModeSelection nothing = band(1.0);
  nothing.kinds = std::vector<std::string>{"normal"};
  struct Bad {
    const sid::ReducedBody* body;
    ModeSelection selection;
    std::vector<std::string> parts;
  };
  const std::vector<Bad> cases = {
      {&cb, listed({std::string("normal_99")}), {"unknown mode 'normal_99'", "normal_1"}},
      {&cb, listed({Index{10}}), {"mode index 10 out of range", "10 modes"}},
      {&cb, listed({Index{-1}}), {"mode index -1 out of range"}},
      {&cb, listed({Index{7}, std::string("normal_2")}), {"mode 7 ('normal_2') listed twice"}},
      {&free, listed({std::string("rigid_tx")}), {"'rigid_tx'", "rigid-body mode"}},
      {&free, kinds({"rigid"}), {"kind 'rigid'", "floating frame"}},
      {&cb, kinds({"elastic"}), {"unknown mode kind 'elastic'", "static_correction"}},
      {&cb, kinds({"normal", "normal"}), {"kind 'normal' listed twice"}},
      {&cb, band(-1.0), {"max_frequency_hz -1 must be finite and >= 0"}},
      {&cb, band(std::nan("")), {"max_frequency_hz nan"}},
      {&cb, both, {"either a list of modes or the filters"}},
      {&cb, nothing, {"keeps none of the body's modes", "4 normal", "6 constraint"}},
  };
  for (const Bad& bad : cases) {
    const std::string message = InputErrorMessage([&] { SelectModes(*bad.body, bad.selection, "arm"); });
    EXPECT_EQ(message.rfind("body 'arm': modes: ", 0), 0u) << message;
    for (const std::string& part : bad.parts) EXPECT_NE(message.find(part), std::string::npos) << message;
  }
}

// |restricted - reduced| <= kRoundOff scale; scale: |reduced| unless given (the largest block of
// a Taylor block's m1 or m2 list: some blocks of a list are zero up to round-off).
void ExpectClose(const MatrixXd& restricted, const MatrixXd& reduced, const std::string& what, double scale = -1.0) {
  ASSERT_EQ(restricted.rows(), reduced.rows()) << what;
  ASSERT_EQ(restricted.cols(), reduced.cols()) << what;
  if (reduced.size() == 0) return;
  EXPECT_LE((restricted - reduced).norm(), kRoundOff * (scale < 0.0 ? reduced.norm() : scale)) << what;
}

double LargestNorm(const std::vector<MatrixXd>& blocks) {
  double largest = 0.0;
  for (const MatrixXd& block : blocks) largest = std::max(largest, block.norm());
  return largest;
}

void ExpectClose(const sid::TaylorMatrix& restricted, const sid::TaylorMatrix& reduced, const std::string& what) {
  ExpectClose(restricted.m0, reduced.m0, what + ".m0");
  ASSERT_EQ(restricted.m1.size(), reduced.m1.size()) << what;
  ASSERT_EQ(restricted.m2.size(), reduced.m2.size()) << what;
  for (std::size_t j = 0; j < reduced.m1.size(); ++j) {
    ExpectClose(restricted.m1[j], reduced.m1[j], what + ".m1[" + std::to_string(j) + "]", LargestNorm(reduced.m1));
  }
  for (std::size_t j = 0; j < reduced.m2.size(); ++j) {
    ExpectClose(restricted.m2[j], reduced.m2[j], what + ".m2[" + std::to_string(j) + "]", LargestNorm(reduced.m2));
  }
}

// Kept out of order on purpose: the restricted body's mode i is keep[i].
TEST(RestrictModes, EqualsTheBodyReducedFromTheKeptColumns) {
  const testing::FeReducedBody& fe = CraigBamptonBeam();
  const std::vector<Index> keep = {8, 1, 5, 6, 9};
  const sid::ReducedBody restricted = RestrictModes(fe.body, keep);
  const sid::ReducedBody reduced = testing::Reduce(fe, testing::KeepColumns(fe.basis, keep));
  EXPECT_EQ(restricted.mode_names, reduced.mode_names);
  EXPECT_EQ(restricted.mode_kinds, reduced.mode_kinds);
  ASSERT_EQ(restricted.frequency_hz.size(), reduced.frequency_hz.size());
  for (Index i = 0; i < reduced.frequency_hz.size(); ++i) {
    const double a = restricted.frequency_hz(i), b = reduced.frequency_hz(i);
    EXPECT_TRUE(a == b || (std::isnan(a) && std::isnan(b))) << "frequency of mode " << i;
  }
  ExpectClose(restricted.phi, reduced.phi, "phi");
  const std::vector<std::pair<const char*, const sid::TaylorMatrix sid::ReducedBody::*>> blocks = {
      {"mdCM", &sid::ReducedBody::mdCM}, {"J", &sid::ReducedBody::J},   {"Ct", &sid::ReducedBody::Ct},
      {"Cr", &sid::ReducedBody::Cr},     {"Me", &sid::ReducedBody::Me}, {"Gr", &sid::ReducedBody::Gr},
      {"Ge", &sid::ReducedBody::Ge},     {"Oe", &sid::ReducedBody::Oe}, {"Ke", &sid::ReducedBody::Ke},
      {"De", &sid::ReducedBody::De},     {"ksigma", &sid::ReducedBody::ksigma}};
  for (const auto& [name, block] : blocks) {
    EXPECT_TRUE((fe.body.*block).IsConsistent(fe.body.num_modes())) << name;
    EXPECT_TRUE((restricted.*block).IsConsistent(static_cast<Index>(keep.size()))) << name;
    ExpectClose(restricted.*block, reduced.*block, name);
  }
  for (std::size_t a = 0; a < 3; ++a) {
    ExpectClose(restricted.stiffening.K0t[a], reduced.stiffening.K0t[a], "K0t");
    ExpectClose(restricted.stiffening.K0r[a], reduced.stiffening.K0r[a], "K0r");
  }
  for (std::size_t l = 0; l < 6; ++l) ExpectClose(restricted.stiffening.K0omega[l], reduced.stiffening.K0omega[l], "K0omega");
  ASSERT_EQ(restricted.nodes.size(), reduced.nodes.size());
  for (std::size_t k = 0; k < reduced.nodes.size(); ++k) {
    const std::string node = "node " + reduced.nodes[k].name;
    EXPECT_EQ(restricted.nodes[k].name, reduced.nodes[k].name);
    ExpectClose(restricted.nodes[k].origin, reduced.nodes[k].origin, node + " origin");
    ExpectClose(restricted.nodes[k].phi, reduced.nodes[k].phi, node + " phi");
    ExpectClose(restricted.nodes[k].psi, reduced.nodes[k].psi, node + " psi");
    ExpectClose(restricted.nodes[k].AP, reduced.nodes[k].AP, node + " AP");
  }
  ASSERT_EQ(restricted.surfaces.size(), 1u);
  ASSERT_EQ(reduced.surfaces.size(), 1u);
  ExpectClose(restricted.surfaces[0].phi, reduced.surfaces[0].phi, "surface phi");
}

// A free-free basis with its rigid modes, and the six constraint modes of the only interface of an
// unsupported Craig-Bampton beam (a rigid motion of the whole beam), move the body rigidly.
TEST(CheckNoRigidBodyMotion, RefusesModesThatMoveTheBodyRigidlyAndNamesThem) {
  const sid::ReducedBody& free = FreeFreeBeam().body;
  const std::string message = InputErrorMessage([&] { FlexibleBody("arm", free, false); });
  EXPECT_EQ(message.rfind("body 'arm': modes: ", 0), 0u) << message;
  for (const char* part : {"rigid_tx", "rigid_ty", "rigid_tz", "combine into 6 rigid-body motions"}) {
    EXPECT_NE(message.find(part), std::string::npos) << message;
  }
  EXPECT_EQ(message.find("normal_"), std::string::npos) << message;

  const sid::ReducedBody& unsupported = testing::UnsupportedCraigBamptonBeam().body;
  const std::string cb_message = InputErrorMessage([&] { CheckNoRigidBodyMotion(unsupported, "arm"); });
  for (const char* part : {"constraint_tip_tx", "constraint_tip_rz", "6 rigid-body motions"}) {
    EXPECT_NE(cb_message.find(part), std::string::npos) << cb_message;
  }
  const double share = MinimumDeformationShare(unsupported);
  EXPECT_LT(share, kRigidMotionShare);
  std::cout << "unsupported Craig-Bampton beam, all modes: deformation share " << share << "\n";
}

TEST(CheckNoRigidBodyMotion, AcceptsElasticModesAndAHeldBasis) {
  const sid::ReducedBody& unsupported = testing::UnsupportedCraigBamptonBeam().body;
  ModeSelection normal;
  normal.kinds = std::vector<std::string>{"normal"};
  const sid::ReducedBody held = RestrictModes(unsupported, SelectModes(unsupported, normal, "arm"));
  EXPECT_NO_THROW(CheckNoRigidBodyMotion(held, "arm"));
  EXPECT_NO_THROW(CheckNoRigidBodyMotion(CraigBamptonBeam().body, "arm"));
  const sid::ReducedBody elastic = RestrictModes(FreeFreeBeam().body, SelectModes(FreeFreeBeam().body, {}, "arm"));
  // Free-free elastic modes are M-orthogonal to every rigid motion: their share is 1.
  EXPECT_NEAR(MinimumDeformationShare(elastic), 1.0, kRoundOff);
  std::cout << "deformation shares: held Craig-Bampton " << MinimumDeformationShare(held) << ", clamped Craig-Bampton "
            << MinimumDeformationShare(CraigBamptonBeam().body) << "\n";
}

TEST(FlexibleBodyInput, ErrorsNameTheBodyAndTheItem) {
  sid::ReducedBody body = RestrictModes(CraigBamptonBeam().body, {6, 7});
  sid::ReducedBody origin_node = body;
  origin_node.nodes[0].name = "origin";
  EXPECT_NE(InputErrorMessage([&] { FlexibleBody("arm", origin_node, true); }).find("body 'arm': node 'origin' has the name"),
            std::string::npos);
  sid::ReducedBody bad_order = body;
  bad_order.Me.m1.assign(2, MatrixXd::Zero(2, 2));
  EXPECT_NE(InputErrorMessage([&] { FlexibleBody("arm", bad_order, true); }).find("body 'arm': SID block Me has order 1"),
            std::string::npos);
  sid::ReducedBody bad_shape = body;
  bad_shape.Oe.m0 = MatrixXd::Zero(2, 5);
  EXPECT_NE(InputErrorMessage([&] { FlexibleBody("arm", bad_shape, true); }).find("body 'arm': SID block Oe is 2 x 5"),
            std::string::npos);
}

}  // namespace
}  // namespace flexmbs::mbs
