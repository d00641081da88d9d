#include "contact/gears/gear_mesh_force.h"

#include <algorithm>
#include <cmath>
#include <utility>

#include "contact/laws/law_checks.h"
#include "core/error.h"

namespace flexmbs::contact {
namespace {

/// The z component of the planar cross product a x b.
double Cross(const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
  return a.x() * b.y() - a.y() * b.x();
}

}  // namespace

NormalLaw ToothPairLaw(const GearMeshCompliance& compliance, const GearPair& pair) {
  RequirePositive("mesh stiffness c' [N/m^2]", compliance.single_pair_stiffness);
  const double face_width = std::min(pair.gear1.spec.face_width, pair.gear2.spec.face_width);
  return LinearLaw(compliance.single_pair_stiffness * face_width, compliance.damping);
}

MeshLaw::MeshLaw(NormalLaw law) : law_(law) {}

MeshLaw::MeshLaw(const GearPair& pair, ElasticTeeth teeth, double damping)
    : law_(LinearLaw(1.0, damping)),
      teeth_(std::move(teeth)),
      pair_(pair),
      face_width_(std::min(pair.gear1.spec.face_width, pair.gear2.spec.face_width)),
      damping_(damping) {
  CheckElasticTeeth(*teeth_);
}

std::pair<double, double> MeshLaw::Rolls(const ToothPair& tp) const {
  return {std::max(tp.roll1, teeth_->tooth1.roll.front()),
          std::max(tp.roll2, teeth_->tooth2.roll.front())};
}

NormalLaw MeshLaw::PairLaw(const ToothPair& tp) const {
  if (!teeth_) return law_;
  const auto [t1, t2] = Rolls(tp);
  return LinearLaw(TeethPairStiffness(*teeth_, pair_, t1, t2) * face_width_, damping_);
}

ToothPairDeflection MeshLaw::Deflection(const ToothPair& tp, double force) const {
  if (!teeth_) return {};
  const auto [t1, t2] = Rolls(tp);
  const double w = force / face_width_;  // per face width
  const double w_ref = teeth_->reference_load;
  const ToothComplianceAt q1 = InterpolateCompliance(teeth_->tooth1, t1);
  const ToothComplianceAt q2 = InterpolateCompliance(teeth_->tooth2, t2);
  return {q1.compliance * w, q2.compliance * w,
          WeberFlattening(w_ref, pair_.gear1.base_radius * t1, pair_.gear2.base_radius * t2,
                          q1.centre_depth, q2.centre_depth, teeth_->material) *
              w / w_ref};
}

MeshLoads EvaluateMesh(const GearPair& pair, const MeshLaw& law, double centre_distance,
                       double phi1, double phi2, double omega1, double omega2) {
  MeshLoads loads;
  const Eigen::Vector2d p_O1O2(centre_distance, 0.0);
  for (const ToothPair& tp : MeshingToothPairs(pair, centre_distance, phi1, phi2)) {
    if (!(tp.gap < 0.0)) continue;
    // delta' = -n_12 . (v2 - v1) at the contact point (exact for a corner too: the two
    // points' offset lies along n_12, across which the turning adds nothing).
    const double rate =
        Cross(tp.p_O1C, tp.n_12) * omega1 - Cross(tp.p_O1C - p_O1O2, tp.n_12) * omega2;
    const double force = Evaluate(law.PairLaw(tp), -tp.gap, rate).force;
    if (force == 0.0) continue;
    loads.pairs.push_back({tp, force});
    loads.torque1 += Cross(tp.p_O1C, -force * tp.n_12);
    loads.torque2 += Cross(tp.p_O1C - p_O1O2, force * tp.n_12);
  }
  return loads;
}

double StaticTransmissionError(const GearPair& pair, const MeshLaw& law, double centre_distance,
                               double phi1, double torque) {
  FLEXMBS_CHECK(torque > 0.0 && std::isfinite(torque),
                "StaticTransmissionError needs a torque > 0");
  const double r_b2 = pair.gear2.base_radius;
  const double phi2_0 = TouchingAngle2(pair, centre_distance, phi1, 0.0, FlankSide::kPositive);
  // The excess of the mesh's resisting torque over T at lag delta (< 0: wheel 1 turns on).
  const auto excess = [&](double delta) {
    return -EvaluateMesh(pair, law, centre_distance, phi1, phi2_0 + delta / r_b2, 0.0, 0.0)
                .torque1 -
           torque;
  };
  double lo = 0.0, hi = 1e-9;
  while (excess(hi) < 0.0) {
    lo = hi;
    hi *= 2.0;
    FLEXMBS_CHECK(hi < pair.gear1.base_pitch,
                  "StaticTransmissionError: no equilibrium within a base pitch");
  }
  while (hi - lo > 1e-15 * hi) {
    const double mid = 0.5 * (lo + hi);
    if (excess(mid) < 0.0) {
      lo = mid;
    } else {
      hi = mid;
    }
  }
  return 0.5 * (lo + hi);
}

}  // namespace flexmbs::contact
