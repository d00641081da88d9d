#pragma once
// Tangentially movable elastic teeth (docs/contact.md, "Movable teeth"; the thesis' chapter 7):
// every tooth of both wheels turns about its wheel's axis, relative to the wheel body, by
// psi = d / r_b, d [m] its deflection (the arc at the base circle), held by its FE tooth's stiffness
// and a dashpot of its own; the tooth pairs touch on the moved teeth through the flanks'
// flattening. A tooth is massless: c_t d' + k_t d = Q, Q the mesh's generalised force on it, so
// d is a first-order state integrated with the system (mbs/movable_teeth_gear_contact.h).

#include "contact/gears/gear_mesh.h"
#include "contact/gears/spur_gear.h"
#include "contact/gears/tooth_stiffness.h"

namespace flexmbs::contact {

/// The teeth of a pair with movable teeth: their compliance tables and material (the rims'
/// coupling and the flattening at load are the static law's, not taken) and each tooth's dashpot.
struct MovableTeeth {
  ElasticTeeth teeth;
  double damping = 0.0;  ///< c_t [N s/m] > 0, per tooth, on its deflection's rate
};

/// InputError (one line) unless `teeth` passes CheckElasticTeeth without rim tables or the
/// flattening at load, and the damping is finite and > 0.
void CheckMovableTeeth(const MovableTeeth& teeth);

/// How tooth pair `tp` of `pair` at centre distance a [m] follows its teeth: with tooth i turned
/// by d_i / r_bi about +z, the gap is g + lever1 d1 + lever2 d2 (to first order in d) and a
/// normal force F on the pair puts the generalised force lever_i F on tooth i (the torque about
/// its axis over r_bi). On the line of action lever_i = -sigma, exactly (an involute turned by psi
/// moves r_b psi along its normal everywhere); for a tip corner the corner's wheel's lever is its
/// arm at the contact point over r_b, shorter.
struct ToothLevers {
  double lever1 = 0.0, lever2 = 0.0;  ///< [-]
};
ToothLevers PairLevers(const GearPair& pair, double centre_distance, const ToothPair& tp);

/// The flanks' contact stiffness k_H [N/m] of tooth pair `tp`: Weber's flattening linearised at
/// w_ref, b w_ref / delta_H(w_ref) (b the common face width; roll angles held at or above the
/// tables' first, as the static law's).
double FlatteningStiffness(const MovableTeeth& teeth, const GearPair& pair, const ToothPair& tp);

/// The stiffness k_t [N/m] of a tooth of wheel `wheel` (1 or 2) under a load at roll angle t
/// [rad]: b / q(t) from its compliance table (held beyond the table's ends).
double ToothStiffness(const MovableTeeth& teeth, const GearPair& pair, int wheel, double roll);

/// The roll angle [rad] of the operating pitch point on both wheels' flanks at centre distance
/// a: tan(alpha_w). A tooth out of mesh relaxes on its stiffness there.
double PitchRoll(const GearPair& pair, double centre_distance);

}  // namespace flexmbs::contact
