#pragma once
// The FE stage behind a scene's `teeth: fe` (docs/scene.md, spur_gear_contact): `flexmbs
// simulate` hands it to mbs::LoadScene, which may not link gear_tooth_fe/ itself.

#include "mbs/scene_hooks.h"

namespace flexmbs::app {

/// The wheel's tooth tables with the request's options (the FE tooth's defaults where unset;
/// mesh_size [m] over the module is the tooth model's relative edge): with `rim` the compliance
/// and the rim's coupling of gear_tooth_fe::ToothCouplingFromFe (the three-tooth segment), else
/// the compliance of gear_tooth_fe::ToothComplianceFromFe. InputError (one line) from the FE tooth.
mbs::ToothTables FeToothTables(const mbs::ToothTableRequest& request);

/// The hooks `flexmbs simulate` loads scenes with: FeToothTables for `teeth: fe`.
mbs::SceneHooks SimulateSceneHooks();

}  // namespace flexmbs::app
