#include "tests/fem/test_meshes.h"

#include <unistd.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <stdexcept>
#include <string>

#include "fem/element_integrator.h"
#include "fem/gmsh_import.h"
#include "fem/reference_element.h"

namespace flexmbs::fem::testing {
namespace {

// An affine map from an element's reference coordinates to the doubled lattice of a structured
// cell (lattice point 2 i is corner i of the cells; odd lattice points are mid-sides):
// lattice = offset + A ref.
struct SubElement {
  Eigen::Vector3d offset;
  Eigen::Matrix3d A;
};

// The sub-elements that fill one cell [0, 2]^3 of the doubled lattice.
std::vector<SubElement> CellSplit(ElementType type) {
  std::vector<SubElement> split;
  switch (type) {
    case ElementType::kHex8:
    case ElementType::kHex20:  // reference [-1, 1]^3 -> [0, 2]^3
      split.push_back({Eigen::Vector3d::Ones(), Eigen::Matrix3d::Identity()});
      break;
    case ElementType::kTet4:
    case ElementType::kTet10: {  // Kuhn: 0 -> 2 e_p0 -> 2 (e_p0 + e_p1) -> (2, 2, 2)
      std::array<int, 3> p{0, 1, 2};
      do {
        Eigen::Vector3d v1 = Eigen::Vector3d::Zero(), v2, v3 = 2.0 * Eigen::Vector3d::Ones();
        v1(p[0]) = 2.0;
        v2 = v1;
        v2(p[1]) = 2.0;
        Eigen::Matrix3d A;
        A << v1, v2, v3;
        if (A.determinant() < 0.0) A.col(0).swap(A.col(1));  // keep positive orientation
        split.push_back({Eigen::Vector3d::Zero(), A});
      } while (std::next_permutation(p.begin(), p.end()));
      break;
    }
    case ElementType::kWedge6:
    case ElementType::kWedge15: {  // two prisms over the triangles (00, 20, 22), (00, 22, 02)
      Eigen::Matrix3d A1, A2;
      A1 << 2, 2, 0, 0, 2, 0, 0, 0, 1;
      A2 << 2, 0, 0, 2, 2, 0, 0, 0, 1;
      split.push_back({Eigen::Vector3d(0, 0, 1), A1});
      split.push_back({Eigen::Vector3d(0, 0, 1), A2});
      break;
    }
  }
  return split;
}

// Number of corner (vertex) nodes of `type`: the leading nodes in gmsh order.
int NumCorners(ElementType type) {
  switch (type) {
    case ElementType::kTet4:
    case ElementType::kTet10:
      return 4;
    case ElementType::kHex8:
    case ElementType::kHex20:
      return 8;
    case ElementType::kWedge6:
    case ElementType::kWedge15:
      return 6;
  }
  return 0;
}

// For each node of `type`, the two corners whose midpoint it is (reference coordinates), or
// {-1, -1} for a corner.
std::vector<std::array<int, 2>> EdgeTable(ElementType type) {
  const Eigen::Matrix3Xd& xi = ReferenceElement::Of(type).nodes();
  const int corners = NumCorners(type);
  std::vector<std::array<int, 2>> table(static_cast<std::size_t>(xi.cols()), {-1, -1});
  for (int m = corners; m < xi.cols(); ++m) {
    for (int i = 0; i < corners; ++i) {
      for (int j = i + 1; j < corners; ++j) {
        if ((xi.col(i) + xi.col(j) - 2.0 * xi.col(m)).norm() < 1e-14) {
          table[static_cast<std::size_t>(m)] = {i, j};
        }
      }
    }
    if (table[static_cast<std::size_t>(m)][0] < 0) throw std::logic_error("mid node off an edge");
  }
  return table;
}

}  // namespace

IsotropicMaterial Steel() { return {"steel", 210e9, 0.3, 7850.0}; }

BoxMesh StructuredBox(ElementType type, const Eigen::Vector3i& cells, const Eigen::Vector3d& size,
                      ElementType second_type, int second_from) {
  if (Traits(type).order != Traits(second_type).order) throw std::logic_error("orders differ");
  const Eigen::Vector3i points = 2 * cells + Eigen::Vector3i::Ones();  // doubled lattice
  std::vector<int> node_of(static_cast<std::size_t>(points.prod()), -1);
  std::vector<Eigen::Vector3i> lattice_of_node;
  std::vector<std::vector<int>> connectivity(2);  // per block, element after element

  BoxMesh box;
  box.cell_size = size.cwiseQuotient(cells.cast<double>());
  const ElementType types[2] = {type, second_type};
  for (int k = 0; k < cells(2); ++k) {
    for (int j = 0; j < cells(1); ++j) {
      for (int i = 0; i < cells(0); ++i) {
        const int b = i >= second_from ? 1 : 0;
        const ReferenceElement& ref = ReferenceElement::Of(types[b]);
        for (const SubElement& sub : CellSplit(types[b])) {
          for (int a = 0; a < ref.num_nodes(); ++a) {
            const Eigen::Vector3d p =
                2.0 * Eigen::Vector3d(i, j, k) + sub.offset + sub.A * ref.nodes().col(a);
            const Eigen::Vector3i l = p.array().round().cast<int>();
            const auto slot =
                static_cast<std::size_t>(l(0) + points(0) * (l(1) + points(1) * l(2)));
            if (node_of[slot] < 0) {
              node_of[slot] = static_cast<int>(lattice_of_node.size());
              lattice_of_node.push_back(l);
            }
            connectivity[static_cast<std::size_t>(b)].push_back(node_of[slot]);
          }
        }
      }
    }
  }
  const auto n = static_cast<Eigen::Index>(lattice_of_node.size());
  box.mesh.nodes.resize(3, n);
  box.on_boundary.resize(static_cast<std::size_t>(n));
  box.edge_of.assign(static_cast<std::size_t>(n), {-1, -1});
  for (Eigen::Index v = 0; v < n; ++v) {
    const Eigen::Vector3i& l = lattice_of_node[static_cast<std::size_t>(v)];
    box.mesh.nodes.col(v) = 0.5 * l.cast<double>().cwiseProduct(box.cell_size);
    box.on_boundary[static_cast<std::size_t>(v)] =
        (l.array() == 0).any() || (l.array() == points.array() - 1).any();
    box.mesh.node_ids.push_back(static_cast<std::size_t>(v) + 1);
  }
  std::size_t next_id = 1;
  for (int b = 0; b < 2; ++b) {
    const std::vector<int>& c = connectivity[static_cast<std::size_t>(b)];
    if (c.empty()) continue;
    const int nodes_per_element = Traits(types[b]).num_nodes;
    ElementBlock block{
        types[b],
        b == 0 ? "box" : "box 2",
        Steel(),
        Eigen::Map<const Connectivity>(c.data(), nodes_per_element,
                                       static_cast<Eigen::Index>(c.size()) / nodes_per_element),
        {}};
    const std::vector<std::array<int, 2>> edges = EdgeTable(types[b]);
    for (Eigen::Index e = 0; e < block.num_elements(); ++e) {
      block.element_ids.push_back(next_id++);
      for (std::size_t m = 0; m < edges.size(); ++m) {
        if (edges[m][0] < 0) continue;
        box.edge_of[static_cast<std::size_t>(block.connectivity(static_cast<Eigen::Index>(m), e))] =
            {block.connectivity(edges[m][0], e), block.connectivity(edges[m][1], e)};
      }
    }
    box.mesh.blocks.push_back(std::move(block));
  }
  return box;
}

Mesh GmshCylinder(double radius, double length, const Eigen::Vector3d& base, double mesh_size) {
  const std::filesystem::path geo =
      std::filesystem::temp_directory_path() /
      ("flexmbs_fem_test_cylinder_" + std::to_string(::getpid()) + ".geo");
  {
    std::ofstream out(geo);
    out.precision(17);
    out << "SetFactory(\"OpenCASCADE\");\n"
        << "Cylinder(1) = {" << base(0) << ", " << base(1) << ", " << base(2) << ", 0, 0, "
        << length << ", " << radius << "};\n";
  }
  Mesh mesh = ImportMesh(geo, MeshingOptions{mesh_size, 2}, {});
  std::filesystem::remove(geo);
  for (ElementBlock& block : mesh.blocks) block.material = Steel();
  return mesh;
}

void DistortInterior(BoxMesh* box, double corner_fraction, double curve_fraction,
                     std::mt19937* rng) {
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  auto random_offset = [&](double fraction) {
    const Eigen::Vector3d r(unit(*rng), unit(*rng), unit(*rng));
    return Eigen::Vector3d(fraction * r.cwiseProduct(box->cell_size));
  };
  Eigen::Matrix3Xd& x = box->mesh.nodes;
  for (Eigen::Index v = 0; v < x.cols(); ++v) {
    const auto s = static_cast<std::size_t>(v);
    if (box->edge_of[s][0] < 0 && !box->on_boundary[s]) x.col(v) += random_offset(corner_fraction);
  }
  for (Eigen::Index v = 0; v < x.cols(); ++v) {
    const auto s = static_cast<std::size_t>(v);
    if (box->edge_of[s][0] < 0) continue;
    x.col(v) = 0.5 * (x.col(box->edge_of[s][0]) + x.col(box->edge_of[s][1]));
    if (!box->on_boundary[s]) x.col(v) += random_offset(curve_fraction);
  }
}

void Transform(Mesh* mesh, const Eigen::Matrix3d& R, const Eigen::Vector3d& t) {
  mesh->nodes = (R * mesh->nodes).colwise() + t;
}

double MinJacobian(const Mesh& mesh) {
  double min_det = std::numeric_limits<double>::infinity();
  Eigen::MatrixXd K_e, m_e;
  for (const ElementBlock& block : mesh.blocks) {
    ElementIntegrator integrator(block.type);
    Eigen::Matrix3Xd X(3, integrator.num_nodes());
    for (Eigen::Index e = 0; e < block.num_elements(); ++e) {
      for (int a = 0; a < integrator.num_nodes(); ++a)
        X.col(a) = mesh.nodes.col(block.connectivity(a, e));
      min_det = std::min({min_det, integrator.Stiffness(X, block.material, &K_e),
                          integrator.ScalarMass(X, 1.0, MassMatrixKind::kConsistent, &m_e)});
    }
  }
  return min_det;
}

Eigen::SparseMatrix<double> Submatrix(const Eigen::SparseMatrix<double>& A,
                                      const std::vector<int>& rows, const std::vector<int>& cols) {
  std::vector<int> row_map(static_cast<std::size_t>(A.rows()), -1);
  std::vector<int> col_map(static_cast<std::size_t>(A.cols()), -1);
  for (std::size_t i = 0; i < rows.size(); ++i)
    row_map[static_cast<std::size_t>(rows[i])] = static_cast<int>(i);
  for (std::size_t j = 0; j < cols.size(); ++j)
    col_map[static_cast<std::size_t>(cols[j])] = static_cast<int>(j);
  std::vector<Eigen::Triplet<double>> triplets;
  for (int c = 0; c < A.outerSize(); ++c) {
    for (Eigen::SparseMatrix<double>::InnerIterator it(A, c); it; ++it) {
      const int r = row_map[static_cast<std::size_t>(it.row())];
      const int cc = col_map[static_cast<std::size_t>(it.col())];
      if (r >= 0 && cc >= 0) triplets.emplace_back(r, cc, it.value());
    }
  }
  Eigen::SparseMatrix<double> S(static_cast<Eigen::Index>(rows.size()),
                                static_cast<Eigen::Index>(cols.size()));
  S.setFromTriplets(triplets.begin(), triplets.end());
  return S;
}

Eigen::Matrix3d RandomRotation(std::mt19937* rng) {
  std::normal_distribution<double> normal;
  Eigen::Quaterniond q(normal(*rng), normal(*rng), normal(*rng), normal(*rng));
  return q.normalized().toRotationMatrix();
}

}  // namespace flexmbs::fem::testing
