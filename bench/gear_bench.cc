// A loaded spur gear pair (issue 18; docs/contact.md, "Spur gears"): steps per second of the
// rigid involute mesh (mbs/spur_gear_contact.h: the tooth pairs on the lines of action, their
// gaps in closed form) against a brute-force peer in the same run — the same pair and law with
// every tooth pair of the two wheels tried by a generic flank search: sampled flanks' boxes,
// then for the boxes that meet the deepest point of wheel 1's flank in wheel 2's tooth by
// nested golden-section searches (the search tests/contact/gear_mesh_test.cc takes as the
// reference of the gap), polished by Newton's method. The scene is
// tests/mbs/spur_gear_contact_test.cc's: 19/31 teeth, the pinion driven at 2 rad/s against 10 N m
// on the wheel, explicit, max_step 1e-4 s. Both runs cover the same simulated time from the same
// state; printed: steps, right-hand sides, CPU seconds of this process, the ratio of steps per
// second, the peer's largest gap error against the closed form and its contact points' distance
// from the closed form's, the angles where the two count different pairs in contact, and both runs'
// mean mesh force against T / r_b2. With --corners 1 the peer also lets wheel 1's tip corner
// touch wheel 2's flank beyond the path of contact, which the closed form leaves out. The same
// pair on massless elastic teeth (the FE tables of tests/support/driven_gear_pair.h), and with
// the tip corners off the line of action (the element's default; the rows above are the line's,
// tip_corners: false, as the peer), are timed beside the rigid flanks' constant c'; so are the
// elastic teeth coupled through the rims (the three-tooth FE tables) and with the flattening at
// each pair's load (the element's joint law).
//
// Movable teeth (mbs/movable_teeth_gear_contact.h: each tooth's deflection a state behind its own
// dashpot c_t) over one mesh period from 0.05 s (tip corners on, the element's default), against
// the quasi-static FE teeth of the same tables (SpurGearContact, damping 8e3 N s/m per pair) in
// the same run: steps, Newton iterations, CPU per simulated second and its ratio to the
// quasi-static teeth's explicit run, at tooth time constants c_t / k_t of 1e-6, 1e-5, 1e-4 s (k_t
// the pinion tooth's stiffness at the pitch point), implicit and explicit; and what the states
// change: the wheel's lag along the line of action against the static transmission error of the
// same teeth (contact::StaticTransmissionError on MeshLaw's quasi-static series, as
// tests/mbs/movable_teeth_test.cc measures it), largest and rms over the period. The reference is
// computed after each timed run, outside its CPU time.
//
//   bench_gears [--end 0.05] [--samples 32] [--repeat 5] [--corners 0] [--polish 1] [--movable 1]
#include <fmt/format.h>
#include <unistd.h>

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <Eigen/LU>
#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <ctime>
#include <filesystem>
#include <fstream>
#include <limits>
#include <memory>
#include <numbers>
#include <string>
#include <string_view>
#include <vector>

#include "contact/gears/gear_flank.h"
#include "contact/gears/gear_mesh.h"
#include "contact/gears/gear_mesh_force.h"
#include "contact/gears/movable_teeth.h"
#include "mbs/compliant_contact.h"
#include "mbs/gear_mesh_element.h"
#include "mbs/multibody_system.h"
#include "mbs/scene.h"
#include "mbs/simulation.h"
#include "mbs/spur_gear_contact.h"
#include "tests/support/driven_gear_pair.h"

