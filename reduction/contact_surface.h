#pragma once

// The contact surfaces of a reduced body (sid::ContactSurface): boundary polygons of named
// node sets with the modal displacements of their vertices.

#include <Eigen/Core>
#include <string>
#include <vector>

#include "fem/boundary_surface.h"
#include "fem/mesh.h"
#include "sid/reduced_body.h"

namespace flexmbs::reduction {

/// The contact surface `name` from a polygon mesh through FE nodes and the basis Phi
/// (num_dofs x n): phi row 3 v + a = Phi row 3 fe_nodes[v] + a.
sid::ContactSurface MakeContactSurface(const std::string& name, const fem::PolygonSurface& polygons,
                                       const Eigen::MatrixXd& Phi);

/// One contact surface per node set name in `node_sets` (the `sid:` section's
/// contact_surfaces): the mesh's boundary faces whose nodes all lie in that node set
/// (fem::BoundarySurface), named after the set. Throws InputError "sid.contact_surfaces:
/// '<set>': ..." for a set the mesh lacks or one that covers no boundary face.
std::vector<sid::ContactSurface> ContactSurfaces(const fem::Mesh& mesh,
                                                 const std::vector<std::string>& node_sets,
                                                 const Eigen::MatrixXd& Phi);

}  // namespace flexmbs::reduction
