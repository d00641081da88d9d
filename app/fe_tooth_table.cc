#include "app/fe_tooth_table.h"

#include "gear_tooth_fe/tooth_model.h"

namespace flexmbs::app {

contact::ToothCompliance FeToothTable(const mbs::ToothTableRequest& request) {
  gear_tooth_fe::ToothModelOptions options;
  if (request.mesh_size) options.geometry.mesh_size = *request.mesh_size / request.gear.spec.module;
  if (request.element_order) options.element_order = *request.element_order;
  if (request.loads) options.loads = *request.loads;
  return gear_tooth_fe::ToothComplianceFromFe(request.gear, request.material, options).compliance;
}

mbs::SceneHooks SimulateSceneHooks() { return {FeToothTable}; }

}  // namespace flexmbs::app
