// The checks on what gmsh returns (fem/gmsh_mesh_arrays.h), with arrays no file gives: every bad
// shape is a one-line InputError, and any tags (sparse, huge, repeated) give a compact mesh.
#include "fem/gmsh_mesh_arrays.h"
#include "tests/input_error.h"

#include <gtest/gtest.h>

#include <cstdint>
#include <limits>
#include <string>
#include <vector>

namespace flexmbs::fem {
namespace {

constexpr int kGmshTet4 = 4;
constexpr int kGmshPyramid5 = 7;

// Two tetrahedra sharing the face 1-2-3 (tests/data/two_tets.msh), node 5 renamed `far_tag`.
GmshElementBlock TwoTets(std::size_t far_tag) {
  return {kGmshTet4, "solid", {1, 2}, {1, 2, 3, 4, 1, 3, 2, far_tag}};
}

GmshNodes TwoTetsNodes(std::size_t far_tag) {
  return {{1, 2, 3, 4, far_tag}, {0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1, 0, 0, -1}};
}

std::string ErrorOf(std::vector<GmshElementBlock> blocks, const GmshNodes& nodes) {
  return testing::InputErrorMessage([&] { MeshFromGmshArrays("m.msh", std::move(blocks), nodes); });
}

// Found while extracting these checks for fuzz_mesh_arrays: the import indexed arrays by node tag, so one node
// tagged 2^60 asked for 2^60 entries (std::bad_alloc, an internal error, instead of a mesh).
TEST(GmshMeshArrays, HugeSparseTagsGiveACompactMeshInTagOrder) {
  constexpr std::size_t kFar = std::size_t{1} << 60;
  const Mesh mesh = MeshFromGmshArrays("m.msh", {TwoTets(kFar)}, TwoTetsNodes(kFar));
  ASSERT_EQ(mesh.num_nodes(), 5);
  EXPECT_EQ(mesh.node_ids, (std::vector<std::size_t>{1, 2, 3, 4, kFar}));
  EXPECT_EQ(mesh.nodes(2, 4), -1.0);
  ASSERT_EQ(mesh.blocks.size(), 1u);
  EXPECT_EQ(mesh.blocks[0].connectivity(3, 1), 4);
  EXPECT_EQ(mesh.blocks[0].element_ids, (std::vector<std::size_t>{1, 2}));
}

TEST(GmshMeshArrays, UnusedNodesAreLeftOutAndARepeatedTagTakesItsLastCoordinates) {
  GmshNodes nodes = TwoTetsNodes(5);
  nodes.tags.push_back(9);  // used by no element
  nodes.tags.push_back(4);  // node 4 again, moved
  nodes.coords.insert(nodes.coords.end(), {7, 7, 7, 0, 0, 2});
  const Mesh mesh = MeshFromGmshArrays("m.msh", {TwoTets(5)}, nodes);
  EXPECT_EQ(mesh.node_ids, (std::vector<std::size_t>{1, 2, 3, 4, 5}));
  EXPECT_EQ(mesh.nodes(2, 3), 2.0);
}

TEST(GmshMeshArrays, NodeTagsNotAWholeNumberOfElementsAreAnError) {
  GmshElementBlock block = TwoTets(5);
  block.node_tags.pop_back();
  EXPECT_EQ(ErrorOf({block}, TwoTetsNodes(5)),
            "m.msh: region 'solid': 2 tet4 elements with 7 node tags (expected 4 per element)");
}

TEST(GmshMeshArrays, NodeTagsWithoutElementsAreAnError) {
  const GmshElementBlock block{kGmshTet4, "solid", {}, {1, 2, 3, 4}};
  EXPECT_EQ(ErrorOf({block}, TwoTetsNodes(5)), "m.msh: region 'solid': 4 node tags without elements");
}

TEST(GmshMeshArrays, CoordinatesNotThreePerNodeAreAnError) {
  GmshNodes nodes = TwoTetsNodes(5);
  nodes.coords.pop_back();
  EXPECT_EQ(ErrorOf({TwoTets(5)}, nodes),
            "m.msh: the mesher returned 5 nodes with 14 coordinates (expected 3 per node)");
}

TEST(GmshMeshArrays, ANonFiniteCoordinateIsAnError) {
  GmshNodes nodes = TwoTetsNodes(5);
  nodes.coords[4] = std::numeric_limits<double>::quiet_NaN();
  EXPECT_EQ(ErrorOf({TwoTets(5)}, nodes), "m.msh: node 2 has a non-finite coordinate (1, nan, 0)");
}

TEST(GmshMeshArrays, AnElementNodeWithoutCoordinatesIsAnError) {
  EXPECT_EQ(ErrorOf({TwoTets(6)}, TwoTetsNodes(5)),
            "m.msh: region 'solid': element 2 uses node 6, which has no coordinates");
}

TEST(GmshMeshArrays, AnUnsupportedTypeAndNoElementsAreErrors) {
  const GmshElementBlock pyramid{kGmshPyramid5, "solid", {3}, {1, 2, 3, 4, 5}};
  EXPECT_EQ(ErrorOf({pyramid}, TwoTetsNodes(5)).rfind("m.msh: region 'solid': element 3 is a pyramid5 (gmsh type 7)", 0),
            0u);
  EXPECT_EQ(ErrorOf({}, TwoTetsNodes(5)), "m.msh: the mesh has no volume elements");
}

TEST(GmshMeshArrays, NodeSetTagsMapToSortedMeshNodesSkippingOthers) {
  const Mesh mesh = MeshFromGmshArrays("m.msh", {TwoTets(50)}, TwoTetsNodes(50));
  EXPECT_EQ(MeshNodesOfTags(mesh, {50, 7, 2, 2, 0, std::numeric_limits<std::size_t>::max()}),
            (std::vector<int>{1, 4}));
}

}  // namespace
}  // namespace flexmbs::fem
