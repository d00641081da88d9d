#pragma once
// The FE stage behind a scene's `teeth: fe` (docs/scene.md, spur_gear_contact): `flexmbs
// simulate` hands it to mbs::LoadScene, which may not link gear_tooth_fe/ itself.

#include "contact/gears/tooth_stiffness.h"
#include "mbs/scene_hooks.h"

namespace flexmbs::app {

/// The wheel's tooth compliance table from gear_tooth_fe::ToothComplianceFromFe with the
/// request's options (the FE tooth's defaults where unset; mesh_size [m] over the module is the
/// tooth model's relative edge). InputError (one line) from the FE tooth.
contact::ToothCompliance FeToothTable(const mbs::ToothTableRequest& request);

/// The hooks `flexmbs simulate` loads scenes with: FeToothTable for `teeth: fe`.
mbs::SceneHooks SimulateSceneHooks();

}  // namespace flexmbs::app
