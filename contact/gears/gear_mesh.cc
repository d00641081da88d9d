#include "contact/gears/gear_mesh.h"

#include <cmath>
#include <limits>
#include <numbers>

#include "core/error.h"

namespace flexmbs::contact {
namespace {

/// Tooth index sigma i mod z of the i-th roll angle t = t_0 + i 2 pi / z.
int ToothIndex(double sigma, long i, int teeth) {
  const long k = (static_cast<long>(sigma) * i) % teeth;
  return static_cast<int>(k < 0 ? k + teeth : k);
}

/// Tooth pair `tp` (its side, teeth, line rolls) turned into a tip corner's contact: wheel 2's
/// corner on wheel 1's flank (`corner_of_2`) or wheel 1's on wheel 2's, at centre distance a and
/// angles phi1, phi2. False where the foot lies off the other flank.
bool MakeCorner(const GearPair& pair, double a, double phi1, double phi2, bool corner_of_2,
                ToothPair& tp) {
  const SpurGear& g1 = pair.gear1;
  const SpurGear& g2 = pair.gear2;
  const Eigen::Vector2d p_O1O2(a, 0.0);
  if (corner_of_2) {
    const Eigen::Vector2d p_O1P = p_O1O2 + FlankPoint(g2, tp.tooth2, tp.side, g2.tip_roll, phi2);
    const FlankFoot foot = FootOnFlank(g1, tp.tooth1, tp.side, phi1, p_O1P);
    if (foot.roll < 0.0 || foot.roll > g1.tip_roll) return false;
    tp.contact = ToothContact::kTip2OnFlank1;
    tp.roll1 = foot.roll;
    tp.roll2 = g2.tip_roll;
    tp.p_O1C = p_O1P - 0.5 * foot.gap * foot.normal;
    tp.n_12 = foot.normal;
    tp.gap = foot.gap;
  } else {
    const Eigen::Vector2d p_O1P = FlankPoint(g1, tp.tooth1, tp.side, g1.tip_roll, phi1);
    const FlankFoot foot = FootOnFlank(g2, tp.tooth2, tp.side, phi2, p_O1P - p_O1O2);
    if (foot.roll < 0.0 || foot.roll > g2.tip_roll) return false;
    tp.contact = ToothContact::kTip1OnFlank2;
    tp.roll1 = g1.tip_roll;
    tp.roll2 = foot.roll;
    tp.p_O1C = p_O1P - 0.5 * foot.gap * foot.normal;
    tp.n_12 = -foot.normal;
    tp.gap = foot.gap;
  }
  tp.gap += TipRelief(g1, tp.roll1) + TipRelief(g2, tp.roll2);
  return true;
}

/// Appends the tooth pairs on one side (MeshingToothPairs).
void AddSide(const GearPair& pair, double a, double phi1, double phi2, FlankSide side,
             std::vector<ToothPair>& out) {
  const SpurGear& g1 = pair.gear1;
  const SpurGear& g2 = pair.gear2;
  const double sigma = Sign(side);
  const double alpha_w = std::acos((g1.base_radius + g2.base_radius) / a);
  const double line = a * std::sin(alpha_w);
  const double centre = PairBacklash(pair, a) / 2.0;
  const double step1 = 2.0 * std::numbers::pi / g1.spec.teeth;
  const double step2 = 2.0 * std::numbers::pi / g2.spec.teeth;
  const double base1 = alpha_w + sigma * phi1 + g1.base_half_angle;
  const double base2 = alpha_w + std::numbers::pi + sigma * phi2 + g2.base_half_angle;
  const Eigen::Vector2d n(std::cos(alpha_w), -sigma * std::sin(alpha_w));
  const Eigen::Vector2d e(std::sin(alpha_w), sigma * std::cos(alpha_w));
  // With corners, the line's points up to a pitch beyond either tip: a corner stands off the
  // mating flank by about the distance beyond it, so one further off never touches.
  const double beyond = pair.tip_corners ? step1 : 0.0;
  const long first = static_cast<long>(std::ceil((-beyond - base1) / step1));
  const long last = static_cast<long>(std::floor((g1.tip_roll + beyond - base1) / step1));
  for (long i1 = first; i1 <= last; ++i1) {
    ToothPair tp;
    tp.side = side;
    tp.roll1 = base1 + static_cast<double>(i1) * step1;
    const double s1 = g1.base_radius * tp.roll1;
    // Wheel 2's flank expected at s1 + half the backlash: the nearest of its flanks, p_b apart.
    const double target = (line - s1 - centre) / g2.base_radius;
    const long i2 = std::lround((target - base2) / step2);
    tp.roll2 = base2 + static_cast<double>(i2) * step2;
    tp.tooth1 = ToothIndex(sigma, i1, g1.spec.teeth);
    tp.tooth2 = ToothIndex(sigma, i2, g2.spec.teeth);
    const bool on1 = tp.roll1 >= 0.0 && tp.roll1 <= g1.tip_roll;
    const bool on2 = tp.roll2 >= 0.0 && tp.roll2 <= g2.tip_roll;
    if (!on1 || !on2) {
      const bool corner_of_2 = tp.roll1 <= g1.tip_roll && tp.roll2 > g2.tip_roll;
      const bool corner_of_1 = tp.roll2 <= g2.tip_roll && tp.roll1 > g1.tip_roll;
      if (pair.tip_corners && (corner_of_1 || corner_of_2) &&
          MakeCorner(pair, a, phi1, phi2, corner_of_2, tp))
        out.push_back(tp);
      continue;
    }
    const double s2 = line - g2.base_radius * tp.roll2;
    tp.gap = s2 - s1 + TipRelief(g1, tp.roll1) + TipRelief(g2, tp.roll2);
    tp.p_O1C = g1.base_radius * n + 0.5 * (s1 + s2) * e;
    tp.n_12 = e;
    out.push_back(tp);
  }
}

}  // namespace

std::vector<ToothPair> MeshingToothPairs(const GearPair& pair, double centre_distance, double phi1,
                                         double phi2) {
  FLEXMBS_CHECK(centre_distance > pair.gear1.base_radius + pair.gear2.base_radius &&
                    std::isfinite(centre_distance),
                "a gear pair's centre distance must exceed the sum of the base radii");
  std::vector<ToothPair> pairs;
  AddSide(pair, centre_distance, phi1, phi2, FlankSide::kPositive, pairs);
  AddSide(pair, centre_distance, phi1, phi2, FlankSide::kNegative, pairs);
  return pairs;
}

double SmallestGap(const std::vector<ToothPair>& pairs, FlankSide side) {
  double smallest = std::numeric_limits<double>::infinity();
  for (const ToothPair& tp : pairs) {
    if (tp.side == side && tp.contact == ToothContact::kFlanks) smallest = std::min(smallest, tp.gap);
  }
  return smallest;
}

double TouchingAngle2(const GearPair& pair, double centre_distance, double phi1, double phi2_guess,
                      FlankSide side) {
  const double sigma = Sign(side);
  const double half_pitch = std::numbers::pi / pair.gear2.spec.teeth;
  double phi2 = phi2_guess;
  for (int i = 0; i < 20; ++i) {
    const double gap = SmallestGap(MeshingToothPairs(pair, centre_distance, phi1, phi2), side);
    if (!std::isfinite(gap)) {  // no pair on this side at this angle: try half a pitch on
      phi2 += half_pitch;
      continue;
    }
    phi2 += sigma * gap / pair.gear2.base_radius;
    if (std::abs(gap) <= 1e-15 * centre_distance) return phi2;
  }
  FLEXMBS_CHECK(false, "TouchingAngle2 did not close the gap in 20 steps");
  return phi2;
}

}  // namespace flexmbs::contact
