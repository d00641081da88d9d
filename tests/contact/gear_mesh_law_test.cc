// contact/gears MeshLaw::ForcesWithDerivatives: the derivatives of the mesh's forces by the pairs'
// penetrations and rates against central differences of MeshLaw::Forces (teeth coupled through
// the rims, both pairs kept and one dropped; the flattening at each pair's load), the forces of
// the uncoupled laws unchanged to the bit, and the rim tables' one-line errors.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <numbers>
#include <string>
#include <vector>

#include "contact/gears/gear_mesh_force.h"
#include "tests/input_error.h"

namespace flexmbs::contact {
namespace {

using testing::InputErrorMessage;

constexpr double kDeg = std::numbers::pi / 180.0;

/// z 20/40, m 4 mm, b 40 mm (tests/contact/gear_teeth_test.cc's pair).
GearPair Pair() {
  const auto wheel = [](int teeth) {
    return SpurGearSpec{4e-3, teeth, 20.0 * kDeg, 0.0, 1.0, 1.25, 0.04};
  };
  return MakeGearPair({wheel(20), wheel(40), 0.0, 0.0, false});
}

/// Teeth of 1.5e-11 ... 3e-11 m^2/N (the FE tooth's size, gear_tooth_fe_test.cc) and, with
/// `rims`, neighbours moving 0.2 / 0.07 of that ahead / behind (ToothCouplingFromFe's range).
ElasticTeeth Teeth(bool rims) {
  ElasticTeeth teeth;
  teeth.tooth1 = teeth.tooth2 = {{0.05, 0.7}, {1.5e-11, 3e-11}, {2e-3, 1e-3}};
  if (rims) teeth.rim1 = teeth.rim2 = RimCoupling{{0.05, 0.7}, {3e-12, 6e-12}, {1e-12, 2e-12}};
  return teeth;
}

/// The two pairs in contact on the driving flanks at wheel 1's angle phi1 [rad] with wheel 2
/// `depth` [m] behind its touching angle (empty unless there are two).
std::vector<ToothPair> DoublePairs(const GearPair& pair, double phi1, double depth) {
  const double a = pair.centre_distance;
  const double phi2 =
      TouchingAngle2(pair, a, phi1, 0.0, FlankSide::kPositive) + depth / pair.gear2.base_radius;
  std::vector<ToothPair> in;
  for (const ToothPair& tp : MeshingToothPairs(pair, a, phi1, phi2))
    if (tp.gap < 0.0) in.push_back(tp);
  if (in.size() != 2) in.clear();
  return in;
}

/// Two pairs in double contact 5 um deep.
std::vector<ToothPair> DoubleContact(const GearPair& pair) {
  for (double phi1 = 0.0; phi1 < 2.0 * std::numbers::pi / 20; phi1 += 1e-3) {
    const std::vector<ToothPair> in = DoublePairs(pair, phi1, 5e-6);
    if (!in.empty()) return in;
  }
  return {};
}

/// The largest difference between the law's K, D and central differences of its forces (steps
/// of 1e-10 m in delta, 1e-6 m/s in delta'), each relative to the largest entry of K, D.
struct DerivativeErrors {
  double d_delta = 0.0, d_rate = 0.0;
};
DerivativeErrors Compare(const MeshLaw& law, const std::vector<ToothPair>& pairs,
                         const std::vector<double>& rates) {
  const MeshPairForces at = law.ForcesWithDerivatives(pairs, rates);
  const std::size_t n = pairs.size();
  Eigen::MatrixXd K(n, n), D(n, n);
  for (std::size_t j = 0; j < n; ++j) {
    std::vector<ToothPair> plus = pairs, minus = pairs;
    plus[j].gap -= 1e-10;  // delta = -gap
    minus[j].gap += 1e-10;
    std::vector<double> up = rates, down = rates;
    up[j] += 1e-6;
    down[j] -= 1e-6;
    const std::vector<double> fp = law.Forces(plus, rates), fm = law.Forces(minus, rates);
    const std::vector<double> gp = law.Forces(pairs, up), gm = law.Forces(pairs, down);
    for (std::size_t i = 0; i < n; ++i) {
      K(i, j) = (fp[i] - fm[i]) / 2e-10;
      D(i, j) = (gp[i] - gm[i]) / 2e-6;
    }
  }
  return {(at.d_delta - K).cwiseAbs().maxCoeff() / K.cwiseAbs().maxCoeff(),
          (at.d_rate - D).cwiseAbs().maxCoeff() / D.cwiseAbs().maxCoeff()};
}

// Coupled through the rims, two pairs on one side share the 2 x 2 compliance C: K = C^-1 with
// its cross terms, D the damping on the diagonal. With one pair's penetration a fiftieth of the
// other's, that pair would pull and is dropped: its row is
// zero and the other's stiffness is 1 / C_jj.
TEST(MeshLawDerivatives, CoupledPairsCrossTermsAreTheCompliancesInverse) {
  const GearPair pair = Pair();
  const MeshLaw law(pair, Teeth(true), 2e3);
  std::vector<ToothPair> in = DoubleContact(pair);
  ASSERT_EQ(in.size(), 2u);
  const std::vector<double> rates = {3e-3, -2e-3};
  const MeshPairForces both = law.ForcesWithDerivatives(in, rates);
  const double cross = std::abs(both.d_delta(0, 1)) / both.d_delta(0, 0);
  const DerivativeErrors kept = Compare(law, in, rates);
  in[1].gap = 0.02 * in[0].gap;
  const MeshPairForces one = law.ForcesWithDerivatives(in, rates);
  ASSERT_EQ(one.force[1], 0.0);  // dropped
  EXPECT_EQ(one.d_delta(0, 0), law.PairLaw(in[0]).stiffness);
  const DerivativeErrors dropped = Compare(law, in, rates);
  std::printf("[measured] coupled K, D against central differences: %.2g, %.2g (cross term %.3f "
              "of the diagonal); one pair dropped: %.2g, %.2g\n",
              kept.d_delta, kept.d_rate, cross, dropped.d_delta, dropped.d_rate);
  EXPECT_GT(cross, 0.05);  // measured 0.098 of the diagonal: the cross term the element needs
  EXPECT_LT(kept.d_delta, 4e-11);     // measured 4.0e-12 (the forces' round-off over 2e-10 m)
  EXPECT_LT(kept.d_rate, 2.5e-10);    // measured 2.4e-11
  EXPECT_LT(dropped.d_delta, 1e-11);  // measured 1.0e-12
  EXPECT_LT(dropped.d_rate, 2.5e-10); // measured 2.4e-11
}

// With the flattening at each pair's load, F_e = b w with (q1 + q2) w + delta_H(w) = delta: the
// implicit derivative b / (q1 + q2 + delta_H / w - 2 s) against central differences of the
// bisection's forces, at 1, 5 and 30 um; and the energy's derivative is the elastic force.
TEST(MeshLawDerivatives, FlatteningAtLoadDerivativeIsTheImplicitOnes) {
  const GearPair pair = Pair();
  ElasticTeeth teeth = Teeth(false);
  teeth.flattening_at_load = true;
  const MeshLaw law(pair, teeth, 2e3);
  std::vector<ToothPair> in = DoubleContact(pair);
  ASSERT_EQ(in.size(), 2u);
  double worst_k = 0.0, worst_d = 0.0, worst_energy = 0.0;
  for (const double depth : {1e-6, 5e-6, 30e-6}) {
    in[0].gap = -depth;
    in[1].gap = -0.7 * depth;
    const std::vector<double> rates = {1e-3, 2e-3};
    const DerivativeErrors e = Compare(law, in, rates);
    worst_k = std::max(worst_k, e.d_delta);
    worst_d = std::max(worst_d, e.d_rate);
    const std::vector<double> still = {0.0, 0.0};
    std::vector<ToothPair> plus = in, minus = in;
    plus[0].gap -= 1e-9;
    minus[0].gap += 1e-9;
    const double force = law.Forces(in, still)[0];
    const double de = (law.ForcesWithDerivatives(plus, still).energy -
                       law.ForcesWithDerivatives(minus, still).energy) / 2e-9;
    worst_energy = std::max(worst_energy, std::abs(de / force - 1.0));
  }
  std::printf("[measured] flattening at load: K, D against central differences %.2g, %.2g; the "
              "energy's derivative against the force %.2g\n",
              worst_k, worst_d, worst_energy);
  // Measured 1.3e-10 (the differences' truncation: 1.3e-8 with steps of 1e-9 m), 2.0e-10, and
  // 7.8e-9 (steps of 1e-9 m).
  EXPECT_LT(worst_k, 1.5e-9);
  EXPECT_LT(worst_d, 2e-9);
  EXPECT_LT(worst_energy, 8e-8);
}

// Laws that are each pair's own (constant c', elastic teeth linearised at w_ref, coupled teeth
// in single contact) give Forces to the bit as the pair's law always did,
// Evaluate(PairLaw(tp), -g, delta').
TEST(MeshLawDerivatives, UncoupledForcesAreEachPairsLawToTheBit) {
  const GearPair pair = Pair();
  const std::vector<ToothPair> in = DoubleContact(pair);
  ASSERT_EQ(in.size(), 2u);
  const std::vector<double> rates = {3e-3, -2e-3};
  const MeshLaw constant(ToothPairLaw({1.4e10, 2e3}, pair));
  const MeshLaw linearised(pair, Teeth(false), 2e3);
  const MeshLaw coupled(pair, Teeth(true), 2e3);
  for (const MeshLaw* law : {&constant, &linearised}) {
    const MeshPairForces f = law->ForcesWithDerivatives(in, rates);
    for (std::size_t i = 0; i < 2; ++i) {
      const NormalForce expected = Evaluate(law->PairLaw(in[i]), -in[i].gap, rates[i]);
      EXPECT_EQ(f.force[i], expected.force);
      EXPECT_EQ(law->Forces(in, rates)[i], expected.force);
      EXPECT_EQ(f.d_delta(i, i), expected.d_delta);
      EXPECT_EQ(f.d_delta(i, 1 - i), 0.0);
    }
  }
  for (std::size_t i = 0; i < 2; ++i) {
    EXPECT_EQ(coupled.Forces({in[i]}, {rates[i]})[0],
              Evaluate(coupled.PairLaw(in[i]), -in[i].gap, rates[i]).force);
  }
}

// Coupled and at each pair's load together: the loads solve (q1 + q2)_i w_i + delta_H,i(w_i) +
// b C_ij w_j = delta_i, checked here from the tables' public interpolations and WeberFlattening;
// K = b J^-1 against central differences, both pairs kept and one dropped (then the other at its
// load alone, ForceAtLoad's single pair); with a symmetric coupling (constant rim columns, C_AB
// = C_BA) the forces derive from the energy: d E / d delta_j = F_j.
TEST(MeshLawDerivatives, CoupledAtLoadSolvesBothSeriesTogether) {
  const GearPair pair = Pair();
  ElasticTeeth teeth = Teeth(true);
  teeth.flattening_at_load = true;
  const MeshLaw law(pair, teeth, 2e3);
  std::vector<ToothPair> in = DoubleContact(pair);
  ASSERT_EQ(in.size(), 2u);
  const double b = 0.04;
  double worst_residual = 0.0;
  for (const double depth : {2e-6, 1e-5, 3e-5}) {
    in[0].gap = -depth;
    in[1].gap = -0.8 * depth;
    const std::vector<double> f = law.Forces(in, {0.0, 0.0});
    const std::size_t A = in[0].roll1 > in[1].roll1 ? 0 : 1;  // nearer wheel 1's tip
    const auto cross = [&](std::size_t i) {  // b C_ij: i's teeth under j's load
      const RimCoupling &r1 = *teeth.rim1, &r2 = *teeth.rim2;
      const ToothPair& other = in[1 - i];
      return i == A ? RimCouplingAt(r1.roll, r1.ahead, other.roll1) +
                          RimCouplingAt(r2.roll, r2.behind, other.roll2)
                    : RimCouplingAt(r1.roll, r1.behind, other.roll1) +
                          RimCouplingAt(r2.roll, r2.ahead, other.roll2);
    };
    for (std::size_t i = 0; i < 2; ++i) {
      const ToothComplianceAt q1 = InterpolateCompliance(teeth.tooth1, in[i].roll1);
      const ToothComplianceAt q2 = InterpolateCompliance(teeth.tooth2, in[i].roll2);
      const double w = f[i] / b;
      const double approach =
          (q1.compliance + q2.compliance) * w +
          WeberFlattening(w, pair.gear1.base_radius * in[i].roll1,
                          pair.gear2.base_radius * in[i].roll2, q1.centre_depth, q2.centre_depth,
                          teeth.material) +
          cross(i) * f[1 - i] / b;
      worst_residual = std::max(worst_residual, std::abs(approach / -in[i].gap - 1.0));
    }
  }
  in[0].gap = -1e-5;
  in[1].gap = -0.8e-5;
  const std::vector<double> rates = {1e-3, -1e-3};
  const DerivativeErrors kept = Compare(law, in, rates);
  ElasticTeeth symmetric_teeth = teeth;
  symmetric_teeth.rim1 = symmetric_teeth.rim2 = RimCoupling{{0.05, 0.7}, {2e-12, 2e-12},
                                                            {2e-12, 2e-12}};
  const MeshLaw symmetric(pair, symmetric_teeth, 0.0);
  const std::vector<double> still = {0.0, 0.0};
  const std::vector<double> f = symmetric.Forces(in, still);
  double energy_error = 0.0;
  for (std::size_t j = 0; j < 2; ++j) {
    std::vector<ToothPair> plus = in, minus = in;
    plus[j].gap -= 1e-10;
    minus[j].gap += 1e-10;
    const double de = (symmetric.ForcesWithDerivatives(plus, still).energy -
                       symmetric.ForcesWithDerivatives(minus, still).energy) / 2e-10;
    energy_error = std::max(energy_error, std::abs(de / f[j] - 1.0));
  }
  in[1].gap = 0.02 * in[0].gap;
  const MeshPairForces one = law.ForcesWithDerivatives(in, rates);
  ASSERT_EQ(one.force[1], 0.0);  // dropped
  ElasticTeeth alone_teeth = teeth;
  alone_teeth.rim1.reset();
  alone_teeth.rim2.reset();
  const MeshLaw alone(pair, alone_teeth, 2e3);
  EXPECT_EQ(one.force[0], alone.Forces({in[0]}, {rates[0]})[0]);
  const DerivativeErrors dropped = Compare(law, in, rates);
  std::printf("[measured] coupled at load: the series' residual %.2g; K, D against central "
              "differences %.2g, %.2g; one dropped %.2g, %.2g; the symmetric one's energy gradient "
              "against its forces %.2g\n",
              worst_residual, kept.d_delta, kept.d_rate, dropped.d_delta, dropped.d_rate,
              energy_error);
  EXPECT_LT(worst_residual, 2e-15);    // measured 2.2e-16 (Newton's method to 1e-15 of w)
  EXPECT_LT(kept.d_delta, 1.5e-10);    // measured 1.5e-11
  EXPECT_LT(kept.d_rate, 2e-9);        // measured 2.0e-10
  EXPECT_LT(dropped.d_delta, 2.5e-10); // measured 2.6e-11
  EXPECT_LT(dropped.d_rate, 2e-9);     // measured 2.0e-10
  EXPECT_LT(energy_error, 6e-11);      // measured 6.0e-12
}

// Undamped, each pair's teeth and flattening under the law's forces add up to its penetration:
// the rims' share of the other pair's load in the teeth of coupled pairs, the flattening at the
// pair's load where the law takes it there; and a pair alone (Deflection) likewise.
TEST(MeshLawDerivatives, DeflectionsAddUpToEachPairsPenetration) {
  const GearPair pair = Pair();
  std::vector<ToothPair> in = DoubleContact(pair);
  ASSERT_EQ(in.size(), 2u);
  in[0].gap = -1e-5;
  in[1].gap = -0.8e-5;
  double worst = 0.0, worst_alone = 0.0, rim_share = 0.0;
  for (const bool rims : {false, true}) {
    for (const bool at_load : {false, true}) {
      ElasticTeeth teeth = Teeth(rims);
      teeth.flattening_at_load = at_load;
      const MeshLaw law(pair, teeth, 0.0);
      const std::vector<double> forces = law.Forces(in, {0.0, 0.0});
      const std::vector<ToothPairDeflection> d = law.Deflections(in, forces);
      for (std::size_t i = 0; i < 2; ++i) {
        worst = std::max(worst,
                         std::abs((d[i].tooth1 + d[i].tooth2 + d[i].flattening) / -in[i].gap - 1.0));
        const ToothPairDeflection own = law.Deflection(in[i], forces[i]);
        if (rims) rim_share = std::max(rim_share, (d[i].tooth1 - own.tooth1) / d[i].tooth1);
        const double alone = law.Forces({in[i]}, {0.0})[0];
        const ToothPairDeflection one = law.Deflection(in[i], alone);
        worst_alone = std::max(
            worst_alone, std::abs((one.tooth1 + one.tooth2 + one.flattening) / -in[i].gap - 1.0));
      }
    }
  }
  std::printf("[measured] deflections against the penetrations: pairs together %.2g, alone %.2g; "
              "the rim's share of a tooth's deflection up to %.3f\n",
              worst, worst_alone, rim_share);
  EXPECT_LT(worst, 3e-15);        // measured 3.3e-16 (Newton's and the bisection's 1e-15 of w)
  EXPECT_LT(worst_alone, 3e-15);  // measured 3.3e-16
  EXPECT_GT(rim_share, 0.05);     // measured 0.156 of the tooth's deflection from the other pair
}

// A rim coupling is given for both wheels or neither, as a table of increasing rolls whose
// neighbours move less than the loaded tooth (NaN off the neighbour's flank): one line each.
TEST(MeshLawDerivatives, BadRimTablesAreOneLineErrors) {
  const GearPair pair = Pair();
  const auto refused = [&](const ElasticTeeth& teeth) {
    return InputErrorMessage([&] { MeshLaw(pair, teeth, 0.0); });
  };
  ElasticTeeth teeth = Teeth(true);
  teeth.rim2.reset();
  EXPECT_NE(refused(teeth).find("elastic teeth: gear 1's rim coupling without gear 2's; give both "
                                "or neither"),
            std::string::npos);
  teeth = Teeth(true);
  teeth.rim2->ahead = {3e-12, 4e-11};
  EXPECT_NE(refused(teeth).find("gear 2 rim: ahead[1] 4e-11 m^2/N must be NaN (off the "
                                "neighbour's flank) or in [0, 3e-11)"),
            std::string::npos)
      << refused(teeth);
  teeth = Teeth(true);
  teeth.rim1->behind = {std::numeric_limits<double>::quiet_NaN(), 1e-12};
  EXPECT_NE(refused(teeth).find("gear 1 rim: behind has 1 finite values; give two or more"),
            std::string::npos)
      << refused(teeth);
  teeth = Teeth(true);
  teeth.rim1->roll = {0.3, 0.2};
  EXPECT_NE(refused(teeth).find("gear 1 rim: roll[1] 0.2 rad must be finite, > 0 and above "
                                "roll[0]"),
            std::string::npos)
      << refused(teeth);
  teeth = Teeth(true);
  teeth.rim1->ahead = {3e-12};
  EXPECT_NE(refused(teeth).find("gear 1 rim: the rim coupling needs two or more samples and as "
                                "many of each column (roll 2, ahead 1, behind 2)"),
            std::string::npos)
      << refused(teeth);
}

}  // namespace
}  // namespace flexmbs::contact
