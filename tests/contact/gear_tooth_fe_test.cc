// gear_tooth_fe/: the FE tooth's compliance along its flank and the single-pair mesh
// stiffness it gives in series with Weber's flattening, against ISO 6336-1 and the expected shape
// along the path of contact. A coarse mesh (edge 0.4 m, hex20, 0.4 s); bench_gear_tooth prints the
// same numbers on finer meshes (edge 0.1 m: c at the pitch point 0.09 % lower) and for other rim
// segments (up to 8 % apart: the clamp's distance sets the wheel body's share).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <Eigen/Geometry>
#include <Eigen/LU>
#include <limits>
#include <numbers>
#include <utility>

#include "contact/gears/gear_mesh_force.h"
#include "contact/gears/tooth_profile.h"
#include "gear_tooth_fe/tooth_model.h"
#include "contact/gears/tooth_stiffness.h"
#include "tests/input_error.h"

namespace flexmbs::gear_tooth_fe {
namespace {

using testing::InputErrorMessage;

constexpr double kDeg = std::numbers::pi / 180.0;
constexpr double kPerMmMicron = 1e9;  // 1 N/(mm um) in N/m^2

contact::SpurGearSpec Wheel(int teeth) {
  return contact::SpurGearSpec{4e-3, teeth, 20.0 * kDeg, 0.0, 1.0, 1.25, 0.04};
}

ToothModelOptions Coarse() {
  ToothModelOptions options;
  options.geometry.mesh_size = 0.4;
  return options;
}

// A standard steel pair (m 4 mm, z 20/40, basic rack with rho_fP = 0.38 m): each tooth's
// compliance grows from the form circle to the tip, and the single-pair stiffness
// c(s) = 1 / (q1 + q2 + delta_H / w) along the path of contact is softest at its ends (a tip on
// the other's root), stiffest in the middle, and at the pitch point within ISO 6336-1's
// theoretical c'_th (Weber-Banaschek's numbers the standard fits) by its measured 9.5 %; times
// C_M C_B it gives ISO's c' ~ 14 N/(mm um).
TEST(ToothFe, SinglePairStiffnessAlongThePathHasIsoSizeAndShape) {
  const contact::GearPair pair = contact::MakeGearPair({Wheel(20), Wheel(40), 0.0, 0.0});
  contact::ElasticTeeth teeth;
  const ToothModelResult fe1 =
      ToothComplianceFromFe(contact::MakeSpurGear(Wheel(20), "gear 1"), teeth.material, Coarse());
  const ToothModelResult fe2 =
      ToothComplianceFromFe(contact::MakeSpurGear(Wheel(40), "gear 2"), teeth.material, Coarse());
  teeth.tooth1 = fe1.compliance;
  teeth.tooth2 = fe2.compliance;
  for (const contact::ToothCompliance* tooth : {&teeth.tooth1, &teeth.tooth2}) {
    for (std::size_t k = 1; k < tooth->roll.size(); ++k)
      EXPECT_GT(tooth->compliance[k], tooth->compliance[k - 1]) << k;
  }
  const double line = pair.line_length;
  const auto stiffness = [&](double s) {
    return contact::TeethPairStiffness(teeth, pair, s / pair.gear1.base_radius,
                                       (line - s) / pair.gear2.base_radius);
  };
  constexpr int kSamples = 200;
  double c_max = 0.0, s_max = 0.0;
  for (int i = 0; i <= kSamples; ++i) {
    const double s = pair.path_start + (pair.path_end - pair.path_start) * i / kSamples;
    if (stiffness(s) > c_max) {
      c_max = stiffness(s);
      s_max = s;
    }
  }
  const double length = pair.path_end - pair.path_start;
  const double c_start = stiffness(pair.path_start), c_end = stiffness(pair.path_end);
  const double s_pitch = pair.gear1.base_radius * std::tan(pair.working_pressure_angle);
  const double c_pitch = stiffness(s_pitch);
  const contact::IsoMeshStiffness iso = contact::IsoSinglePairStiffness(Wheel(20), Wheel(40));
  std::printf(
      "[measured] FE teeth (%ld + %ld nodes): c at start %.4g, max %.4g at %.3f of the path, end "
      "%.4g, pitch point (%.3f) %.4g N/(mm um); ISO c'_th %.4g, c' %.4g; FE c_pitch C_M C_B %.4g\n",
      fe1.nodes, fe2.nodes, c_start / kPerMmMicron, c_max / kPerMmMicron,
      (s_max - pair.path_start) / length, c_end / kPerMmMicron,
      (s_pitch - pair.path_start) / length, c_pitch / kPerMmMicron, iso.theoretical / kPerMmMicron,
      iso.single_pair / kPerMmMicron, c_pitch * iso.c_m * iso.c_b / kPerMmMicron);
  // Shape: the ends a third softer than the middle, the maximum inside the middle third.
  EXPECT_LT(c_start, 0.8 * c_max);                           // measured 0.66
  EXPECT_LT(c_end, 0.8 * c_max);                             // measured 0.68
  EXPECT_GT((s_max - pair.path_start) / length, 1.0 / 3.0);  // measured 0.565
  EXPECT_LT((s_max - pair.path_start) / length, 2.0 / 3.0);
  EXPECT_LT(std::abs(s_max - s_pitch), 0.15 * length);  // measured 0.041
  // Size: at the pitch point against ISO's c'_th.
  EXPECT_NEAR(c_pitch / iso.theoretical, 1.0, 0.15);  // measured +0.095
}

/// The FE teeth of the z 20/40 pair on the coarse mesh, computed once for the tests below.
const contact::ElasticTeeth& CoarseTeeth() {
  static const contact::ElasticTeeth teeth = [] {
    contact::ElasticTeeth t;
    t.tooth1 =
        ToothComplianceFromFe(contact::MakeSpurGear(Wheel(20), "gear 1"), t.material, Coarse())
            .compliance;
    t.tooth2 =
        ToothComplianceFromFe(contact::MakeSpurGear(Wheel(40), "gear 2"), t.material, Coarse())
            .compliance;
    return t;
  }();
  return teeth;
}

// Under a constant torque T on wheel 1 (wheel 2 held), the static transmission error of the
// FE-tooth mesh repeats with the mesh (2 pi / z1 of wheel 1), is T / (r_b1 b c(s)) in single and
// T / (r_b1 b (c(s) + c(s + p_b))) in double contact with c from the pairs' places on the path,
// and the share of double contact is epsilon_alpha - 1 (the involutes on the line of action
// alone, tip corners off: a pair enters the mesh at the path's start whatever the load;
// gear_corner_test.cc has the corners); each pair's two tooth deflections and the flattening add
// up to its penetration (the springs in series).
TEST(ToothFe, StaticTransmissionErrorVariesWithTheStiffnessAlongThePathAndRepeatsWithTheMesh) {
  const contact::GearPair pair = contact::MakeGearPair({Wheel(20), Wheel(40), 0.0, 0.0, false});
  const contact::MeshLaw law(pair, CoarseTeeth(), 0.0);
  const double r_b1 = pair.gear1.base_radius, r_b2 = pair.gear2.base_radius;
  const double torque = 400.0, a = pair.centre_distance;
  const double period = 2.0 * std::numbers::pi / 20;
  const int per_cycle = 400, cycles = 3;
  int doubles = 0;
  double worst_level = 0.0, worst_period = 0.0, worst_split = 0.0, single_max = 0.0,
         single_min = 1e30, double_max = 0.0;
  for (int i = 0; i < per_cycle; ++i) {
    const double phi1 = 0.05 + period * (i + 0.5) / per_cycle;
    const double ste = contact::StaticTransmissionError(pair, law, a, phi1, torque);
    const double phi2 =
        contact::TouchingAngle2(pair, a, phi1, 0.0, contact::FlankSide::kPositive) + ste / r_b2;
    const contact::MeshLoads loads = contact::EvaluateMesh(pair, law, a, phi1, phi2, 0.0, 0.0);
    double stiffness = 0.0;  // sum of c b over the pairs in contact
    for (const contact::ToothPairLoad& load : loads.pairs) {
      stiffness += law.PairLaw(load.pair).stiffness;
      const contact::ToothPairDeflection d = law.Deflection(load.pair, load.force);
      worst_split = std::max(worst_split,
                             std::abs((d.tooth1 + d.tooth2 + d.flattening) / -load.pair.gap - 1.0));
    }
    const double expected = torque / (r_b1 * stiffness);
    worst_level = std::max(worst_level, std::abs(ste / expected - 1.0));
    const bool is_double = loads.pairs.size() == 2;
    doubles += is_double;
    if (is_double) {
      double_max = std::max(double_max, ste);
    } else {
      single_max = std::max(single_max, ste);
      single_min = std::min(single_min, ste);
    }
    for (int k = 1; k < cycles; ++k) {
      const double later =
          contact::StaticTransmissionError(pair, law, a, phi1 + k * period, torque);
      worst_period = std::max(worst_period, std::abs(later / ste - 1.0));
    }
  }
  const double share = static_cast<double>(doubles) / per_cycle;
  std::printf(
      "[measured] FE-tooth STE under %.0f N m: single contact %.4g ... %.4g um, double up to %.4g "
      "um; against T / (r_b1 b sum c) %.2g, periodicity %.2g; double contact %.4f of the cycle, "
      "epsilon - 1 = %.4f; teeth' deflections and flattening add to the penetration to %.2g\n",
      torque, single_min * 1e6, single_max * 1e6, double_max * 1e6, worst_level, worst_period,
      share, pair.contact_ratio - 1.0, worst_split);
  // The bisection's round-off on the angles against delta ~ 1e-5 m: measured 3.7e-12, 5.7e-12.
  EXPECT_LT(worst_level, 4e-11);
  EXPECT_LT(worst_period, 6e-11);
  EXPECT_NEAR(share, pair.contact_ratio - 1.0, 1.0 / per_cycle);  // measured 2e-4 (sampling 2.5e-3)
  EXPECT_GT(single_min, 1.2 * double_max);                        // measured 1.65
  EXPECT_LT(worst_split, 5e-15);  // measured 4.4e-16
}

/// p turned by angle a [rad] about the wheel's centre.
Eigen::Vector2d Turned(const Eigen::Vector2d& p, double a) {
  return Eigen::Rotation2Dd(a) * p;
}

// On a three-tooth segment the line of action through the loaded tooth's load point k (along its
// normal) is also the neighbour's: the involute property (every right flank's normal at a point
// of a base tangent is that tangent) puts the tooth ahead (turned by -2 pi / z) on it at roll
// t_k + 2 pi / z with the same normal, the one behind at t_k - 2 pi / z; the neighbour points the
// FE model measures lie where that line crosses their centre lines (contact/gears' flank, no FE).
TEST(ToothFe, NeighboursMeetTheLoadedToothsLinesOfActionOnePitchOfRollAway) {
  const contact::SpurGear gear = contact::MakeSpurGear(Wheel(20), "gear");
  ToothGeometryOptions options;
  options.teeth = 3;
  const ToothGeometry g = MakeToothGeometry(gear, options, 7);
  const double pitch = 2.0 * std::numbers::pi / 20;
  ASSERT_EQ(g.ahead.size(), 7u);
  ASSERT_EQ(g.behind.size(), 7u);
  int valid = 0;
  double worst_point = 0.0, worst_normal = 0.0, worst_centre = 0.0;
  for (std::size_t k = 0; k < 7; ++k) {
    const Eigen::Vector2d across(-g.load_normal[k].y(), g.load_normal[k].x());
    for (const auto& [side, turn] : {std::pair{&g.ahead, -pitch}, std::pair{&g.behind, pitch}}) {
      const NeighbourPoint& c = (*side)[k];
      EXPECT_DOUBLE_EQ(c.roll, g.roll[k] - turn);
      if (!c.valid) continue;
      ++valid;
      const Eigen::Vector2d p = Turned(contact::ToothFlankPoint(gear, c.roll), turn);
      const Eigen::Vector2d n = Turned(contact::ToothFlankNormal(gear, c.roll), turn);
      worst_point = std::max(worst_point, std::abs((p - g.load_point[k]).dot(across)));
      worst_normal = std::max(worst_normal, (n - g.load_normal[k]).norm());
      const Eigen::Vector2d axis = Turned(Eigen::Vector2d::UnitY(), turn);
      worst_centre = std::max({worst_centre, std::abs((c.centre_point - g.load_point[k]).dot(across)),
                               std::abs(c.centre_point.x() * axis.y() - c.centre_point.y() * axis.x())});
    }
  }
  std::printf("[measured] %d neighbour points: flank off the line %.3g m, normal %.3g, centre point "
              "off the lines %.3g m\n",
              valid, worst_point, worst_normal, worst_centre);
  EXPECT_GE(valid, 6);
  EXPECT_LT(worst_point, 1e-16);   // measured 1.8e-17 m (round-off on 0.04 m)
  EXPECT_LT(worst_normal, 1e-15);  // measured 1.2e-16
  EXPECT_LT(worst_centre, 1e-16);  // measured 3.5e-18 m
  options.teeth = 2;
  EXPECT_NE(InputErrorMessage([&] { MakeToothGeometry(gear, options, 7); })
                .find("FE tooth segment: 2 teeth must be 1 or 3"),
            std::string::npos);
}

// A load on the loaded tooth moves its neighbours through the rim (ToothCouplingFromFe, coarse
// mesh). The neighbour carries no load, so it moves nearly as a rigid body, and along the line of
// action a rigid motion moves every point of the line alike: its centre point stands for its flank
// point, and Betti's reciprocity (the deflection ahead at t + 2 pi / z from a load at t equals the
// deflection behind at t from the same load at t + 2 pi / z) holds up to the neighbour's own
// deformation between flank and centre line.
TEST(ToothFe, NeighboursDeflectionsThroughTheRimAreReciprocal) {
  const double pitch = 2.0 * std::numbers::pi / 20;
  const contact::SpurGear gear = contact::MakeSpurGear(Wheel(20), "gear");
  const ToothCoupling c = ToothCouplingFromFe(gear, {}, Coarse());
  const ToothModelResult single = ToothComplianceFromFe(gear, {}, Coarse());
  const std::vector<double>& roll = c.rim.roll;
  const std::vector<double>& own = c.compliance.compliance;
  const auto behind_at = [&](double t) {  // behind[] linear in its load points' rolls
    for (std::size_t k = 0; k + 1 < roll.size(); ++k) {
      if (t >= roll[k] && t <= roll[k + 1] && std::isfinite(c.rim.behind[k]) &&
          std::isfinite(c.rim.behind[k + 1]))
        return c.rim.behind[k] +
               (c.rim.behind[k + 1] - c.rim.behind[k]) * (t - roll[k]) / (roll[k + 1] - roll[k]);
    }
    return std::numeric_limits<double>::quiet_NaN();
  };
  double worst = 0.0, ratio_lo = 1.0, ratio_hi = 0.0, own_lo = 1e9, own_hi = 0.0;
  int compared = 0;
  for (std::size_t k = 0; k < roll.size(); ++k) {
    own_lo = std::min(own_lo, own[k] / single.compliance.compliance[k]);
    own_hi = std::max(own_hi, own[k] / single.compliance.compliance[k]);
    if (!std::isfinite(c.rim.ahead[k])) continue;
    ratio_lo = std::min(ratio_lo, c.rim.ahead[k] / own[k]);
    ratio_hi = std::max(ratio_hi, c.rim.ahead[k] / own[k]);
    const double reciprocal = behind_at(roll[k] + pitch);
    if (!std::isfinite(reciprocal)) continue;
    ++compared;
    worst = std::max(worst, std::abs(c.rim.ahead[k] / reciprocal - 1.0));
  }
  std::printf("[measured] %ld nodes; the neighbour ahead deflects %.3f ... %.3f of the loaded "
              "tooth; Betti over %d loads: %.3g; the loaded tooth on three teeth / on one: %.4f "
              "... %.4f\n",
              c.nodes, ratio_lo, ratio_hi, compared, worst, own_lo, own_hi);
  EXPECT_GE(compared, 2);
  // Measured 0.109 over 3 loads (the unloaded neighbour's own bending between flank and centre
  // line); the neighbour ahead moves 0.170 ... 0.223 of the loaded tooth's deflection.
  EXPECT_LT(worst, 0.2);
  EXPECT_GT(ratio_lo, 0.0);
}

// Teeth coupled through their rims (both wheels' three-tooth segments, coarse): under T on wheel
// 1 the pairs in double contact solve delta 1 = C F together, so the static transmission error is
// T / (r_b1 1' C^-1 1) with C from the tables (c(t1, t2) b on the diagonal, the rims' cross terms
// off it, built here from the tables' public interpolations), above the same segments' teeth
// uncoupled; in single contact the coupling changes nothing.
TEST(ToothFe, CoupledPairsInDoubleContactShareTheRimsCompliance) {
  const contact::GearPair pair = contact::MakeGearPair({Wheel(20), Wheel(40), 0.0, 0.0, false});
  const ToothCoupling c1 = ToothCouplingFromFe(pair.gear1, {}, Coarse());
  const ToothCoupling c2 = ToothCouplingFromFe(pair.gear2, {}, Coarse());
  contact::ElasticTeeth teeth;
  teeth.tooth1 = c1.compliance;
  teeth.tooth2 = c2.compliance;
  const contact::MeshLaw alone(pair, teeth, 0.0);
  teeth.rim1 = c1.rim;
  teeth.rim2 = c2.rim;
  const contact::MeshLaw coupled(pair, teeth, 0.0);
  ASSERT_TRUE(coupled.coupled());
  ASSERT_FALSE(alone.coupled());
  const double r_b1 = pair.gear1.base_radius, b = 0.04, torque = 400.0, a = pair.centre_distance;
  const double period = 2.0 * std::numbers::pi / 20;
  double worst = 0.0, worst_single = 0.0, rise_lo = 1.0, rise_hi = 0.0;
  int doubles = 0, singles = 0;
  for (int i = 0; i < 40; ++i) {
    const double phi1 = 0.05 + period * (i + 0.5) / 40;
    const double ste = contact::StaticTransmissionError(pair, coupled, a, phi1, torque);
    const double ste_alone = contact::StaticTransmissionError(pair, alone, a, phi1, torque);
    const double phi2 =
        contact::TouchingAngle2(pair, a, phi1, 0.0, contact::FlankSide::kPositive) + ste / pair.gear2.base_radius;
    std::vector<contact::ToothPair> in;
    for (const contact::ToothPair& tp : contact::MeshingToothPairs(pair, a, phi1, phi2))
      if (tp.gap < 0.0) in.push_back(tp);
    if (in.size() == 1) {
      ++singles;
      worst_single = std::max(worst_single, std::abs(ste / ste_alone - 1.0));
      continue;
    }
    ASSERT_EQ(in.size(), 2u);
    ++doubles;
    const std::size_t A = in[0].roll1 > in[1].roll1 ? 0 : 1, B = 1 - A;
    Eigen::Matrix2d C;
    for (const std::size_t k : {A, B})
      C(k, k) = 1.0 / (contact::TeethPairStiffness(teeth, pair, in[k].roll1, in[k].roll2) * b);
    C(A, B) = (contact::RimCouplingAt(c1.rim.roll, c1.rim.ahead, in[B].roll1) +
               contact::RimCouplingAt(c2.rim.roll, c2.rim.behind, in[B].roll2)) / b;
    C(B, A) = (contact::RimCouplingAt(c1.rim.roll, c1.rim.behind, in[A].roll1) +
               contact::RimCouplingAt(c2.rim.roll, c2.rim.ahead, in[A].roll2)) / b;
    const double expected = torque / (r_b1 * (C.inverse() * Eigen::Vector2d::Ones()).sum());
    worst = std::max(worst, std::abs(ste / expected - 1.0));
    rise_lo = std::min(rise_lo, ste / ste_alone - 1.0);
    rise_hi = std::max(rise_hi, ste / ste_alone - 1.0);
  }
  std::printf("[measured] coupled STE against T / (r_b1 1' C^-1 1) over %d double-contact angles: "
              "%.3g; above the uncoupled segments by %.3f ... %.3f; %d single-contact angles "
              "unchanged to %.3g\n",
              doubles, worst, rise_lo, rise_hi, singles, worst_single);
  EXPECT_GT(doubles, 10);
  EXPECT_GT(singles, 5);
  EXPECT_LT(worst, 3e-11);          // measured 2.7e-12 (the bisection's round-off)
  EXPECT_LT(worst_single, 1e-15);  // measured 0 (the same law: one pair is never coupled)
  EXPECT_GT(rise_lo, 0.0);
}

TEST(ToothFe, RefusesAnOutlineOutOfRange) {
  const contact::SpurGear gear = contact::MakeSpurGear(Wheel(20), "gear");
  ToothModelOptions options = Coarse();
  options.geometry.rim_depth = 0.0;
  EXPECT_NE(InputErrorMessage([&] {
              ToothComplianceFromFe(gear, {}, options);
            }).find("FE tooth rim depth / m 0 must be"),
            std::string::npos);
  options = Coarse();
  options.geometry.segment_pitches = 5.0;
  const std::string wide = InputErrorMessage([&] { ToothComplianceFromFe(gear, {}, options); });
  EXPECT_NE(wide.find("FE tooth segment 5 pitches must be >= 0.5 and span less than 90 deg on 20 "
                      "teeth"),
            std::string::npos)
      << wide;
  const std::string material = InputErrorMessage([&] {
    ToothComplianceFromFe(gear, {-2e11, 0.3}, Coarse());
  });
  EXPECT_NE(material.find("FE tooth: material 'tooth'"), std::string::npos) << material;
}

}  // namespace
}  // namespace flexmbs::gear_tooth_fe
