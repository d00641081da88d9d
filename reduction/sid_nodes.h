#pragma once

// The marker nodes of a reduced body (sid::Node, the SID `frame` node data): the interface
// markers of the reduction and the markers of the body file's `sid:` section.
//
// For a node K with position p_BoK_B and, per mode j, the translation phi_j and small rotation
// psi_j of its frame (docs/sid.md, SID node data; Wallrapp 1994):
//
//     origin: m0 = p_BoK_B, m1[j] = phi_j;   phi: m0 = [phi_1 .. phi_n];
//     psi:    m0 = [psi_1 .. psi_n];         AP: m0 = I, m1[j] = psi_j~.
//
// The order-1 stiffening blocks of phi and psi (unit nodal forces and moments, K0F, K0M) are
// left empty here. phi_j, psi_j come from the node's coupling: the rigid fit of the node set's
// motion (rigid and averaging markers, reduction::MarkerMotion) or the FE node's displacement
// and 1/2 curl u there (single nodes, fem::NodalRotation).

#include <Eigen/Core>
#include <string>
#include <vector>

#include "fem/mesh.h"
#include "reduction/interface_coupling.h"
#include "reduction/reduction_spec.h"
#include "reduction/sid_spec.h"
#include "sid/reduced_body.h"

namespace flexmbs::reduction {

/// The node of a rigid or averaging interface (its weights and marker position as given),
/// named after the interface, coupling "rigid" or "averaging". Phi: num_dofs x n.
/// Throws InputError for a node-set interface or nodes on one line (MarkerMotion).
sid::Node InterfaceMarkerNode(const fem::Mesh& mesh, const InterfaceSpec& interface,
                              const Eigen::MatrixXd& Phi);

/// The node of one FE node `fe_node`, coupling "node": at the node, phi = its rows of Phi,
/// psi = fem::NodalRotation.
sid::Node SingleFeNode(const fem::Mesh& mesh, const std::string& name, int fe_node,
                       const Eigen::MatrixXd& Phi);

/// The node list of a body: first the interfaces of `held_by` that have a marker (rigid and
/// averaging; node-set interfaces and supports have none), in order, then `markers` (the
/// `sid:` section) in order, their node sets resolved in mesh.node_sets. Throws InputError for
/// a marker's node set the mesh lacks or with the wrong count (CheckMarkerNodeSets), a name used
/// twice, or nodes on one line (rigid, averaging).
std::vector<sid::Node> MarkerNodes(const fem::Mesh& mesh, const Eigen::MatrixXd& Phi,
                                   const BoundaryConditions& held_by,
                                   const std::vector<MarkerSetting>& markers);

/// The names MarkerNodes gives the interface markers of a basis reduced as `spec` says (the
/// node set names of its rigid and averaging interfaces, as ResolveConditions names them): the
/// `reserved_names` of LoadSidSpec.
std::vector<std::string> InterfaceMarkerNames(const ReductionSpec& spec);

}  // namespace flexmbs::reduction