namespace flexmbs::bench {
namespace {

constexpr double kTorque = 10.0;  // the wheel's load [N m]

struct Settings {
  double end_time = 0.05;  // simulated [s]
  int samples = 32;        // points per flank of the peer's grid
  int repeat = 5;          // runs of the closed-form mesh (the fastest kept)
  bool corners = false;    // the peer also takes wheel 1's tip corner on wheel 2's flank
  bool polish = true;      // the peer polishes its deepest points by Newton's method
  bool movable = true;     // the movable teeth' runs over a mesh period
};

/// The flank search's result for one tooth pair: the signed distance of wheel 1's flank point
/// deepest in wheel 2's tooth (< 0: penetration) and the middle of it and its nearest point.
struct FlankContact {
  double gap = std::numeric_limits<double>::infinity();
  Eigen::Vector2d p_O1C = Eigen::Vector2d::Zero();
  Eigen::Vector2d n_12 = Eigen::Vector2d::UnitX();
};

/// The minimiser of f on [lo, hi] by 60 golden-section steps (a bracket shrunk by 3e-13).
template <typename F>
double Golden(F f, double lo, double hi) {
  const double r = (std::sqrt(5.0) - 1.0) / 2.0;
  double x1 = hi - r * (hi - lo), x2 = lo + r * (hi - lo), f1 = f(x1), f2 = f(x2);
  for (int k = 0; k < 60; ++k) {
    if (f1 < f2) {
      hi = x2, x2 = x1, f2 = f1, x1 = hi - r * (hi - lo), f1 = f(x1);
    } else {
      lo = x1, x1 = x2, f1 = f2, x2 = lo + r * (hi - lo), f2 = f(x2);
    }
  }
  return 0.5 * (lo + hi);
}

/// The peer: the spur pair's mesh force by a generic search over every tooth pair, with the
/// same law at the same contact points as SpurGearContact (wheel 2 takes F n_12 in the middle of
/// the two flank points). For the bench's scene only: axes fixed and parallel to W's z.
class BruteForceMesh final : public mbs::ForceElement {
 public:
  BruteForceMesh(mbs::MarkerRef wheel1, mbs::MarkerRef wheel2, contact::GearPair pair,
                 contact::NormalLaw law, int samples, bool corners, bool polish)
      : wheel1_(wheel1),
        wheel2_(wheel2),
        pair_(std::move(pair)),
        samples_(samples),
        corners_(corners),
        polish_(polish),
        contact_(mbs::CompliantContactLaw{law, {}}, wheel2, wheel1) {}
  const std::string& name() const override { return name_; }

  void AddForces(double, const mbs::MultibodySystem& system, const mbs::ConstVectorRef& y,
                 Eigen::Ref<Eigen::VectorXd> h) const override {
    for (const mbs::ContactPoint& point : Contacts(system, y)) contact_.AddForces(system, point, h);
  }
  /// The sum of the pairs' normal forces [N] (SpurGearContact::MeshForce's measure).
  double MeshForce(const mbs::MultibodySystem& system, const mbs::ConstVectorRef& y) const {
    double force = 0.0;
    for (const mbs::ContactPoint& point : Contacts(system, y)) force += contact_.NormalForce(point);
    return force;
  }

  /// The contact points of the penetrating pairs Search finds at state y.
  std::vector<mbs::ContactPoint> Contacts(const mbs::MultibodySystem& system,
                                          const mbs::ConstVectorRef& y) const {
    const mbs::MarkerKinematics m1 = system.MarkerState(wheel1_, y),
                                m2 = system.MarkerState(wheel2_, y);
    const Eigen::Vector3d x_W = (m2.p_WM_W - m1.p_WM_W).normalized(),
                          y_W = Eigen::Vector3d::UnitZ().cross(x_W);
    const double a = (m2.p_WM_W - m1.p_WM_W).norm();
    const auto angle = [&](const mbs::MarkerKinematics& m) {
      return std::atan2(m.R_WM.col(0).dot(y_W), m.R_WM.col(0).dot(x_W));
    };
    std::vector<mbs::ContactPoint> points;
    for (const FlankContact& c : Search(a, angle(m1), angle(m2))) {
      if (!(c.gap < 0.0)) continue;
      mbs::ContactPoint point;
      point.a = m2;
      point.b = m1;
      point.n_W = c.n_12.x() * x_W + c.n_12.y() * y_W;
      point.p_Wc_W = m1.p_WM_W + c.p_O1C.x() * x_W + c.p_O1C.y() * y_W;
      point.penetration = -c.gap;
      points.push_back(point);
    }
    return points;
  }

