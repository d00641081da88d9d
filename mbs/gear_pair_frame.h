#pragma once
// The transverse frame of a spur gear pair between two markers (docs/contact.md, "Spur gears"),
// shared by the gear force elements: where the wheels are, how far apart, at which angles, and
// where a tooth pair's contact point and normal lie in W.

#include <Eigen/Core>
#include <string_view>

#include "contact/gears/gear_mesh.h"
#include "contact/gears/spur_gear.h"
#include "mbs/body.h"
#include "mbs/compliant_contact.h"
#include "mbs/marker_ref.h"

namespace flexmbs::mbs {

class MultibodySystem;

/// Wheel 1 on marker W1, wheel 2 on marker W2, each marker's z axis its wheel's axis and its x axis
/// tooth 0's centre line. The transverse plane is W1's xy plane; the pair frame's x axis runs from
/// W1 to W2's origin projected on it (the current centre distance a), its origin is W1's origin
/// moved half the axial offset, and each wheel's angle phi_i (contact::FlankPoint) is that of its
/// marker's x axis from there about W1's z.
struct GearPairFrame {
  MarkerKinematics wheel1, wheel2;
  double centre_distance = 0.0;   ///< a [m]
  Eigen::Vector3d x_W, y_W;       ///< the pair frame's x (W1 -> W2) and y axes in W
  Eigen::Vector3d p_WO_W;         ///< its origin [m]
  double phi1 = 0.0, phi2 = 0.0;  ///< the wheels' angles [rad]
};

/// The frame of `pair` on markers wheel1, wheel2 at (t, y). Throws SimulationError naming the
/// element `name` if the axes come within r_b1 + r_b2 of each other or are more than 8.1 deg from
/// parallel (a marker's z reversed).
GearPairFrame MeasureGearPairFrame(double t, const MultibodySystem& system, const ConstVectorRef& y,
                                   const MarkerRef& wheel1, const MarkerRef& wheel2,
                                   const contact::GearPair& pair, std::string_view name);

/// The contact point of tooth pair `tp` in frame `f` with penetration `penetration` [m]: in the
/// middle of its two flank points, half way between the markers' planes, normal n_12 (wheel 2,
/// body a, takes F n_12; wheel 1 is body b).
ContactPoint GearContactPoint(const GearPairFrame& f, const contact::ToothPair& tp, double penetration);

/// Adds a tooth pair's load `force` [N] at `point` to h (size num_velocities()): wheel 2 (marker
/// wheel2, point.a) F n_W at the contact point, wheel 1 -F n_W. With force 1 it adds w, the pair's
/// generalised force per unit normal force (delta' = -w^T u).
void AddGearPairLoad(const MultibodySystem& system, const MarkerRef& wheel1, const MarkerRef& wheel2,
                     const ContactPoint& point, double force, Eigen::Ref<Eigen::VectorXd> h);

}  // namespace flexmbs::mbs
