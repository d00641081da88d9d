#pragma once
// What reading a scene needs from stages mbs/ may not link (docs/design.md: mbs/ never reaches
// fem/): computations the caller of LoadScene hands in, app/'s for `flexmbs simulate`.

#include <functional>
#include <optional>

#include "contact/gears/spur_gear.h"
#include "contact/gears/tooth_stiffness.h"

namespace flexmbs::mbs {

/// One wheel's FE tooth as a scene's `teeth: fe` asks for it (docs/scene.md, spur_gear_contact).
struct ToothTableRequest {
  contact::SpurGear gear;           ///< the wheel, unthinned (contact::MakeSpurGear)
  contact::ToothMaterial material;  ///< the teeth's E and nu
  /// The options the scene gives; unset: the FE tooth's defaults.
  std::optional<double> mesh_size;  ///< the elements' edge [m] > 0
  std::optional<int> element_order;  ///< 1 or 2
  std::optional<int> loads;          ///< load points from the form circle to the tip, 2 to 100
  /// true: the tooth between its two neighbours on a three-tooth segment, giving its coupling to
  /// them through the rim as well (gear_tooth_fe::ToothCouplingFromFe); false: the tooth alone.
  bool rim = false;
};

/// A wheel's tooth tables from its FE tooth: its own compliance and, when the request asks for the
/// rim, its neighbours' deflections (then the compliance is the three-tooth segment's own).
struct ToothTables {
  contact::ToothCompliance compliance;
  std::optional<contact::RimCoupling> rim;  ///< set exactly when ToothTableRequest::rim
};

/// Computes a wheel's tooth tables from its FE tooth; may throw InputError (one line, unlocated:
/// the reader adds the scene's place).
using ToothTableProvider = std::function<ToothTables(const ToothTableRequest&)>;

/// The computations LoadScene may call; an empty one refuses the scene entries that need it.
struct SceneHooks {
  /// For `spur_gear_contact`'s `teeth: fe` (app/fe_tooth_table.h: gear_tooth_fe's FE tooth).
  ToothTableProvider tooth_table;
};

}  // namespace flexmbs::mbs
