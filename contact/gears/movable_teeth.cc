#include "contact/gears/movable_teeth.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "contact/gears/gear_flank.h"
#include "core/error.h"

namespace flexmbs::contact {
namespace {

double FaceWidth(const GearPair& pair) {
  return std::min(pair.gear1.spec.face_width, pair.gear2.spec.face_width);
}

/// (p - O) x f about +z in the pair frame.
double Moment(const Eigen::Vector2d& p_OC, const Eigen::Vector2d& f) {
  return p_OC.x() * f.y() - p_OC.y() * f.x();
}

}  // namespace

void CheckMovableTeeth(const MovableTeeth& teeth) {
  CheckElasticTeeth(teeth.teeth);
  if (teeth.teeth.rim1 || teeth.teeth.rim2 || teeth.teeth.flattening_at_load) {
    throw InputError(
        "movable teeth: the rims' coupling and the flattening at each pair's load are the static "
        "law's (contact::MeshLaw), not the movable teeth's");
  }
  if (!(teeth.damping > 0.0) || !std::isfinite(teeth.damping)) {
    throw InputError(fmt::format(
        "movable teeth: tooth damping {} N s/m must be finite and > 0 (a massless tooth needs its "
        "dashpot)",
        teeth.damping));
  }
}

ToothLevers PairLevers(const GearPair& pair, double centre_distance, const ToothPair& tp) {
  // Wheel 2 takes F n_12 at the contact point, wheel 1 -F n_12.
  const Eigen::Vector2d p_O2C = tp.p_O1C - Eigen::Vector2d(centre_distance, 0.0);
  return {Moment(tp.p_O1C, -tp.n_12) / pair.gear1.base_radius,
          Moment(p_O2C, tp.n_12) / pair.gear2.base_radius};
}

double FlatteningStiffness(const MovableTeeth& teeth, const GearPair& pair, const ToothPair& tp) {
  const ElasticTeeth& e = teeth.teeth;
  return FaceWidth(pair) / FlatteningCompliance(e, pair, std::max(tp.roll1, e.tooth1.roll.front()),
                                                std::max(tp.roll2, e.tooth2.roll.front()));
}

double ToothStiffness(const MovableTeeth& teeth, const GearPair& pair, int wheel, double roll) {
  FLEXMBS_CHECK(wheel == 1 || wheel == 2, "ToothStiffness: wheel 1 or 2");
  const ToothCompliance& table = wheel == 1 ? teeth.teeth.tooth1 : teeth.teeth.tooth2;
  return FaceWidth(pair) / InterpolateCompliance(table, roll).compliance;
}

double PitchRoll(const GearPair& pair, double centre_distance) {
  return std::sqrt(std::pow(centre_distance / (pair.gear1.base_radius + pair.gear2.base_radius), 2) -
                   1.0);
}

}  // namespace flexmbs::contact
