#include "reduction/sid_nodes.h"

#include <fmt/format.h>

#include <algorithm>

#include "core/error.h"
#include "core/skew.h"
#include "fem/nodal_rotation.h"

namespace flexmbs::reduction {
namespace {

using Index = Eigen::Index;

// The SID node data from the node's position and its per-mode translations and rotations
// (3 x n each), as in the file comment of sid_nodes.h.
sid::Node MakeNode(std::string name, std::vector<int> fe_nodes, std::string_view coupling,
                   const Eigen::Vector3d& p_BoK_B, const Eigen::MatrixXd& translations,
                   const Eigen::MatrixXd& rotations) {
  sid::Node node;
  node.name = std::move(name);
  node.fe_nodes = std::move(fe_nodes);
  node.coupling = coupling;
  node.origin.m0 = p_BoK_B;
  node.phi.m0 = translations;
  node.psi.m0 = rotations;
  node.AP.m0 = Eigen::Matrix3d::Identity();
  for (Index j = 0; j < translations.cols(); ++j) {
    node.origin.m1.push_back(translations.col(j));
    node.AP.m1.push_back(Skew(rotations.col(j)));
  }
  return node;
}

}  // namespace

sid::Node InterfaceMarkerNode(const fem::Mesh& mesh, const InterfaceSpec& interface,
                              const Eigen::MatrixXd& Phi) {
  const Eigen::MatrixXd motion = MarkerMotion(mesh.nodes, interface, Phi);  // 6 x n: [t; theta]
  return MakeNode(interface.name, interface.nodes, CouplingName(interface.coupling),
                  MarkerPosition(mesh.nodes, interface), motion.topRows<3>(),
                  motion.bottomRows<3>());
}

sid::Node SingleFeNode(const fem::Mesh& mesh, const std::string& name, int fe_node,
                       const Eigen::MatrixXd& Phi) {
  FLEXMBS_CHECK(fe_node >= 0 && fe_node < mesh.num_nodes(), "FE node in range");
  FLEXMBS_CHECK(Phi.rows() == mesh.num_dofs(), "one row of Phi per DOF");
  return MakeNode(name, {fe_node}, MarkerCouplingName(MarkerCoupling::kNode),
                  mesh.nodes.col(fe_node), Phi.middleRows<3>(3 * static_cast<Index>(fe_node)),
                  fem::NodalRotation(mesh, fe_node, Phi));
}

std::vector<sid::Node> MarkerNodes(const fem::Mesh& mesh, const Eigen::MatrixXd& Phi,
                                   const BoundaryConditions& held_by,
                                   const std::vector<MarkerSetting>& markers) {
  CheckMarkerNodeSets(markers, mesh.node_sets);
  std::vector<sid::Node> nodes;
  for (const InterfaceSpec& interface : held_by.interfaces) {
    if (interface.coupling != Coupling::kNodes)
      nodes.push_back(InterfaceMarkerNode(mesh, interface, Phi));
  }
  for (const MarkerSetting& marker : markers) {
    const bool repeated = std::any_of(nodes.begin(), nodes.end(),
                                      [&](const sid::Node& n) { return n.name == marker.name; });
    if (repeated)
      marker.Fail(
          fmt::format("the name '{}' is already a marker or interface marker", marker.name));
    const std::vector<int>& set = mesh.node_sets.at(marker.node_set);
    if (marker.coupling == MarkerCoupling::kNode) {
      nodes.push_back(SingleFeNode(mesh, marker.name, set.front(), Phi));
      continue;
    }
    InterfaceSpec fit;
    fit.name = marker.name;
    fit.nodes = set;
    fit.coupling =
        marker.coupling == MarkerCoupling::kRigid ? Coupling::kRigid : Coupling::kAveraging;
    fit.marker_position = marker.p_BoMarker_B;
    try {
      nodes.push_back(InterfaceMarkerNode(mesh, fit, Phi));
    } catch (const InputError& e) {
      marker.Fail(e.what());
    }
  }
  return nodes;
}

std::vector<std::string> InterfaceMarkerNames(const ReductionSpec& spec) {
  std::vector<std::string> names;
  for (const InterfaceSetting& interface : spec.interfaces) {
    if (interface.coupling != Coupling::kNodes) names.push_back(interface.node_set);
  }
  return names;
}

}  // namespace flexmbs::reduction
