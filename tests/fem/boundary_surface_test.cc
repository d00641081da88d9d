// The boundary surface of solid meshes: faces found, oriented outward, closed.
#include "fem/boundary_surface.h"

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <random>
#include <string>

#include "fem/reference_element.h"
#include "tests/fem/test_meshes.h"

namespace flexmbs::fem {
namespace {

// Reference coordinates and box coordinates are O(1) and the sums run over a few hundred
// polygons: round-off of a few hundred eps.
constexpr double kRoundOff = 1e-12;
// Cylinder of radius R meshed with size h, second order: the boundary polygons run through the
// mid-side nodes, so the section is an inscribed polygon with chord angle theta ~ h / (2 R)
// = 0.2. Its area deficit is theta^2 / 6 ~ 0.7 %, its perimeter deficit theta^2 / 24 ~ 0.2 %.
constexpr double kCylinderVolumeError = 0.01;
constexpr double kCylinderAreaError = 0.005;

std::vector<int> AllNodes(const Mesh& mesh) {
  std::vector<int> all(static_cast<std::size_t>(mesh.num_nodes()));
  for (std::size_t n = 0; n < all.size(); ++n) all[n] = static_cast<int>(n);
  return all;
}

std::vector<int> NodesWithCoordinate(const Mesh& mesh, int axis, double value) {
  std::vector<int> nodes;
  for (Eigen::Index n = 0; n < mesh.num_nodes(); ++n) {
    if (std::abs(mesh.nodes(axis, n) - value) < 1e-12) nodes.push_back(static_cast<int>(n));
  }
  return nodes;
}

Eigen::Vector3d Centroid(const PolygonSurface& s, std::size_t first, int size) {
  Eigen::Vector3d c = Eigen::Vector3d::Zero();
  for (int k = 0; k < size; ++k)
    c += s.vertices.row(s.face_vertices[first + static_cast<std::size_t>(k)]).transpose();
  return c / size;
}

// Sum of area * normal (the closed-surface integral of n dA, zero), sum of area * (n . x) / 3
// (the enclosed volume by the divergence theorem; exact for planar polygons) and the area.
struct SurfaceIntegrals {
  Eigen::Vector3d vector_area = Eigen::Vector3d::Zero();
  double volume = 0.0;
  double area = 0.0;
};
SurfaceIntegrals Integrate(const PolygonSurface& s) {
  SurfaceIntegrals out;
  std::size_t first = 0;
  for (Eigen::Index f = 0; f < s.num_faces(); ++f) {
    const int size = s.face_sizes[static_cast<std::size_t>(f)];
    const Eigen::Vector3d n = s.face_normals.row(f).transpose();
    out.vector_area += s.face_areas(f) * n;
    out.volume += s.face_areas(f) * n.dot(Centroid(s, first, size)) / 3.0;
    out.area += s.face_areas(f);
    first += static_cast<std::size_t>(size);
  }
  return out;
}

TEST(BoundaryFaces, ReferenceElementFacesAreItsFacesOrientedOutward) {
  for (const ElementTraits& traits : kElementTraits) {
    SCOPED_TRACE(std::string(traits.name));
    const ReferenceElement& ref = ReferenceElement::Of(traits.type);
    Mesh mesh;
    mesh.nodes = ref.nodes();
    ElementBlock block;
    block.type = traits.type;
    block.connectivity.resize(traits.num_nodes, 1);
    for (int a = 0; a < traits.num_nodes; ++a) block.connectivity(a, 0) = a;
    mesh.blocks.push_back(block);
    const Eigen::Vector3d centre = ref.nodes().rowwise().mean();

    const std::vector<BoundaryFace> faces = BoundaryFaces(mesh);
    const std::size_t expected_faces = traits.name.starts_with("tet")   ? 4
                                       : traits.name.starts_with("hex") ? 6
                                                                        : 5;
    ASSERT_EQ(faces.size(), expected_faces);
    std::vector<int> uses(static_cast<std::size_t>(traits.num_nodes), 0);
    for (const BoundaryFace& f : faces) {
      ASSERT_EQ(f.num_nodes, traits.order == 2 ? 2 * f.num_corners : f.num_corners);
      auto x = [&](int k) {
        return Eigen::Vector3d(ref.nodes().col(f.nodes[static_cast<std::size_t>(k)]));
      };
      Eigen::Vector3d normal = Eigen::Vector3d::Zero();
      for (int k = 0; k < f.num_corners; ++k) normal += x(k).cross(x((k + 1) % f.num_corners));
      normal.normalize();
      // Outward: every other node of the (convex) element lies strictly inside the face plane,
      // every face node on it; the centre is inside.
      EXPECT_LT(normal.dot(centre - x(0)), 0.0);
      for (int a = 0; a < traits.num_nodes; ++a) {
        const double height = normal.dot(ref.nodes().col(a) - x(0));
        const bool on_face = std::find(f.nodes.begin(), f.nodes.begin() + f.num_nodes, a) !=
                             f.nodes.begin() + f.num_nodes;
        if (on_face) {
          EXPECT_NEAR(height, 0.0, kRoundOff) << "node " << a;
          ++uses[static_cast<std::size_t>(a)];
        } else {
          EXPECT_LT(height, -0.1) << "node " << a;
        }
      }
      // Mid-side node k on edge corner k -> corner k + 1.
      for (int k = 0; f.num_nodes > f.num_corners && k < f.num_corners; ++k) {
        EXPECT_LT((x(f.num_corners + k) - 0.5 * (x(k) + x((k + 1) % f.num_corners))).norm(),
                  kRoundOff);
      }
    }
    // Every node of the element lies on some face (interior nodes do not exist in these types).
    for (int a = 0; a < traits.num_nodes; ++a)
      EXPECT_GT(uses[static_cast<std::size_t>(a)], 0) << "node " << a;
  }
}

struct BoxCase {
  ElementType type;
  ElementType second_type;
};

class BoxSurface : public ::testing::TestWithParam<BoxCase> {};

TEST_P(BoxSurface, IsClosedOutwardAndHasTheBoxAreaAndVolume) {
  const Eigen::Vector3d size(0.3, 0.5, 0.7);
  const Eigen::Vector3i cells(2, 3, 2);
  testing::BoxMesh box =
      testing::StructuredBox(GetParam().type, cells, size, GetParam().second_type, 1);
  std::mt19937 rng(7);
  testing::DistortInterior(&box, 0.2, 0.1,
                           &rng);  // interior faces become curved, the outside stays
  const Mesh& mesh = box.mesh;

  const PolygonSurface s = BoundarySurface(mesh, AllNodes(mesh));
  const bool quadratic = Traits(GetParam().type).order == 2;
  const bool tets = GetParam().type == ElementType::kTet4 || GetParam().type == ElementType::kTet10;
  if (tets) {
    // Each cell face is split into 2 triangles (Kuhn split), each into 4 if quadratic.
    const int cell_faces = 2 * (cells(0) * cells(1) + cells(1) * cells(2) + cells(2) * cells(0));
    EXPECT_EQ(s.num_faces(), cell_faces * 2 * (quadratic ? 4 : 1));
  }
  const SurfaceIntegrals integral = Integrate(s);
  const double area = 2.0 * (size(0) * size(1) + size(1) * size(2) + size(2) * size(0));
  EXPECT_NEAR(integral.area, area, kRoundOff * area);
  EXPECT_LT(integral.vector_area.norm(), kRoundOff * area);
  EXPECT_NEAR(integral.volume, size.prod(), kRoundOff * size.prod());

  // Every polygon lies on a face of the box and has that face's outward normal.
  std::size_t first = 0;
  for (Eigen::Index f = 0; f < s.num_faces(); ++f) {
    const int count = s.face_sizes[static_cast<std::size_t>(f)];
    const Eigen::Vector3d c = Centroid(s, first, count);
    Eigen::Vector3d expected = Eigen::Vector3d::Zero();
    int on_faces = 0;
    for (int axis = 0; axis < 3; ++axis) {
      for (const double side : {0.0, 1.0}) {
        if (std::abs(c(axis) - side * size(axis)) < 1e-12) {
          expected(axis) = side == 0.0 ? -1.0 : 1.0;
          ++on_faces;
        }
      }
    }
    ASSERT_EQ(on_faces, 1) << "polygon " << f << " at " << c.transpose();
    EXPECT_LT((s.face_normals.row(f).transpose() - expected).norm(), kRoundOff) << "polygon " << f;
    first += static_cast<std::size_t>(count);
  }
  // Vertices are the FE nodes used, ascending, at their positions: all boundary nodes.
  std::vector<int> boundary_nodes;
  for (std::size_t n = 0; n < box.on_boundary.size(); ++n) {
    if (box.on_boundary[n]) boundary_nodes.push_back(static_cast<int>(n));
  }
  EXPECT_EQ(s.fe_nodes, boundary_nodes);
  for (std::size_t v = 0; v < s.fe_nodes.size(); ++v) {
    EXPECT_EQ(s.vertices.row(static_cast<Eigen::Index>(v)).transpose(),
              mesh.nodes.col(s.fe_nodes[v]));
  }
}

TEST_P(BoxSurface, ANodeSetOfOneFaceGivesThatFaceOnly) {
  const Eigen::Vector3d size(0.3, 0.5, 0.7);
  const testing::BoxMesh box =
      testing::StructuredBox(GetParam().type, {2, 3, 2}, size, GetParam().second_type, 1);
  // The nodes of the face x = size(0) (they also lie on edges shared with other faces, whose
  // faces are not entirely in the set).
  const PolygonSurface s = BoundarySurface(box.mesh, NodesWithCoordinate(box.mesh, 0, size(0)));
  const SurfaceIntegrals integral = Integrate(s);
  EXPECT_NEAR(integral.area, size(1) * size(2), kRoundOff);
  for (Eigen::Index f = 0; f < s.num_faces(); ++f) {
    EXPECT_LT((s.face_normals.row(f).transpose() - Eigen::Vector3d::UnitX()).norm(), kRoundOff);
  }
  EXPECT_EQ(BoundarySurface(box.mesh, {}).num_faces(), 0);
}

INSTANTIATE_TEST_SUITE_P(ElementTypes, BoxSurface,
                         ::testing::Values(BoxCase{ElementType::kTet4, ElementType::kTet4},
                                           BoxCase{ElementType::kTet10, ElementType::kTet10},
                                           BoxCase{ElementType::kHex8, ElementType::kHex8},
                                           BoxCase{ElementType::kHex20, ElementType::kHex20},
                                           BoxCase{ElementType::kWedge15, ElementType::kWedge15},
                                           BoxCase{ElementType::kHex20, ElementType::kWedge15}),
                         [](const ::testing::TestParamInfo<BoxCase>& param_info) {
                           return std::string(Traits(param_info.param.type).name) + "_" +
                                  std::string(Traits(param_info.param.second_type).name);
                         });

TEST(BoundarySurface, CurvedTet10CylinderIsClosedOutwardWithItsVolumeWithinDiscretisation) {
  const double radius = 0.1, length = 0.3;
  const Eigen::Vector3d base(0.1, 0.2, -0.1);
  const Mesh mesh = testing::GmshCylinder(radius, length, base, 0.04);
  ASSERT_EQ(mesh.blocks.at(0).type, ElementType::kTet10);
  const PolygonSurface s = BoundarySurface(mesh, AllNodes(mesh));
  const SurfaceIntegrals integral = Integrate(s);
  const double volume = std::numbers::pi * radius * radius * length;
  const double area = 2.0 * std::numbers::pi * radius * (radius + length);
  EXPECT_NEAR(integral.volume, volume, kCylinderVolumeError * volume);
  EXPECT_LT(integral.volume, volume);  // inscribed
  EXPECT_NEAR(integral.area, area, kCylinderAreaError * area);
  EXPECT_LT(integral.vector_area.norm(), kRoundOff * area);
  // The body is convex: every outward normal points away from its centre.
  const Eigen::Vector3d centre = base + Eigen::Vector3d(0, 0, 0.5 * length);
  std::size_t first = 0;
  for (Eigen::Index f = 0; f < s.num_faces(); ++f) {
    const int count = s.face_sizes[static_cast<std::size_t>(f)];
    EXPECT_GT(s.face_normals.row(f).dot((Centroid(s, first, count) - centre).transpose()), 0.0)
        << "polygon " << f;
    first += static_cast<std::size_t>(count);
  }
  std::printf("cylinder: %ld polygons, volume error %.2e, area error %.2e\n",
              static_cast<long>(s.num_faces()), integral.volume / volume - 1.0,
              integral.area / area - 1.0);
}

}  // namespace
}  // namespace flexmbs::fem
