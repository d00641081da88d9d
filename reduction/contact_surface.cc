#include "reduction/contact_surface.h"

#include <fmt/format.h>

#include "core/error.h"

namespace flexmbs::reduction {

sid::ContactSurface MakeContactSurface(const std::string& name, const fem::PolygonSurface& polygons,
                                       const Eigen::MatrixXd& Phi) {
  sid::ContactSurface surface;
  surface.name = name;
  surface.fe_nodes = polygons.fe_nodes;
  surface.vertices = polygons.vertices;
  surface.face_sizes = polygons.face_sizes;
  surface.face_vertices = polygons.face_vertices;
  surface.face_normals = polygons.face_normals;
  surface.phi.resize(3 * static_cast<Eigen::Index>(polygons.fe_nodes.size()), Phi.cols());
  for (std::size_t v = 0; v < polygons.fe_nodes.size(); ++v) {
    const Eigen::Index node = polygons.fe_nodes[v];
    FLEXMBS_CHECK(3 * node + 3 <= Phi.rows(), "the surface's FE nodes are rows of Phi");
    surface.phi.middleRows<3>(3 * static_cast<Eigen::Index>(v)) = Phi.middleRows<3>(3 * node);
  }
  return surface;
}

std::vector<sid::ContactSurface> ContactSurfaces(const fem::Mesh& mesh,
                                                 const std::vector<std::string>& node_sets,
                                                 const Eigen::MatrixXd& Phi) {
  std::vector<sid::ContactSurface> surfaces;
  if (node_sets.empty()) return surfaces;
  const std::vector<fem::BoundaryFace> faces = fem::BoundaryFaces(mesh);
  for (const std::string& name : node_sets) {
    const auto set = mesh.node_sets.find(name);
    if (set == mesh.node_sets.end()) {
      throw InputError(
          fmt::format("sid.contact_surfaces: '{}': the mesh has no such node set", name));
    }
    const fem::PolygonSurface polygons = fem::BoundarySurface(mesh, faces, set->second);
    if (polygons.num_faces() == 0) {
      const std::size_t count = set->second.size();
      throw InputError(fmt::format(
          "sid.contact_surfaces: '{}': none of the mesh's {} boundary faces has all its "
          "nodes in this set of {} node{}: name a set of whole boundary faces (a "
          "physical surface)",
          name, faces.size(), count, count == 1 ? "" : "s"));
    }
    surfaces.push_back(MakeContactSurface(name, polygons, Phi));
  }
  return surfaces;
}

}  // namespace flexmbs::reduction