  /// Newton's method (3 steps, difference quotients of 1e-7 rad) on the two conditions of the
  /// deepest point, from the golden sections' rolls: p1 - p2 normal to wheel 2's flank and the
  /// flanks' tangents parallel. Golden sections find a flat minimum's place to sqrt(eps) only;
  /// these conditions cross zero, so their roots are found to round-off. Ends at the rolls'
  /// bounds are left to the caller's checks.
  void Polish(int k1, int k2, contact::FlankSide side, double phi1, double phi2,
              const Eigen::Vector2d& o2, double* t1, double* t2) const {
    const auto perp = [](const Eigen::Vector2d& n) { return Eigen::Vector2d(-n.y(), n.x()); };
    const auto conditions = [&](double a, double b) {
      const Eigen::Vector2d n1 = contact::FlankNormal(pair_.gear1, k1, side, a, phi1),
                            n2 = contact::FlankNormal(pair_.gear2, k2, side, b, phi2);
      const Eigen::Vector2d d = contact::FlankPoint(pair_.gear1, k1, side, a, phi1) - o2 -
                                contact::FlankPoint(pair_.gear2, k2, side, b, phi2);
      return Eigen::Vector2d(d.dot(perp(n2)), perp(n1).dot(n2));
    };
    constexpr double kStep = 1e-7;
    for (int it = 0; it < 3; ++it) {
      const Eigen::Vector2d f = conditions(*t1, *t2);
      Eigen::Matrix2d jacobian;
      jacobian.col(0) = (conditions(*t1 + kStep, *t2) - f) / kStep;
      jacobian.col(1) = (conditions(*t1, *t2 + kStep) - f) / kStep;
      const Eigen::Vector2d step = jacobian.partialPivLu().solve(f);
      if (!step.allFinite() || step.cwiseAbs().maxCoeff() > 1e-3) return;  // keep golden's
      *t1 = std::clamp(*t1 - step(0), 0.0, pair_.gear1.tip_roll);
      *t2 = std::clamp(*t2 - step(1), 0.0, pair_.gear2.tip_roll);
    }
  }

