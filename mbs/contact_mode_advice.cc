#include "mbs/contact_mode_advice.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <memory>
#include <numbers>
#include <optional>
#include <utility>

#include "core/error.h"
#include "core/rotation.h"
#include "mbs/contact_mode_advice_pcm.h"
#include "mbs/flexible_body.h"
#include "mbs/joint.h"
#include "mbs/surface_contact_force.h"
#include "mbs/surface_state.h"
#include "mbs/unilateral_contact.h"

namespace flexmbs::mbs {
namespace {

/// One point of a pair at the start: its gap g_N [m] (< 0 penetrating), normal from B to A, place
/// [m], gap rate n . v_rel [m/s], and per end the modal row n^T R sum_i w_i phi_i (empty for an end
/// that is not a reduced body's surface point).
struct PairPoint {
  double gap = 0.0;
  Eigen::Vector3d n_W = Eigen::Vector3d::UnitZ();
  Eigen::Vector3d p_W = Eigen::Vector3d::Zero();
  double gap_rate = 0.0;
  Eigen::RowVectorXd modal_a, modal_b;
};

/// A pair at the start: its name and type, its two bodies (kGround for the ground), its points,
/// and its law's k [N/m^n] and n (none for a unilateral contact; a PCM pair's fitted from its
/// probe once the effective mass and speed are known, its one point the first touch).
struct Pair {
  std::string name, type;
  int body_a = kGround, body_b = kGround;
  std::vector<PairPoint> points;
  bool unilateral = false;
  double stiffness = 0.0, exponent = 1.0;
  std::shared_ptr<const PcmTouchProbe> pcm;
};

PairPoint FromContactPoint(const ContactPoint& point) {
  PairPoint p;
  p.gap = -point.penetration;
  p.n_W = point.n_W;
  p.p_W = point.p_Wc_W;
  p.gap_rate = point.n_W.dot(RelativeVelocity(point));
  if (point.modal_a.cols() > 0) p.modal_a = point.n_W.transpose() * point.modal_a;
  if (point.modal_b.cols() > 0) p.modal_b = point.n_W.transpose() * point.modal_b;
  return p;
}

/// The modal columns of body b (a flexible one) in a row over the system's velocities.
Eigen::RowVectorXd ModalColumns(const MultibodySystem& system, int b, const Eigen::RowVectorXd& row) {
  const Eigen::Index n = dynamic_cast<const FlexibleBody&>(system.body(b)).data().num_modes();
  return row.segment(system.velocity_block(b).start + 6, n);
}

bool IsFlexible(const MultibodySystem& system, int b) {
  return b != kGround && dynamic_cast<const FlexibleBody*>(&system.body(b)) != nullptr;
}

/// A PCM pair with a reduced body's surface on either side, if its sides come together.
std::optional<Pair> PcmPair(const MultibodySystem& system, const PcmContactForce& element, const ConstVectorRef& y0) {
  if (!element.A().is_modal() && !element.B().is_modal()) return std::nullopt;
  auto probe = std::make_shared<const PcmTouchProbe>(system, element, y0);
  if (!probe->found()) return std::nullopt;
  Pair pair;
  pair.name = element.name();
  pair.type = "pcm_contact";
  pair.body_a = element.A().marker.body;
  pair.body_b = element.B().marker.body;
  PairPoint touch;
  touch.gap = probe->gap();
  touch.n_W = probe->normal_W();
  touch.p_W = probe->point_W();
  touch.gap_rate = probe->gap_rate();
  pair.points.push_back(std::move(touch));
  pair.pcm = std::move(probe);
  return pair;
}

/// The pairs of `system` that touch a reduced body's surface, at y0.
std::vector<Pair> Pairs(const MultibodySystem& system, const ConstVectorRef& y0) {
  std::vector<Pair> pairs;
  const auto add_law = [](Pair& pair, const CompliantContactLaw& law) {
    pair.stiffness = law.normal.stiffness;
    pair.exponent = law.normal.exponent;
  };
  for (int k = 0; k < system.num_force_elements(); ++k) {
    const ForceElement& element = system.force_element(k);
    Pair pair;
    pair.name = element.name();
    if (const auto* sphere = dynamic_cast<const SphereSurfaceContact*>(&element)) {
      pair.type = "sphere_surface_contact";
      pair.body_a = sphere->sphere().body;
      pair.body_b = sphere->origin().body;
      pair.points.push_back(FromContactPoint(sphere->Geometry(0.0, system, y0)));
      add_law(pair, sphere->law());
    } else if (const auto* surface = dynamic_cast<const SurfacePlaneContact*>(&element)) {
      pair.type = "surface_plane_contact";
      pair.body_a = surface->origin().body;
      pair.body_b = surface->plane().body;
      // Points gives the modal Jacobian of penetrating vertices only: every vertex's from the surface.
      const CompliantPointsContact& points = *surface;  // Points is public on the base
      const Eigen::Index modes = dynamic_cast<const FlexibleBody&>(system.body(pair.body_a)).data().num_modes();
      const SurfaceState state(system, surface->origin(), surface->surface(), modes, y0);
      int v = 0;
      for (const ContactPoint& point : points.Points(system, y0)) {
        pair.points.push_back(FromContactPoint(point));
        pair.points.back().modal_a = point.n_W.transpose() * state.ModalJacobian(v++);
      }
      add_law(pair, surface->law());
    } else if (const auto* pcm = dynamic_cast<const PcmContactForce*>(&element)) {
      if (std::optional<Pair> one = PcmPair(system, *pcm, y0)) pairs.push_back(std::move(*one));
      continue;
    } else {
      continue;
    }
    pairs.push_back(std::move(pair));
  }
  const Eigen::VectorXd u0 = y0.tail(system.num_velocities());
  for (int k = 0; k < system.num_unilateral_contacts(); ++k) {
    const UnilateralContact& contact = system.unilateral_contact(k);
    Pair pair;
    pair.name = contact.name();
    pair.type = contact.type();
    pair.body_a = contact.marker_a().body;
    pair.body_b = contact.marker_b().body;
    if (!IsFlexible(system, pair.body_a) && !IsFlexible(system, pair.body_b)) continue;
    pair.unilateral = true;
    for (const UnilateralContactKinematics& point : contact.Evaluate(0.0, system, y0)) {
      PairPoint p;
      p.gap = point.g_N;
      p.n_W = point.n_W;
      p.p_W = 0.5 * (point.p_WA_W + point.p_WB_W);
      p.gap_rate = point.W_N.dot(u0);
      if (IsFlexible(system, pair.body_a)) p.modal_a = ModalColumns(system, pair.body_a, point.W_N);
      if (IsFlexible(system, pair.body_b)) p.modal_b = -ModalColumns(system, pair.body_b, point.W_N);
      pair.points.push_back(std::move(p));
    }
    pairs.push_back(std::move(pair));
  }
  return pairs;
}

/// The points of `points` that touch first: those within 1e-8 of the points' extent of the
/// smallest gap (a face lying flat on a plane: all its vertices).
std::vector<const PairPoint*> FirstPoints(const std::vector<PairPoint>& points) {
  double lowest = HUGE_VAL;
  Eigen::Vector3d lo = Eigen::Vector3d::Constant(HUGE_VAL), hi = -lo;
  for (const PairPoint& p : points) {
    lowest = std::min(lowest, p.gap);
    lo = lo.cwiseMin(p.p_W);
    hi = hi.cwiseMax(p.p_W);
  }
  const double tolerance = 1e-8 * (hi - lo).norm();
  std::vector<const PairPoint*> first;
  for (const PairPoint& p : points) {
    if (p.gap <= lowest + tolerance) first.push_back(&p);
  }
  return first;
}

/// Whether body b is welded to the ground by a fixed joint (a clamped plate).
bool WeldedToGround(const MultibodySystem& system, int b) {
  for (int k = 0; k < system.num_joints(); ++k) {
    const Joint& joint = system.joint(k);
    if (joint.type() != JointType::kFixed) continue;
    const int i = joint.marker_i().body, j = joint.marker_j().body;
    if ((i == b && j == kGround) || (j == b && i == kGround)) return true;
  }
  return false;
}

/// 1 / m_b along n at p [1/kg]: body b held rigid, n^T J M_rr^-1 J^T n with J the point's
/// velocity by the frame's velocities (v_WBo_W, w_WB_B) and M_rr the body's rigid block at y0
/// (Goldsmith, "Impact", 1960, ch. 4: the effective mass of an eccentric impact). 0 for the ground
/// and for a body welded to it.
double InverseMass(const MultibodySystem& system, int b, const Eigen::Vector3d& n_W, const Eigen::Vector3d& p_W,
                   const ConstVectorRef& y0) {
  if (b == kGround || WeldedToGround(system, b)) return 0.0;
  const Eigen::Map<const Eigen::VectorXd> x = system.BodyPositions(y0, b);
  const Eigen::Matrix3d R_WB = RotationFromEulerParameters(x.segment<4>(3));
  const Eigen::Vector3d s_B = R_WB.transpose() * (p_W - x.head<3>());
  Eigen::Matrix<double, 6, 1> j;
  j << n_W, s_B.cross(R_WB.transpose() * n_W);  // n . (v + R (w x s)) = n . v + w . (s x R^T n)
  const Eigen::Matrix<double, 6, 6> M_rr = system.BodyMassMatrix(b, y0).topLeftCorner<6, 6>();
  return j.dot(M_rr.ldlt().solve(j));
}

/// The advice on flexible body `body` (end a if `end_a`) of `pair`, if it approaches.
std::optional<ContactModeAdvice> Advise(const MultibodySystem& system, const Pair& pair, int body, bool end_a,
                                        const ConstVectorRef& y0) {
  const std::vector<const PairPoint*> first = FirstPoints(pair.points);
  if (first.empty()) return std::nullopt;
  ContactModeAdvice advice;
  advice.element = pair.name;
  advice.type = pair.type;
  advice.unilateral = pair.unilateral;
  advice.first_points = static_cast<int>(first.size());
  Eigen::Vector3d p_W = Eigen::Vector3d::Zero();
  double gap_rate = 0.0;
  for (const PairPoint* p : first) {
    p_W += p->p_W / static_cast<double>(first.size());
    gap_rate += p->gap_rate / static_cast<double>(first.size());
  }
  const Eigen::Vector3d& n_W = first.front()->n_W;
  const double gap = std::max(0.0, first.front()->gap);
  const double approach = std::max(0.0, -gap_rate);
  const double fall = std::max(0.0, -system.gravity().dot(n_W));  // gravity pulls A towards B
  advice.impact_speed = std::sqrt(approach * approach + 2.0 * fall * gap);
  if (!(advice.impact_speed > 0.0)) return std::nullopt;
  const double inverse_mass = InverseMass(system, pair.body_a, n_W, p_W, y0) + InverseMass(system, pair.body_b, n_W, p_W, y0);
  if (!(inverse_mass > 0.0)) return std::nullopt;  // both ends held
  advice.effective_mass = 1.0 / inverse_mass;
  advice.law_stiffness = advice.first_points * pair.stiffness;
  advice.law_exponent = pair.exponent;
  std::optional<PcmLawFit> fit;
  if (pair.pcm) {
    fit = FitPcmLaw(*pair.pcm, advice.effective_mass, advice.impact_speed);
    advice.law_stiffness = fit->stiffness;
    advice.law_exponent = fit->exponent;
  }

  const auto& flexible = dynamic_cast<const FlexibleBody&>(system.body(body));
  const sid::ReducedBody& data = flexible.data();
  advice.body = flexible.name();
  const std::vector<std::string>& kinds = data.mode_kinds;
  advice.correction_mode = std::find(kinds.begin(), kinds.end(), "static_correction") != kinds.end();
  // The modes the contact's normal load on the first points reaches: the sum of their rows.
  Eigen::RowVectorXd load = Eigen::RowVectorXd::Zero(data.num_modes());
  for (const PairPoint* p : first) {
    const Eigen::RowVectorXd& row = end_a ? p->modal_a : p->modal_b;
    if (row.size() == load.size()) load += row;
  }
  if (fit) {  // a PCM pair: the elements' load at the largest compression
    const Eigen::RowVectorXd& row = end_a ? fit->load.modal_a : fit->load.modal_b;
    if (row.size() == load.size()) load += row;
  }
  const double largest = load.size() > 0 ? load.cwiseAbs().maxCoeff() : 0.0;
  for (Eigen::Index j = 0; j < load.size(); ++j) {
    if (std::abs(load(j)) > 1e-6 * largest) advice.loaded.push_back(static_cast<int>(j));
  }
  std::stable_sort(advice.loaded.begin(), advice.loaded.end(), [&](int i, int j) {
    const double fi = data.frequency_hz(i), fj = data.frequency_hz(j);
    return (std::isnan(fi) ? HUGE_VAL : fi) < (std::isnan(fj) ? HUGE_VAL : fj);
  });

  if (pair.unilateral) {
    // The lowest loaded elastic mode's period (a free bar struck at its end: 2L/c).
    double lowest = HUGE_VAL;
    for (int j : advice.loaded) {
      if (kinds.at(static_cast<std::size_t>(j)) == "normal" && data.frequency_hz(j) > 0.0) {
        lowest = std::min(lowest, data.frequency_hz(j));
      }
    }
    if (!std::isfinite(lowest)) return std::nullopt;
    advice.contact_time = 1.0 / lowest;
    advice.cutoff_hz = kCutoffTimesContactTimeUnilateral / advice.contact_time;
  } else {
    if (!(advice.law_stiffness > 0.0)) return std::nullopt;
    advice.contact_time =
        PowerLawContactTime(advice.effective_mass, advice.impact_speed, advice.law_stiffness, advice.law_exponent);
    advice.cutoff_hz =
        (advice.correction_mode ? kCutoffTimesContactTimeWithCorrection : kCutoffTimesContactTimeWithout) /
        advice.contact_time;
  }
  for (int j : advice.loaded) {
    const double f = data.frequency_hz(j);
    if (std::isnan(f)) continue;
    ++advice.loaded_modes;
    if (f > advice.cutoff_hz) ++advice.loaded_modes_above;
    advice.highest_loaded_hz = std::max(advice.highest_loaded_hz, f);
  }
  return advice;
}

}  // namespace

double PowerLawContactTime(double mass, double speed, double stiffness, double exponent) {
  FLEXMBS_CHECK(mass > 0.0 && speed > 0.0 && stiffness > 0.0 && exponent >= 1.0, "a power law's contact time");
  const double p = exponent + 1.0;
  const double delta_m = std::pow(p * mass * speed * speed / (2.0 * stiffness), 1.0 / p);
  return 2.0 * delta_m / speed * std::sqrt(std::numbers::pi) * std::tgamma(1.0 + 1.0 / p) / std::tgamma(0.5 + 1.0 / p);
}

std::string ContactModeAdvice::Describe() const {
  // A PCM pair's fitted exponent names the features that meet first (mbs/contact_mode_advice_pcm.h).
  const std::string features = law_exponent < 1.5   ? "faces flat on each other"
                               : law_exponent < 2.5 ? "an edge on a face, or a curved cap"
                                                    : "a vertex into a face, or an edge across an edge";
  const std::string source =
      unilateral ? fmt::format("the period of {}'s lowest loaded mode (rigid contact)", body)
      : type == "pcm_contact"
          ? fmt::format("the layers' F = {:.3g} delta^{:.3g} past first touch ({}) at {:.3g} m/s, {:.3g} kg",
                        law_stiffness, law_exponent, features, impact_speed, effective_mass)
          : fmt::format("the law's contact time at {:.3g} m/s, {:.3g} kg, {} point{}", impact_speed, effective_mass,
                        first_points, first_points == 1 ? "" : "s");
  const std::string rule =
      unilateral ? fmt::format("{:g} / t_c, measured on a bar struck by a wall", kCutoffTimesContactTimeUnilateral)
      : correction_mode ? fmt::format("{:g} / t_c, as {} keeps a static correction mode",
                                      kCutoffTimesContactTimeWithCorrection, body)
      : type == "pcm_contact"
          ? fmt::format("{:g} / t_c; measured on PCM strikes it is not enough without a static correction mode of "
                        "the surface (peak +1.5 to +6.5 %): keep one, then {:g} / t_c",
                        kCutoffTimesContactTimeWithout, kCutoffTimesContactTimeWithCorrection)
          : fmt::format("{:g} / t_c; a static correction mode of the surface would halve it",
                        kCutoffTimesContactTimeWithout);
  return fmt::format("contact '{}' ({}) on {}: contact time {:.3g} us ({}); keep the modes it loads up to "
                     "{:.4g} kHz ({}); {} keeps {} loaded modes up to {:.4g} kHz, {} above",
                     element, type, body, 1e6 * contact_time, source, 1e-3 * cutoff_hz, rule, body, loaded_modes,
                     1e-3 * highest_loaded_hz, loaded_modes_above);
}

std::vector<ContactModeAdvice> AdviseContactModes(const MultibodySystem& system, const ConstVectorRef& y0) {
  std::vector<ContactModeAdvice> advice;
  for (const Pair& pair : Pairs(system, y0)) {
    for (const bool end_a : {true, false}) {
      const int body = end_a ? pair.body_a : pair.body_b;
      if (!IsFlexible(system, body)) continue;
      if (std::optional<ContactModeAdvice> one = Advise(system, pair, body, end_a, y0)) {
        advice.push_back(std::move(*one));
      }
    }
  }
  return advice;
}

}  // namespace flexmbs::mbs
