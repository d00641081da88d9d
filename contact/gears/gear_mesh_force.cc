#include "contact/gears/gear_mesh_force.h"

#include <fmt/format.h>

#include <Eigen/LU>
#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>
#include <utility>

#include "contact/laws/law_checks.h"
#include "core/error.h"

namespace flexmbs::contact {
namespace {

/// The z component of the planar cross product a x b.
double Cross(const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
  return a.x() * b.y() - a.y() * b.x();
}

/// InputError (one line, `item` the wheel's rim) unless `rim` is a table over two or more
/// finite, increasing roll angles > 0 whose columns ahead and behind have as many values, each
/// NaN (off the neighbour's flank) or in [0, q(t)) with q the loaded tooth's own compliance
/// `tooth` there, two or more of them finite.
void CheckRimCoupling(const RimCoupling& rim, const ToothCompliance& tooth, const char* item) {
  const std::size_t n = rim.roll.size();
  if (n < 2 || rim.ahead.size() != n || rim.behind.size() != n) {
    throw InputError(fmt::format(
        "{}: the rim coupling needs two or more samples and as many of each column (roll {}, "
        "ahead {}, behind {})",
        item, n, rim.ahead.size(), rim.behind.size()));
  }
  for (std::size_t k = 0; k < n; ++k) {
    const double previous = k == 0 ? 0.0 : rim.roll[k - 1];
    if (!(rim.roll[k] > previous) || !std::isfinite(rim.roll[k])) {
      throw InputError(fmt::format("{}: roll[{}] {} rad must be finite, > 0 and above roll[{}]",
                                   item, k, rim.roll[k], k == 0 ? 0 : k - 1));
    }
  }
  for (const auto& [name, column] : {std::pair{"ahead", &rim.ahead}, {"behind", &rim.behind}}) {
    int finite = 0;
    for (std::size_t k = 0; k < n; ++k) {
      const double v = (*column)[k], q = InterpolateCompliance(tooth, rim.roll[k]).compliance;
      if (std::isnan(v)) continue;
      if (!(v >= 0.0 && v < q)) {
        throw InputError(fmt::format("{}: {}[{}] {} m^2/N must be NaN (off the neighbour's flank) "
                                     "or in [0, {}), the loaded tooth's own compliance there",
                                     item, name, k, v, q));
      }
      ++finite;
    }
    if (finite < 2) {
      throw InputError(fmt::format("{}: {} has {} finite values; give two or more", item, name,
                                   finite));
    }
  }
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
  if (teeth_->rim1.has_value() != teeth_->rim2.has_value()) {
    throw InputError(fmt::format("elastic teeth: gear {}'s rim coupling without gear {}'s; give "
                                 "both or neither",
                                 teeth_->rim1 ? 1 : 2, teeth_->rim1 ? 2 : 1));
  }
  if (coupled()) {
    CheckRimCoupling(*teeth_->rim1, teeth_->tooth1, "gear 1 rim");
    CheckRimCoupling(*teeth_->rim2, teeth_->tooth2, "gear 2 rim");
  }
}

struct MeshLaw::Series {
  double q = 0.0;  ///< q1 + q2 [m^2/N]
  double rho1 = 0.0, rho2 = 0.0, h1 = 0.0, h2 = 0.0;
  ToothMaterial material;
  /// delta_H(w) [m] (WeberFlattening).
  double Flattening(double w) const { return WeberFlattening(w, rho1, rho2, h1, h2, material); }
  /// d(q w + delta_H(w)) / dw [m^2/N]: delta_H = 2 s w (ln(2 h1 / a) + ln(2 h2 / a) - nu /
  /// (1 - nu)) with a ~ sqrt(w), so d delta_H / dw = delta_H / w - 2 s.
  double Slope(double w) const {
    const double nu = material.poisson_ratio;
    const double s = (1.0 - nu * nu) / (std::numbers::pi * material.youngs_modulus);
    return q + Flattening(w) / w - 2.0 * s;
  }
  /// The energy b (w delta - integral of the approach over w) at load w and approach delta [J]
  /// for face width b: (b w delta - b s w^2) / 2.
  double Energy(double w, double delta, double b) const {
    const double nu = material.poisson_ratio;
    const double s = (1.0 - nu * nu) / (std::numbers::pi * material.youngs_modulus);
    return 0.5 * b * (w * delta - s * w * w);
  }
};

MeshLaw::Series MeshLaw::PairSeries(const ToothPair& tp) const {
  const auto [t1, t2] = Rolls(tp);
  const ToothComplianceAt q1 = InterpolateCompliance(teeth_->tooth1, t1);
  const ToothComplianceAt q2 = InterpolateCompliance(teeth_->tooth2, t2);
  return {q1.compliance + q2.compliance,
          pair_.gear1.base_radius * t1,
          pair_.gear2.base_radius * t2,
          q1.centre_depth,
          q2.centre_depth,
          teeth_->material};
}

MeshLaw::AtLoad MeshLaw::ForceAtLoad(const ToothPair& tp, double delta) const {
  const Series series = PairSeries(tp);
  // The approach at load w grows with w; at w = delta / (q1 + q2) the teeth alone take delta.
  double lo = 0.0, hi = delta / series.q;
  while (hi - lo > 1e-15 * hi) {
    const double mid = 0.5 * (lo + hi);
    (series.q * mid + series.Flattening(mid) < delta ? lo : hi) = mid;
  }
  const double w = 0.5 * (lo + hi);
  return {w * face_width_, face_width_ / series.Slope(w), series.Energy(w, delta, face_width_)};
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

std::vector<double> MeshLaw::Forces(const std::vector<ToothPair>& pairs,
                                    const std::vector<double>& rates) const {
  return ForcesWithDerivatives(pairs, rates).force;
}

MeshPairForces MeshLaw::ForcesWithDerivatives(const std::vector<ToothPair>& pairs,
                                              const std::vector<double>& rates) const {
  FLEXMBS_CHECK(rates.size() == pairs.size(), "MeshLaw::Forces needs a rate per pair");
  const auto n = static_cast<Eigen::Index>(pairs.size());
  MeshPairForces out{std::vector<double>(pairs.size(), 0.0), Eigen::MatrixXd::Zero(n, n),
                     Eigen::MatrixXd::Zero(n, n), 0.0};
  if (coupled() && pairs.size() == 2 && pairs[0].side == pairs[1].side) {
    CoupledForces(pairs, rates, &out);
    return out;
  }
  for (Eigen::Index i = 0; i < n; ++i) {
    const auto k = static_cast<std::size_t>(i);
    const double delta = -pairs[k].gap;
    if (teeth_ && teeth_->flattening_at_load) {
      const AtLoad elastic = delta > 0.0 ? ForceAtLoad(pairs[k], delta) : AtLoad{};
      out.force[k] = std::max(0.0, elastic.force + damping_ * rates[k]);
      if (out.force[k] > 0.0) {
        out.d_delta(i, i) = elastic.d_delta;
        out.d_rate(i, i) = damping_;
      }
      out.energy += elastic.energy;
    } else {
      const NormalLaw law = PairLaw(pairs[k]);
      const NormalForce f = Evaluate(law, delta, rates[k]);
      out.force[k] = f.force;
      out.d_delta(i, i) = f.d_delta;
      out.d_rate(i, i) = f.d_rate;
      out.energy += ElasticEnergy(law, delta);
    }
  }
  return out;
}

void MeshLaw::CoupledForces(const std::vector<ToothPair>& pairs, const std::vector<double>& rates,
                            MeshPairForces* out) const {
  const std::size_t a = pairs[0].roll1 > pairs[1].roll1 ? 0 : 1, b = 1 - a;
  const ToothPair &A = pairs[a], &B = pairs[b];
  const RimCoupling &rim1 = *teeth_->rim1, &rim2 = *teeth_->rim2;
  Eigen::Matrix2d C;
  C(a, a) = 1.0 / PairLaw(A).stiffness;
  C(b, b) = 1.0 / PairLaw(B).stiffness;
  C(a, b) = (RimCouplingAt(rim1.roll, rim1.ahead, B.roll1) +
             RimCouplingAt(rim2.roll, rim2.behind, B.roll2)) / face_width_;
  C(b, a) = (RimCouplingAt(rim1.roll, rim1.behind, A.roll1) +
             RimCouplingAt(rim2.roll, rim2.ahead, A.roll2)) / face_width_;
  const Eigen::Vector2d delta(-pairs[0].gap, -pairs[1].gap);
  Eigen::Matrix2d K = C.inverse();
  Eigen::Vector2d elastic = K * delta;
  Eigen::Index dropped = -1;  // a pair that would pull: the other alone
  for (Eigen::Index i = 0; i < 2 && dropped < 0; ++i) {
    if (elastic(i) < 0.0) dropped = i;
  }
  const bool at_load = teeth_->flattening_at_load;
  if (dropped < 0 && at_load) dropped = CoupledAtLoad(pairs, C, delta, &elastic, &K);
  if (dropped >= 0) {
    const Eigen::Index j = 1 - dropped;
    const AtLoad alone = at_load ? ForceAtLoad(pairs[static_cast<std::size_t>(j)], delta(j))
                                 : AtLoad{delta(j) / C(j, j), 1.0 / C(j, j), 0.0};
    elastic(dropped) = 0.0;
    elastic(j) = alone.force;
    K.setZero();
    K(j, j) = alone.d_delta;
  }
  for (Eigen::Index i = 0; i < 2; ++i) {
    const auto k = static_cast<std::size_t>(i);
    out->force[k] = std::max(0.0, elastic(i) + damping_ * rates[k]);
    if (out->force[k] > 0.0) {
      out->d_delta.row(i) = K.row(i);
      out->d_rate(i, i) = damping_;
    }
  }
  out->energy = 0.5 * elastic.dot(delta);
  if (at_load) {  // minus b s w^2 / 2 per pair (Series::Energy)
    for (Eigen::Index i = 0; i < 2; ++i) {
      const Series series = PairSeries(pairs[static_cast<std::size_t>(i)]);
      out->energy += series.Energy(elastic(i) / face_width_, 0.0, face_width_);
    }
  }
}

Eigen::Index MeshLaw::CoupledAtLoad(const std::vector<ToothPair>& pairs,
                                    const Eigen::Matrix2d& C, const Eigen::Vector2d& delta,
                                    Eigen::Vector2d* elastic, Eigen::Matrix2d* K) const {
  const std::array<Series, 2> series{PairSeries(pairs[0]), PairSeries(pairs[1])};
  const double b = face_width_;
  Eigen::Vector2d w = *elastic / b;  // the linearised loads per face width
  Eigen::Index lowest = 0;
  if (!(w.minCoeff(&lowest) > 0.0)) return lowest;
  Eigen::Matrix2d J;
  bool converged = false;
  for (int iteration = 0; iteration < 100 && !converged; ++iteration) {
    Eigen::Vector2d residual;
    for (Eigen::Index i = 0; i < 2; ++i) {
      const Eigen::Index j = 1 - i;
      const Series& s = series[static_cast<std::size_t>(i)];
      residual(i) = s.q * w(i) + s.Flattening(w(i)) + b * C(i, j) * w(j) - delta(i);
      J(i, i) = s.Slope(w(i));
      J(i, j) = b * C(i, j);
    }
    const Eigen::Vector2d step = J.inverse() * residual;
    w -= step;
    if (!(w.minCoeff(&lowest) > 0.0)) return lowest;
    converged = step.cwiseAbs().maxCoeff() <= 1e-15 * w.cwiseAbs().maxCoeff();
  }
  // Each pair's series is convex in its load and the coupling linear: Newton from the linearised
  // loads converges in a few steps, so running out of them is a bug, not an input.
  FLEXMBS_CHECK(converged, "MeshLaw: the coupled pairs' loads at the flattening at load did not converge");
  for (Eigen::Index i = 0; i < 2; ++i) J(i, i) = series[static_cast<std::size_t>(i)].Slope(w(i));
  *elastic = b * w;
  *K = b * J.inverse();
  return -1;
}

ToothPairDeflection MeshLaw::Deflection(const ToothPair& tp, double force) const {
  return Deflections({tp}, {force}).front();
}

std::vector<ToothPairDeflection> MeshLaw::Deflections(const std::vector<ToothPair>& pairs,
                                                      const std::vector<double>& forces) const {
  FLEXMBS_CHECK(forces.size() == pairs.size(), "MeshLaw::Deflections needs a force per pair");
  std::vector<ToothPairDeflection> out(pairs.size());
  if (!teeth_) return out;
  const double w_ref = teeth_->reference_load;
  for (std::size_t i = 0; i < pairs.size(); ++i) {
    const auto [t1, t2] = Rolls(pairs[i]);
    const double w = forces[i] / face_width_;  // per face width
    const ToothComplianceAt q1 = InterpolateCompliance(teeth_->tooth1, t1);
    const ToothComplianceAt q2 = InterpolateCompliance(teeth_->tooth2, t2);
    const Series series = PairSeries(pairs[i]);
    const double flat = !teeth_->flattening_at_load ? series.Flattening(w_ref) * w / w_ref
                        : w > 0.0                   ? series.Flattening(w)
                                                    : 0.0;
    out[i] = {q1.compliance * w, q2.compliance * w, flat};
  }
  if (coupled() && pairs.size() == 2 && pairs[0].side == pairs[1].side) {
    const std::size_t a = pairs[0].roll1 > pairs[1].roll1 ? 0 : 1, b = 1 - a;
    const RimCoupling &rim1 = *teeth_->rim1, &rim2 = *teeth_->rim2;
    const double w_a = forces[a] / face_width_, w_b = forces[b] / face_width_;
    out[a].tooth1 += RimCouplingAt(rim1.roll, rim1.ahead, pairs[b].roll1) * w_b;
    out[a].tooth2 += RimCouplingAt(rim2.roll, rim2.behind, pairs[b].roll2) * w_b;
    out[b].tooth1 += RimCouplingAt(rim1.roll, rim1.behind, pairs[a].roll1) * w_a;
    out[b].tooth2 += RimCouplingAt(rim2.roll, rim2.ahead, pairs[a].roll2) * w_a;
  }
  return out;
}

MeshLoads EvaluateMesh(const GearPair& pair, const MeshLaw& law, double centre_distance,
                       double phi1, double phi2, double omega1, double omega2) {
  MeshLoads loads;
  const Eigen::Vector2d p_O1O2(centre_distance, 0.0);
  std::vector<ToothPair> touching;
  std::vector<double> rates;
  for (const ToothPair& tp : MeshingToothPairs(pair, centre_distance, phi1, phi2)) {
    if (!(tp.gap < 0.0)) continue;
    touching.push_back(tp);
    // delta' = -n_12 . (v2 - v1) at the contact point (exact for a corner too: the two
    // points' offset lies along n_12, across which the turning adds nothing).
    rates.push_back(Cross(tp.p_O1C, tp.n_12) * omega1 - Cross(tp.p_O1C - p_O1O2, tp.n_12) * omega2);
  }
  const std::vector<double> forces = law.Forces(touching, rates);
  for (std::size_t i = 0; i < touching.size(); ++i) {
    const ToothPair& tp = touching[i];
    const double force = forces[i];
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
