#pragma once
// A spur gear tooth's compliance along its flank from the project's FE stage (docs/contact.md,
// "Elastic teeth"): gmsh meshes the tooth on its rim segment (tooth_geo.h), fem/ assembles K,
// and one sparse factorisation gives the tooth's deflection under a load along the line of action
// at each load point of the flank.

#include <vector>

#include "contact/gears/spur_gear.h"
#include "gear_tooth_fe/tooth_geo.h"
#include "contact/gears/tooth_stiffness.h"

namespace flexmbs::gear_tooth_fe {

/// The FE tooth's options: its outline, the elements and the load points.
struct ToothModelOptions {
  ToothGeometryOptions geometry;
  int element_order = 2;  ///< 1: hex8 (wedge6), 2: hex20 (wedge15)
  int loads = 9;          ///< load points from the form circle to the tip (>= 2)
};

/// What an FE tooth run gives: the compliance table and the size of the model.
struct ToothModelResult {
  contact::ToothCompliance compliance;
  long nodes = 0;     ///< the mesh's nodes
  long elements = 0;  ///< its elements
};

/// The compliance of `gear`'s tooth (unthinned, MakeSpurGear) in plane strain: the slab's faces
/// held in z, the cut faces and the bore clamped, a unit load per face width along -n (into the
/// tooth) at each load point, spread over the face width by the element edges' consistent
/// weights; the deflection is the centre point's displacement along -n (ToothCompliance).
/// InputError from MakeToothGeometry, fem::ImportMesh, or for an invalid material.
ToothModelResult ToothComplianceFromFe(const contact::SpurGear& gear,
                                       const contact::ToothMaterial& material,
                                       const ToothModelOptions& options);

/// The loaded tooth between its two neighbours on a three-tooth segment (ToothGeometryOptions::
/// teeth = 3): for a load on the loaded tooth's flank at roll t_k, its own deflection and the
/// neighbours' where the same line of action crosses their centre lines (ToothGeometry::ahead,
/// behind), along the line, per load per face width [m^2/N]. In double contact the other pair's
/// tooth is such a neighbour: `ahead` the one at roll t_k + 2 pi / z on that line, `behind` at
/// t_k - 2 pi / z; these are the cross-compliances the one-tooth table leaves out.
struct ToothCoupling {
  /// The loaded tooth's own table on the three-tooth segment (ToothComplianceFromFe's columns).
  contact::ToothCompliance compliance;
  /// The neighbours' deflections at the same rolls: ahead (t_k + 2 pi / z), behind (t_k - 2 pi /
  /// z); NaN off the neighbour's flank.
  contact::RimCoupling rim;
  long nodes = 0;  ///< the mesh's nodes
};

/// ToothCoupling of `gear`'s tooth (options.geometry.teeth set to 3; the rest as
/// ToothComplianceFromFe). InputError as ToothComplianceFromFe.
ToothCoupling ToothCouplingFromFe(const contact::SpurGear& gear,
                                  const contact::ToothMaterial& material,
                                  ToothModelOptions options);

}  // namespace flexmbs::gear_tooth_fe
