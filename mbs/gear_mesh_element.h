#pragma once
// What the gear force elements (SpurGearContact, MovableTeethGearContact) show of their mesh: the
// common base the results file's gears/ group reads (app/gear_results.h).

#include <vector>

#include "contact/gears/gear_mesh_force.h"
#include "contact/gears/spur_gear.h"
#include "mbs/compliant_contact.h"
#include "mbs/force_element.h"
#include "mbs/gear_pair_frame.h"

namespace flexmbs::mbs {

/// A force element meshing a spur gear pair between two markers (mbs/gear_pair_frame.h).
class GearMeshElement : public ForceElement {
 public:
  /// The mesh at a state as an engineer reads it: every tooth pair that can mesh with its force,
  /// the wheels' angles and the torques the element puts on them.
  struct Readout {
    double centre_distance = 0.0;   ///< a [m], the markers' current one
    double phi1 = 0.0, phi2 = 0.0;  ///< the wheels' angles [rad] (contact::FlankPoint)
    /// Every pair of contact::MeshingToothPairs (gap: on the teeth as they stand); force [N] the
    /// law's, 0 for a pair apart.
    std::vector<contact::ToothPairLoad> pairs;
    /// Per pair (same order) its teeth's deflections along the line, each the gap's share (zeros
    /// for rigid teeth).
    std::vector<contact::ToothPairDeflection> deflections;
    /// The torques [N m] on wheel 1 and wheel 2 about their axes (the markers' z through the
    /// markers' origins) from the pairs' loads at their contact points.
    double torque1 = 0.0, torque2 = 0.0;
  };
  /// The mesh at time t [s] and state y.
  virtual Readout Read(double t, const MultibodySystem& system, const ConstVectorRef& y) const = 0;
  /// The pair's geometry (its nominal centre distance; the element uses the markers' one).
  virtual const contact::GearPair& pair() const = 0;
};

/// Adds to `readout`'s torques those of a pair's load `force` [N] at `point` in frame `f` (wheel
/// 2 F n_W at the contact point, wheel 1 -F n_W).
void AddPairTorques(const GearPairFrame& f, const ContactPoint& point, double force,
                    GearMeshElement::Readout* readout);

}  // namespace flexmbs::mbs
