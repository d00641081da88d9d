// Contact surfaces of a reduced body: boundary polygons of node sets with their vertices' modes.
#include "reduction/contact_surface.h"

#include <gtest/gtest.h>

#include <random>

#include "basis_test_support.h"
#include "tests/input_error.h"

namespace flexmbs::reduction {
namespace {

using fem::ElementType;

// Face normals of a box face: exact up to round-off of O(0.1) coordinates.
constexpr double kRoundOff = 1e-12;

TEST(ContactSurfaces, VertexModesAreTheRowsOfPhiOfTheirNodes) {
  testing::Body b =
      testing::MakeBox(ElementType::kTet10, {3, 2, 1}, {0.3, 0.2, 0.05}, testing::Steel());
  fem::Mesh& mesh = b.mesh;
  mesh.node_sets["top"] = testing::NodesAt(mesh, 2, 0.05);
  mesh.node_sets["end"] = testing::NodesAt(mesh, 0, 0.3);
  std::mt19937 rng(9);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  const Eigen::MatrixXd Phi = Eigen::MatrixXd::NullaryExpr(
      mesh.num_dofs(), 4, [&](Eigen::Index, Eigen::Index) { return unit(rng); });

  const std::vector<sid::ContactSurface> surfaces = ContactSurfaces(mesh, {"top", "end"}, Phi);
  ASSERT_EQ(surfaces.size(), 2u);
  const std::vector<Eigen::Vector3d> normals = {Eigen::Vector3d::UnitZ(), Eigen::Vector3d::UnitX()};
  for (std::size_t i = 0; i < surfaces.size(); ++i) {
    const sid::ContactSurface& s = surfaces[i];
    SCOPED_TRACE(s.name);
    EXPECT_EQ(s.name, i == 0 ? "top" : "end");
    // The whole face lies in its node set: every node of the set is a vertex.
    EXPECT_EQ(s.fe_nodes, mesh.node_sets[s.name]);
    ASSERT_EQ(s.phi.rows(), 3 * static_cast<Eigen::Index>(s.fe_nodes.size()));
    ASSERT_EQ(s.phi.cols(), 4);
    for (std::size_t v = 0; v < s.fe_nodes.size(); ++v) {
      const auto row = static_cast<Eigen::Index>(v);
      EXPECT_EQ(s.vertices.row(row).transpose(), mesh.nodes.col(s.fe_nodes[v]));
      EXPECT_EQ(s.phi.middleRows<3>(3 * row),
                Phi.middleRows<3>(3 * static_cast<Eigen::Index>(s.fe_nodes[v])));
    }
    const auto num_faces = static_cast<Eigen::Index>(s.face_sizes.size());
    ASSERT_EQ(s.face_normals.rows(), num_faces);
    std::size_t total = 0;
    for (const int size : s.face_sizes) total += static_cast<std::size_t>(size);
    EXPECT_EQ(s.face_vertices.size(), total);
    for (Eigen::Index f = 0; f < num_faces; ++f) {
      EXPECT_LT((s.face_normals.row(f).transpose() - normals[i]).norm(), kRoundOff);
    }
  }
}

TEST(ContactSurfaces, ASetWithoutBoundaryFacesIsAnInputError) {
  testing::Body b =
      testing::MakeBox(ElementType::kHex8, {2, 2, 2}, {0.2, 0.2, 0.2}, testing::Steel());
  b.mesh.node_sets["centre"] = testing::NodesWhere(
      b.mesh, [](const Eigen::Vector3d& x) { return x.isApproxToConstant(0.1); });
  ASSERT_EQ(b.mesh.node_sets["centre"].size(), 1u);
  const Eigen::MatrixXd Phi = Eigen::MatrixXd::Zero(b.mesh.num_dofs(), 1);
  EXPECT_EQ(flexmbs::testing::InputErrorMessage([&] { ContactSurfaces(b.mesh, {"centre"}, Phi); }),
            "sid.contact_surfaces: 'centre': none of the mesh's 24 boundary faces has all its "
            "nodes in this set of 1 "
            "node: name a set of whole boundary faces (a physical surface)");
  EXPECT_EQ(flexmbs::testing::InputErrorMessage([&] { ContactSurfaces(b.mesh, {"pad"}, Phi); }),
            "sid.contact_surfaces: 'pad': the mesh has no such node set");
}

}  // namespace
}  // namespace flexmbs::reduction
