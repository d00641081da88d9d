#include "mbs/contact_mode_advice_pcm.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <vector>

#include "contact/pcm/bvh.h"
#include "contact/pcm/candidate_pairs.h"
#include "contact/pcm/contact_element.h"
#include "contact/pcm/foundation.h"
#include "core/error.h"

namespace flexmbs::mbs {
namespace {

/// The velocity of the point p_W carried by a marker's frame [m/s].
Eigen::Vector3d FrameVelocity(const MarkerKinematics& M, const Eigen::Vector3d& p_W) {
  return M.v_WM_W + M.w_WM_W.cross(p_W - M.p_WM_W);
}

double Volume(const std::vector<contact::PcmElement>& elements) {
  double volume = 0.0;
  for (const contact::PcmElement& e : elements) volume += e.volume;
  return volume;
}

}  // namespace

PcmTouchProbe::PcmTouchProbe(const MultibodySystem& system, const PcmContactForce& element, const ConstVectorRef& y0)
    : A_(system, element.A(), y0), B_(system, element.B(), y0) {
  c_ = contact::MakeElasticFoundation(element.A().layer, element.A().name, element.B().layer, element.B().name, 0.0,
                                      contact::RegularisedCoulomb{0.0, 1.0})
           .stiffness;
  const Eigen::Matrix3Xd& a = A_.mesh().vertices_W;
  const Eigen::Matrix3Xd& b = B_.mesh().vertices_W;
  extent_ = (a.rowwise().maxCoeff().cwiseMax(b.rowwise().maxCoeff()) -
             a.rowwise().minCoeff().cwiseMin(b.rowwise().minCoeff()))
                .norm();
  // The approach direction: A's velocity against B's at A's centroid, else gravity's pull.
  const Eigen::Vector3d centroid = a.rowwise().mean();
  const Eigen::Vector3d v_AB = A_.velocities_W().rowwise().mean() - FrameVelocity(B_.frame(), centroid);
  Eigen::Vector3d t = v_AB;
  if (!(t.norm() > 0.0)) {
    if (element.A().marker.is_ground() == element.B().marker.is_ground()) return;  // no relative fall
    t = element.A().marker.is_ground() ? Eigen::Vector3d(-system.gravity()) : system.gravity();
  }
  if (!(t.norm() > 0.0) || !(extent_ > 0.0)) return;
  t.normalize();
  const auto touching = [&](double s, double depth) { return Volume(Elements(s * t, depth)) > 0.0; };
  // Bracket first touch between lo (apart) and hi (overlapping); any penetration at hi is at most
  // hi - lo deep (or, overlapping at y0, the meshes' extent).
  double lo = 0.0, hi = 0.0;
  if (touching(0.0, extent_)) {
    for (double step = 1e-6 * extent_; lo > -2.0 * extent_; step *= 2.0) {
      lo = -step;
      if (!touching(lo, extent_)) break;
    }
    if (touching(lo, extent_)) return;
  } else {
    for (double step = 1e-6 * extent_;; step *= 2.0) {
      if (step > 2.0 * extent_) return;
      if (touching(step, 1.01 * (step - lo))) {
        hi = step;
        break;
      }
      lo = step;
    }
  }
  for (int k = 0; k < 200 && hi - lo > 1e-15 * extent_; ++k) {
    const double mid = 0.5 * (lo + hi);
    (touching(mid, 1.01 * (mid - lo) + 1e-15 * extent_) ? hi : lo) = mid;
  }
  touch_W_ = hi * t;
  // The normal from the elements 1e-6 of the extent past first touch: there every face pair that
  // meets first has a volume well above the bisection's round-off (an edge across an edge: all
  // four, the normal their symmetric mean). The touch point and the gap rate from the elements at
  // first touch.
  const double past = 1e-6 * extent_;
  const std::vector<contact::PcmElement> deeper = Elements(touch_W_ + past * t, 1.01 * (hi - lo + past));
  const std::vector<contact::PcmElement> first = Elements(touch_W_, 1.01 * (hi - lo) + 1e-15 * extent_);
  const double deeper_volume = Volume(deeper), volume = Volume(first);
  if (!(volume > 0.0 && deeper_volume > 0.0)) return;
  Eigen::Vector3d n = Eigen::Vector3d::Zero(), v_touch = Eigen::Vector3d::Zero();
  for (const contact::PcmElement& e : deeper) n += (e.volume / deeper_volume) * e.normal_W;
  n_W_ = n.normalized();
  contact::PolygonMesh moved = A_.mesh();
  moved.vertices_W.colwise() += touch_W_;
  for (const contact::PcmElement& e : first) {
    const double w = e.volume / volume;
    p_W_ += w * e.pressure_centre_W;
    v_touch += w * contact::RelativeVelocity(e, moved, A_.velocities_W(), B_.mesh(), B_.velocities_W());
  }
  gap_rate_ = n_W_.dot(v_touch);
  gap_ = std::max(0.0, -hi * t.dot(n_W_));
  found_ = true;
}

std::vector<contact::PcmElement> PcmTouchProbe::Elements(const Eigen::Vector3d& offset_W, double max_depth) const {
  contact::PolygonMesh moved = A_.mesh();
  moved.vertices_W.colwise() += offset_W;
  const contact::Bvh tree_A(moved), tree_B(B_.mesh(), max_depth);
  return contact::ContactElements(moved, B_.mesh(), contact::CandidatePairs(tree_A, tree_B), max_depth);
}

PcmTouchProbe::Load PcmTouchProbe::At(double depth) const {
  FLEXMBS_CHECK(found_ && depth > 0.0, "a PCM probe's depth past first touch");
  const std::vector<contact::PcmElement> elements =
      Elements(touch_W_ - depth * n_W_, 1.5 * depth + 1e-12 * extent_);
  Load load;
  const double volume = Volume(elements);
  if (!(volume > 0.0)) return load;
  load.force = c_ * volume;
  const auto modal_row = [&](const PlacedPcmSurface& side, bool a) {
    Eigen::RowVectorXd row;
    for (const contact::PcmElement& e : elements) {
      const Eigen::Matrix3Xd J = a ? side.ModalJacobian(e.face_A, e.weights_A) : side.ModalJacobian(e.face_B, e.weights_B);
      if (J.cols() == 0) return Eigen::RowVectorXd();
      if (row.size() == 0) row = Eigen::RowVectorXd::Zero(J.cols());
      row += (e.volume / volume) * (a ? 1.0 : -1.0) * e.normal_W.transpose() * J;
    }
    return row;
  };
  for (const contact::PcmElement& e : elements) load.p_W += (e.volume / volume) * e.pressure_centre_W;
  load.modal_a = modal_row(A_, true);
  load.modal_b = modal_row(B_, false);
  return load;
}

PcmLawFit FitPcmLaw(const PcmTouchProbe& probe, double mass, double speed) {
  FLEXMBS_CHECK(probe.found() && mass > 0.0 && speed > 0.0, "a PCM law's fit");
  PcmLawFit fit;
  double delta = 1e-4 * probe.extent();
  for (int k = 0; k < 50; ++k) {
    const double f2 = probe.At(delta).force, f1 = probe.At(0.5 * delta).force;
    if (!(f1 > 0.0 && f2 > 0.0)) break;
    fit.exponent = std::clamp(std::log2(f2 / f1), 1.0, 4.0);
    fit.stiffness = f2 / std::pow(delta, fit.exponent);
    const double p = fit.exponent + 1.0;
    const double next = std::pow(p * mass * speed * speed / (2.0 * fit.stiffness), 1.0 / p);
    const bool settled = std::abs(next - delta) <= 1e-9 * delta;
    delta = next;
    if (settled) break;
  }
  fit.depth = delta;
  fit.load = probe.At(delta);
  return fit;
}

}  // namespace flexmbs::mbs