  /// Every tooth pair (z1 z2 per side) whose sampled flanks' boxes, grown by 5e-4 m, meet: the
  /// grid's deepest sample of wheel 1's flank against wheel 2's samples, refined by golden
  /// sections within a grid cell (outer: wheel 1's roll, inner: wheel 2's nearest point).
  std::vector<FlankContact> Search(double a, double phi1, double phi2) const {
    const contact::SpurGear &g1 = pair_.gear1, &g2 = pair_.gear2;
    const int n = samples_;
    const Eigen::Vector2d o2(a, 0.0);
    const auto roll = [n](const contact::SpurGear& g, int i) { return g.tip_roll * i / (n - 1); };
    std::vector<FlankContact> found;
    for (const contact::FlankSide side :
         {contact::FlankSide::kPositive, contact::FlankSide::kNegative}) {
      const auto sampled = [&](const contact::SpurGear& g, const Eigen::Vector2d& o, double phi) {
        std::vector<Eigen::Matrix2Xd> flanks;
        for (int k = 0; k < g.spec.teeth; ++k) {
          Eigen::Matrix2Xd points(2, n);
          for (int i = 0; i < n; ++i)
            points.col(i) = o + contact::FlankPoint(g, k, side, roll(g, i), phi);
          flanks.push_back(points);
        }
        return flanks;
      };
      const std::vector<Eigen::Matrix2Xd> f1 = sampled(g1, Eigen::Vector2d::Zero(), phi1),
                                          f2 = sampled(g2, o2, phi2);
      constexpr double kMargin = 5e-4;
      for (int k1 = 0; k1 < g1.spec.teeth; ++k1) {
        const Eigen::Array2d lo1 = f1[k1].rowwise().minCoeff().array() - kMargin,
                             hi1 = f1[k1].rowwise().maxCoeff().array() + kMargin;
        for (int k2 = 0; k2 < g2.spec.teeth; ++k2) {
          const Eigen::Array2d lo2 = f2[k2].rowwise().minCoeff().array(),
                               hi2 = f2[k2].rowwise().maxCoeff().array();
          if ((hi2 < lo1).any() || (lo2 > hi1).any()) continue;
          const auto p1 = [&](double t) { return contact::FlankPoint(g1, k1, side, t, phi1); };
          const auto p2 = [&](double t) {
            return Eigen::Vector2d(o2 + contact::FlankPoint(g2, k2, side, t, phi2));
          };
          // Grid: per sample of wheel 1 the nearest sample of wheel 2, signed by its normal.
          double best = std::numeric_limits<double>::infinity();
          int i1 = 0, j1 = 0;
          for (int i = 0; i < n; ++i) {
            const Eigen::Index j = [&] {
              Eigen::Index nearest;
              (f2[k2].colwise() - f1[k1].col(i)).colwise().squaredNorm().minCoeff(&nearest);
              return nearest;
            }();
            const double d =
                (f1[k1].col(i) - f2[k2].col(j))
                    .dot(contact::FlankNormal(g2, k2, side, roll(g2, static_cast<int>(j)), phi2));
            if (d < best) best = d, i1 = i, j1 = static_cast<int>(j);
          }
          if (!(best < kMargin)) continue;
          const double w1 = g1.tip_roll / (n - 1), w2 = g2.tip_roll / (n - 1);
          const auto nearest2 = [&](double t1) {
            return Golden([&](double t2) { return (p1(t1) - p2(t2)).squaredNorm(); },
                          std::max(0.0, roll(g2, j1) - 2 * w2),
                          std::min(g2.tip_roll, roll(g2, j1) + 2 * w2));
          };
          const auto signed_distance = [&](double t1) {
            const double t2 = nearest2(t1);
            return (p1(t1) - p2(t2)).dot(contact::FlankNormal(g2, k2, side, t2, phi2));
          };
          double t1 = Golden(signed_distance, std::max(0.0, roll(g1, i1) - w1),
                             std::min(g1.tip_roll, roll(g1, i1) + w1));
          double t2 = nearest2(t1);
          if (polish_) Polish(k1, k2, side, phi1, phi2, o2, &t1, &t2);
          // A nearest point at wheel 2's base or tip: wheel 1's point lies beyond its flank.
          // The deepest point at wheel 1's base or tip: a corner, not involute on involute.
          const auto at_end = [](double t, const contact::SpurGear& g) {
            return t <= 1e-9 * g.tip_roll || t >= (1.0 - 1e-9) * g.tip_roll;
          };
          if (at_end(t2, g2) || (!corners_ && at_end(t1, g1))) continue;
          const Eigen::Vector2d n2 = contact::FlankNormal(g2, k2, side, t2, phi2);
          FlankContact c;
          c.gap = (p1(t1) - p2(t2)).dot(n2);
          c.p_O1C = 0.5 * (p1(t1) + p2(t2));
          c.n_12 = -n2;
          found.push_back(c);
        }
      }
    }
    return found;
  }

