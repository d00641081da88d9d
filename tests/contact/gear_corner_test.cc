// contact/gears: a tooth's tip corner against the mating flank off the line of action, against
// an independent computation in SciPy (tests/contact/gear_corner_reference.py: the teeth in
// ISO 21771's polar form, a dense polygon of the flank and the nearest point by brute force; the
// start of contact where the tip circle cuts the lagged involute), and the static transmission
// error it smooths at the mesh's switches.
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <limits>
#include <numbers>
#include <sstream>
#include <string>
#include <vector>

#include "contact/gears/gear_mesh.h"
#include "contact/gears/gear_mesh_force.h"

namespace flexmbs::contact {
namespace {

constexpr double kDeg = std::numbers::pi / 180.0;
constexpr double kCentre = 0.0505;  // a [m]

/// m 2 mm, z 19 (x 0.3) and 31 (x -0.1), b 20 mm at a = 50.5 mm (1.0e-4 m of backlash).
GearPair Pair(bool tip_corners) {
  GearPairSpec spec;
  spec.gear1 = SpurGearSpec{2e-3, 19, 20.0 * kDeg, 0.3, 1.0, 1.25, 0.02};
  spec.gear2 = SpurGearSpec{2e-3, 31, 20.0 * kDeg, -0.1, 1.0, 1.25, 0.02};
  spec.centre_distance = kCentre;
  spec.tip_corners = tip_corners;
  return MakeGearPair(spec);
}

/// Runs the reference script on `input`; its lines of numbers, or empty with a skip reason.
std::vector<std::vector<double>> RunReference(const std::string& input, std::string* skip) {
  const std::filesystem::path python = "/usr/bin/python3";
  const std::filesystem::path script =
      std::filesystem::path(FLEXMBS_SOURCE_DIR) / "tests/contact/gear_corner_reference.py";
  if (!std::filesystem::exists(python)) {
    *skip = "no /usr/bin/python3";
    return {};
  }
  const std::filesystem::path in = std::filesystem::temp_directory_path() /
                                   ("flexmbs_gear_corner_" + std::to_string(::getpid()) + ".txt");
  {
    std::FILE* file = std::fopen(in.c_str(), "w");
    std::fputs(input.c_str(), file);
    std::fclose(file);
  }
  const std::string command = python.string() + " " + script.string() + " < " + in.string();
  std::FILE* pipe = ::popen(command.c_str(), "r");
  std::string output;
  std::array<char, 4096> buffer{};
  while (pipe != nullptr && std::fgets(buffer.data(), buffer.size(), pipe) != nullptr)
    output += buffer.data();
  const int status = pipe != nullptr ? ::pclose(pipe) : -1;
  std::filesystem::remove(in);
  if (!WIFEXITED(status) || WEXITSTATUS(status) != 0) {
    *skip = "the reference script failed (SciPy missing?): " + command;
    return {};
  }
  std::vector<std::vector<double>> rows;
  std::istringstream lines(output);
  for (std::string line; std::getline(lines, line);) {
    std::istringstream numbers(line);
    std::vector<double> row;
    for (double v; numbers >> v;) row.push_back(v);
    rows.push_back(row);
  }
  return rows;
}

std::string PairLine() {
  char line[128];
  std::snprintf(line, sizeof line, "pair 2e-3 19 0.3 31 -0.1 %.17g 1.0 %.17g\n", 20.0 * kDeg,
                kCentre);
  return line;
}

/// Wheel 2's angle where the flanks on `side` overlap by delta [m] along the line of action.
double LaggedPhi2(const GearPair& pair, double phi1, double delta, FlankSide side) {
  return TouchingAngle2(pair, kCentre, phi1, 0.0, side) +
         Sign(side) * delta / pair.gear2.base_radius;
}

int Kind(const ToothPair& tp) { return tp.contact == ToothContact::kTip1OnFlank2 ? 1 : 2; }

// Wheel 1 turned through a mesh cycle with wheel 2 at 0, 10 and 30 um of overlap on either side:
// every corner within 0.1 mm of the other flank, its gap, foot and normal against the brute
// force on a 40001-point polygon of that flank, built from ISO 21771's polar form.
TEST(GearCorner, GapFootAndNormalAreTheBruteForceNearestPointOfThePolygonFlank) {
  const GearPair pair = Pair(true);
  std::ostringstream input;
  input.precision(17);
  input << PairLine();
  struct Seen {
    ToothPair tp;
    double phi1, phi2;
  };
  std::vector<Seen> seen;
  for (const FlankSide side : {FlankSide::kPositive, FlankSide::kNegative}) {
    for (const double delta : {0.0, 1e-5, 3e-5}) {
      for (int i = 0; i < 60; ++i) {
        const double phi1 = 0.1 + (2.0 * std::numbers::pi / 19) * i / 60.0;
        const double phi2 = LaggedPhi2(pair, phi1, delta, side);
        for (const ToothPair& tp : MeshingToothPairs(pair, kCentre, phi1, phi2)) {
          if (tp.contact == ToothContact::kFlanks || tp.side != side || tp.gap > 1e-4) continue;
          seen.push_back({tp, phi1, phi2});
          input << "corner " << Sign(side) << " " << Kind(tp) << " " << tp.tooth1 << " "
                << tp.tooth2 << " " << phi1 << " " << phi2 << "\n";
        }
      }
    }
  }
  std::string skip;
  const auto rows = RunReference(input.str(), &skip);
  if (!skip.empty()) GTEST_SKIP() << skip;
  ASSERT_EQ(rows.size(), seen.size());
  double worst_gap = 0.0, worst_foot = 0.0, worst_normal = 0.0, deepest = 0.0;
  int kinds[3] = {0, 0, 0};
  for (std::size_t k = 0; k < seen.size(); ++k) {
    const ToothPair& tp = seen[k].tp;
    ASSERT_EQ(rows[k].size(), 5u);
    const bool corner_of_2 = tp.contact == ToothContact::kTip2OnFlank1;
    ++kinds[Kind(tp)];
    const Eigen::Vector2d foot =
        corner_of_2 ? FlankPoint(pair.gear1, tp.tooth1, tp.side, tp.roll1, seen[k].phi1)
                    : Eigen::Vector2d(Eigen::Vector2d(kCentre, 0.0) +
                                      FlankPoint(pair.gear2, tp.tooth2, tp.side, tp.roll2,
                                                 seen[k].phi2));
    // The reference's normal points out of the flank's tooth: wheel 1's is n_12, wheel 2's -n_12.
    const Eigen::Vector2d normal = corner_of_2 ? tp.n_12 : Eigen::Vector2d(-tp.n_12);
    worst_gap = std::max(worst_gap, std::abs(tp.gap - rows[k][0]));
    worst_foot = std::max(worst_foot, (foot - Eigen::Vector2d(rows[k][1], rows[k][2])).norm());
    worst_normal =
        std::max(worst_normal, (normal - Eigen::Vector2d(rows[k][3], rows[k][4])).norm());
    deepest = std::min(deepest, tp.gap);
  }
  std::printf(
      "[measured] %zu corners (%d of wheel 1, %d of wheel 2, deepest %.3g m) against the polygon: "
      "gap %.3g m, foot %.3g m, normal %.3g\n",
      seen.size(), kinds[1], kinds[2], deepest, worst_gap, worst_foot, worst_normal);
  EXPECT_GT(kinds[1], 10);
  EXPECT_GT(kinds[2], 10);
  EXPECT_LT(deepest, -1e-6);  // some corners overlap the flank (under the 30 um lag)
  EXPECT_LT(worst_gap, 2e-12);    // measured 1.9e-13 m (the polygon's sag ~5e-13 m)
  EXPECT_LT(worst_foot, 1e-8);    // measured 7.6e-10 m (a segment 2.2e-7 m long)
  EXPECT_LT(worst_normal, 1e-4);  // measured 8.5e-6 (a segment turns its tangent by 1.75e-5)
}

/// The gap [m] of the tooth pair of teeth k1, k2 on the positive side if it is listed as
/// `contact`, NaN otherwise, at wheel 1's angle phi1 with the flanks delta into each other.
double PairGap(const GearPair& pair, double phi1, double delta, int k1, int k2,
               ToothContact contact) {
  for (const ToothPair& tp :
       MeshingToothPairs(pair, kCentre, phi1, LaggedPhi2(pair, phi1, delta, FlankSide::kPositive))) {
    if (tp.side == FlankSide::kPositive && tp.tooth1 == k1 && tp.tooth2 == k2 &&
        tp.contact == contact)
      return tp.gap;
  }
  return std::numeric_limits<double>::quiet_NaN();
}

/// Wheel 1's angles where a corner of kind `contact` of the positive side starts touching (its
/// gap crossing 0, bisected to 1e-15 rad) over one mesh cycle, with its teeth.
struct Crossing {
  double phi1;
  int tooth1, tooth2;
};
std::vector<Crossing> CornerCrossings(const GearPair& pair, double delta, ToothContact contact) {
  std::vector<Crossing> found;
  const double period = 2.0 * std::numbers::pi / 19;
  const int steps = 2000;
  for (int i = 0; i < steps; ++i) {
    const double lo = 0.1 + period * i / steps, hi = lo + period / steps;
    for (const ToothPair& tp : MeshingToothPairs(pair, kCentre, lo,
                                                 LaggedPhi2(pair, lo, delta, FlankSide::kPositive))) {
      if (tp.side != FlankSide::kPositive || tp.contact != contact) continue;
      const auto gap = [&](double phi1) {
        return PairGap(pair, phi1, delta, tp.tooth1, tp.tooth2, contact);
      };
      const double g_lo = gap(lo), g_hi = gap(hi);
      if (!(g_lo * g_hi < 0.0)) continue;
      double a = lo, b = hi;
      while (b - a > 1e-15) {
        const double mid = 0.5 * (a + b);
        ((gap(mid) < 0.0) == (g_lo < 0.0) ? a : b) = mid;
      }
      found.push_back({0.5 * (a + b), tp.tooth1, tp.tooth2});
    }
  }
  return found;
}

// Under a deflection delta (wheel 2 lagging the rigid pair along the line of action), a pair
// starts touching where wheel 2's tip circle cuts wheel 1's involute, before the line of action
// reaches the path's start s_A, and stops where wheel 1's tip circle leaves wheel 2's involute,
// after s_E: wheel 1's angle at both against the polar form's intersection (SciPy brentq).
TEST(GearCorner, LoadedPairEntersWhereTheTipCircleCutsTheLaggedInvolute) {
  const GearPair pair = Pair(true);
  std::ostringstream input;
  input.precision(17);
  input << PairLine();
  struct Case {
    double delta;
    int kind;
    Crossing crossing;
  };
  std::vector<Case> cases;
  for (const double delta : {4e-6, 2e-5}) {
    for (const ToothContact contact : {ToothContact::kTip2OnFlank1, ToothContact::kTip1OnFlank2}) {
      const int kind = contact == ToothContact::kTip1OnFlank2 ? 1 : 2;
      const std::vector<Crossing> found = CornerCrossings(pair, delta, contact);
      ASSERT_EQ(found.size(), 1u) << "delta " << delta << " kind " << kind;
      cases.push_back({delta, kind, found[0]});
      input << "start 1 " << kind << " " << found[0].tooth1 << " " << found[0].tooth2 << " "
            << delta << " " << found[0].phi1 - 0.005 << " " << found[0].phi1 + 0.005 << "\n";
    }
  }
  std::string skip;
  const auto rows = RunReference(input.str(), &skip);
  if (!skip.empty()) GTEST_SKIP() << skip;
  ASSERT_EQ(rows.size(), cases.size());
  double worst = 0.0;
  for (std::size_t k = 0; k < cases.size(); ++k) {
    ASSERT_EQ(rows[k].size(), 1u);
    const Case& c = cases[k];
    // Where the line of action's point of wheel 1's flank then is, against the path's ends.
    const double t1 = pair.working_pressure_angle + c.crossing.phi1 +
                      2.0 * std::numbers::pi * c.crossing.tooth1 / 19 +
                      pair.gear1.base_half_angle;
    const double s = pair.gear1.base_radius * std::remainder(t1, 2.0 * std::numbers::pi);
    std::printf(
        "[measured] delta %.3g m, %s: phi1 %.15f against the polar form's %.15f (%.3g rad); the "
        "line's point at %.4f mm, %.4f mm %s the path's %s\n",
        c.delta, c.kind == 2 ? "wheel 2's corner enters" : "wheel 1's corner leaves",
        c.crossing.phi1, rows[k][0], c.crossing.phi1 - rows[k][0], s * 1e3,
        std::abs(c.kind == 2 ? pair.path_start - s : s - pair.path_end) * 1e3,
        c.kind == 2 ? "before" : "after", c.kind == 2 ? "start s_A" : "end s_E");
    worst = std::max(worst, std::abs(c.crossing.phi1 - rows[k][0]));
    // Outside the rigid path: entering before s_A, leaving after s_E.
    if (c.kind == 2) {
      EXPECT_LT(s, pair.path_start);
    } else {
      EXPECT_GT(s, pair.path_end);
    }
  }
  EXPECT_LT(worst, 4e-13);  // measured 3.7e-14 rad (bisection 1e-15; brentq xtol 1e-16)
}

// Under T = 20 N m on teeth of c' = 1.4e10 N/m^2 (delta = T / (r_b1 c' b) = 4.0 um in single
// contact), a pair takes load from where wheel 2's corner meets wheel 1's flank under the single
// pair's deflection until wheel 1's corner leaves wheel 2's flank under it (the other pair alone
// then carries T): double contact grows from epsilon_alpha - 1 to the share those two crossings
// give (CornerCrossings at delta, checked against SciPy above), and the transmission error runs
// on without the line model's step of delta / 2 at each switch.
TEST(GearCorner, LoadedMeshSharesTheLoadOverTheExtendedPathAndItsTransmissionErrorHasNoStep) {
  const GearPair corners = Pair(true), line = Pair(false);
  const NormalLaw law = ToothPairLaw({}, corners);
  const double r_b1 = corners.gear1.base_radius, torque = 20.0;
  const double single = torque / (r_b1 * 1.4e10 * 0.02);
  const double period = 2.0 * std::numbers::pi / 19;
  const auto enter = CornerCrossings(corners, single, ToothContact::kTip2OnFlank1);
  const auto leave = CornerCrossings(corners, single, ToothContact::kTip1OnFlank2);
  ASSERT_EQ(enter.size(), 1u);
  ASSERT_EQ(leave.size(), 1u);
  const double single_span = std::remainder(enter[0].phi1 - leave[0].phi1, period);
  const double expected = 1.0 - (single_span < 0.0 ? single_span + period : single_span) / period;
  const int samples = 2000;
  int doubles = 0;
  double step_line = 0.0, step_corners = 0.0, below = 0.0, last_line = 0.0, last_corners = 0.0;
  for (int i = 0; i <= samples; ++i) {
    const double phi1 = 0.1 + period * i / samples;
    const double ste_line = StaticTransmissionError(line, law, kCentre, phi1, torque);
    const double ste = StaticTransmissionError(corners, law, kCentre, phi1, torque);
    below = std::max(below, ste - ste_line);  // the corners only add contacts
    if (i > 0) {
      step_line = std::max(step_line, std::abs(ste_line - last_line));
      step_corners = std::max(step_corners, std::abs(ste - last_corners));
    }
    last_line = ste_line;
    last_corners = ste;
    if (i == samples) break;
    const double phi2 = TouchingAngle2(corners, kCentre, phi1, 0.0, FlankSide::kPositive) +
                        ste / corners.gear2.base_radius;
    doubles += EvaluateMesh(corners, law, kCentre, phi1, phi2, 0.0, 0.0).pairs.size() >= 2;
  }
  const double share = static_cast<double>(doubles) / samples;
  std::printf(
      "[measured] double contact %.4f of the cycle against %.4f from the corners' crossings "
      "(epsilon_alpha - 1 = %.4f on the line alone); largest STE step between samples %.3g m "
      "against the line's %.3g m (delta / 2 = %.3g m); STE above the line's by at most %.3g m\n",
      share, expected, corners.contact_ratio - 1.0, step_corners, step_line, single / 2.0, below);
  EXPECT_NEAR(share, expected, 2.0 / samples);  // measured 0.5695 against 0.5697 (sampling 5e-4)
  EXPECT_GT(share, corners.contact_ratio - 1.0 + 0.05);
  EXPECT_GT(step_line, 0.45 * single);
  EXPECT_LT(step_corners, 0.05 * single);  // measured 4.3e-8 m = 0.011 delta (2000 samples)
  EXPECT_LT(below, 1e-15);
}

}  // namespace
}  // namespace flexmbs::contact
