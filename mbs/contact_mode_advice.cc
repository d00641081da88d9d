#include "mbs/contact_mode_advice.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <optional>
#include <utility>

#include "mbs/flexible_body.h"
#include "mbs/rigid_body.h"
#include "mbs/surface_contact_force.h"

namespace flexmbs::mbs {
namespace {

/// The mass of body b [kg].
double BodyMass(const MultibodySystem& system, int b) {
  if (const auto* rigid = dynamic_cast<const RigidBody*>(&system.body(b))) return rigid->mass();
  return dynamic_cast<const FlexibleBody&>(system.body(b)).data().mass;
}

/// The advice for one element, if its law is Hertz's and the sphere approaches.
std::optional<ContactModeAdvice> Advise(const MultibodySystem& system, const SphereSurfaceContact& element,
                                        const ConstVectorRef& y0) {
  const contact::NormalLaw& law = element.law().normal;
  if (law.exponent != 1.5 || !(law.stiffness > 0.0)) return std::nullopt;
  const ContactPoint point = element.Geometry(0.0, system, y0);
  const double gap = std::max(0.0, -point.penetration);
  const double approach = std::max(0.0, -point.n_W.dot(RelativeVelocity(point)));
  const double fall = std::max(0.0, -system.gravity().dot(point.n_W));  // gravity towards the surface
  ContactModeAdvice advice;
  advice.impact_speed = std::sqrt(approach * approach + 2.0 * fall * gap);
  if (!(advice.impact_speed > 0.0)) return std::nullopt;

  const int body = element.origin().body;
  const auto& flexible = dynamic_cast<const FlexibleBody&>(system.body(body));
  const double m1 = element.sphere().is_ground() ? HUGE_VAL : BodyMass(system, element.sphere().body);
  const double m2 = BodyMass(system, body);
  const double mass = std::isinf(m1) ? m2 : m1 * m2 / (m1 + m2);
  const double v = advice.impact_speed;
  advice.element = element.name();
  advice.body = flexible.name();
  advice.contact_time = 2.94 * std::pow(5.0 * mass * v * v / (4.0 * law.stiffness), 0.4) / v;
  const std::vector<std::string>& kinds = flexible.data().mode_kinds;
  advice.correction_mode = std::find(kinds.begin(), kinds.end(), "static_correction") != kinds.end();
  advice.cutoff_hz = (advice.correction_mode ? kCutoffTimesContactTimeWithCorrection : kCutoffTimesContactTimeWithout) /
                     advice.contact_time;
  // The modes the contact's normal load reaches: n . R phi_c of the surface point per mode.
  const Eigen::RowVectorXd load = point.n_W.transpose() * point.modal_b;
  const double largest = load.size() > 0 ? load.cwiseAbs().maxCoeff() : 0.0;
  for (Eigen::Index j = 0; j < load.size(); ++j) {
    const double f = flexible.data().frequency_hz(j);
    if (!(std::abs(load(j)) > 1e-6 * largest) || std::isnan(f)) continue;
    ++advice.loaded_modes;
    if (f > advice.cutoff_hz) ++advice.loaded_modes_above;
    advice.highest_loaded_hz = std::max(advice.highest_loaded_hz, f);
  }
  return advice;
}

}  // namespace

std::string ContactModeAdvice::Describe() const {
  const std::string rule =
      correction_mode ? fmt::format("{:g} / t_c, as {} keeps a static correction mode",
                                    kCutoffTimesContactTimeWithCorrection, body)
                      : fmt::format("{:g} / t_c; a static correction mode of the surface would halve it",
                                    kCutoffTimesContactTimeWithout);
  return fmt::format("contact '{}' on {}: Hertz contact time {:.3g} us at {:.3g} m/s; keep the modes it loads up to "
                     "{:.4g} kHz ({}); {} keeps {} loaded modes up to {:.4g} kHz, {} above",
                     element, body, 1e6 * contact_time, impact_speed, 1e-3 * cutoff_hz, rule, body, loaded_modes,
                     1e-3 * highest_loaded_hz, loaded_modes_above);
}

std::vector<ContactModeAdvice> AdviseContactModes(const MultibodySystem& system, const ConstVectorRef& y0) {
  std::vector<ContactModeAdvice> advice;
  for (int k = 0; k < system.num_force_elements(); ++k) {
    const auto* element = dynamic_cast<const SphereSurfaceContact*>(&system.force_element(k));
    if (element == nullptr) continue;
    if (std::optional<ContactModeAdvice> one = Advise(system, *element, y0)) advice.push_back(std::move(*one));
  }
  return advice;
}

}  // namespace flexmbs::mbs