 private:
  std::string name_ = "mesh_brute_force";
  mbs::MarkerRef wheel1_, wheel2_;
  contact::GearPair pair_;
  int samples_;
  bool corners_;  ///< whether wheel 1's tip corner may touch wheel 2's flank
  bool polish_;   ///< whether Polish refines golden's rolls
  mbs::CompliantContact contact_;
};

/// The scene of `text`, through a file in the temporary folder.
mbs::Scene Load(const std::string& text) {
  const std::filesystem::path file =
      std::filesystem::temp_directory_path() /
      ("flexmbs_bench_gears_" + std::to_string(::getpid()) + ".yaml");
  std::ofstream(file) << text;
  mbs::Scene scene = mbs::LoadScene(file);
  std::filesystem::remove(file);
  return scene;
}

/// One timed run: steps, right-hand sides, Newton iterations (implicit), CPU seconds, the time
/// mean of the mesh force [N].
struct Run {
  long steps = 0, rhs = 0, newton = 0;
  double cpu = 0.0, mean_force = 0.0;
};

/// Runs `scene` once; `force` gives the mesh force at an output.
template <typename Force>
Run Time(mbs::Scene& scene, Force force) {
  double impulse = 0.0, last_t = 0.0, last_f = 0.0;
  bool first = true;
  const std::clock_t start = std::clock();
  const mbs::SimulationStatistics stats =
      mbs::Simulate(*scene.system, scene.options, scene.initial_state,
                    [&](double t, const Eigen::VectorXd& y, const Eigen::VectorXd&) {
                      const double f = force(t, y);
                      if (!first) impulse += 0.5 * (f + last_f) * (t - last_t);
                      first = false;
                      last_t = t;
                      last_f = f;
                    });
  Run run;
  run.cpu = static_cast<double>(std::clock() - start) / CLOCKS_PER_SEC;
  run.steps = stats.integrator.steps;
  run.rhs = stats.integrator.rhs_evaluations;
  run.newton = stats.integrator.newton_iterations;
  run.mean_force = impulse / (scene.options.end_time - scene.options.start_time);
  return run;
}

/// How the peer's search agrees with the closed form over one mesh cycle, 2 um into the driving
/// flanks: the largest gap difference and contact-point offset over the pairs in contact [m], how
/// many pairs were compared, and at how many angles the two count different pairs in contact.
struct SearchAgreement {
  static constexpr int kAngles = 1000;
  double gap_error = 0.0, point_offset = 0.0;
  int compared = 0, count_differs = 0;
};

/// SearchAgreement of `peer` for `pair`, the wheel touching at `start` [rad] when the pinion is at
/// 0 (BENCH_GEARS_DEBUG set: the angles where the counts differ, printed to stderr).
SearchAgreement CompareSearches(const BruteForceMesh& peer, const contact::GearPair& pair,
                                double start) {
  SearchAgreement agreement;
  for (int k = 0; k < SearchAgreement::kAngles; ++k) {
    const double phi1 = 2.0 * std::numbers::pi / 19.0 * k / SearchAgreement::kAngles;
    const double phi2 = contact::TouchingAngle2(pair, 0.0505, phi1, start - 19.0 / 31.0 * phi1,
                                                contact::FlankSide::kPositive) +
                        2e-6 / pair.gear2.base_radius;
    const std::vector<FlankContact> found = peer.Search(0.0505, phi1, phi2);
    int exact_count = 0, peer_count = 0;
    for (const FlankContact& c : found) peer_count += c.gap < 0.0;
    for (const contact::ToothPair& tp : contact::MeshingToothPairs(pair, 0.0505, phi1, phi2)) {
      if (!(tp.gap < 0.0)) continue;
      ++exact_count;
      double nearest = std::numeric_limits<double>::infinity();  // the peer's gap at the same point
      double gap = 0.0;
      for (const FlankContact& c : found) {
        if ((c.p_O1C - tp.p_O1C).norm() < nearest)
          nearest = (c.p_O1C - tp.p_O1C).norm(), gap = c.gap;
      }
      agreement.gap_error = std::max(agreement.gap_error, std::abs(gap - tp.gap));
      agreement.point_offset = std::max(agreement.point_offset, nearest);
      ++agreement.compared;
    }
    if (exact_count != peer_count) {
      ++agreement.count_differs;
      if (std::getenv("BENCH_GEARS_DEBUG")) {
        fmt::print(stderr, "phi1 {:.6f}: exact {} pairs, peer {}\n", phi1, exact_count, peer_count);
        for (const FlankContact& c : found)
          fmt::print(stderr, "  peer gap {:.3g} at ({:.6f}, {:.6f})\n", c.gap, c.p_O1C.x(),
                     c.p_O1C.y());
        for (const contact::ToothPair& tp : contact::MeshingToothPairs(pair, 0.0505, phi1, phi2))
          fmt::print(stderr, "  exact gap {:.3g} at ({:.6f}, {:.6f}) rolls {:.4f} {:.4f}\n", tp.gap,
                     tp.p_O1C.x(), tp.p_O1C.y(), tp.roll1, tp.roll2);
      }
    }
  }
  return agreement;
}

/// The fastest of `settings.repeat` runs of the driven pair with the mesh's `gear_keys`, the wheel
/// starting at `start` [rad].
Run BestRun(const Settings& settings, double start, const std::string& gear_keys) {
  Run best;
  for (int r = 0; r < settings.repeat; ++r) {
    mbs::Scene scene = Load(testing::DrivenGearPairScene(start, gear_keys, settings.end_time));
    const auto& element = dynamic_cast<const mbs::SpurGearContact&>(scene.system->force_element(1));
    const Run run = Time(scene, [&](double t, const Eigen::VectorXd& y) {
      return element.MeshForce(t, *scene.system, y);
    });
    if (r == 0 || run.cpu < best.cpu) best = run;
  }
  return best;
}

/// The movable teeth' window [s]: one mesh period of the pinion at 2 rad/s from 0.05 s (the
/// start-up settled).
constexpr double kSettled = 0.05;
constexpr double kMeshPeriod = 2.0 * std::numbers::pi / (19.0 * 2.0);

/// A timed run to the window's end and the wheel's lag along the line of action against the
/// static transmission error over the window's outputs: largest and rms difference, the largest
/// static error [m].
struct LagRun {
  Run run;
  double worst = 0.0, rms = 0.0, largest = 0.0;
  long samples = 0;
};

/// Runs the driven pair with the mesh's `gear_keys` (the wheel starting at `start` [rad]) by
/// `method` to the window's end, then compares the lag r_b2 (phi2 - phi2_0(phi1)) at each output
/// in the window with contact::StaticTransmissionError of `law` (outside the timed run).
LagRun LagAgainstStatic(double start, const std::string& gear_keys, mbs::OdeMethod method,
                        const contact::MeshLaw& law) {
  mbs::Scene scene = Load(testing::DrivenGearPairScene(start, gear_keys, kSettled + kMeshPeriod));
  scene.options.integrator.method = method;
  const auto& element = dynamic_cast<const mbs::GearMeshElement&>(scene.system->force_element(1));
  struct Angles {
    double centre_distance, phi1, phi2;
  };
  std::vector<Angles> window;
  LagRun out;
  out.run = Time(scene, [&](double t, const Eigen::VectorXd& y) {
    const mbs::GearMeshElement::Readout mesh = element.Read(t, *scene.system, y);
    if (t >= kSettled) window.push_back({mesh.centre_distance, mesh.phi1, mesh.phi2});
    double force = 0.0;
    for (const contact::ToothPairLoad& p : mesh.pairs) force += p.force;
    return force;
  });
  const contact::GearPair& pair = element.pair();
  const double torque1 = kTorque * pair.gear1.base_radius / pair.gear2.base_radius;
  double squares = 0.0;
  for (const Angles& w : window) {
    const double lag =
        pair.gear2.base_radius *
        std::remainder(w.phi2 - contact::TouchingAngle2(pair, w.centre_distance, w.phi1, w.phi2,
                                                        contact::FlankSide::kPositive),
                       2.0 * std::numbers::pi);
    const double ste =
        contact::StaticTransmissionError(pair, law, w.centre_distance, w.phi1, torque1);
    out.worst = std::max(out.worst, std::abs(lag - ste));
    squares += (lag - ste) * (lag - ste);
    out.largest = std::max(out.largest, ste);
  }
  out.samples = static_cast<long>(window.size());
  out.rms = std::sqrt(squares / static_cast<double>(window.size()));
  return out;
}

/// The movable teeth' table: the quasi-static FE teeth (explicit, the peer of the ratios, and
/// implicit) and the movable teeth at three time constants, implicit and explicit.
void MovableTeethRows(double start) {
  using testing::kDrivenPairFeTeeth, testing::kDrivenPairGearKeys;
  const std::string quasi_keys = std::string(kDrivenPairGearKeys) + kDrivenPairFeTeeth;
  const mbs::Scene probe = Load(testing::DrivenGearPairScene(start, quasi_keys, 0.01));
  const auto& quasi = dynamic_cast<const mbs::SpurGearContact&>(probe.system->force_element(1));
  const contact::GearPair& pair = quasi.pair();
  const contact::MeshLaw law(pair, *quasi.law().teeth(), 0.0);
  const double k_t = contact::ToothStiffness(contact::MovableTeeth{*quasi.law().teeth(), 1.0}, pair,
                                             1, contact::PitchRoll(pair, 0.0505));
  // The pair's keys without its per-pair damping (refused beside movable teeth).
  const std::string pair_damping = "    damping: 8e3\n";
  std::string movable_keys = kDrivenPairGearKeys;
  movable_keys.erase(movable_keys.find(pair_damping), pair_damping.size());
  movable_keys += kDrivenPairFeTeeth;

  fmt::print(
      "\nmovable teeth: {} s simulated, the lag against the static transmission error over "
      "one mesh period from {} s (k_t = {:.4g} N/m at the pitch point)\n",
      kSettled + kMeshPeriod, kSettled, k_t);
  fmt::print("{:<26} {:>8} {:>7} {:>8} {:>8} {:>11} {:>11} {:>9} {:>11} {:>11}\n", "teeth",
             "method", "steps", "newton", "cpu s", "steps/s", "cpu/sim s", "cpu ratio",
             "lag-STE max", "lag-STE rms");
  const LagRun peer = LagAgainstStatic(start, quasi_keys, mbs::OdeMethod::kExplicit, law);
  const double simulated = kSettled + kMeshPeriod;
  const auto row = [&](const std::string& name, mbs::OdeMethod method, const LagRun& r) {
    fmt::print(
        "{:<26} {:>8} {:>7} {:>8} {:>8.3f} {:>11.4g} {:>11.4g} {:>9.2f} {:>11.3g} {:>11.3g}\n",
        name, mbs::OdeMethodName(method), r.run.steps, r.run.newton, r.run.cpu,
        r.run.steps / r.run.cpu, r.run.cpu / simulated, r.run.cpu / peer.run.cpu, r.worst, r.rms);
  };
  row("quasi-static FE teeth", mbs::OdeMethod::kExplicit, peer);
  row("quasi-static FE teeth", mbs::OdeMethod::kImplicit,
      LagAgainstStatic(start, quasi_keys, mbs::OdeMethod::kImplicit, law));
  for (const double time_constant : {1e-6, 1e-5, 1e-4}) {
    const double damping = time_constant * k_t;
    const std::string keys =
        movable_keys + fmt::format("      movable: {{damping: {:.6g}}}\n", damping);
    for (const mbs::OdeMethod method : {mbs::OdeMethod::kImplicit, mbs::OdeMethod::kExplicit}) {
      row(fmt::format("movable, c_t/k_t {:.0e} s", time_constant), method,
          LagAgainstStatic(start, keys, method, law));
    }
  }
  fmt::print(
      "largest static transmission error {:.4g} m over {} outputs; cpu ratio: cpu time over "
      "the quasi-static FE teeth' explicit run's\n",
      peer.largest, peer.samples);
}

int Main(const Settings& settings) {
  using flexmbs::testing::DrivenGearPairScene, flexmbs::testing::kDrivenPairGearKeys;
  // The involutes on the line of action, as the peer searches them; the tip corners timed apart.
  const std::string line_keys = std::string(kDrivenPairGearKeys) + "    tip_corners: false\n";
  mbs::Scene exact = Load(DrivenGearPairScene(0.0, line_keys, settings.end_time));
  const auto* mesh = dynamic_cast<const mbs::SpurGearContact*>(&exact.system->force_element(1));
  const contact::GearPair pair = mesh->pair();
  const double start =
      contact::TouchingAngle2(pair, 0.0505, 0.0, 0.0, contact::FlankSide::kPositive);
  const contact::NormalLaw law = contact::ToothPairLaw({1.4e10, 8e3}, pair);
  const double load = kTorque / pair.gear2.base_radius;

  const BruteForceMesh peer_probe(exact.system->Marker("pinion", "axis"),
                                  exact.system->Marker("wheel", "axis"), pair, law,
                                  settings.samples, settings.corners, settings.polish);
  const SearchAgreement agreement = CompareSearches(peer_probe, pair, start);

  const Run best = BestRun(settings, start, line_keys);
  const Run corners = BestRun(settings, start, kDrivenPairGearKeys);
  const Run elastic = BestRun(settings, start, line_keys + testing::kDrivenPairFeTeeth);
  const Run coupled = BestRun(settings, start, line_keys + testing::kDrivenPairCoupledTeeth);
  const Run at_load = BestRun(
      settings, start, line_keys + testing::kDrivenPairFeTeeth + "      flattening: at_load\n");
  mbs::Scene brute = Load(DrivenGearPairScene(start, "", settings.end_time));
  brute.system->AddForceElement(std::make_unique<BruteForceMesh>(
      brute.system->Marker("pinion", "axis"), brute.system->Marker("wheel", "axis"), pair, law,
      settings.samples, settings.corners, settings.polish));
  const auto& peer = dynamic_cast<const BruteForceMesh&>(brute.system->force_element(1));
  const Run slow = Time(
      brute, [&](double, const Eigen::VectorXd& y) { return peer.MeshForce(*brute.system, y); });

  fmt::print("loaded spur pair 19/31, 10 N m, {} s simulated (explicit, max_step 1e-4 s)\n",
             settings.end_time);
  fmt::print("{:<34} {:>7} {:>8} {:>9} {:>11} {:>16}\n", "mesh", "steps", "rhs", "cpu s", "steps/s",
             "mean F/(T/r_b2)");
  const auto row = [&](const char* name, const Run& run) {
    fmt::print("{:<34} {:>7} {:>8} {:>9.4f} {:>11.4g} {:>16.6f}\n", name, run.steps, run.rhs,
               run.cpu, run.steps / run.cpu, run.mean_force / load);
  };
  row("closed form (SpurGearContact)", best);
  row("closed form with tip corners", corners);
  row("closed form, elastic FE teeth", elastic);
  row("  coupled through the rims", coupled);
  row("  flattening at load", at_load);
  row(fmt::format("brute force, {} samples per flank", settings.samples).c_str(), slow);
  fmt::print(
      "steps/s ratio closed form / brute force: {:.1f}; rigid / elastic teeth: {:.2f}; "
      "elastic / coupled: {:.2f}; elastic / at load: {:.2f}\n",
      (best.steps / best.cpu) / (slow.steps / slow.cpu),
      (best.steps / best.cpu) / (elastic.steps / elastic.cpu),
      (elastic.steps / elastic.cpu) / (coupled.steps / coupled.cpu),
      (elastic.steps / elastic.cpu) / (at_load.steps / at_load.cpu));
  fmt::print(
      "brute force over one mesh cycle 2 um deep ({} angles, {} pairs in contact): largest gap "
      "error {:.3g} m, contact point offset {:.3g} m; pairs in contact counted differently at {} "
      "angles\n",
      SearchAgreement::kAngles, agreement.compared, agreement.gap_error, agreement.point_offset,
      agreement.count_differs);
  if (settings.movable) MovableTeethRows(start);
  return 0;
}

}  // namespace
}  // namespace flexmbs::bench

int main(int argc, char** argv) {
  flexmbs::bench::Settings settings;
  for (int i = 1; i + 1 < argc; i += 2) {
    const std::string_view key = argv[i];
    if (key == "--end") {
      settings.end_time = std::atof(argv[i + 1]);
    } else if (key == "--samples") {
      settings.samples = std::atoi(argv[i + 1]);
    } else if (key == "--polish") {
      settings.polish = std::atoi(argv[i + 1]) != 0;
    } else if (key == "--corners") {
      settings.corners = std::atoi(argv[i + 1]) != 0;
    } else if (key == "--repeat") {
      settings.repeat = std::atoi(argv[i + 1]);
    } else if (key == "--movable") {
      settings.movable = std::atoi(argv[i + 1]) != 0;
    } else {
      fmt::print(stderr,
                 "usage: bench_gears [--end 0.05] [--samples 32] [--repeat 5] [--corners 0] "
                 "[--polish 0] [--movable 1]\n");
      return 2;
    }
  }
  return flexmbs::bench::Main(settings);
}
