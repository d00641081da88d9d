#pragma once
// The load at one contact point at an output time, as the ParaView files draw it (docs/results.md,
// "ParaView files"): compliant contact force elements give theirs from the state, Moreau-Jean and
// event-driven integration from their impulses and contact forces.

#include <Eigen/Core>

namespace flexmbs::mbs {

/// One contact point's load on body A (body B carries the opposite) in W.
struct ContactLoad {
  int contact_id = 0;                                ///< which contact (docs/results.md numbers them)
  Eigen::Vector3d p_W = Eigen::Vector3d::Zero();     ///< the contact point on A's surface [m]
  Eigen::Vector3d n_W = Eigen::Vector3d::UnitZ();    ///< the unit normal from B to A
  Eigen::Vector3d f_W = Eigen::Vector3d::Zero();     ///< the load on A [N]: normal and friction
};

}  // namespace flexmbs::mbs
