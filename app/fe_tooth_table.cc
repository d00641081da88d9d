#include "app/fe_tooth_table.h"

#include <optional>
#include <utility>

#include "gear_tooth_fe/tooth_model.h"

namespace flexmbs::app {

mbs::ToothTables FeToothTables(const mbs::ToothTableRequest& request) {
  gear_tooth_fe::ToothModelOptions options;
  if (request.mesh_size) options.geometry.mesh_size = *request.mesh_size / request.gear.spec.module;
  if (request.element_order) options.element_order = *request.element_order;
  if (request.loads) options.loads = *request.loads;
  if (request.rim) {
    gear_tooth_fe::ToothCoupling coupling =
        gear_tooth_fe::ToothCouplingFromFe(request.gear, request.material, options);
    return {std::move(coupling.compliance), std::move(coupling.rim)};
  }
  return {gear_tooth_fe::ToothComplianceFromFe(request.gear, request.material, options).compliance,
          std::nullopt};
}

mbs::SceneHooks SimulateSceneHooks() { return {FeToothTables}; }

}  // namespace flexmbs::app
