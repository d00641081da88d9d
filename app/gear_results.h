#pragma once
// The results file's gears/ groups (docs/results.md): per spur_gear_contact force element the
// series an engineer looks at — tooth pairs in contact, mesh force in total and per pair, the
// elastic teeth's deflections per pair, transmission error, the wheels' torques — as neutral
// element series of mbs/results_file.h, which knows no gear types.

#include <Eigen/Core>
#include <vector>

#include "mbs/multibody_system.h"
#include "mbs/results_file.h"

namespace flexmbs::app {

/// One ElementSeries "gears/<name>" per gear element of `system` (mbs::GearMeshElement:
/// SpurGearContact, MovableTeethGearContact), in its force element order.
std::vector<mbs::ResultsLayout::ElementSeries> GearSeries(const mbs::MultibodySystem& system);

/// The rows of GearSeries' channels at time t [s] and state y, in the same order.
std::vector<std::vector<Eigen::VectorXd>> GearRows(const mbs::MultibodySystem& system, double t,
                                                   const Eigen::VectorXd& y);

}  // namespace flexmbs::app
