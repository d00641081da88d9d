#pragma once
// The law of a Polygonal Contact Model pair near its first touch, for the mode advice
// (mbs/contact_mode_advice.h; docs/contact.md, "Which modes a contact needs"). The layers press
// with p = c delta, so the force is c V(delta), V the overlap's volume under B's faces; how V grows
// with the depth past first touch depends on the features that meet: faces flat on each other
// V = A delta (n = 1), an edge on a face V ~ delta^2, a vertex into a face or an edge across an
// edge V ~ delta^3, a finely meshed sphere on a flat c pi R delta^2 (R - delta/3), about n = 2.
// Rather than classify the features, the probe moves A rigidly along the approach to first touch
// and measures c V at chosen depths past it; FitPcmLaw fits F = k delta^n there.

#include <Eigen/Core>

#include "mbs/multibody_system.h"
#include "mbs/pcm_contact_force.h"
#include "mbs/pcm_surface.h"

namespace flexmbs::mbs {

/// A PCM pair at y0 (both sides placed, a modal side deformed by its coordinates at y0), and A
/// moved rigidly towards B: first along the approach direction t (A's velocity against B's at A's
/// vertices' centroid, or gravity's pull on the pair when both are at rest) to first touch, then
/// along -n, B's normal there, by a depth delta.
class PcmTouchProbe {
 public:
  /// The layers' force and where it acts at one depth.
  struct Load {
    double force = 0.0;                                       ///< c V [N]
    Eigen::Vector3d p_W = Eigen::Vector3d::Zero();            ///< its pressure centre [m]
    /// Per flexible side, n^T of the force-weighted modal Jacobians of the elements' material
    /// points (A's under each pressure centre, B's at it) over the total force: the modes the
    /// load reaches. Empty for a rigid side.
    Eigen::RowVectorXd modal_a, modal_b;
  };

  /// Finds the first touch; found() false if A does not reach B within twice the extent of both
  /// meshes along t, or the pair neither moves nor falls. `element` and `system` must outlive this.
  PcmTouchProbe(const MultibodySystem& system, const PcmContactForce& element, const ConstVectorRef& y0);

  bool found() const { return found_; }
  /// The distance A moves along -n from y0 to first touch [m] (0 if it overlaps B at y0).
  double gap() const { return gap_; }
  /// B's outward normal at first touch: the volume-weighted mean of the elements' normals 1e-6 of
  /// the extent past it.
  const Eigen::Vector3d& normal_W() const { return n_W_; }
  /// Where A first touches B: the pressure centre of the elements at first touch [m].
  const Eigen::Vector3d& point_W() const { return p_W_; }
  /// n . (v_A - v_B) at first touch [m/s], the relative velocity the elements' volume-weighted mean
  /// (< 0 approaching).
  double gap_rate() const { return gap_rate_; }
  /// The layers' load with A pressed `depth` [m] (> 0) past first touch along -n.
  Load At(double depth) const;
  /// The diagonal of both meshes' bounding box at y0 [m]: the pair's length scale.
  double extent() const { return extent_; }

 private:
  /// The elements with A moved by `offset_W` [m]; B's face boxes swept to `max_depth`.
  std::vector<contact::PcmElement> Elements(const Eigen::Vector3d& offset_W, double max_depth) const;

  PlacedPcmSurface A_, B_;
  double c_ = 0.0;       // the layers' stiffness [N/m^3]
  double extent_ = 0.0;  // the diagonal of both meshes' bounding box [m]
  bool found_ = false;
  Eigen::Vector3d touch_W_ = Eigen::Vector3d::Zero();  // A's offset at first touch [m]
  Eigen::Vector3d n_W_ = Eigen::Vector3d::UnitZ(), p_W_ = Eigen::Vector3d::Zero();
  double gap_ = 0.0, gap_rate_ = 0.0;
};

/// F = k delta^n fitted to a probe's force at delta_m / 2 and delta_m, where delta_m is the
/// largest compression of that law meeting `mass` [kg] at `speed` [m/s] ((n + 1) m v^2 / (2k))^(1 /
/// (n + 1)) (mbs/contact_mode_advice.h): repeated from a first guess of 1e-4 of the meshes'
/// extent until delta_m changes by less than 1e-9 of itself (at most 50 times). n is kept in
/// [1, 4] (a convex overlap's volume grows at least linearly).
struct PcmLawFit {
  double stiffness = 0.0;  ///< k [N/m^n]
  double exponent = 1.0;   ///< n
  double depth = 0.0;      ///< delta_m [m]
  PcmTouchProbe::Load load;  ///< at delta_m
};
PcmLawFit FitPcmLaw(const PcmTouchProbe& probe, double mass, double speed);

}  // namespace flexmbs::mbs
