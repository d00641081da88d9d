#pragma once
// The gmsh input of one spur gear tooth on its rim segment (docs/contact.md, "Elastic teeth"):
// the transverse outline as the generating rack cuts it, extruded to a slab.

#include <Eigen/Core>
#include <string>
#include <vector>

#include "contact/gears/spur_gear.h"

namespace flexmbs::gear_tooth_fe {

/// The outline's proportions, relative to the module m.
struct ToothGeometryOptions {
  double rack_tip_radius = 0.38;  ///< rho_fP / m of the generating rack (ISO 53 profile A)
  /// The rim segment's half angle in pitches, 2 pi / z each: 1.5 keeps one pitch of bare rim on
  /// each side of the tooth's spaces, cut radially there.
  double segment_pitches = 1.5;
  /// The bore's depth below the root circle / m: r_i = r_f - rim_depth m (>= 0.2 r_f).
  double rim_depth = 3.5;
  double mesh_size = 0.25;  ///< the elements' edge / m
  /// Teeth on the segment: 1, or 3 (the loaded tooth between its two neighbours, the cuts
  /// segment_pitches beyond the neighbours' centre lines): the neighbours' coupling through the rim.
  int teeth = 1;
};

/// Where a neighbour tooth meets the line of action of the loaded tooth's load point k (the line
/// through it along its normal, tangent to the base circle): that line crosses the neighbour's
/// flank at roll t_k + 2 pi / z (the neighbour on the loaded flank's side, +x) or t_k - 2 pi / z
/// (the other), and its centre line at `centre_point`; `valid` where that roll lies on the
/// neighbour's involute (form circle to tip), where a second tooth pair can be in contact.
struct NeighbourPoint {
  bool valid = false;
  double roll = 0.0;                                  ///< the neighbour's roll there [rad]
  Eigen::Vector2d centre_point = Eigen::Vector2d::Zero();  ///< [m], tooth frame of the loaded tooth
};

/// The outline and the points the FE model needs.
struct ToothGeometry {
  std::string geo;  ///< a gmsh .geo script (built-in kernel): the slab, hex and wedge elements
  double face_width = 0.0;      ///< b [m] of the slab (plane strain makes it arbitrary)
  double bore_radius = 0.0;     ///< r_i [m]: clamped there
  double segment_angle = 0.0;   ///< Theta [rad]: the cut faces at +-Theta from the centre line
  std::vector<double> roll;     ///< t_k [rad] of the load points on the right flank
  std::vector<Eigen::Vector2d> load_point;    ///< the flank points [m], tooth frame
  std::vector<Eigen::Vector2d> load_normal;   ///< their outward normals (lines of action)
  std::vector<Eigen::Vector2d> centre_point;  ///< where each line crosses the centre line x = 0
  /// With three teeth, per load point: the neighbour on the loaded flank's side (ahead, +x) and
  /// the other (behind), embedded where valid; empty for one tooth.
  std::vector<NeighbourPoint> ahead, behind;
};

/// The tooth of `gear` (unthinned, MakeSpurGear) in its tooth frame (contact/gears/tooth_profile.h)
/// with `loads` >= 2 load points at roll angles from the form circle to the tip, equally spaced.
/// The load points and centre points are mesh vertices (curve ends, points embedded in the face);
/// with options.teeth = 3 the loaded tooth sits between two neighbours (ToothGeometry::ahead,
/// behind). InputError from RightFlankProfile, or for options out of range (teeth not 1 or 3).
ToothGeometry MakeToothGeometry(const contact::SpurGear& gear, const ToothGeometryOptions& options,
                                int loads);

}  // namespace flexmbs::gear_tooth_fe
